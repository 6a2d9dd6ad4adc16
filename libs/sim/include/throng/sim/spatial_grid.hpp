// SpatialGrid — uniform grid over agent positions, rebuilt every tick by counting sort (the
// `sense` phase). Within a cell, rows keep ascending order, so neighbour candidates come out in a
// fixed order and ties break by row (stable id order, unless the World sorts its rows spatially:
// ScenarioDesc::rowOrder). Agents outside the bounds are clamped into
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
  /// Candidates are gathered as packed (distance², row) keys — the 5 × 5 cells around the query
  /// as five contiguous spans, then ring by ring outward — until no unvisited cell can hold
  /// anything closer than the current k-th neighbour; the k smallest keys are then selected and
  /// sorted. Returns the count written to `out` (at most k). No allocation for k <= 64.
  /// Runs on the SIMD path core::simdPath() named at the last rebuild(); every path gives the same
  /// rows in the same order.
  std::size_t nearest(float x, float y, float range, std::size_t k, std::uint32_t self, std::uint32_t* out) const;

  /// Number of rows sorted into cells by the last rebuild().
  [[nodiscard]] std::size_t size() const { return size_; }
  /// The i-th agent in cell order (i < size()): its row and position as of the last rebuild().
  [[nodiscard]] std::uint32_t rowAt(std::size_t i) const { return rows_[i]; }
  [[nodiscard]] float xAt(std::size_t i) const { return cellX_[i]; }
  [[nodiscard]] float yAt(std::size_t i) const { return cellY_[i]; }

  /// Agents per m² in the 3×3 cells around (x, y) (Musse et al. §3.2.4's density measure).
  [[nodiscard]] float density(float x, float y) const {
    const int cx = cellX(x), cy = cellY(y);
    const int gx0 = std::max(0, cx - 1), gx1 = std::min(nx_ - 1, cx + 1);
    const int gy0 = std::max(0, cy - 1), gy1 = std::min(ny_ - 1, cy + 1);
    std::uint32_t count = 0;
    for (int gy = gy0; gy <= gy1; ++gy) {  // the cells of one grid row are one span of entries
      const std::size_t base = static_cast<std::size_t>(gy) * static_cast<std::size_t>(nx_);
      count += cellStart_[base + static_cast<std::size_t>(gx1) + 1] - cellStart_[base + static_cast<std::size_t>(gx0)];
    }
    const int cells = (gx1 - gx0 + 1) * (gy1 - gy0 + 1);
    return static_cast<float>(count) / (static_cast<float>(cells) * cellSize_ * cellSize_);
  }

  [[nodiscard]] int cellX(float x) const { return toCell((x - originX_) * invCell_, nx_); }
  [[nodiscard]] int cellY(float y) const { return toCell((y - originY_) * invCell_, ny_); }
  [[nodiscard]] float cellSize() const { return cellSize_; }
  /// Rows in cell order (agents of one cell are contiguous): a cache-friendly visiting order.
  [[nodiscard]] std::span<const std::uint32_t> rowsInCellOrder() const { return {rows_.data(), size_}; }

 private:
  /// Feeds `gather` the cell spans around (x, y): the block of the first rings at once, then ring
  /// by ring until the range is covered or gather has k candidates nearer than the next ring.
  /// Returns the number of cells in the first block (for the density estimate).
  template <class G>
  int gatherRings(float x, float y, float range, G& gather) const;
  /// nearest() with vectors of `Lanes` floats (4: the portable path; 8: AVX2).
  template <int Lanes>
  std::size_t nearestIn(float x, float y, float range, std::size_t k, std::uint32_t self, std::uint32_t* out) const;
  std::size_t nearestAvx2(float x, float y, float range, std::size_t k, std::uint32_t self, std::uint32_t* out) const;
  /// floor(v) clamped to [0, n): truncation equals floor on [0, n), and everything below 0 (NaN
  /// too) clamps to 0 either way — without a call to floorf (no SSE4.1 in the baseline ISA).
  static int toCell(float v, int n) {
    if (!(v >= 0.0f)) return 0;
    if (v >= static_cast<float>(n)) return n - 1;
    return std::min(static_cast<int>(v), n - 1);
  }
  float originX_ = 0, originY_ = 0, cellSize_ = 1, invCell_ = 1;
  int nx_ = 1, ny_ = 1;
  std::vector<std::uint32_t> cellStart_;  // size nx*ny + 1
  // Rows sorted by cell and their positions in that order (nearest() reads these four at a time);
  // each array has kPad slack entries after size_ so that a span's last group of eight may be read
  // whole.
  static constexpr std::size_t kPad = 8;
  bool avx2_ = false;  // core::simdPath() at the last rebuild()
  std::size_t size_ = 0;
  std::vector<std::uint32_t> rows_;
  std::vector<float> cellX_, cellY_;
  std::vector<std::uint32_t> cursor_;
};

}  // namespace throng::sim
