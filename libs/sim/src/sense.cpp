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
  const float dense = std::min(desc.steering.denseNeighbourDistance, range);
  tasks.parallelFor(n, grainFor(n), [&](std::size_t begin, std::size_t end) {
    auto& best = worker(tasks).candidates;
    for (std::size_t row = begin; row < end; ++row) {
      // Density-dependent detection range (Musse et al. §3.2.4): d in dense places, D elsewhere.
      float r = range;
      if (dense > 0.0f && grid.density(agents.posX[row], agents.posY[row]) >= desc.steering.denseThreshold) r = dense;
      agents.neighbourCount[row] = static_cast<std::uint16_t>(
          grid.nearest(agents.posX[row], agents.posY[row], r, k, static_cast<std::uint32_t>(row), agents.posX.data(),
                       agents.posY.data(), best, &agents.neighbours[row * k]));
    }
  });
}

}  // namespace throng::sim
