// Google Benchmark micro benchmarks of the steering hot spots: the k-nearest neighbour search
// (SpatialGrid::nearest, agents visited in row order and in cell order) and ORCA (agentOrcaLine,
// solveOrca) on the `throng bench` density of 1 agent/m². Counters: searches or solves per second.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "throng/sim/spatial_grid.hpp"
#include "throng/core/rng.hpp"
#include "throng/sim/orca.hpp"

namespace {

using namespace throng;

/// N agents uniformly in a square of side √N m (1 agent/m²), sorted into 1 m cells.
struct Field {
  std::vector<float> xs, ys;
  sim::SpatialGrid grid;
  explicit Field(std::size_t n) {
    const float side = std::sqrt(static_cast<float>(n));
    core::Rng rng(7, 0, core::RngPurpose::Bench);
    for (std::size_t i = 0; i < n; ++i) {
      xs.push_back(static_cast<float>(rng.uniform(0, side)));
      ys.push_back(static_cast<float>(rng.uniform(0, side)));
    }
    grid.configure(core::Aabb{{0, 0}, {side, side}}, 1.0f);
    core::TaskSystem tasks(1);
    grid.rebuild(xs, ys, tasks);
  }
};

/// k = 10 within 3 m (the scenario defaults), every agent once per iteration.
void BM_Nearest(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const bool cellOrder = state.range(1) != 0;
  Field f(n);
  std::vector<std::uint32_t> out(n * 10);
  for (auto _ : state) {
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t row = cellOrder ? f.grid.rowAt(i) : static_cast<std::uint32_t>(i);
      f.grid.nearest(f.xs[row], f.ys[row], 3.0f, 10, row, &out[row * 10]);
    }
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["searches/s"] =
      benchmark::Counter(static_cast<double>(n) * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Nearest)->ArgNames({"agents", "cell_order"})->Args({10000, 0})->Args({10000, 1})->Args({100000, 0})->Args({100000, 1});

/// Per agent: 10 half-planes from its nearest neighbours (random velocities) and the LP.
void BM_Orca(benchmark::State& state) {
  constexpr std::size_t kAgents = 4096, kK = 10;
  Field f(kAgents);
  core::Rng rng(8, 0, core::RngPurpose::Bench);
  std::vector<core::Vec2> vel(kAgents);
  for (core::Vec2& v : vel) v = {static_cast<float>(rng.uniform(-1.3, 1.3)), static_cast<float>(rng.uniform(-1.3, 1.3))};
  std::vector<std::uint32_t> nb(kAgents * kK);
  std::vector<std::size_t> count(kAgents);
  for (std::uint32_t a = 0; a < kAgents; ++a) count[a] = f.grid.nearest(f.xs[a], f.ys[a], 3.0f, kK, a, &nb[a * kK]);
  std::vector<sim::OrcaLine> lines, scratch;
  for (auto _ : state) {
    for (std::uint32_t a = 0; a < kAgents; ++a) {
      lines.clear();
      for (std::size_t i = 0; i < count[a]; ++i) {
        const std::uint32_t o = nb[a * kK + i];
        lines.push_back(sim::agentOrcaLine(core::Vec2{f.xs[o] - f.xs[a], f.ys[o] - f.ys[a]}, vel[a] - vel[o], vel[a], 0.5f,
                                           2.0f, 0.1f));
      }
      benchmark::DoNotOptimize(sim::solveOrca(lines, 0, 1.34f, vel[a], scratch));
    }
  }
  state.counters["agents/s"] =
      benchmark::Counter(static_cast<double>(kAgents) * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Orca);

}  // namespace
