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
  entries_.resize(n);
  tasks.parallelFor(n, 4096, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) entries_[k] = {posX[rows_[k]], posY[rows_[k]], rows_[k]};
  });
}

std::size_t SpatialGrid::nearest(float x, float y, float range, std::size_t k, std::uint32_t self, const float* posX,
                                 const float* posY, std::vector<std::pair<float, std::uint32_t>>& best,
                                 std::uint32_t* out) const {
  (void)posX;
  (void)posY;
  if (k == 0) return 0;
  best.resize(k);
  std::pair<float, std::uint32_t>* b = best.data();
  std::size_t n = 0;  // entries in b, sorted by (distance², row)
  const float rangeSq = range * range;
  // Admission bound: anything farther than this cannot enter the list (the range until the list
  // is full, then its k-th distance; equal distances are settled by row, as everywhere).
  float bound = rangeSq;
  const int cx = cellX(x), cy = cellY(y);
  // Distance from (x, y) to the nearest edge of its own cell: ring r cells are at least
  // (r - 1) * cellSize + edge away.
  const float fx = x - (originX_ + static_cast<float>(cx) * cellSize_);
  const float fy = y - (originY_ + static_cast<float>(cy) * cellSize_);
  const float edge = std::max(0.0f, std::min(std::min(fx, cellSize_ - fx), std::min(fy, cellSize_ - fy)));
  const int maxRing = static_cast<int>(std::ceil(range * invCell_)) + 1;
  const Entry* e = entries_.data();
  // Scans entries [first, last): cells of one grid row are contiguous, so a ring's top and bottom
  // rows are one span each.
  auto scan = [&](std::uint32_t first, std::uint32_t last) {
    for (std::uint32_t i = first; i < last; ++i) {
      const float dx = e[i].x - x, dy = e[i].y - y;
      const float d2 = dx * dx + dy * dy;
      if (d2 > bound) continue;
      const std::uint32_t row = e[i].row;
      if (row == self || d2 >= rangeSq) continue;
      std::size_t pos;
      if (n < k) {
        pos = n++;
      } else {
        if (d2 == b[k - 1].first && row > b[k - 1].second) continue;
        pos = k - 1;
      }
      while (pos > 0 && (b[pos - 1].first > d2 || (b[pos - 1].first == d2 && b[pos - 1].second > row))) {
        b[pos] = b[pos - 1];
        --pos;
      }
      b[pos] = {d2, row};
      if (n == k) bound = b[k - 1].first;
    }
  };
  auto cellIndex = [&](int gx, int gy) {
    return static_cast<std::size_t>(gy) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(gx);
  };
  for (int ring = 0; ring <= maxRing; ++ring) {
    const float minDist = ring == 0 ? 0.0f : static_cast<float>(ring - 1) * cellSize_ + edge;
    if (minDist * minDist >= rangeSq) break;
    if (n == k && minDist * minDist > b[k - 1].first) break;
    if (ring == 0) {
      const std::size_t c = cellIndex(cx, cy);
      scan(cellStart_[c], cellStart_[c + 1]);
      continue;
    }
    const int x0 = cx - ring, x1 = cx + ring, y0 = cy - ring, y1 = cy + ring;
    const int gx0 = std::max(0, x0), gx1 = std::min(nx_ - 1, x1);
    if (y0 >= 0) scan(cellStart_[cellIndex(gx0, y0)], cellStart_[cellIndex(gx1, y0) + 1]);
    if (y1 < ny_) scan(cellStart_[cellIndex(gx0, y1)], cellStart_[cellIndex(gx1, y1) + 1]);
    for (int gy = std::max(0, y0 + 1); gy <= std::min(ny_ - 1, y1 - 1); ++gy) {
      if (x0 >= 0) scan(cellStart_[cellIndex(x0, gy)], cellStart_[cellIndex(x0, gy) + 1]);
      if (x1 < nx_) scan(cellStart_[cellIndex(x1, gy)], cellStart_[cellIndex(x1, gy) + 1]);
    }
  }
  for (std::size_t i = 0; i < n; ++i) out[i] = b[i].second;
  return n;
}

}  // namespace throng::sim
