// throng::sim::ScenarioDesc — derived facts about a scenario description (largest body radius,
// presence of exits). Reads the description only.
#include "throng/sim/scenario.hpp"

#include <algorithm>

namespace throng::sim {

float ScenarioDesc::maxRadius() const {
  float r = 0.0f;
  for (const PopulationDesc& p : populations) r = std::max(r, p.radius);
  return r;
}

bool ScenarioDesc::hasExit() const {
  return std::any_of(points.begin(), points.end(), [](const PointDesc& p) { return p.kind == PointKind::Exit; });
}

}  // namespace throng::sim
