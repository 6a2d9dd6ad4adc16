// throng::hub animation granularity — Musse et al. §4.3's factor X: a client receives its crowd's
// animation (clip, phase, joint poses) every X frames, positions every frame. X is regulated per
// client from what the server measures of it: bandwidth actually sent, round-trip time, the depth
// of its send queue and the crowd frames dropped because a newer one replaced them (the client did
// not read fast enough). Multiplicative increase on congestion, additive decrease when clear (the
// shape of TCP's congestion control, inverted because X is a divisor of the rate). No I/O, no clock:
// the caller passes the time.
#pragma once
#include <cstdint>

namespace throng::hub {

struct GranularityOptions {
  std::uint32_t minFactor = 1;           ///< X at best (animation every frame)
  std::uint32_t maxFactor = 16;          ///< X at worst
  double budgetKbitPerSecond = 500.0;    ///< target bandwidth per client [kbit/s]
  double maxRoundTripMs = 400.0;         ///< above this round-trip time the client is congested [ms]
  std::uint64_t maxQueueBytes = 256 * 1024;  ///< above this much unsent data the client is congested
  double evaluateEverySeconds = 1.0;     ///< X changes at most this often [s]
};

/// What the server measured of one client over the last evaluation period.
struct LinkSample {
  double seconds = 0.0;             ///< now [s] (any monotonic origin)
  std::uint64_t bytesSent = 0;      ///< total bytes sent to the client so far
  std::uint64_t framesDropped = 0;  ///< total crowd frames replaced before they were sent, so far
  std::uint64_t queueBytes = 0;     ///< bytes waiting in its send queue now
  double roundTripMs = 0.0;         ///< latest heartbeat round trip [ms] (0 = unknown)
};

class GranularityController {
 public:
  explicit GranularityController(GranularityOptions options = {});
  /// Feeds a measurement; returns the factor X to use from now on.
  std::uint32_t update(const LinkSample& sample);
  [[nodiscard]] std::uint32_t factor() const { return factor_; }
  /// Bandwidth measured over the last evaluation period [kbit/s].
  [[nodiscard]] double kbitPerSecond() const { return kbitPerSecond_; }
  /// Why X last changed ("congested: queue", "clear", ...), for the server's status output.
  [[nodiscard]] const char* reason() const { return reason_; }
  /// Whether frame `frameNumber` carries animation for this client.
  [[nodiscard]] bool animationFrame(std::uint64_t frameNumber) const { return frameNumber % factor_ == 0; }

 private:
  GranularityOptions options_;
  std::uint32_t factor_ = 1;
  bool started_ = false;
  double lastSeconds_ = 0.0;
  std::uint64_t lastBytes_ = 0;
  std::uint64_t lastDropped_ = 0;
  double kbitPerSecond_ = 0.0;
  const char* reason_ = "start";
};

}  // namespace throng::hub
