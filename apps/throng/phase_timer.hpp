// PhaseTimer — wall time spent in each phase of the tick (`throng run --phase-times`, `throng bench
// --phase-times`), summed over the ticks it observed, in the order the phases first ran. The clock
// reads cost a little, so it is attached only when asked for.
#pragma once
#include <chrono>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "throng/sim/world.hpp"

namespace throng::cli {

class PhaseTimer final : public sim::PhaseObserver {
 public:
  using Clock = std::chrono::steady_clock;
  void phaseBegin(std::string_view) override { begin_ = Clock::now(); }
  void phaseEnd(std::string_view phase) override {
    const double s = std::chrono::duration<double>(Clock::now() - begin_).count();
    for (auto& [name, total] : totals_) {
      if (name == phase) {
        total += s;
        return;
      }
    }
    totals_.emplace_back(std::string(phase), s);
  }
  /// Each phase's total [s].
  [[nodiscard]] const std::vector<std::pair<std::string, double>>& totals() const { return totals_; }
  void clear() { totals_.clear(); }

 private:
  Clock::time_point begin_;
  std::vector<std::pair<std::string, double>> totals_;
};

}  // namespace throng::cli
