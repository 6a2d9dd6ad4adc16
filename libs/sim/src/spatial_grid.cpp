#include "spatial_grid.hpp"

#include <algorithm>
#include <cmath>

#include "throng/core/assert.hpp"

namespace throng::sim {

void SpatialGrid::configure(const core::Aabb& bounds, float cellSize) {
  THRONG_ASSERT(cellSize > 0.0f && bounds.valid());
  cellSize_ = cellSize;
  invCell_ = 1.0f / cellSize;
  originX_ = bounds.min.x;
  originY_ = bounds.min.y;
  nx_ = std::max(1, static_cast<int>(std::ceil((bounds.max.x - bounds.min.x) * invCell_)));
  ny_ = std::max(1, static_cast<int>(std::ceil((bounds.max.y - bounds.min.y) * invCell_)));
  cellStart_.assign(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_) + 1, 0);
}

void SpatialGrid::rebuild(std::span<const float> posX, std::span<const float> posY, const core::TaskSystem& tasks) {
  const std::size_t n = posX.size();
  cellOfRow_.resize(n);
  rows_.resize(n);
  tasks.parallelFor(n, 4096, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      cellOfRow_[i] = static_cast<std::uint32_t>(cellY(posY[i]) * nx_ + cellX(posX[i]));
    }
  });
  // Counting sort, stable in row order (serial: a few ns per agent).
  std::fill(cellStart_.begin(), cellStart_.end(), 0u);
  for (std::size_t i = 0; i < n; ++i) ++cellStart_[cellOfRow_[i] + 1];
  for (std::size_t c = 1; c < cellStart_.size(); ++c) cellStart_[c] += cellStart_[c - 1];
  cursor_.assign(cellStart_.begin(), cellStart_.end() - 1);
  for (std::size_t i = 0; i < n; ++i) rows_[cursor_[cellOfRow_[i]]++] = static_cast<std::uint32_t>(i);
}

}  // namespace throng::sim
