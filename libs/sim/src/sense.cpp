// sense — rebuilds the spatial grid and finds each agent's k nearest neighbours within
// steering.neighbourDistance (parallel; each agent writes only its own neighbour slots). Agents are
// visited in the grid's cell order, so consecutive searches read the same cells from cache; ties
// in distance break by row (stable-id order unless the rows are sorted spatially, row_order.cpp),
// so the lists never depend on threads or on the visiting order. Reads SenseInput (positions, floor heights, steering); writes SenseOutput
// (the grid, the neighbour lists and counts) — phases.hpp.
#include <algorithm>
#include <cmath>

#include "phases.hpp"

namespace throng::sim {

void sense(const SenseInput& in, const SenseOutput& out, const core::TaskSystem& tasks) {
  const std::size_t n = in.posX.size();
  SpatialGrid& grid = out.grid;
  grid.rebuild(in.posX, in.posY, tasks);
  const std::size_t k = in.steering.maxNeighbours;
  out.neighbours.resize(n * k);
  out.neighbourCount.resize(n);
  const float range = in.steering.neighbourDistance;
  const float dense = std::min(in.steering.denseNeighbourDistance, range);
  const float denseThreshold = in.steering.denseThreshold;
  const bool levels = !in.posZ.empty();
  tasks.parallelFor(n, phaseGrain(n, tasks), [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const std::uint32_t row = grid.rowAt(i);
      const float x = grid.xAt(i), y = grid.yAt(i);
      // Density-dependent detection range (Musse et al. §3.2.4): d in dense places, D elsewhere.
      float r = range;
      if (dense > 0.0f && grid.density(x, y) >= denseThreshold) r = dense;
      std::uint32_t* list = &out.neighbours[static_cast<std::size_t>(row) * k];
      std::size_t count = grid.nearest(x, y, r, k, row, list);
      if (!in.goalState.empty()) {
        const auto carried = [&](std::uint32_t r) { return in.goalState[r] == GoalState::Riding && in.mode[r] == AgentMode::Acting; };
        std::size_t kept = 0;
        if (!carried(row)) {
          for (std::size_t j = 0; j < count; ++j) {
            if (!carried(list[j])) list[kept++] = list[j];
          }
        }
        count = kept;
      }
      if (levels) {
        // Multi-level worlds: agents on another floor (above or below) are no neighbours.
        std::size_t kept = 0;
        for (std::size_t j = 0; j < count; ++j) {
          if (std::abs(in.posZ[row] - in.posZ[list[j]]) < AgentStore::kSameLevel) list[kept++] = list[j];
        }
        count = kept;
      }
      out.neighbourCount[row] = static_cast<std::uint16_t>(count);
    }
  });
}

}  // namespace throng::sim
