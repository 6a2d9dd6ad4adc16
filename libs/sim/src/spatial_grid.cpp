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
  best.clear();
  if (k == 0) return 0;
  const float rangeSq = range * range;
  const int cx = cellX(x), cy = cellY(y);
  // Distance from (x, y) to the nearest edge of its own cell: ring r cells are at least
  // (r - 1) * cellSize + edge away.
  const float fx = x - (originX_ + static_cast<float>(cx) * cellSize_);
  const float fy = y - (originY_ + static_cast<float>(cy) * cellSize_);
  const float edge = std::max(0.0f, std::min(std::min(fx, cellSize_ - fx), std::min(fy, cellSize_ - fy)));
  const int maxRing = static_cast<int>(std::ceil(range * invCell_)) + 1;
  auto visitCell = [&](int gx, int gy) {
    const std::size_t c = static_cast<std::size_t>(gy) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(gx);
    const Entry* e = entries_.data();
    for (std::uint32_t i = cellStart_[c]; i < cellStart_[c + 1]; ++i) {
      const std::uint32_t row = e[i].row;
      const float dx = e[i].x - x, dy = e[i].y - y;
      const float d2 = dx * dx + dy * dy;
      if (d2 >= rangeSq || row == self) continue;
      if (best.size() == k && !(d2 < best.back().first || (d2 == best.back().first && row < best.back().second))) continue;
      // Insertion into the short sorted list (k is small).
      std::size_t pos = best.size();
      if (best.size() < k) best.emplace_back(); else --pos;
      while (pos > 0 && (best[pos - 1].first > d2 || (best[pos - 1].first == d2 && best[pos - 1].second > row))) {
        best[pos] = best[pos - 1];
        --pos;
      }
      best[pos] = {d2, row};
    }
  };
  for (int ring = 0; ring <= maxRing; ++ring) {
    const float minDist = ring == 0 ? 0.0f : static_cast<float>(ring - 1) * cellSize_ + edge;
    if (minDist * minDist >= rangeSq) break;
    if (best.size() == k && minDist * minDist > best.back().first) break;
    if (ring == 0) {
      visitCell(cx, cy);
      continue;
    }
    const int x0 = cx - ring, x1 = cx + ring, y0 = cy - ring, y1 = cy + ring;
    for (int gx = std::max(0, x0); gx <= std::min(nx_ - 1, x1); ++gx) {
      if (y0 >= 0) visitCell(gx, y0);
      if (y1 < ny_) visitCell(gx, y1);
    }
    for (int gy = std::max(0, y0 + 1); gy <= std::min(ny_ - 1, y1 - 1); ++gy) {
      if (x0 >= 0) visitCell(x0, gy);
      if (x1 < nx_) visitCell(x1, gy);
    }
  }
  for (std::size_t i = 0; i < best.size(); ++i) out[i] = best[i].second;
  return best.size();
}

}  // namespace throng::sim
