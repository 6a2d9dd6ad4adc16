// throng::bench scenarios — see throng/bench/scenarios.hpp.
#include "throng/bench/scenarios.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "throng/core/rng.hpp"

namespace throng::bench {
namespace {

core::Polygon rect(float x0, float y0, float x1, float y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

sim::PopulationDesc wanderers(std::string id, core::Polygon area, std::uint32_t count) {
  sim::PopulationDesc p;
  p.id = std::move(id);
  p.groups = count;  // groups of one: every agent walks on its own
  p.sizeMin = p.sizeMax = 1;
  p.spawn.kind = sim::SpawnKind::Polygon;
  p.spawn.polygon = std::move(area);
  p.start = 0.0f;
  p.wander = true;
  p.speedMean = kSpeed;
  p.speedSd = 0.0f;
  p.speedMin = kSpeed;
  p.speedMax = kSpeed;
  p.radius = kRadius;
  // ORCA whatever the engine's default model: the in-memory scenarios are compared with DetourCrowd and
  // RVO2, which avoid the same way (`throng bench --model NAME` picks another).
  p.model = sim::ModelDesc(sim::ModelKind::Orca);
  return p;
}

/// Pillar rows sit at y in [c - h, c + h] with c = spacing/2 + k*spacing; the spawn strips are the
/// bands between them (kept a radius away), each given agents in proportion to its area.
std::vector<sim::PopulationDesc> stripPopulations(float side, std::size_t agents) {
  const float h = kPillarSize / 2 + kRadius;
  std::vector<std::pair<float, float>> bands;
  float y = kRadius;
  for (float c = kPillarSpacing / 2; c + kPillarSize / 2 <= side; c += kPillarSpacing) {
    if (c - h > y) bands.emplace_back(y, c - h);
    y = c + h;
  }
  if (side - kRadius > y) bands.emplace_back(y, side - kRadius);
  double total = 0;
  for (const auto& [a, b] : bands) total += b - a;
  std::vector<sim::PopulationDesc> populations;
  std::size_t given = 0;
  double cumulative = 0;
  for (std::size_t i = 0; i < bands.size(); ++i) {
    cumulative += bands[i].second - bands[i].first;
    // Cumulative rounding: the counts add up to exactly `agents`.
    const auto upTo = i + 1 == bands.size() ? agents : static_cast<std::size_t>(std::llround(agents * cumulative / total));
    const auto count = static_cast<std::uint32_t>(upTo - given);
    given = upTo;
    if (count == 0) continue;
    populations.push_back(
        wanderers(fmt::format("band{}", i), rect(kRadius, bands[i].first, side - kRadius, bands[i].second), count));
  }
  return populations;
}

}  // namespace

float squareSide(std::size_t agents) {
  return std::max(2.0f, std::sqrt(static_cast<float>(agents) / kDensity));
}

sim::ScenarioDesc makeScenario(Layout layout, std::size_t agents, std::uint64_t seed) {
  const float side = squareSide(agents);
  sim::ScenarioDesc desc;
  desc.name = fmt::format("bench-{}-{}", kLayoutNames[static_cast<int>(layout)], agents);
  desc.seed = seed;
  desc.duration = 1.0e6f;  // wanderers never finish; bench stops after its ticks
  desc.dt = kDt;
  desc.navCellSize = kCellSize;
  desc.walkable.push_back(rect(0, 0, side, side));
  if (layout == Layout::Musse) {
    // The crowd model on: flocking groups of three (shared speed, walking abreast, waiting for each
    // other) wandering together between random points; the remainder walks alone.
    const auto area = rect(kRadius, kRadius, side - kRadius, side - kRadius);
    sim::PopulationDesc groups = wanderers("groups", area, static_cast<std::uint32_t>(agents / 3));
    groups.sizeMin = groups.sizeMax = 3;
    if (groups.groups > 0) desc.populations.push_back(groups);
    if (agents % 3 != 0) desc.populations.push_back(wanderers("singles", area, static_cast<std::uint32_t>(agents % 3)));
    return desc;
  }
  if (layout == Layout::Random) {
    desc.populations.push_back(wanderers("crowd", rect(kRadius, kRadius, side - kRadius, side - kRadius),
                                         static_cast<std::uint32_t>(agents)));
    return desc;
  }
  const float h = kPillarSize / 2;
  for (float cx = kPillarSpacing / 2; cx + h <= side; cx += kPillarSpacing) {
    for (float cy = kPillarSpacing / 2; cy + h <= side; cy += kPillarSpacing) {
      desc.obstacles.push_back(rect(cx - h, cy - h, cx + h, cy + h));
    }
  }
  desc.populations = stripPopulations(side, agents);
  return desc;
}

core::Result<std::shared_ptr<const nav::NavMesh>> buildNavMesh(const sim::ScenarioDesc& desc) {
  return nav::NavMesh::build(desc.walkable, desc.obstacles, desc.navMeshConfig());
}

std::vector<core::Vec2> drawStarts(const std::shared_ptr<const nav::NavMesh>& navmesh, std::size_t count,
                                   std::uint64_t seed) {
  nav::NavQuery query(navmesh);
  std::vector<core::Vec2> starts;
  starts.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    core::Rng rng(seed, i, core::RngPurpose::Bench);
    for (int attempt = 0; attempt < 8; ++attempt) {
      const auto p = query.randomPoint(static_cast<float>(rng.uniform()), static_cast<float>(rng.uniform()),
                                       static_cast<float>(rng.uniform()));
      if (p) {
        starts.push_back(*p);
        break;
      }
    }
  }
  return starts;
}

std::optional<Layout> layoutFromName(const std::string& name) {
  if (name == "random") return Layout::Random;
  if (name == "navmesh") return Layout::Navmesh;
  if (name == "musse") return Layout::Musse;
  return std::nullopt;
}

}  // namespace throng::bench
