// throng::bench::runDetourCrowd — DetourCrowd on a throng NavMesh with random goals. Timing
// (std::chrono::steady_clock; benchmarks only) covers dtCrowd::update() of the measured ticks and
// nothing else: goal picking and arrival checks run between updates, untimed.
//
// bytesPerAgent: resident set size (/proc/self/statm, field 2, times the page size) just before
// dtAllocCrowd and just after every agent is added, divided by the agent count. It includes the
// crowd's own arrays (agents, corridors, local boundaries, proximity grid, path queue, obstacle
// avoidance query) and excludes the shared navmesh. Allocator reuse of freed memory can make it
// read low for tiny crowds; it is meaningful for thousands of agents.
#include "throng/bench/detour_crowd_baseline.hpp"

#include <DetourCrowd.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "throng/core/rng.hpp"

namespace throng::bench {
namespace {

core::Diagnostic diag(std::string pointer, std::string what, std::string expected) {
  core::Diagnostic d;
  d.source = "detourcrowd";
  d.pointer = std::move(pointer);
  d.what = std::move(what);
  d.expected = std::move(expected);
  return d;
}

double residentBytes() {
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (!f) return 0.0;
  long size = 0;
  long resident = 0;
  const int read = std::fscanf(f, "%ld %ld", &size, &resident);
  std::fclose(f);
  if (read != 2) return 0.0;
  return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE));
}

struct CrowdDeleter {
  void operator()(dtCrowd* c) const { dtFreeCrowd(c); }
};

// Picks a random navmesh point as agent i's next goal and sends it to the crowd.
bool newGoal(dtCrowd& crowd, const nav::NavQuery& query, core::Rng& rng, int agent, float goal[3]) {
  for (int attempt = 0; attempt < 8; ++attempt) {
    const auto r0 = static_cast<float>(rng.uniform());
    const auto r1 = static_cast<float>(rng.uniform());
    const auto r2 = static_cast<float>(rng.uniform());
    const auto p = query.randomPoint(r0, r1, r2);
    if (!p) return false;
    const float pos[3] = {p->x, 0.0f, p->y};
    dtPolyRef ref = 0;
    crowd.getNavMeshQuery()->findNearestPoly(pos, crowd.getQueryHalfExtents(), crowd.getFilter(0), &ref, goal);
    if (ref != 0 && crowd.requestMoveTarget(agent, ref, goal)) return true;
  }
  return false;
}


using CrowdPtr = std::unique_ptr<dtCrowd, CrowdDeleter>;

/// Every problem of the config at once.
core::Diagnostics checkConfig(const BaselineConfig& config) {
  core::Diagnostics errors;
  if (!config.navmesh) errors.push_back(diag("/navmesh", "no navmesh", "a built nav::NavMesh"));
  if (config.starts.empty()) errors.push_back(diag("/starts", "no agents", "at least one start position"));
  if (config.starts.size() > kDetourCrowdMaxAgents) {
    errors.push_back(diag("/starts", std::to_string(config.starts.size()) + " agents",
                          "at most " + std::to_string(kDetourCrowdMaxAgents) +
                              " agents: dtCrowd keeps agent and proximity-grid indices in 16 bits with 4 grid "
                              "items per agent, so larger crowds silently lose neighbours"));
  }
  if (!(config.radius > 0.0f)) errors.push_back(diag("/radius", "radius " + std::to_string(config.radius) + " m", "> 0 m"));
  if (!(config.speed > 0.0f)) errors.push_back(diag("/speed", "speed " + std::to_string(config.speed) + " m/s", "> 0 m/s"));
  if (!(config.dt > 0.0f)) errors.push_back(diag("/dt", "dt " + std::to_string(config.dt) + " s", "> 0 s"));
  if (config.warmupTicks < 0) errors.push_back(diag("/warmupTicks", std::to_string(config.warmupTicks), ">= 0"));
  if (config.ticks < 1) errors.push_back(diag("/ticks", std::to_string(config.ticks), ">= 1"));
  return errors;
}

/// A dtCrowd for `n` agents with the RecastDemo crowd tool's "good quality" avoidance; null when
/// dtCrowd::init fails.
CrowdPtr makeCrowd(const BaselineConfig& config, int n) {
  CrowdPtr crowd(dtAllocCrowd());
  // dtCrowd::init takes a mutable dtNavMesh* but only reads it.
  if (!crowd || !crowd->init(n, config.radius, const_cast<dtNavMesh*>(config.navmesh->detour()))) return nullptr;
  // Obstacle avoidance: dtCrowd's defaults with adaptive sampling (7 divisions, 2 rings, depth 3).
  dtObstacleAvoidanceParams avoidance = *crowd->getObstacleAvoidanceParams(0);
  avoidance.adaptiveDivs = 7;
  avoidance.adaptiveRings = 2;
  avoidance.adaptiveDepth = 3;
  crowd->setObstacleAvoidanceParams(0, &avoidance);
  return crowd;
}

