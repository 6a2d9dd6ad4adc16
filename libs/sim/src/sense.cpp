// sense — rebuilds the spatial grid and finds each agent's k nearest neighbours within
// steering.neighbourDistance (parallel; each agent writes only its own neighbour slots). Ties in
// distance break by row, which is stable-id order, so the lists never depend on threads.
#include <algorithm>

#include "world_impl.hpp"

namespace throng::sim {

void World::Impl::sense(const core::TaskSystem& tasks) {
  const std::size_t n = agents.size();
  grid.rebuild(agents.posX, agents.posY, tasks);
  const std::size_t k = desc.steering.maxNeighbours;
  agents.neighbours.resize(n * k);
  agents.neighbourCount.resize(n);
  const float range = desc.steering.neighbourDistance;
  const float rangeSq = range * range;
  tasks.parallelFor(n, grainFor(n), [&](std::size_t begin, std::size_t end) {
    auto& best = worker(tasks).candidates;  // (distSq, row), kept sorted, at most k
    for (std::size_t row = begin; row < end; ++row) {
      best.clear();
      const float x = agents.posX[row], y = agents.posY[row];
      grid.forEachNear(x, y, range, [&](std::uint32_t other) {
        if (other == row) return;
        const float dx = agents.posX[other] - x, dy = agents.posY[other] - y;
        const float d2 = dx * dx + dy * dy;
        if (d2 >= rangeSq) return;
        if (best.size() == k && !(std::make_pair(d2, other) < best.back())) return;
        const auto entry = std::make_pair(d2, other);
        auto it = std::upper_bound(best.begin(), best.end(), entry);
        if (best.size() == k) best.pop_back();
        best.insert(it, entry);
      });
      std::uint32_t* slots = &agents.neighbours[row * k];
      for (std::size_t i = 0; i < best.size(); ++i) slots[i] = best[i].second;
      agents.neighbourCount[row] = static_cast<std::uint16_t>(best.size());
    }
  });
}

}  // namespace throng::sim
