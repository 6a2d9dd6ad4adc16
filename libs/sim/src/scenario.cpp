// throng::sim::ScenarioDesc — derived facts about a scenario description (largest body radius, navmesh erosion radius,
// presence of exits, a crowd's most agents). Reads the description only.
#include "throng/sim/scenario.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace throng::sim {

float ScenarioDesc::maxRadius() const {
  float r = 0.0f;
  for (const PopulationDesc& p : populations) r = std::max(r, p.largestRadius());
  return r;
}

float ScenarioDesc::navRadius() const {
  float r = 0.0f;
  for (const PopulationDesc& p : populations) r = std::max(r, p.largestRadius() * p.model.passageRatio());
  return r;
}

std::uint64_t CrowdDesc::maxAgents() const {
  std::uint64_t n = 0;
  for (const PopulationDesc& p : populations) n += std::uint64_t{p.groups} * p.sizeMax;
  return n;
}

bool ScenarioDesc::hasExit() const {
  return std::any_of(points.begin(), points.end(), [](const PointDesc& p) { return p.kind == PointKind::Exit; });
}

nav::CutRegion cutRegion(const PointDesc& point) {
  nav::CutRegion r;
  r.centre = point.position;
  r.radius = point.radius;
  r.polygon = point.polygon;
  r.height = point.height;
  return r;
}

nav::NavMeshConfig ScenarioDesc::navMeshConfig() const {
  nav::NavMeshConfig config;
  config.agentRadius = navRadius();
  config.cellSize = navCellSize;
  config.stairSlopeDeg = stairSlopeDeg;
  for (const PointDesc& p : points) {
    if (p.kind == PointKind::Exit) config.cuts.push_back(cutRegion(p));
  }
  // The exits of the timeline's crowds too: known now, inserted later (World::insertCrowd's
  // crowds are not known when the mesh is built; theirs are not cut).
  for (const TimelineEntry& e : timeline) {
    if (e.action != TimelineAction::Insert) continue;
    for (const PointDesc& p : e.crowd.points) {
      if (p.kind == PointKind::Exit) config.cuts.push_back(cutRegion(p));
    }
  }
  return config;
}

std::size_t rideTo(const ScenarioDesc& desc, const TransportDesc& t, std::size_t from, std::uint32_t next) {
  if (t.kind == TransportKind::Escalator) return 1;
  std::size_t best = from == 0 ? 1 : 0;
  if (next >= desc.points.size()) return best;
  float bestGap = std::numeric_limits<float>::max();
  for (std::size_t i = 0; i < t.stops.size(); ++i) {
    if (i == from) continue;
    if (t.stops[i] == next) return i;
    const float gap = std::abs(desc.points[t.stops[i]].height - desc.points[next].height);
    if (gap < bestGap) {
      bestGap = gap;
      best = i;
    }
  }
  return best;
}

}  // namespace throng::sim
