// libFuzzer target for the BVH motion clip parser (libs/motion bvh_parser): arbitrary bytes →
// parseBvh. Reads the input only. Checks that nothing crashes, throws or hangs, and that results
// are coherent: a parsed clip's joints form a tree in file order, its channel columns tile the
// frame row, and it holds frameCount × channelCount finite values; a rejected input has located
// diagnostics naming the source.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "throng/motion/bvh.hpp"

namespace {

void check(bool condition) {
  if (!condition) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const auto r = throng::motion::parseBvh(text, "fuzz.bvh");
  if (!r.ok()) {
    check(!r.errors().empty());
    for (const auto& d : r.errors()) {
      check(d.source == "fuzz.bvh");
      check(!d.what.empty());
      check(d.line >= 1 && d.column >= 1);  // every BVH problem has a place in the text
    }
    return 0;
  }
  const auto& clip = r.value();
  check(clip.name == "fuzz");
  check(!clip.joints.empty() && clip.joints.size() <= throng::motion::kMaxBvhJoints);
  check(clip.joints[0].parent == -1);
  std::size_t column = 0;
  for (std::size_t i = 0; i < clip.joints.size(); ++i) {
    const auto& j = clip.joints[i];
    if (i > 0) check(j.parent >= 0 && static_cast<std::size_t>(j.parent) < i);
    check(j.channels.size() <= 6);
    check(j.firstChannel == column);
    column += j.channels.size();
    check(clip.findJoint(j.name) == static_cast<int>(i));
    for (const float v : j.offset) check(std::isfinite(v));
  }
  check(column == clip.channelCount && clip.channelCount >= 1);
  check(clip.frameCount >= 1 && clip.frameCount <= throng::motion::kMaxBvhFrames);
  check(clip.frameTime > 0.0 && clip.frameTime <= throng::motion::kMaxBvhFrameTime);
  check(clip.values.size() == clip.frameCount * clip.channelCount);
  for (const float v : clip.values) check(std::isfinite(v));
  check(clip.duration() > 0.0);
  return 0;
}
