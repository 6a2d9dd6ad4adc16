// throng::protocol::CrowdEncoder — server side, one per client: turns the CrowdView of each tick
// into one CrowdFrame message, delta-coded against the newest frame the client acknowledged
// (a key frame when that frame is unknown or older than the history), with far agents refreshed
// every farInterval frames, animation (clip, phase, joints) every CrowdView::animationInterval
// frames, identical near poses sent once, and zstd when the payload is large enough to gain.
// Keeps the last `historyFrames` frames as the client will reconstruct them. Not thread-safe:
// one encoder per client, used by one thread at a time.
#pragma once
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include "throng/core/result.hpp"
#include "throng/protocol/crowd_frame.hpp"

namespace throng::protocol {

struct CrowdEncoderOptions {
  std::size_t historyFrames = 64;   ///< frames kept to delta against [1, 4096]
  std::uint32_t farInterval = 4;    ///< far agents are refreshed every farInterval frames (≥ 1)
  std::uint8_t jointShift = 4;      ///< joint angles in units of 2^jointShift/65536 turn [0, 8]
  std::size_t compressMinBytes = 96;///< payloads smaller than this travel raw [bytes]
  int compressionLevel = 3;         ///< zstd level [1, 22]
};

/// What encode produced: the message, its header, and counts for statistics.
struct EncodedCrowdFrame {
  std::vector<std::uint8_t> bytes;  ///< the whole message (one WebSocket frame / datagram)
  CrowdFrameHeader header;
  std::size_t records = 0;          ///< agents with a record (new or changed)
  std::size_t removals = 0;
  std::size_t poses = 0;            ///< entries of the pose table
  [[nodiscard]] bool keyFrame() const { return header.baseFrame == 0; }
};

class CrowdEncoder {
 public:
  explicit CrowdEncoder(CrowdEncoderOptions options = {});
  ~CrowdEncoder();
  CrowdEncoder(CrowdEncoder&&) noexcept;
  CrowdEncoder& operator=(CrowdEncoder&&) noexcept;

  /// Encodes the next frame. `ackedFrame` is the newest frame number the client acknowledged
  /// (0: none → key frame). Errors (nothing is sent, the history is unchanged): duplicate agent
  /// ids, more than kMaxAgents agents, jointCount > kMaxJoints, animationInterval 0.
  [[nodiscard]] core::Result<EncodedCrowdFrame> encode(const CrowdView& view, std::uint32_t ackedFrame);

  /// The next frame will be a key frame (after a reconnect, or when the client asks for one).
  void reset();

  /// Number the next frame will get.
  [[nodiscard]] std::uint32_t nextFrameNumber() const;

  /// The view the client reconstructs from frame `frameNumber` (quantized, possibly stale far
  /// agents and animation), while it is in the history.
  [[nodiscard]] std::optional<CrowdView> sentView(std::uint32_t frameNumber) const;

  [[nodiscard]] const CrowdEncoderOptions& options() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace throng::protocol
