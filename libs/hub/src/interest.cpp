// Interest management and detail tiers for one client (see interest.hpp).
#include "throng/hub/interest.hpp"

#include <algorithm>

namespace throng::hub {

void selectInterest(const sim::Frame& frame, const core::Vec2* viewpoint,
                    const InterestOptions& options, std::vector<Interested>& out,
                    std::vector<std::pair<float, std::uint32_t>>& scratch) {
  out.clear();
  const std::size_t n = frame.size();
  if (viewpoint == nullptr) {
    if (!options.overviewWhenNoViewpoint) return;
    out.reserve(n);
    for (std::size_t i = 0; i < n; ++i) out.push_back({static_cast<std::uint32_t>(i), Tier::Middle});
    return;
  }
  const float aoi2 = options.areaOfInterest * options.areaOfInterest;
  const float mid2 = options.middleRadius * options.middleRadius;
  const float near2 = options.nearRadius * options.nearRadius;
  scratch.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const float dx = frame.posX[i] - viewpoint->x, dy = frame.posY[i] - viewpoint->y;
    const float d2 = dx * dx + dy * dy;
    if (d2 > aoi2) continue;
    if (d2 <= near2) scratch.emplace_back(d2, static_cast<std::uint32_t>(i));
    if (d2 <= mid2) {
      out.push_back({static_cast<std::uint32_t>(i), Tier::Middle});
    } else {
      out.push_back({static_cast<std::uint32_t>(i), Tier::Far});
    }
  }
  // The nearMax closest of the near candidates get full poses (ties broken by row: deterministic).
  if (scratch.size() > options.nearMax) {
    std::nth_element(scratch.begin(), scratch.begin() + static_cast<std::ptrdiff_t>(options.nearMax), scratch.end());
    scratch.resize(options.nearMax);
  }
  std::sort(scratch.begin(), scratch.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
  // Both lists ascend by row: one merge pass marks the near ones.
  std::size_t k = 0;
  for (Interested& it : out) {
    while (k < scratch.size() && scratch[k].second < it.row) ++k;
    if (k < scratch.size() && scratch[k].second == it.row) it.tier = Tier::Near;
  }
}

}  // namespace throng::hub
