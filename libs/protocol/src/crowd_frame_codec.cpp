// throng::protocol crowd frame codec (private) — writes and reads the CrowdFrame header
// (docs/protocol.md "CrowdFrame") and compresses / decompresses the payload with zstd.
#include "crowd_frame_codec.hpp"

#include "zstd_codec.hpp"

namespace throng::protocol::detail {

std::vector<std::uint8_t> encodeCrowdFrame(const CrowdFrame& frame, const std::vector<std::uint8_t>* compressed) {
  const CrowdFrameHeader& h = frame.header;
  std::vector<std::uint8_t> out{kMagic, static_cast<std::uint8_t>(MessageType::CrowdFrame)};
  ByteWriter w(out);
  w.u8(static_cast<std::uint8_t>((h.compressed ? kCrowdFlagCompressed : 0) | (h.farIncluded ? kCrowdFlagFarIncluded : 0)));
  w.varint(h.frameNumber);
  w.varint(h.baseFrame);
  w.varint(h.simTick);
  w.u8(h.animationInterval);
  w.u8(h.jointCount);
  w.u8(h.jointShift);
  w.varint(h.nearCount);
  w.varint(h.middleCount);
  w.varint(h.farCount);
  w.varint(frame.payload.size());
  if (h.compressed) {
    if (compressed) {
      w.bytes(*compressed);
    } else {
      w.bytes(zstdCompress(frame.payload, kCrowdZstdLevel));
    }
  } else {
    w.bytes(frame.payload);
  }
  return out;
}

CrowdFrame decodeCrowdFrame(ByteReader& r) {
  CrowdFrame f;
  CrowdFrameHeader& h = f.header;
  std::size_t at = r.offset();
  const std::uint8_t flags = r.u8("flags");
  if (flags & ~(kCrowdFlagCompressed | kCrowdFlagFarIncluded)) {
    r.fail("flags", at, "unknown flag bits " + std::to_string(flags), "bit 0 (compressed) and bit 1 (far included) only");
  }
  h.compressed = (flags & kCrowdFlagCompressed) != 0;
  h.farIncluded = (flags & kCrowdFlagFarIncluded) != 0;
  at = r.offset();
  h.frameNumber = static_cast<std::uint32_t>(r.varint("frameNumber", 0xffffffffu));
  if (r.ok() && h.frameNumber == 0) r.fail("frameNumber", at, "frame number 0", "a frame number ≥ 1");
  at = r.offset();
  h.baseFrame = static_cast<std::uint32_t>(r.varint("baseFrame", 0xffffffffu));
  if (r.ok() && h.baseFrame >= h.frameNumber) {
    r.fail("baseFrame", at, "base frame " + std::to_string(h.baseFrame) + " not before frame " + std::to_string(h.frameNumber),
           "0 (key frame) or an earlier frame number");
  }
  h.simTick = r.varint("simTick");
  at = r.offset();
  h.animationInterval = r.u8("animationInterval");
  if (r.ok() && h.animationInterval == 0) r.fail("animationInterval", at, "animation interval 0", "X ≥ 1");
  at = r.offset();
  h.jointCount = r.u8("jointCount");
  if (r.ok() && h.jointCount > kMaxJoints) {
    r.fail("jointCount", at, std::to_string(h.jointCount) + " joints", "at most " + std::to_string(kMaxJoints));
  }
  at = r.offset();
  h.jointShift = r.u8("jointShift");
  if (r.ok() && h.jointShift > kMaxJointShift) {
    r.fail("jointShift", at, "joint shift " + std::to_string(h.jointShift), "at most " + std::to_string(kMaxJointShift));
  }
  h.nearCount = static_cast<std::uint32_t>(r.varint("nearCount", kMaxAgents));
  h.middleCount = static_cast<std::uint32_t>(r.varint("middleCount", kMaxAgents));
  at = r.offset();
  h.farCount = static_cast<std::uint32_t>(r.varint("farCount", kMaxAgents));
  if (r.ok() && std::uint64_t{h.nearCount} + h.middleCount + h.farCount > kMaxAgents) {
    r.fail("farCount", at, std::to_string(std::uint64_t{h.nearCount} + h.middleCount + h.farCount) + " agents",
           "at most " + std::to_string(kMaxAgents) + " agents in view");
  }
  h.payloadSize = static_cast<std::uint32_t>(r.varint("payloadSize", kMaxCrowdPayload));
  if (!r.ok()) return f;
  at = r.offset();
  if (!h.compressed) {
    if (r.remaining() != h.payloadSize) {
      r.fail("payload", at, std::to_string(r.remaining()) + " payload bytes", std::to_string(h.payloadSize) + " (payloadSize)");
      return f;
    }
    const auto b = r.bytes("payload", h.payloadSize);
    f.payload.assign(b.begin(), b.end());
    return f;
  }
  const auto compressed = r.bytes("payload", r.remaining());
  std::string why;
  auto raw = zstdDecompress(compressed, h.payloadSize, why);
  if (!raw) {
    r.fail("payload", at, why, "one zstd frame of payloadSize bytes");
    return f;
  }
  f.payload = std::move(*raw);
  return f;
}

}  // namespace throng::protocol::detail
