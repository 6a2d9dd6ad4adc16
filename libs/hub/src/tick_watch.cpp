// TickWatch (see tick_watch.hpp): late and stalled ticks, the running one included.
#include "throng/hub/tick_watch.hpp"

#include <algorithm>

namespace throng::hub {

TickWatch::TickWatch(double periodSeconds, double stallPeriods)
    : period_(periodSeconds), stallSeconds_(periodSeconds * stallPeriods) {}

void TickWatch::started(double now) {
  std::lock_guard lock(mutex_);
  running_ = true;
  startedAt_ = now;
}

void TickWatch::finished(double now, bool late) {
  std::lock_guard lock(mutex_);
  const double took = running_ ? now - startedAt_ : 0.0;
  running_ = false;
  ++done_.ticks;
  if (late || took > period_) ++done_.late;
  if (took >= stallSeconds_) ++done_.stalls;
  done_.longestMs = std::max(done_.longestMs, took * 1e3);
}

TickReport TickWatch::report(double now) const {
  std::lock_guard lock(mutex_);
  TickReport r = done_;
  if (!running_) return r;
  const double running = std::max(0.0, now - startedAt_);
  r.runningMs = running * 1e3;
  r.longestMs = std::max(r.longestMs, r.runningMs);
  if (running > period_) ++r.late;
  if (running >= stallSeconds_) ++r.stalls;
  return r;
}

}  // namespace throng::hub
