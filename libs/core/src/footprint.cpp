// throng::core footprints — union of projected triangles with Boost.Geometry (see
// throng/core/footprint.hpp).
#include "throng/core/footprint.hpp"

#include <cmath>

#include <boost/geometry.hpp>
#include <boost/geometry/geometries/multi_polygon.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>

namespace throng::core {

namespace {

namespace bg = boost::geometry;
using Pt = bg::model::d2::point_xy<double>;
using Poly = bg::model::polygon<Pt>;  // clockwise, closed
using Multi = bg::model::multi_polygon<Poly>;

constexpr double kSnap = 1e-3;        // [m]
constexpr double kMinArea = 1e-6;     // [m²]
constexpr double kSimplify = 5e-4;    // [m] collinear tolerance

double snap(float v) { return std::round(static_cast<double>(v) / kSnap) * kSnap; }

core::Polygon toPolygon(const bg::model::ring<Pt>& ring) {
  bg::model::ring<Pt> simple;
  bg::simplify(ring, simple, kSimplify);
  core::Polygon out;
  // Boost rings are clockwise and closed: drop the closing vertex, reverse to counter-clockwise.
  for (std::size_t i = simple.size(); i-- > 0;) {
    if (i + 1 == simple.size() && simple.size() > 1 && bg::equals(simple[i], simple[0])) continue;
    out.emplace_back(static_cast<float>(simple[i].x()), static_cast<float>(simple[i].y()));
  }
  return out;
}

}  // namespace

Footprint unionOfTriangles(const std::vector<std::array<core::Vec2, 3>>& triangles) {
  std::vector<Multi> parts;
  parts.reserve(triangles.size());
  for (const auto& t : triangles) {
    Poly p;
    for (const auto& v : t) bg::append(p.outer(), Pt(snap(v.x), snap(v.y)));
    bg::append(p.outer(), Pt(snap(t[0].x), snap(t[0].y)));
    bg::correct(p);
    if (std::abs(bg::area(p)) < kMinArea) continue;
    parts.push_back(Multi{p});
  }
  // Cascaded union: merge neighbours pairwise until one remains.
  while (parts.size() > 1) {
    std::vector<Multi> next;
    next.reserve(parts.size() / 2 + 1);
    for (std::size_t i = 0; i + 1 < parts.size(); i += 2) {
      Multi u;
      bg::union_(parts[i], parts[i + 1], u);
      next.push_back(std::move(u));
    }
    if (parts.size() % 2 == 1) next.push_back(std::move(parts.back()));
    parts = std::move(next);
  }
  Footprint out;
  if (parts.empty()) return out;
  for (const Poly& p : parts.front()) {
    if (std::abs(bg::area(p)) < kMinArea) continue;
    core::Polygon outer = toPolygon(p.outer());
    if (outer.size() < 3) continue;
    out.outer.push_back(std::move(outer));
    for (const auto& hole : p.inners()) {
      if (std::abs(bg::area(hole)) < kMinArea) continue;
      core::Polygon h = toPolygon(hole);
      if (h.size() >= 3) out.holes.push_back(std::move(h));
    }
  }
  return out;
}

}  // namespace throng::core
