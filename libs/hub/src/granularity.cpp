// Animation granularity controller (see granularity.hpp).
#include "throng/hub/granularity.hpp"

#include <algorithm>

namespace throng::hub {

GranularityController::GranularityController(GranularityOptions options) : options_(options) {
  options_.minFactor = std::max<std::uint32_t>(1, options_.minFactor);
  options_.maxFactor = std::max(options_.minFactor, options_.maxFactor);
  factor_ = options_.minFactor;
}

std::uint32_t GranularityController::update(const LinkSample& s) {
  if (!started_) {
    started_ = true;
    lastSeconds_ = s.seconds;
    lastBytes_ = s.bytesSent;
    lastDropped_ = s.framesDropped;
    return factor_;
  }
  const double elapsed = s.seconds - lastSeconds_;
  if (elapsed < options_.evaluateEverySeconds) return factor_;
  kbitPerSecond_ = static_cast<double>(s.bytesSent - lastBytes_) * 8.0 / 1000.0 / elapsed;
  const bool dropped = s.framesDropped > lastDropped_;
  lastSeconds_ = s.seconds;
  lastBytes_ = s.bytesSent;
  lastDropped_ = s.framesDropped;

  const char* congestion = nullptr;
  if (dropped) congestion = "congested: frames dropped";
  else if (s.queueBytes > options_.maxQueueBytes) congestion = "congested: send queue";
  else if (options_.maxRoundTripMs > 0 && s.roundTripMs > options_.maxRoundTripMs) congestion = "congested: round trip";
  else if (kbitPerSecond_ > options_.budgetKbitPerSecond) congestion = "over budget";

  if (congestion != nullptr) {
    factor_ = std::min(options_.maxFactor, factor_ * 2);
    reason_ = congestion;
  } else if (factor_ > options_.minFactor && kbitPerSecond_ * (static_cast<double>(factor_) /
                                                                static_cast<double>(factor_ - 1)) <
                                                    options_.budgetKbitPerSecond) {
    // Lowering X raises the animation share of the traffic by at most X/(X-1): only step down when
    // that still fits the budget, so X does not oscillate around it.
    factor_ -= 1;
    reason_ = "clear";
  } else {
    reason_ = "steady";
  }
  return factor_;
}

}  // namespace throng::hub
