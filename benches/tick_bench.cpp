// Google Benchmark of the full tick (sense, decide, plan, steer with ORCA, integrate, emit) on the
// `throng bench` random scenario: a square at 1 agent/m² where agents wander between random goals.
// Counter agent_steps/s = agents × ticks per second of wall time.
#include <benchmark/benchmark.h>

#include "throng/bench/scenarios.hpp"
#include "throng/sim/world.hpp"

namespace {

using namespace throng;

void BM_Tick(benchmark::State& state) {
  const auto agents = static_cast<std::size_t>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  const sim::ScenarioDesc desc = bench::makeScenario(bench::Layout::Random, agents, 1);
  auto navmesh = bench::buildNavMesh(desc);
  if (!navmesh) {
    state.SkipWithError("navmesh build failed");
    return;
  }
  auto world = sim::World::create(desc, navmesh.value());
  if (!world) {
    state.SkipWithError("world creation failed");
    return;
  }
  core::TaskSystem tasks(threads);
  for (int i = 0; i < 10; ++i) world.value()->step(tasks);  // warm up: paths planned, crowd moving
  for (auto _ : state) world.value()->step(tasks);
  state.counters["agent_steps/s"] =
      benchmark::Counter(static_cast<double>(agents) * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

}  // namespace

BENCHMARK(BM_Tick)
    ->ArgNames({"agents", "threads"})
    ->Args({1000, 1})->Args({1000, 2})
    ->Args({10000, 1})->Args({10000, 2})
    ->Args({100000, 1})->Args({100000, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
