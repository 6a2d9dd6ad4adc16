// throng::protocol::CrowdDecoder — client side: applies CrowdFrame messages to the frames decoded
// before (a delta frame names its base), keeping the last `historyFrames` reconstructed views.
// A frame whose base it does not have gives a clean error and changes nothing: the client keeps
// acknowledging its newest frame and waits for a delta against it or a key frame.
// Agents a frame does not mention keep their state in the base frame (far agents between their
// refreshes, animation between two animation frames).
#pragma once
#include <cstdint>
#include <memory>
#include <span>

#include "throng/core/result.hpp"
#include "throng/protocol/crowd_frame.hpp"

namespace throng::protocol {

struct DecodedCrowdFrame {
  CrowdFrameHeader header;
  CrowdView view;  ///< the whole crowd in view, ascending id, quantized values
};

class CrowdDecoder {
 public:
  explicit CrowdDecoder(std::size_t historyFrames = 64);
  ~CrowdDecoder();
  CrowdDecoder(CrowdDecoder&&) noexcept;
  CrowdDecoder& operator=(CrowdDecoder&&) noexcept;

  /// Applies a frame decodeAny returned. Errors: unknown base frame, a payload that does not
  /// parse (byte offset into the payload), records contradicting the base (removing an absent
  /// agent, ids not ascending, fields the tier does not carry), counts not matching the header.
  [[nodiscard]] core::Result<DecodedCrowdFrame> apply(const CrowdFrame& frame);

  /// decodeAny + apply; an error for any other message type.
  [[nodiscard]] core::Result<DecodedCrowdFrame> decode(std::span<const std::uint8_t> bytes);

  /// Newest frame number decoded (0: none) — what the client acknowledges.
  [[nodiscard]] std::uint32_t newestFrame() const;
  [[nodiscard]] bool hasFrame(std::uint32_t frameNumber) const;
  void reset();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace throng::protocol
