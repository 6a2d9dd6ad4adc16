// throng::transport::detail::TokenBucket — incoming-message rate limit per peer: `rate` tokens per
// second refill a bucket of `burst` tokens; each message takes one. Time is passed in.
#pragma once
#include <algorithm>
#include <chrono>

namespace throng::transport::detail {

class TokenBucket {
 public:
  using Clock = std::chrono::steady_clock;

  /// rate [1/s] (<= 0: unlimited), burst [tokens] (at least 1).
  TokenBucket(double rate, double burst, Clock::time_point now)
      : rate_(rate), burst_(std::max(1.0, burst)), tokens_(burst_), last_(now) {}

  /// Takes one token; false when the bucket is empty (over the limit).
  bool take(Clock::time_point now) {
    if (rate_ <= 0.0) return true;
    const double elapsed = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    tokens_ = std::min(burst_, tokens_ + std::max(0.0, elapsed) * rate_);
    if (tokens_ < 1.0) return false;
    tokens_ -= 1.0;
    return true;
  }

 private:
  double rate_;
  double burst_;
  double tokens_;
  Clock::time_point last_;
};

}  // namespace throng::transport::detail
