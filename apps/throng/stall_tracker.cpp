// throng CLI stall tracker — see stall_tracker.hpp.
#include "stall_tracker.hpp"

#include <algorithm>

namespace throng::cli {

void StallTracker::close(std::uint32_t id, const Track& t, double end) {
  if (end - t.since >= minSeconds_) spans_.push_back({id, t.since, end, t.state});
}

void StallTracker::observe(const sim::Frame& f, const StateOf& stateOf) {
  lastTime_ = f.time;
  const float r2 = radius_ * radius_;
  for (std::size_t i = 0; i < f.size(); ++i) {
    const std::uint32_t id = f.ids[i];
    if (id >= tracks_.size()) tracks_.resize(static_cast<std::size_t>(id) + 1);
    Track& t = tracks_[id];
    const float x = f.posX[i], y = f.posY[i];
    const bool acting = i < f.mode.size() && f.mode[i] == sim::AgentMode::Acting;
    const float dx = x - t.x, dy = y - t.y;
    if (!t.seen || acting || dx * dx + dy * dy > r2) {
      if (t.seen) close(id, t, t.last);
      t.x = x;
      t.y = y;
      t.since = f.time;
      t.seen = true;
      t.state.clear();
    } else if (f.time - t.since >= minSeconds_ && t.last - t.since < minSeconds_) {  // asked once per spell
      if (auto state = stateOf(id)) t.state = std::move(*state);
      else t.since = f.time;  // standing is its task: not a stall
    }
    t.last = f.time;
  }
}

std::vector<StallSpan> StallTracker::finish(double endTime) {
  for (std::uint32_t id = 0; id < tracks_.size(); ++id) {
    const Track& t = tracks_[id];
    if (!t.seen) continue;
    close(id, t, t.last < lastTime_ ? t.last : endTime);
  }
  tracks_.clear();
  std::vector<StallSpan> out = std::move(spans_);
  spans_.clear();
  std::sort(out.begin(), out.end(), [](const StallSpan& a, const StallSpan& b) {
    return a.from != b.from ? a.from < b.from : a.agent < b.agent;
  });
  return out;
}

}  // namespace throng::cli