/// Every agent's parameters: throng's radius and speed, the crowd tool's other defaults.
dtCrowdAgentParams agentParams(const BaselineConfig& config) {
  dtCrowdAgentParams params{};
  params.radius = config.radius;
  params.height = 2.0f;
  params.maxAcceleration = 8.0f;
  params.maxSpeed = config.speed;
  params.collisionQueryRange = config.radius * 12.0f;
  params.pathOptimizationRange = config.radius * 30.0f;
  params.separationWeight = 2.0f;
  params.updateFlags = DT_CROWD_ANTICIPATE_TURNS | DT_CROWD_OPTIMIZE_VIS | DT_CROWD_OPTIMIZE_TOPO |
                       DT_CROWD_OBSTACLE_AVOIDANCE | DT_CROWD_SEPARATION;
  params.obstacleAvoidanceType = 0;
  params.queryFilterType = 0;
  return params;
}

/// The agents walking the crowd: their goal streams and current goals, and what the timed ticks
/// measured.
struct Walkers {
  dtCrowd& crowd;
  const nav::NavQuery& query;
  std::vector<core::Rng> rngs;
  std::vector<float> goals;  ///< 3 per agent (Detour's x, y, z)
  std::vector<double> tickMs;
  double speedSum = 0.0;     ///< agent speeds summed over the timed ticks [m/s]

  void newGoal(int i) { bench::newGoal(crowd, query, rngs[i], i, &goals[static_cast<std::size_t>(i) * 3]); }

  /// One update (timed when `measured`), then a new goal for each agent that arrived or failed.
  void tick(const BaselineConfig& config, int n, bool measured) {
    const float arrive = config.radius * 2.0f;
    const auto begin = std::chrono::steady_clock::now();
    crowd.update(config.dt, nullptr);
    const auto end = std::chrono::steady_clock::now();
    if (measured) tickMs.push_back(std::chrono::duration<double, std::milli>(end - begin).count());
    for (int i = 0; i < n; ++i) {
      const dtCrowdAgent* ag = crowd.getAgent(i);
      if (!ag || !ag->active) continue;
      if (measured) speedSum += std::hypot(ag->vel[0], ag->vel[2]);
      const float* g = &goals[static_cast<std::size_t>(i) * 3];
      const bool arrived = std::hypot(ag->npos[0] - g[0], ag->npos[2] - g[2]) < arrive;
      if (arrived || ag->targetState == DT_CROWDAGENT_TARGET_FAILED || ag->targetState == DT_CROWDAGENT_TARGET_NONE) newGoal(i);
    }
  }
};

/// The figures of the timed ticks.
BaselineResult summarize(const BaselineConfig& config, const Walkers& w, int n, double rssGrowth) {
  BaselineResult result;
  result.agents = config.starts.size();
  result.ticks = config.ticks;
  double totalMs = 0.0;
  for (double ms : w.tickMs) totalMs += ms;
  std::vector<double> sorted = w.tickMs;
  std::sort(sorted.begin(), sorted.end());
  result.msPerTickMedian = sorted[sorted.size() / 2];
  result.msPerTickP99 = sorted[std::min(sorted.size() - 1, static_cast<std::size_t>(std::ceil(0.99 * sorted.size())) - 1)];
  result.agentStepsPerSec = totalMs > 0.0 ? static_cast<double>(n) * config.ticks / (totalMs / 1000.0) : 0.0;
  result.bytesPerAgent = std::max(0.0, rssGrowth) / n;
  result.meanSpeed = w.speedSum / (static_cast<double>(n) * config.ticks);
  return result;
}

}  // namespace

core::Result<BaselineResult> runDetourCrowd(const BaselineConfig& config) {
  if (core::Diagnostics errors = checkConfig(config); !errors.empty()) return errors;
  const int n = static_cast<int>(config.starts.size());
  nav::NavQuery query(config.navmesh);
  const double rssBefore = residentBytes();
  CrowdPtr crowd = makeCrowd(config, n);
  if (!crowd) return diag("", "dtCrowd::init failed for " + std::to_string(n) + " agents", "a successful dtCrowd::init");
  const dtCrowdAgentParams params = agentParams(config);
  Walkers walkers{*crowd, query, {}, std::vector<float>(config.starts.size() * 3, 0.0f), {}, 0.0};
  walkers.rngs.reserve(config.starts.size());
  for (int i = 0; i < n; ++i) {
    const float pos[3] = {config.starts[i].x, 0.0f, config.starts[i].y};
    if (crowd->addAgent(pos, &params) != i)
      return diag("/starts/" + std::to_string(i), "dtCrowd refused the agent", "a free crowd slot");
    walkers.rngs.emplace_back(config.seed, static_cast<std::uint64_t>(i), core::RngPurpose::Goal);
  }
  const double rssAfter = residentBytes();
  for (int i = 0; i < n; ++i) walkers.newGoal(i);

  walkers.tickMs.reserve(static_cast<std::size_t>(config.ticks));
  for (int t = 0; t < config.warmupTicks + config.ticks; ++t) {
    walkers.tick(config, n, t >= config.warmupTicks);
    if (config.progress) config.progress(t + 1, config.warmupTicks + config.ticks);
  }
  return summarize(config, walkers, n, rssAfter - rssBefore);
}

}  // namespace throng::bench
