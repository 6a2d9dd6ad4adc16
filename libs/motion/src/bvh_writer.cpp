// throng::motion motion clip writer — MotionClip → BVH text (writeBvh), the checks that make that text
// valid (checkMotionClip) and an atomic file save (saveBvhFile: temporary file in the same
// directory, fsync, rename). Numbers use std::to_chars' shortest round-trip form.
#include "throng/motion/bvh_writer.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <set>
#include <string_view>
#include <vector>

namespace throng::motion {
namespace {

/// Shortest decimal that reads back to the same float (or double); "-0" becomes "0".
template <class T>
void appendNumber(std::string& out, T v) {
  if (v == T(0)) v = T(0);  // drops the sign of -0
  std::array<char, 64> buf{};
  const auto [end, ec] = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  if (ec != std::errc()) {
    out += '0';
    return;
  }
  out.append(buf.data(), end);
}

void appendOffset(std::string& out, const std::array<float, 3>& offset) {
  out += "OFFSET";
  for (const float v : offset) {
    out += ' ';
    appendNumber(out, v);
  }
  out += '\n';
}

/// Joint indices in depth-first order from the root (joint 0), children in index order. For a
/// well-formed clip this is 0, 1, 2, …; unreachable joints and bad parent links are skipped.
std::vector<std::size_t> depthFirst(const MotionClip& clip, std::vector<std::vector<std::size_t>>& children) {
  const std::size_t n = clip.joints.size();
  children.assign(n, {});
  for (std::size_t i = 1; i < n; ++i) {
    const int p = clip.joints[i].parent;
    if (p >= 0 && static_cast<std::size_t>(p) < i) children[static_cast<std::size_t>(p)].push_back(i);
  }
  std::vector<std::size_t> order;
  if (n == 0) return order;
  std::vector<std::size_t> stack = {0};
  while (!stack.empty()) {
    const std::size_t j = stack.back();
    stack.pop_back();
    order.push_back(j);
    for (auto it = children[j].rbegin(); it != children[j].rend(); ++it) stack.push_back(*it);
  }
  return order;
}

void appendJoint(std::string& out, const MotionClip& clip, const std::vector<std::vector<std::size_t>>& children,
                 std::size_t index, std::size_t depth) {
  // Recursion depth is bounded by the clip's nesting; saveBvhFile checks kMaxBvhDepth first.
  const MotionClip::Joint& joint = clip.joints[index];
  const std::string pad(2 * depth, ' ');
  out += pad + (depth == 0 ? "ROOT " : "JOINT ") + joint.name + '\n';
  out += pad + "{\n";
  out += pad + "  ";
  appendOffset(out, joint.offset);
  if (!joint.channels.empty()) {
    out += pad + "  CHANNELS " + std::to_string(joint.channels.size());
    for (const MotionChannel c : joint.channels) {
      out += ' ';
      out += channelName(c);
    }
    out += '\n';
  }
  for (const std::size_t child : children[index]) appendJoint(out, clip, children, child, depth + 1);
  if (joint.hasEndSite) {
    out += pad + "  End Site\n";
    out += pad + "  {\n";
    out += pad + "    ";
    appendOffset(out, joint.endSite);
    out += pad + "  }\n";
  }
  out += pad + "}\n";
}

core::Diagnostic problem(const std::string& source, std::string what, std::string expected) {
  return core::Diagnostic{source, 0, 0, "", std::move(what), std::move(expected), ""};
}

std::string quoteText(std::string_view s) { return "\"" + std::string(s) + "\""; }

bool finiteInRange(double v) { return std::isfinite(v) && std::fabs(v) <= kMaxBvhMagnitude; }

}  // namespace

std::string writeBvh(const MotionClip& clip) {
  std::string out = "HIERARCHY\n";
  std::vector<std::vector<std::size_t>> children;
  const std::vector<std::size_t> order = depthFirst(clip, children);
  if (!order.empty()) appendJoint(out, clip, children, 0, 0);
  out += "MOTION\nFrames: " + std::to_string(clip.frameCount) + "\nFrame Time: ";
  appendNumber(out, clip.frameTime);
  out += '\n';
  out.reserve(out.size() + clip.frameCount * clip.channelCount * 8);
  for (std::size_t f = 0; f < clip.frameCount; ++f) {
    bool first = true;
    for (const std::size_t j : order) {
      const MotionClip::Joint& joint = clip.joints[j];
      for (std::size_t k = 0; k < joint.channels.size(); ++k) {
        if (!first) out += ' ';
        first = false;
        const std::size_t column = joint.firstChannel + k;
        const std::size_t at = f * clip.channelCount + column;
        appendNumber(out, column < clip.channelCount && at < clip.values.size() ? clip.values[at] : 0.0f);
      }
    }
    out += '\n';
  }
  return out;
}

core::Status checkMotionClip(const MotionClip& clip, const std::string& source) {
  constexpr std::size_t kMaxProblems = 20;
  core::Diagnostics ds;
  auto add = [&](std::string what, std::string expected) {
    if (ds.size() < kMaxProblems) ds.push_back(problem(source, std::move(what), std::move(expected)));
  };
  const auto& joints = clip.joints;
  if (joints.empty()) add("the clip has no joints", "at least a root joint");
  if (joints.size() > kMaxBvhJoints) {
    add("the clip has " + std::to_string(joints.size()) + " joints", "at most " + std::to_string(kMaxBvhJoints) + " joints");
  }
  std::set<std::string_view> names;
  std::vector<std::size_t> stack;  // ancestors of the current joint (depth-first order check)
  std::size_t columns = 0;
  for (std::size_t i = 0; i < joints.size() && ds.size() < kMaxProblems; ++i) {
    const MotionClip::Joint& joint = joints[i];
    const std::string label = "joint " + std::to_string(i) + " " + quoteText(joint.name);
    const bool badName = joint.name.empty() || joint.name == "{" || joint.name == "}" ||
                         std::any_of(joint.name.begin(), joint.name.end(), [](unsigned char c) { return c <= ' ' || c == 127; });
    if (badName) add(label + " has an unusable name", "a non-empty joint name without spaces, control characters or lone braces");
    if (!names.insert(joint.name).second) add("duplicate joint name " + quoteText(joint.name), "joint names unique within the clip");
    if (i == 0) {
      if (joint.parent != -1) add(label + " (the root) has parent " + std::to_string(joint.parent), "parent -1 for joints[0]");
      stack = {0};
    } else {
      while (!stack.empty() && static_cast<int>(stack.back()) != joint.parent) stack.pop_back();
      if (stack.empty()) {
        add(label + " has parent " + std::to_string(joint.parent),
            "depth-first order: the parent is an earlier joint on the path from the root to the previous joint");
        stack = {0};
      } else if (stack.size() > kMaxBvhDepth) {
        add(label + " is nested deeper than " + std::to_string(kMaxBvhDepth) + " joints",
            "at most " + std::to_string(kMaxBvhDepth) + " levels of JOINT below ROOT");
      }
      stack.push_back(i);
    }
    if (joint.channels.size() > 6) {
      add(label + " has " + std::to_string(joint.channels.size()) + " channels", "at most 6 channels per joint");
    }
    for (std::size_t k = 0; k < joint.channels.size(); ++k) {
      const auto c = joint.channels[k];
      if (static_cast<unsigned>(c) > static_cast<unsigned>(MotionChannel::Zrotation)) {
        add(label + " has an unknown channel", "Xposition, Yposition, Zposition, Xrotation, Yrotation or Zrotation");
      } else if (std::find(joint.channels.begin(), joint.channels.begin() + static_cast<std::ptrdiff_t>(k), c) !=
                 joint.channels.begin() + static_cast<std::ptrdiff_t>(k)) {
        add(label + " lists channel " + quoteText(channelName(c)) + " twice", "each channel at most once per joint");
      }
    }
    if (!joint.channels.empty() && joint.firstChannel != columns) {  // (parseBvh leaves 0 when there are none)
      add(label + " has firstChannel " + std::to_string(joint.firstChannel),
          std::to_string(columns) + " (the channels of the joints before it)");
    }
    columns += joint.channels.size();
    for (const float v : joint.offset) {
      if (!finiteInRange(v)) add(label + " has a non-finite or huge OFFSET", "finite numbers with magnitude at most 1e9");
    }
    for (const float v : joint.endSite) {
      if (joint.hasEndSite && !finiteInRange(v)) {
        add(label + " has a non-finite or huge End Site offset", "finite numbers with magnitude at most 1e9");
      }
    }
  }
  if (!joints.empty() && columns != clip.channelCount) {
    add("channelCount is " + std::to_string(clip.channelCount), std::to_string(columns) + " (the sum of the joints' channels)");
  }
  if (clip.channelCount == 0) add("the clip has no channels", "at least one joint with channels");
  if (clip.frameCount == 0 || clip.frameCount > kMaxBvhFrames) {
    add("frameCount is " + std::to_string(clip.frameCount), "1 to " + std::to_string(kMaxBvhFrames) + " frames");
  }
  if (!(clip.frameTime > 0.0 && clip.frameTime <= kMaxBvhFrameTime)) {
    add("frame time " + std::to_string(clip.frameTime) + " s is out of range", "a frame time > 0 and <= 60 s");
  }
  if (clip.values.size() != clip.frameCount * clip.channelCount) {
    add("the clip has " + std::to_string(clip.values.size()) + " values",
        std::to_string(clip.frameCount * clip.channelCount) + " (frameCount × channelCount)");
  } else {
    for (std::size_t at = 0; at < clip.values.size() && ds.size() < kMaxProblems; ++at) {
      if (!finiteInRange(clip.values[at])) {
        add("value of frame " + std::to_string(at / clip.channelCount) + ", channel " +
                std::to_string(at % clip.channelCount) + " is not finite or too large",
            "finite numbers with magnitude at most 1e9");
      }
    }
  }
  if (!ds.empty()) return ds;
  return core::Ok{};
}

core::Status saveBvhFile(const std::string& path, const MotionClip& clip) {
  namespace fs = std::filesystem;
  const std::string expected = "a writable file path in an existing directory";
  core::Status checked = checkMotionClip(clip, path);
  if (!checked.ok()) return checked;
  std::string text;
  try {
    text = writeBvh(clip);
  } catch (const std::exception& e) {
    return problem(path, std::string("cannot write file: ") + e.what(), expected);
  }

  const fs::path target(path);
  if (path.empty() || !target.has_filename()) return problem(path, "cannot write file: not a file path", expected);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::string tmp = (dir / ("." + target.filename().string() + ".tmp-XXXXXX")).string();
  const int fd = ::mkstemp(tmp.data());
  if (fd < 0) {
    return problem(path, "cannot write file: cannot create a temporary file in " + quoteText(dir.string()) + ": " +
                             std::strerror(errno), expected);
  }
  auto failWith = [&](const std::string& step, int err) {
    ::close(fd);
    ::unlink(tmp.c_str());
    return problem(path, "cannot write file: " + step + ": " + std::strerror(err), expected);
  };
  // mkstemp creates the file 0600; a saved clip is an ordinary readable file.
  if (::fchmod(fd, S_IRUSR | S_IWUSR | S_IRGRP | S_IROTH) != 0) return failWith("cannot set permissions", errno);
  std::size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      return failWith("write failed", errno);
    }
    written += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) return failWith("fsync failed", errno);
  if (::close(fd) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    return problem(path, std::string("cannot write file: close failed: ") + std::strerror(err), expected);
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    return problem(path, std::string("cannot write file: cannot rename the temporary file over it: ") + std::strerror(err),
                   expected);
  }
  return core::Ok{};
}

}  // namespace throng::motion
