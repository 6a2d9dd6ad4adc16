// throng CLI stall tracker — finds agents that made no progress for a long time during a run:
// agents that stayed within a small disc for at least a minimum time, except while they play an
// action or a Common Ground script (standing is their task then). Each span carries what the agent
// was doing when it had stood still that long ("walking to its goal": stuck; "done": it reached
// its last goal and stays). `throng run` feeds it every recorded frame and names the spans in its
// summary. Pure bookkeeping over sim::Frame; the caller says what an agent is doing.
#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "throng/sim/frame.hpp"

namespace throng::cli {

/// One agent standing still from `from` to `to` [s].
struct StallSpan {
  std::uint32_t agent = 0;
  double from = 0.0;
  double to = 0.0;
  std::string state;  ///< what it was doing once it had stood still `minSeconds` (the caller's words)
};

/// What an agent is doing (the caller's words), or nullopt when standing still is its task now.
using StateOf = std::function<std::optional<std::string>(std::uint32_t id)>;

class StallTracker {
 public:
  /// A stall: at least `minSeconds` within `radius` metres of where it began.
  explicit StallTracker(double minSeconds = 60.0, float radius = 0.5f) : minSeconds_(minSeconds), radius_(radius) {}

  /// One frame. `stateOf(id)` is asked once an agent has stood still for `minSeconds`: nullopt
  /// (standing is its task) restarts its clock instead of counting a stall. Acting agents (the
  /// frame's mode) never stall.
  void observe(const sim::Frame& frame, const StateOf& stateOf);

  /// Spans of at least `minSeconds`, closed at `endTime` for agents still standing (at the last
  /// frame they were seen in for agents that left), ordered by start time, then agent id.
  [[nodiscard]] std::vector<StallSpan> finish(double endTime);

  [[nodiscard]] double minSeconds() const { return minSeconds_; }
  [[nodiscard]] float radius() const { return radius_; }

 private:
  struct Track {
    float x = 0.0f, y = 0.0f;  ///< where the still spell began
    double since = 0.0;        ///< when it began [s]
    double last = 0.0;         ///< last frame the agent was seen in [s]
    bool seen = false;
    std::string state;         ///< set once the spell is long enough
  };
  void close(std::uint32_t id, const Track& t, double end);

  double minSeconds_;
  float radius_;
  std::vector<Track> tracks_;  ///< by stable agent id
  std::vector<StallSpan> spans_;
  double lastTime_ = 0.0;
};

}  // namespace throng::cli
