// throng::bench::runDetourCrowd — DetourCrowd (recastnavigation's dtCrowd) on a throng NavMesh,
// the reference our crowd engine is benchmarked against. Agents walk to random navmesh points and
// pick a new one on arrival. Reads the NavMesh; measures only dtCrowd::update() of the measured ticks.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "throng/core/result.hpp"
#include "throng/core/vec2.hpp"
#include "throng/nav/navmesh.hpp"

namespace throng::bench {

/// dtCrowd stores agent and neighbour-grid pool indices as unsigned short (0xffff = end of list)
/// and sizes the proximity grid pool at 4 items per agent, so above this many agents its neighbour
/// queries silently lose entries. runDetourCrowd refuses more.
inline constexpr std::size_t kDetourCrowdMaxAgents = 0xffff / 4;

struct BaselineConfig {
  std::shared_ptr<const nav::NavMesh> navmesh;
  std::vector<core::Vec2> starts;  ///< one per agent [m] [Limit: 1..kDetourCrowdMaxAgents agents]
  float radius = 0.25f;            ///< agent radius [m] [Limit: > 0]
  float speed = 1.34f;             ///< preferred speed [m/s] [Limit: > 0]
  float dt = 0.1f;                 ///< tick [s] [Limit: > 0]
  std::uint64_t seed = 1;          ///< goal choice: core::Rng(seed, agent, Goal)
  int warmupTicks = 20;            ///< untimed ticks first [Limit: >= 0]
  int ticks = 100;                 ///< timed ticks [Limit: >= 1]
  /// Called after every tick (warm-up and timed, outside the timing) with the ticks done and the
  /// total (warmupTicks + ticks); may be empty.
  std::function<void(int done, int total)> progress;
};

struct BaselineResult {
  std::string engine = "detourcrowd";
  std::size_t agents = 0;
  int ticks = 0;                  ///< timed ticks
  double agentStepsPerSec = 0;    ///< agents * ticks / total update() time
  double msPerTickMedian = 0;     ///< [ms]
  double msPerTickP99 = 0;        ///< [ms]
  double bytesPerAgent = 0;       ///< resident-set growth over crowd creation / agents (see .cpp)
  double meanSpeed = 0;           ///< mean agent speed over the timed ticks and all agents [m/s]
};

/// Runs the baseline. Fails with a diagnostic for bad config or when dtCrowd cannot be set up.
core::Result<BaselineResult> runDetourCrowd(const BaselineConfig& config);

}  // namespace throng::bench
