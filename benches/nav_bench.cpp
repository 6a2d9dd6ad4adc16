// Micro benchmarks of libs/nav: NavMesh::build on pillar worlds, NavQuery::findPath and PathQueue
// throughput. Run: build/benches/throng_micro_benches [--benchmark_filter=FindPath].
#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

#include "throng/core/rng.hpp"
#include "throng/nav/navmesh.hpp"
#include "throng/nav/path_queue.hpp"

namespace {
using throng::nav::NavMesh;
using throng::nav::NavMeshConfig;
using throng::nav::Polygon;
using throng::nav::Vec2;

Polygon rect(float x0, float y0, float x1, float y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

// side x side square with 1 m pillars every 10 m.
std::shared_ptr<const NavMesh> pillarWorld(float side, float cellSize) {
  std::vector<Polygon> obstacles;
  for (float x = 10; x < side - 1; x += 10)
    for (float y = 10; y < side - 1; y += 10) obstacles.push_back(rect(x - 0.5f, y - 0.5f, x + 0.5f, y + 0.5f));
  NavMeshConfig cfg;
  cfg.cellSize = cellSize;
  auto mesh = NavMesh::build(std::vector<Polygon>{rect(0, 0, side, side)}, obstacles, cfg);
  return mesh.ok() ? mesh.value() : nullptr;
}

const std::shared_ptr<const NavMesh>& world300() {
  static const auto mesh = pillarWorld(300, 0.1f);
  return mesh;
}

std::vector<std::pair<Vec2, Vec2>> randomPairs(float side, int n) {
  throng::core::Rng rng(1, 0, throng::core::RngPurpose::Bench);
  std::vector<std::pair<Vec2, Vec2>> out;
  for (int i = 0; i < n; ++i) {
    auto p = [&] { return Vec2{static_cast<float>(rng.uniform(2, side - 2)), static_cast<float>(rng.uniform(2, side - 2))}; };
    out.emplace_back(p(), p());
  }
  return out;
}

void BM_NavMeshBuild(benchmark::State& state) {
  const auto side = static_cast<float>(state.range(0));
  const float cs = static_cast<float>(state.range(1)) / 1000.0f;
  for (auto _ : state) {
    auto mesh = pillarWorld(side, cs);
    if (!mesh) state.SkipWithError("build failed");
    benchmark::DoNotOptimize(mesh);
  }
  state.counters["m2_per_s"] = benchmark::Counter(side * side, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_NavMeshBuild)->Args({300, 100})->Args({300, 125})->Args({1000, 125})->Unit(benchmark::kMillisecond)->Iterations(1);

void BM_FindPath(benchmark::State& state) {
  const auto& mesh = world300();
  if (!mesh) {
    state.SkipWithError("build failed");
    return;
  }
  throng::nav::NavQuery query(mesh);
  const auto pairs = randomPairs(static_cast<float>(state.range(0)), 1024);
  std::vector<Vec2> corners;
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& [a, b] = pairs[i++ % pairs.size()];
    benchmark::DoNotOptimize(query.findPath(a, b, corners));
  }
  state.counters["paths_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
// Pairs drawn from a 30 m and from the whole 300 m square of the 300 m world.
BENCHMARK(BM_FindPath)->Arg(30)->Arg(300);

void BM_PathQueue(benchmark::State& state) {
  const auto& mesh = world300();
  if (!mesh) {
    state.SkipWithError("build failed");
    return;
  }
  throng::nav::PathQueue queue(mesh);
  const auto pairs = randomPairs(300, 256);
  const int budget = static_cast<int>(state.range(0));
  std::int64_t paths = 0;
  for (auto _ : state) {
    std::vector<throng::nav::PathTicket> tickets;
    for (const auto& [a, b] : pairs) tickets.push_back(queue.request(a, b));
    while (queue.pending() > 0) queue.update(budget);
    for (auto t : tickets) benchmark::DoNotOptimize(queue.take(t));
    paths += static_cast<std::int64_t>(pairs.size());
  }
  state.counters["paths_per_s"] = benchmark::Counter(static_cast<double>(paths), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PathQueue)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);

}  // namespace
