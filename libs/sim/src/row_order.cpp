// Row order (ScenarioDesc::rowOrder, docs/performance.md "Row order"): every kRowSortPeriod of
// simulated time, in a world that keeps its rows spatially, the rows are sorted along a Hilbert
// curve over the neighbour grid's cells (ties: the row before), so that an agent's neighbours —
// whose positions, velocities and radii sense and steer read for every agent — lie a few rows away
// in memory instead of anywhere in the columns. Ids stay what they are: rowOfId follows the rows,
// and frames gather by ascending id (idOrder). The sort reads only positions, so it is the same
// for any thread or rank count.
#include <algorithm>
#include <cmath>

#include "hilbert.hpp"
#include "world_impl.hpp"

namespace throng::sim {

bool World::Impl::keepsRowsSpatially() const {
  switch (desc.rowOrder) {
    case RowOrder::Id: return false;
    case RowOrder::Spatial: return true;
    case RowOrder::Auto: return agents.size() >= kSpatialRowsMinAgents;
  }
  return false;
}

void World::Impl::sortRows(const core::TaskSystem& tasks) {
  const std::size_t n = agents.size();
  if (n < 2 || !keepsRowsSpatially()) return;
  const auto period = static_cast<std::uint64_t>(std::max(1.0, std::round(static_cast<double>(kRowSortPeriod) / desc.dt)));
  if (tick % period != 0) return;
  // The keys: 8 bytes an agent for this sort only, given back at once.
  std::vector<std::uint64_t> rowKeys(n);
  tasks.parallelFor(n, phaseGrain(n, tasks), [&](std::size_t begin, std::size_t end) {
    for (std::size_t row = begin; row < end; ++row) {
      const auto cx = static_cast<std::uint32_t>(std::min(grid.cellX(agents.posX[row]), 65535));
      const auto cy = static_cast<std::uint32_t>(std::min(grid.cellY(agents.posY[row]), 65535));
      rowKeys[row] = hilbertIndex(cx, cy) << 32 | row;
    }
  });
  if (std::is_sorted(rowKeys.begin(), rowKeys.end())) return;
  std::sort(rowKeys.begin(), rowKeys.end());
  // The columns' scratch: the spare floats (free between ticks: world_impl.hpp), 4 bytes a row.
  spareX.resize(n);
  agents.permute(rowKeys, std::as_writable_bytes(std::span<float>(spareX)));
  rowsById = false;
  rowsChanged = true;
  refreshRowOfId();
}

std::span<const std::uint32_t> World::Impl::rowsInIdOrder() {
  if (rowsById) return {};
  refreshRowOfId();
  idOrder.clear();
  idOrder.reserve(agents.size());
  for (const std::uint32_t row : rowOfId) {
    if (row != kNoRow) idOrder.push_back(row);
  }
  return idOrder;
}

std::uint32_t World::Impl::rowOf(std::uint32_t id) const {
  if (!rowsChanged) return id < rowOfId.size() ? rowOfId[id] : kNoRow;
  if (rowsById) {
    const auto it = std::lower_bound(agents.id.begin(), agents.id.end(), id);
    return it != agents.id.end() && *it == id ? static_cast<std::uint32_t>(it - agents.id.begin()) : kNoRow;
  }
  const auto it = std::find(agents.id.begin(), agents.id.end(), id);
  return it != agents.id.end() ? static_cast<std::uint32_t>(it - agents.id.begin()) : kNoRow;
}

}  // namespace throng::sim
