// rvo2_driver — the `throng bench --scenario random` workload run by RVO2 (Snape, van den Berg, Guy,
// Lin, Manocha; github.com/snape/RVO2), for the side-by-side agent-steps/s in docs/performance.md.
// Not part of the build: RVO2 is no Debian package, so scripts/bench_rvo2.sh compiles this file
// against an RVO2 checkout the user names (`-O3 -fopenmp`, as RVO2's own build does with OpenMP).
//
// Workload (libs/bench/src/scenarios.cpp): N agents in a square of side sqrt(N) m (1 agent/m²),
// radius 0.25 m, desired speed 1.34 m/s, dt 0.1 s, 10 neighbours within 3 m, time horizons 2 s
// (agents) and 0.5 s (walls; there are none). Each agent walks to a uniformly random point of the
// square and draws a new one within 0.5 m of it. Untimed warm-up steps, then each step is timed
// alone (preferred velocities set, then RVOSimulator::doStep). Threads: OMP_NUM_THREADS.
//
// Usage: rvo2_driver AGENTS [TIMED_STEPS=20] [WARMUP=10] [SEED=1]
// Prints one JSON object: engine, agents, threads, steps, agent_steps_per_s, ms_per_tick_median,
// mean_speed_mps.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "RVOSimulator.h"
#include "Vector2.h"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace {

constexpr float kRadius = 0.25f;
constexpr float kSpeed = 1.34f;
constexpr float kDt = 0.1f;
constexpr float kArrive = 0.5f;

struct Crowd {
  RVO::RVOSimulator sim;
  std::vector<RVO::Vector2> goals;
  std::mt19937_64 rng;
  std::uniform_real_distribution<float> coord;

  Crowd(std::size_t n, float side, unsigned seed) : rng(seed), coord(kRadius, side - kRadius) {
    sim.setTimeStep(kDt);
    sim.setAgentDefaults(3.0f, 10, 2.0f, 0.5f, kRadius, kSpeed);
    // A jittered grid: 1 agent/m² without initial overlaps (random uniform spawns would overlap).
    const auto perRow = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(n))));
    const float cell = side / static_cast<float>(perRow);
    std::uniform_real_distribution<float> jitter(-0.2f * cell, 0.2f * cell);
    for (std::size_t i = 0; i < n; ++i) {
      const float x = (static_cast<float>(i % perRow) + 0.5f) * cell + jitter(rng);
      const float y = (static_cast<float>(i / perRow) + 0.5f) * cell + jitter(rng);
      sim.addAgent(RVO::Vector2(x, y));
      goals.emplace_back(coord(rng), coord(rng));
    }
  }

  void setPreferred() {
    for (std::size_t i = 0; i < goals.size(); ++i) {
      RVO::Vector2 to = goals[i] - sim.getAgentPosition(i);
      if (RVO::absSq(to) < kArrive * kArrive) {
        goals[i] = RVO::Vector2(coord(rng), coord(rng));
        to = goals[i] - sim.getAgentPosition(i);
      }
      const float d = RVO::abs(to);
      sim.setAgentPrefVelocity(i, d > 1e-6f ? to * (kSpeed / d) : RVO::Vector2());
    }
  }
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s AGENTS [TIMED_STEPS=20] [WARMUP=10] [SEED=1]\n", argv[0]);
    return 2;
  }
  const auto n = static_cast<std::size_t>(std::strtoull(argv[1], nullptr, 10));
  const int steps = argc > 2 ? std::atoi(argv[2]) : 20;
  const int warmup = argc > 3 ? std::atoi(argv[3]) : 10;
  const auto seed = static_cast<unsigned>(argc > 4 ? std::atoi(argv[4]) : 1);
  if (n == 0 || steps <= 0 || warmup < 0) {
    std::fprintf(stderr, "AGENTS and TIMED_STEPS must be positive, WARMUP >= 0\n");
    return 2;
  }
  Crowd crowd(n, std::sqrt(static_cast<float>(n)), seed);
  for (int i = 0; i < warmup; ++i) {
    crowd.setPreferred();
    crowd.sim.doStep();
  }
  std::vector<RVO::Vector2> before(n);
  for (std::size_t i = 0; i < n; ++i) before[i] = crowd.sim.getAgentPosition(i);
  std::vector<double> ms;
  double walked = 0.0;
  for (int s = 0; s < steps; ++s) {
    const auto t0 = std::chrono::steady_clock::now();
    crowd.setPreferred();
    crowd.sim.doStep();
    const auto t1 = std::chrono::steady_clock::now();
    ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    for (std::size_t i = 0; i < n; ++i) {
      const RVO::Vector2 p = crowd.sim.getAgentPosition(i);
      walked += RVO::abs(p - before[i]);
      before[i] = p;
    }
  }
  double total = 0.0;
  for (double m : ms) total += m;
  std::sort(ms.begin(), ms.end());
  int threads = 1;
#ifdef _OPENMP
  threads = omp_get_max_threads();
#endif
  std::printf(
      "{\"engine\":\"RVO2\",\"agents\":%zu,\"threads\":%d,\"steps\":%d,\"agent_steps_per_s\":%.0f,"
      "\"ms_per_tick_median\":%.3f,\"mean_speed_mps\":%.3f}\n",
      n, threads, steps, static_cast<double>(n) * steps / (total / 1000.0), ms[ms.size() / 2],
      walked / (static_cast<double>(n) * steps * kDt));
  return 0;
}
