// SpatialGrid — uniform grid over agent positions, rebuilt every tick by counting sort (the
// `sense` phase). Within a cell, rows keep ascending order, so neighbour candidates come out in a
// fixed order and ties break by row (= stable id order). Agents outside the bounds are clamped into
// the border cells, so nobody is ever lost.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "throng/core/geometry.hpp"
#include "throng/core/parallel.hpp"

namespace throng::sim {

class SpatialGrid {
 public:
  /// Covers `bounds` with square cells of `cellSize` metres [Limit: > 0].
  void configure(const core::Aabb& bounds, float cellSize);

  /// Sorts rows [0, n) into cells. Positions are read from the two columns.
  void rebuild(std::span<const float> posX, std::span<const float> posY, const core::TaskSystem& tasks);

  /// Calls visit(row) for every row in cells overlapping the disc (x, y, r), cell by cell in
  /// row-major order, rows ascending within a cell.
  template <class Visit>
  void forEachNear(float x, float y, float r, Visit&& visit) const {
    const int cx0 = cellX(x - r), cx1 = cellX(x + r);
    const int cy0 = cellY(y - r), cy1 = cellY(y + r);
    for (int cy = cy0; cy <= cy1; ++cy) {
      for (int cx = cx0; cx <= cx1; ++cx) {
        const std::size_t c = static_cast<std::size_t>(cy) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(cx);
        for (std::uint32_t k = cellStart_[c]; k < cellStart_[c + 1]; ++k) visit(rows_[k]);
      }
    }
  }

  /// The k nearest rows to (x, y) within `range` (excluding `self`), nearest first, ties by row.
  /// Cells are searched ring by ring outward and the search stops once no unvisited cell can hold
  /// anything closer than the current k-th neighbour. `best` is caller scratch; returns the count
  /// written to `out` (at most k).
  std::size_t nearest(float x, float y, float range, std::size_t k, std::uint32_t self, const float* posX,
                      const float* posY, std::vector<std::pair<float, std::uint32_t>>& best, std::uint32_t* out) const;

  /// Agents per m² in the 3×3 cells around (x, y) (Musse et al. §3.2.4's density measure).
  [[nodiscard]] float density(float x, float y) const {
    const int cx = cellX(x), cy = cellY(y);
    std::uint32_t count = 0;
    int cells = 0;
    for (int gy = std::max(0, cy - 1); gy <= std::min(ny_ - 1, cy + 1); ++gy) {
      for (int gx = std::max(0, cx - 1); gx <= std::min(nx_ - 1, cx + 1); ++gx) {
        const std::size_t c = static_cast<std::size_t>(gy) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(gx);
        count += cellStart_[c + 1] - cellStart_[c];
        ++cells;
      }
    }
    return static_cast<float>(count) / (static_cast<float>(cells) * cellSize_ * cellSize_);
  }

  [[nodiscard]] int cellX(float x) const { return clampCell(static_cast<int>(std::floor((x - originX_) * invCell_)), nx_); }
  [[nodiscard]] int cellY(float y) const { return clampCell(static_cast<int>(std::floor((y - originY_) * invCell_)), ny_); }
  [[nodiscard]] float cellSize() const { return cellSize_; }
  /// Rows in cell order (agents of one cell are contiguous): a cache-friendly visiting order.
  [[nodiscard]] std::span<const std::uint32_t> rowsInCellOrder() const { return rows_; }

 private:
  static int clampCell(int c, int n) { return c < 0 ? 0 : (c >= n ? n - 1 : c); }
  float originX_ = 0, originY_ = 0, cellSize_ = 1, invCell_ = 1;
  int nx_ = 1, ny_ = 1;
  std::vector<std::uint32_t> cellStart_;  // size nx*ny + 1
  std::vector<std::uint32_t> rows_;       // rows sorted by cell
  struct Entry {
    float x, y;
    std::uint32_t row;
  };
  std::vector<Entry> entries_;            // positions packed in cell order (nearest() reads these)
  std::vector<std::uint32_t> cellOfRow_;
  std::vector<std::uint32_t> cursor_;
};

}  // namespace throng::sim
