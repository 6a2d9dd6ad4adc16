// CommonGroundState (common_ground_state.hpp): the categories of points and what populations and
// needs want of them.
#include "common_ground_state.hpp"

#include <algorithm>

namespace throng::sim {

std::int32_t CommonGroundState::categoryIndex(std::string_view category) const {
  const auto it = std::find(categories.begin(), categories.end(), category);
  return it == categories.end() ? -1 : static_cast<std::int32_t>(it - categories.begin());
}

void CommonGroundState::addPoints(const std::vector<PointDesc>& points, std::uint32_t first) {
  pointCategory.resize(points.size(), -1);
  for (std::uint32_t p = first; p < points.size(); ++p) {
    const std::string& c = points[p].category;
    if (c.empty()) continue;
    std::int32_t index = categoryIndex(c);
    if (index < 0) {
      categories.push_back(c);
      categoryPoints.emplace_back();
      index = static_cast<std::int32_t>(categories.size() - 1);
    }
    pointCategory[p] = index;
    categoryPoints[static_cast<std::size_t>(index)].push_back(p);
  }
}

void CommonGroundState::refreshInterests(const ScenarioDesc& desc) {
  attractionPoints.clear();
  for (std::uint32_t p = 0; p < desc.points.size(); ++p) {
    if (pointCategory[p] < 0) continue;
    const bool wanted = std::any_of(desc.populations.begin(), desc.populations.end(), [&](const PopulationDesc& pop) {
      return std::find(pop.interests.begin(), pop.interests.end(), desc.points[p].category) != pop.interests.end();
    });
    if (wanted) attractionPoints.push_back(p);
  }
  needCategory.clear();
  for (const NeedDesc& need : desc.social.needs) needCategory.push_back(categoryIndex(need.category));
}

}  // namespace throng::sim
