// throng::recording walkable-area WKT — Boost.Geometry union / difference of the scenario polygons and
// a WKT writer in shapely's layout ("POLYGON ((0 0, 20 0, …), (…))"), as JuPedSim's
// Geometry.as_wkt() writes it (shapely.to_wkt with full precision).
#include "walkable_area_wkt.hpp"

#include <boost/geometry.hpp>
#include <boost/geometry/geometries/multi_polygon.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>

#include "recording_text.hpp"

namespace throng::recording {
namespace {

namespace bg = boost::geometry;
using BPoint = bg::model::d2::point_xy<double>;
using BPolygon = bg::model::polygon<BPoint, /*ClockWise=*/false, /*Closed=*/true>;
using BMulti = bg::model::multi_polygon<BPolygon>;

/// A scenario polygon as a corrected Boost polygon; empty when it has fewer than 3 points.
BPolygon toBoost(const core::Polygon& poly) {
  BPolygon out;
  if (poly.size() < 3) return out;
  for (const core::Vec2& p : poly) {
    out.outer().emplace_back(floatAsDecimal(p.x), floatAsDecimal(p.y));
  }
  bg::unique(out);   // drop repeated consecutive points
  bg::correct(out);  // close the ring, orient it counter-clockwise
  if (out.outer().size() < 4) out.outer().clear();
  return out;
}

void appendRing(std::string& s, const BPolygon::ring_type& ring) {
  s += '(';
  bool first = true;
  for (const BPoint& p : ring) {
    if (!first) s += ", ";
    first = false;
    s += shortestText(p.x());
    s += ' ';
    s += shortestText(p.y());
  }
  s += ')';
}

void appendPolygonBody(std::string& s, const BPolygon& poly) {
  s += '(';
  appendRing(s, poly.outer());
  for (const auto& hole : poly.inners()) {
    s += ", ";
    appendRing(s, hole);
  }
  s += ')';
}

std::string toWkt(const BMulti& multi) {
  if (multi.empty()) return "POLYGON EMPTY";
  std::string s;
  if (multi.size() == 1) {
    s = "POLYGON ";
    appendPolygonBody(s, multi.front());
    return s;
  }
  s = "MULTIPOLYGON (";
  for (std::size_t i = 0; i < multi.size(); ++i) {
    if (i > 0) s += ", ";
    appendPolygonBody(s, multi[i]);
  }
  s += ')';
  return s;
}

BMulti unionAndSubtract(const std::vector<core::Polygon>& walkable,
                        const std::vector<core::Polygon>& obstacles) {
  BMulti acc;
  for (const core::Polygon& w : walkable) {
    const BPolygon poly = toBoost(w);
    if (poly.outer().empty()) continue;
    BMulti next;
    bg::union_(acc, poly, next);
    acc = std::move(next);
  }
  for (const core::Polygon& o : obstacles) {
    const BPolygon poly = toBoost(o);
    if (poly.outer().empty()) continue;
    BMulti next;
    bg::difference(acc, poly, next);
    acc = std::move(next);
  }
  return acc;
}

}  // namespace

WalkableAreaWkt walkableAreaWkt(const std::vector<core::Polygon>& walkable,
                                const std::vector<core::Polygon>& obstacles) {
  WalkableAreaWkt out;
  BMulti area;
  try {
    area = unionAndSubtract(walkable, obstacles);
  } catch (const std::exception&) {
    // Boost rejects some invalid inputs (self-intersections the validator should have caught):
    // fall back to the walkable polygons alone, flagged invalid.
    area.clear();
    for (const core::Polygon& w : walkable) {
      BPolygon poly = toBoost(w);
      if (!poly.outer().empty()) area.push_back(std::move(poly));
    }
  }
  out.wkt = toWkt(area);
  out.parts = area.size();
  out.area = area.empty() ? 0.0 : bg::area(area);
  out.valid = !area.empty() && bg::is_valid(area);
  if (!area.empty()) {
    const auto box = bg::return_envelope<bg::model::box<BPoint>>(area);
    out.minX = box.min_corner().x();
    out.minY = box.min_corner().y();
    out.maxX = box.max_corner().x();
    out.maxY = box.max_corner().y();
  }
  return out;
}

std::string polygonWkt(const core::Polygon& polygon) {
  const BPolygon poly = toBoost(polygon);
  if (poly.outer().empty()) return "POLYGON EMPTY";
  std::string s = "POLYGON ";
  appendPolygonBody(s, poly);
  return s;
}

}  // namespace throng::recording
