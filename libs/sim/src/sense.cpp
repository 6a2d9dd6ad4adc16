// sense — rebuilds the spatial grid and finds each agent's k nearest neighbours within
// steering.neighbourDistance (parallel; each agent writes only its own neighbour slots). Agents are
// visited in the grid's cell order, so consecutive searches read the same cells from cache; ties
// in distance break by row, which is stable-id order, so the lists never depend on threads or on
// the visiting order.
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
  const float dense = std::min(desc.steering.denseNeighbourDistance, range);
  const float denseThreshold = desc.steering.denseThreshold;
  tasks.parallelFor(n, grainFor(n, tasks), [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const std::uint32_t row = grid.rowAt(i);
      const float x = grid.xAt(i), y = grid.yAt(i);
      // Density-dependent detection range (Musse et al. §3.2.4): d in dense places, D elsewhere.
      float r = range;
      if (dense > 0.0f && grid.density(x, y) >= denseThreshold) r = dense;
      std::uint32_t* list = &agents.neighbours[static_cast<std::size_t>(row) * k];
      std::size_t count = grid.nearest(x, y, r, k, row, list);
      if (agents.levels) {
        // Multi-level worlds: agents on another floor (above or below) are no neighbours.
        std::size_t kept = 0;
        for (std::size_t j = 0; j < count; ++j) {
          if (agents.sameLevel(row, agents.posZ[list[j]])) list[kept++] = list[j];
        }
        count = kept;
      }
      agents.neighbourCount[row] = static_cast<std::uint16_t>(count);
    }
  });
}

}  // namespace throng::sim
