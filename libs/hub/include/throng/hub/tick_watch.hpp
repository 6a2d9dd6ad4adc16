// throng::hub::TickWatch — how a real-time server keeps to its tick period, as /api/status reports
// it: ticks that ended after their deadline (late), ticks that took many periods (stalls), the
// longest tick, and the tick running now, so a tick that has taken 14 s counts as late and as a
// stall while it is still running, not only once it ends. Thread-safe: the simulation thread
// marks ticks, any thread reads. Times are passed in [s]; no clock of its own.
#pragma once
#include <cstdint>
#include <mutex>

namespace throng::hub {

struct TickReport {
  std::uint64_t ticks = 0;   ///< ticks ended
  std::uint64_t late = 0;    ///< ticks that ended after their deadline, and the running one once past its period
  std::uint64_t stalls = 0;  ///< ticks that took at least stallPeriods periods, the running one included
  double longestMs = 0.0;    ///< the longest tick, the running one included [ms]
  double runningMs = 0.0;    ///< how long the tick running now has run (0 between ticks) [ms]
};

class TickWatch {
 public:
  /// `periodSeconds`: the tick period; a tick of at least `stallPeriods` periods is a stall.
  explicit TickWatch(double periodSeconds, double stallPeriods = 10.0);
  /// A tick starts at `now`.
  void started(double now);
  /// The tick started last ends at `now`; `late`: it ended after its deadline (the caller's
  /// schedule decides, e.g. a deadline that a slow tick before it pushed).
  void finished(double now, bool late);
  /// The counts as of `now`.
  [[nodiscard]] TickReport report(double now) const;

 private:
  double period_;
  double stallSeconds_;
  mutable std::mutex mutex_;
  bool running_ = false;
  double startedAt_ = 0.0;
  TickReport done_;
};

}  // namespace throng::hub
