// Walls — the boundary of the walkable area as line segments, for ORCA's wall half-planes.
// Taken from the navigation mesh's outer edges (nav::NavMesh::boundary), so walls are
// right however walkable polygons touch or overlap and however obstacles cross them. The navmesh is
// already eroded by the body radius, so the segments bound agent centres. Built once; read-only.
// Queries: the segments near a disc (query) or along a ray (queryRay).
#pragma once
#include <cstdint>
#include <vector>

#include "throng/core/geometry.hpp"
#include "throng/nav/navmesh.hpp"

namespace throng::sim {

class Walls {
 public:
  void build(const nav::NavMesh& mesh, float cellSize);

  /// Appends to `out` the index of every segment whose cell range overlaps the disc (x, y, r),
  /// ascending and without duplicates.
  void query(float x, float y, float r, std::vector<std::uint32_t>& out) const;
  /// Appends to `out` the index of every segment whose cell range overlaps the cells the ray from p
  /// along the unit vector dir, `len` long, passes through (and a centimetre round it), ascending and
  /// without duplicates: every segment the ray crosses within len is among them, in fewer cells
  /// than the disc of radius len (query) holds.
  void queryRay(core::Vec2 p, core::Vec2 dir, float len, std::vector<std::uint32_t>& out) const;

  [[nodiscard]] const std::vector<core::Segment>& segments() const { return segments_; }
  /// Multi-level worlds: whether segment `s` bounds the floor at height `z` near ground point p
  /// (the segment's height at the point of it closest to p is within AgentStore::kSameLevel).
  /// Always true on a flat mesh.
  [[nodiscard]] bool onLevel(std::uint32_t s, core::Vec2 p, float z) const;

 private:
  std::vector<core::Segment> segments_;
  std::vector<float> heights_;  ///< layered meshes: height at a, height at b per segment; empty when flat
  float originX_ = 0, originY_ = 0, invCell_ = 1;
  int nx_ = 1, ny_ = 1;
  std::vector<std::uint32_t> cellStart_;
  std::vector<std::uint32_t> items_;
  std::vector<std::uint32_t> areaCount_;  ///< summed-area table of the cells' entries, (nx + 1) × (ny + 1)

  /// queryRay's walk: the entries of the cells round the piece a–b, halving it while its box holds
  /// walls and spans more than 2 × 2 cells; unsorted, with repeats.
  void collectAlong(core::Vec2 a, core::Vec2 b, std::vector<std::uint32_t>& out) const;
  /// Whether no wall lies in the cells x0..x1 × y0..y1 (inclusive, on the grid).
  [[nodiscard]] bool boxEmpty(int x0, int y0, int x1, int y1) const;
};

}  // namespace throng::sim
