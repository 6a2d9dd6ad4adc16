// libFuzzer target for every protocol decoder: decodeAny (all message types), then for crowd
// frames a CrowdDecoder that holds the golden key frame (frame 1), so delta payloads against it are
// applied too; a Fragment goes through a Reassembler (completed with copies of itself when its
// count is small, and the whole message decoded). Input: one message. Must never crash, hang or read out of bounds.
#include <cstddef>
#include <cstdint>
#include <span>
#include <variant>

#include "throng/protocol/crowd_decoder.hpp"
#include "throng/protocol/crowd_encoder.hpp"
#include "throng/protocol/fragments.hpp"
#include "throng/protocol/messages.hpp"

using namespace throng::protocol;

namespace {

/// A decoder that already holds frame 1: a few agents of every tier, with joints.
CrowdDecoder primedDecoder() {
  CrowdView v;
  v.jointCount = 2;
  v.agents = {{1, Tier::Near, 1.0f, 2.0f, 0.0f, 0.5f, 1, 0.25f, {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f}},
              {2, Tier::Middle, 3.0f, 4.0f, 0.0f, 1.0f, 2, 0.5f, {}},
              {4, Tier::Far, 10.0f, 20.0f, 0.0f, 0.0f, 0, 0.0f, {}}};
  CrowdEncoder enc;
  CrowdDecoder dec;
  auto key = enc.encode(v, 0);
  if (key.ok()) (void)dec.decode(key.value().bytes);
  return dec;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  auto m = decodeAny(std::span(data, size));
  if (!m.ok()) return 0;
  if (auto* frame = std::get_if<CrowdFrame>(&m.value())) {
    CrowdDecoder dec = primedDecoder();
    (void)dec.apply(*frame);
  } else if (auto* welcome = std::get_if<Welcome>(&m.value())) {
    (void)worldJson(*welcome);
  } else if (auto* fragment = std::get_if<Fragment>(&m.value())) {
    Reassembler reassembler;
    (void)reassembler.add(*fragment);
    if (fragment->count <= 16) {  // the other pieces: copies of this payload
      Fragment other = *fragment;
      for (std::uint32_t i = 0; i < fragment->count; ++i) {
        other.index = i;
        auto whole = reassembler.add(other);
        if (whole.ok() && whole.value()) (void)decodeAny(*whole.value());
      }
    }
  }
  (void)encode(m.value());  // whatever decodes also encodes
  return 0;
}
