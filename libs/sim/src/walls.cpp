// Walls (walls.hpp): the navmesh boundary (nav::NavMesh::boundary) in a uniform grid of cells, the
// disc query ORCA uses, the ray query of avm's look ahead and the floor check on multi-level worlds.
#include "walls.hpp"

#include "agent_store.hpp"

#include <algorithm>
#include <cmath>

namespace throng::sim {

void Walls::build(const nav::NavMesh& mesh, float cellSize) {
  heights_.clear();
  segments_ = mesh.boundary(mesh.layered() ? &heights_ : nullptr);
  const core::Aabb b = mesh.bounds();
  originX_ = b.min.x;
  originY_ = b.min.y;
  invCell_ = 1.0f / cellSize;
  nx_ = std::max(1, static_cast<int>(std::ceil((b.max.x - b.min.x) * invCell_)));
  ny_ = std::max(1, static_cast<int>(std::ceil((b.max.y - b.min.y) * invCell_)));
  auto cx = [&](float x) { return std::clamp(static_cast<int>(std::floor((x - originX_) * invCell_)), 0, nx_ - 1); };
  auto cy = [&](float y) { return std::clamp(static_cast<int>(std::floor((y - originY_) * invCell_)), 0, ny_ - 1); };
  // Two passes (count, fill) over the cells each segment's bounding box covers.
  const std::size_t cells = static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_);
  cellStart_.assign(cells + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<std::uint32_t> cursor;
    if (pass == 1) {
      for (std::size_t c = 1; c <= cells; ++c) cellStart_[c] += cellStart_[c - 1];
      items_.resize(cellStart_[cells]);
      cursor.assign(cellStart_.begin(), cellStart_.end() - 1);
    }
    for (std::uint32_t s = 0; s < segments_.size(); ++s) {
      const core::Segment& seg = segments_[s];
      const int x0 = cx(std::min(seg.a.x, seg.b.x)), x1 = cx(std::max(seg.a.x, seg.b.x));
      const int y0 = cy(std::min(seg.a.y, seg.b.y)), y1 = cy(std::max(seg.a.y, seg.b.y));
      for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
          const std::size_t c = static_cast<std::size_t>(y) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(x);
          if (pass == 0) ++cellStart_[c + 1];
          else items_[cursor[c]++] = s;
        }
      }
    }
  }
  // areaCount_: the segments' cell entries in the cells left of x and below y, at (x, y).
  areaCount_.assign(static_cast<std::size_t>(nx_ + 1) * static_cast<std::size_t>(ny_ + 1), 0);
  for (int y = 0; y < ny_; ++y) {
    for (int x = 0; x < nx_; ++x) {
      const std::size_t c = static_cast<std::size_t>(y) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(x);
      const std::size_t w = static_cast<std::size_t>(nx_ + 1);
      areaCount_[(y + 1) * w + x + 1] = areaCount_[y * w + x + 1] + areaCount_[(y + 1) * w + x] - areaCount_[y * w + x] +
                                        (cellStart_[c + 1] - cellStart_[c]);
    }
  }
}

bool Walls::boxEmpty(int x0, int y0, int x1, int y1) const {
  // Four reads of the summed-area table: the cells' entries in the box, compared with zero.
  const auto corner = [&](int x, int y) {
    return areaCount_[static_cast<std::size_t>(y) * static_cast<std::size_t>(nx_ + 1) + static_cast<std::size_t>(x)];
  };
  return corner(x1 + 1, y1 + 1) + corner(x0, y0) == corner(x0, y1 + 1) + corner(x1 + 1, y0);
}

bool Walls::onLevel(std::uint32_t s, core::Vec2 p, float z) const {
  if (heights_.empty()) return true;
  const core::Segment& seg = segments_[s];
  const core::Vec2 ab = seg.b - seg.a;
  const float len2 = core::lengthSq(ab);
  const float t = len2 > 0.0f ? std::clamp(core::dot(p - seg.a, ab) / len2, 0.0f, 1.0f) : 0.0f;
  const float h = heights_[2 * s] + (heights_[2 * s + 1] - heights_[2 * s]) * t;
  return std::abs(h - z) < AgentStore::kSameLevel;
}

void Walls::query(float x, float y, float r, std::vector<std::uint32_t>& out) const {
  const std::size_t first = out.size();
  // Clamped to the grid before truncating: the same cells as floor-then-clamp (truncation and floor
  // differ only below 0, which clamps to 0 either way), without a call to floorf per bound.
  auto cx = [&](float v) { return static_cast<int>(std::clamp((v - originX_) * invCell_, 0.0f, static_cast<float>(nx_ - 1))); };
  auto cy = [&](float v) { return static_cast<int>(std::clamp((v - originY_) * invCell_, 0.0f, static_cast<float>(ny_ - 1))); };
  const int x0 = cx(x - r), x1 = cx(x + r), y0 = cy(y - r), y1 = cy(y + r);
  if (boxEmpty(x0, y0, x1, y1)) return;  // most of an open crowd: no cell visited
  for (int yy = y0; yy <= y1; ++yy) {
    for (int xx = x0; xx <= x1; ++xx) {
      const std::size_t c = static_cast<std::size_t>(yy) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(xx);
      out.insert(out.end(), items_.begin() + cellStart_[c], items_.begin() + cellStart_[c + 1]);
    }
  }
  std::sort(out.begin() + static_cast<std::ptrdiff_t>(first), out.end());
  out.erase(std::unique(out.begin() + static_cast<std::ptrdiff_t>(first), out.end()), out.end());
}

void Walls::queryRay(core::Vec2 p, core::Vec2 dir, float len, std::vector<std::uint32_t>& out) const {
  const std::size_t first = out.size();
  collectAlong(p, p + dir * std::max(0.0f, len), out);
  if (out.size() - first > 1) {
    std::sort(out.begin() + static_cast<std::ptrdiff_t>(first), out.end());
    out.erase(std::unique(out.begin() + static_cast<std::ptrdiff_t>(first), out.end()), out.end());
  }
}

void Walls::collectAlong(core::Vec2 a, core::Vec2 b, std::vector<std::uint32_t>& out) const {
  constexpr float kSlack = 0.01f;  // [m] round the piece: far above the rounding of a crossing point
  // The cell of v, clamped to the grid as build() does (truncation is floor for what is not clamped).
  const auto cell = [](float v, float origin, float inv, int n) {
    return static_cast<int>(std::clamp((v - origin) * inv, 0.0f, static_cast<float>(n - 1)));
  };
  const int x0 = cell(std::min(a.x, b.x) - kSlack, originX_, invCell_, nx_);
  const int x1 = cell(std::max(a.x, b.x) + kSlack, originX_, invCell_, nx_);
  const int y0 = cell(std::min(a.y, b.y) - kSlack, originY_, invCell_, ny_);
  const int y1 = cell(std::max(a.y, b.y) + kSlack, originY_, invCell_, ny_);
  if (boxEmpty(x0, y0, x1, y1)) return;
  if ((x1 - x0 + 1) * (y1 - y0 + 1) > 4) {  // a box of more than 2 × 2 cells: halve the piece
    const core::Vec2 mid = a + (b - a) * 0.5f;
    collectAlong(a, mid, out);
    collectAlong(mid, b, out);
    return;
  }
  for (int yy = y0; yy <= y1; ++yy) {
    for (int xx = x0; xx <= x1; ++xx) {
      const std::size_t c = static_cast<std::size_t>(yy) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(xx);
      out.insert(out.end(), items_.begin() + cellStart_[c], items_.begin() + cellStart_[c + 1]);
    }
  }
}

}  // namespace throng::sim
