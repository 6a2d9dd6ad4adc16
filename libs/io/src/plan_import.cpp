// throng::io plan import — the drawing a DXF or WKT reader made → the scenario fragment
// {"walkable", "obstacles", "walls"}: each shape's role (fixed by WKT, or by its DXF layer), units
// to metres (× scale), coordinates rounded to the micrometre and checked as the scenario loader
// will check them (|x|, |y| <= 100 km; outlines simple with an area; walls of 2 distinct points,
// at most kMaxWallSegments segments), and the bounding rectangle as the walkable area when the plan
// has no walkable outline. Reads plan text; writes JSON or located diagnostics.
#include "throng/io/plan_import.hpp"
#include "throng/io/world_file.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>

#include "plan_shapes.hpp"
#include "scenario_parser.hpp"
#include "throng/core/polygon_check.hpp"
#include "throng/core/text.hpp"

namespace throng::io {

namespace {

using plan::Point;
using plan::Shape;

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

/// A layer's role: the options' map first, then the name rule (docs/import.md).
PlanRole layerRole(const std::string& layer, const PlanImportOptions& options) {
  const std::string name = lower(layer);
  for (const auto& [key, role] : options.layers) {
    if (lower(key) == name) return role;
  }
  if (name.find("wall") != std::string::npos) return PlanRole::Wall;
  for (const char* walk : {"walk", "floor", "room"}) {
    if (name.find(walk) != std::string::npos) return PlanRole::Walkable;
  }
  return PlanRole::Obstacle;
}

/// A point as the scenario writes it: each coordinate through the float's shortest decimal form
/// (1.234 stays 1.234, not 1.2339999675750732), whole metres as integers ("10", not "10.0").
nlohmann::json pointJson(core::Vec2 p) {
  const auto d = [](float v) -> nlohmann::json {
    char buf[32];
    const auto end = std::to_chars(buf, buf + sizeof buf, v).ptr;
    double out = 0;
    std::from_chars(buf, end, out);
    if (out == std::floor(out)) return static_cast<std::int64_t>(out);
    return out;
  };
  return nlohmann::json::array({d(p.x), d(p.y)});
}

/// Checks and converts the shapes into the fragment's three lists.
class Assembler {
 public:
  Assembler(const plan::Drawing& drawing, const PlanImportOptions& options, plan::Reporter& report)
      : drawing_(drawing), options_(options), report_(report), factor_(drawing.metresPerUnit * options.scale) {}

  nlohmann::json run() {
    for (const Shape& s : drawing_.shapes) {
      const PlanRole role = roleOf(s);
      if (role == PlanRole::Ignore) continue;
      std::vector<core::Vec2> points;
      if (!convert(s, points)) continue;
      // An open polyline whose last point repeats the first is closed (CAD programs draw rectangles so).
      const bool closed = s.closed || (s.points.size() >= 4 && s.points.front() == s.points.back());
      if (role == PlanRole::Wall || !closed) wall(s, std::move(points), closed);
      else outline(s, role, std::move(points));
    }
    if (!report_.failed() && walkable_.empty()) boundingWalkable();
    return {{"walkable", std::move(walkable_)}, {"obstacles", std::move(obstacles_)}, {"walls", std::move(walls_)}};
  }

 private:
  PlanRole roleOf(const Shape& s) const { return s.role ? *s.role : layerRole(s.layer, options_); }

  std::string name(const Shape& s) const {
    return s.what + (s.layer.empty() ? "" : " on layer \"" + core::printable(s.layer, 60) + "\"");
  }

  /// Drawing units → metres, rounded to the micrometre, as floats (the scenario's precision).
  bool convert(const Shape& s, std::vector<core::Vec2>& out) {
    out.reserve(s.points.size());
    for (const Point& p : s.points) {
      // + 0.0: a coordinate rounded to -0 is written as 0.
      const double x = std::round(p.x * factor_ * 1e6) / 1e6 + 0.0, y = std::round(p.y * factor_ * 1e6) / 1e6 + 0.0;
      if (!(std::abs(x) <= kMaxCoordinate && std::abs(y) <= kMaxCoordinate)) {
        report_.error(s.line, s.column,
                      name(s) + " reaches (" + std::to_string(x) + ", " + std::to_string(y) + ") m, beyond ±" +
                          std::to_string(int(kMaxCoordinate)) + " m",
                      "coordinates within ±100 km once in metres", "check the drawing's units ($INSUNITS) or --scale");
        return false;
      }
      out.emplace_back(static_cast<float>(x), static_cast<float>(y));
      grow(x, y);
    }
    return true;
  }

  void grow(double x, double y) {
    lo_[0] = std::min(lo_[0], x);
    lo_[1] = std::min(lo_[1], y);
    hi_[0] = std::max(hi_[0], x);
    hi_[1] = std::max(hi_[1], y);
  }

  void wall(const Shape& s, std::vector<core::Vec2> points, bool closed) {
    std::vector<core::Vec2> run;
    for (const core::Vec2 p : points) {
      if (run.empty() || run.back() != p) run.push_back(p);
    }
    if (closed && run.size() > 2 && run.front() != run.back()) run.push_back(run.front());
    if (run.size() < 2) return;  // a zero-length line: nothing to build
    segments_ += run.size() - 1;
    if (segments_ > kMaxWallSegments) {
      if (!tooManySegments_) {
        report_.error(s.line, s.column, "more than " + std::to_string(kMaxWallSegments) + " wall segments",
                      "at most " + std::to_string(kMaxWallSegments) + " wall segments in a scenario",
                      "assign detailed layers the role ignore");
      }
      tooManySegments_ = true;
      return;
    }
    // A wall line holds at most kMaxPolygonVertices points: longer ones continue in the next wall.
    for (std::size_t start = 0; start + 1 < run.size(); start += kMaxPolygonVertices - 1) {
      const std::size_t end = std::min(run.size(), start + kMaxPolygonVertices);
      nlohmann::json line = nlohmann::json::array();
      for (std::size_t i = start; i < end; ++i) line.push_back(pointJson(run[i]));
      walls_.push_back({{"line", std::move(line)}, {"thickness", options_.wallThickness}});
    }
  }

  void outline(const Shape& s, PlanRole role, const std::vector<core::Vec2>& points) {
    std::vector<std::size_t> original;
    const core::Polygon poly = normalizePolygon(points, original);
    const std::string expected = "a simple closed outline enclosing an area (edges meet only at consecutive vertices)";
    const std::string hint = s.layer.empty() ? "" : "redraw it, or give its layer the role wall or ignore";
    bool collinear = true;
    for (std::size_t i = 2; i < poly.size() && collinear; ++i) {
      collinear = std::abs(core::cross(poly[1] - poly[0], poly[i] - poly[0])) < 1e-9f;
    }
    const auto noArea = [&] {
      report_.error(s.line, s.column, name(s) + " encloses no area (" + std::to_string(poly.size()) + " distinct points)", expected, hint);
    };
    if (poly.size() < 3 || collinear) return noArea();
    // 64 edge pairs per vertex, plus up to n² more from a pool shared by the whole plan (taken as
    // spent): ordinary outlines need a few pairs per edge, and a hostile plan stays linear.
    const std::uint64_t n = poly.size(), extra = std::min(pool_, n * n);
    pool_ -= extra;
    const core::SimplicityCheck simple = core::checkSimple(poly, 64 * n + extra);
    if (simple.tooComplex || simple.crossing) {
      report_.error(s.line, s.column,
                    name(s) + (simple.tooComplex ? " is too complex to check for self-intersections"
                                                 : " crosses itself: edge " + std::to_string(original[simple.crossing->second]) +
                                                       " meets edge " + std::to_string(original[simple.crossing->first]) +
                                                       " (edges numbered from 0 in file order)"),
                    expected, hint);
      return;
    }
    if (std::abs(core::signedArea(poly)) < 1e-6) return noArea();
    nlohmann::json json = nlohmann::json::array();
    for (const core::Vec2 p : poly) json.push_back(pointJson(p));
    (role == PlanRole::Walkable ? walkable_ : obstacles_).push_back(std::move(json));
  }

  /// No walkable outline: the bounding rectangle of everything is the walkable area.
  void boundingWalkable() {
    if (lo_[0] > hi_[0]) {
      report_.error(0, 0, "the plan holds no geometry to import",
                    "lines, polylines, circles or arcs in the ENTITIES section (DXF), or POLYGON / LINESTRING geometries (WKT)");
      return;
    }
    // At least a centimetre each way: the corners are written to the millimetre, and a rectangle of
    // a millimetre or two came out of that rounding with an area the loader calls none (fuzz_dxf).
    if (hi_[0] - lo_[0] < 1e-2 || hi_[1] - lo_[1] < 1e-2) {
      report_.error(0, 0, "the plan has no walkable outline and its bounding rectangle has no area",
                    "a closed walkable outline (a layer named ...floor..., ...room... or ...walk..., or a WKT POLYGON)");
      return;
    }
    nlohmann::json rect = nlohmann::json::array();
    for (const auto& [x, y] : {std::pair{lo_[0], lo_[1]}, {hi_[0], lo_[1]}, {hi_[0], hi_[1]}, {lo_[0], hi_[1]}}) {
      rect.push_back(pointJson(core::Vec2(static_cast<float>(x), static_cast<float>(y))));
    }
    walkable_.push_back(std::move(rect));
  }

  const plan::Drawing& drawing_;
  const PlanImportOptions& options_;
  plan::Reporter& report_;
  double factor_;
  std::uint64_t pool_ = kSelfIntersectionTests;
  std::size_t segments_ = 0;
  bool tooManySegments_ = false;
  double lo_[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  double hi_[2] = {-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  nlohmann::json walkable_ = nlohmann::json::array(), obstacles_ = nlohmann::json::array(), walls_ = nlohmann::json::array();
};

/// Options out of their limits: one diagnostic each (no position: they are not in the file).
void checkOptions(const PlanImportOptions& o, plan::Reporter& report) {
  if (!(o.scale > 0 && o.scale < 1e9)) report.error(0, 0, "scale " + std::to_string(o.scale), "a scale > 0");
  if (!(o.wallThickness >= 0.01 && o.wallThickness <= 5)) {
    report.error(0, 0, "wall thickness " + std::to_string(o.wallThickness) + " m", "a thickness from 0.01 to 5 m");
  }
  if (o.arcSegments < 8 || o.arcSegments > 1024) {
    report.error(0, 0, std::to_string(o.arcSegments) + " segments per turn", "8 to 1024 segments per full turn of an arc");
  }
}

}  // namespace

std::optional<PlanFormat> planFormatOf(std::string_view path) {
  const std::string p = lower(path);
  const auto ends = [&](std::string_view ext) { return p.size() >= ext.size() && p.compare(p.size() - ext.size(), ext.size(), ext) == 0; };
  if (ends(".dxf")) return PlanFormat::Dxf;
  if (ends(".wkt")) return PlanFormat::Wkt;
  if (ends(".gltf") || ends(".glb")) return PlanFormat::Gltf;
  return std::nullopt;
}

namespace {

/// A flat glTF world's floor through the world loader (which unites its walkable meshes and
/// checks the world as a scenario), as {"walkable", "obstacles", "walls": []}.
core::Result<nlohmann::json> importGltfFloor(std::string_view bytes, const std::string& source) {
  LoadOptions load;
  load.checkReachability = false;  // a floor plan, not yet a scenario: nobody has to get anywhere
  auto world = parseWorld(bytes, source, load);
  if (!world.ok()) return world.errors();
  const nlohmann::json doc = nlohmann::json::parse(world.value().text, nullptr, false);
  if (doc.is_discarded() || doc.contains("terrain")) {
    core::Diagnostic d;
    d.source = source;
    d.what = "a multi-level world (floors at several heights)";
    d.expected = "a flat glTF world: the 2D plan has one floor";
    d.hint = "edit multi-level worlds in the glTF file or as \"terrain\" (docs/world-files.md)";
    return core::Diagnostics{d};
  }
  // The loader's coordinates are floats widened to double: written as the other formats' are.
  const auto rounded = [](const nlohmann::json& polygons) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& polygon : polygons) {
      nlohmann::json ring = nlohmann::json::array();
      for (const auto& p : polygon) ring.push_back(pointJson(core::Vec2(p[0].get<float>(), p[1].get<float>())));
      out.push_back(std::move(ring));
    }
    return out;
  };
  return nlohmann::json{{"walkable", rounded(doc.value("walkable", nlohmann::json::array()))},
                        {"obstacles", rounded(doc.value("obstacles", nlohmann::json::array()))},
                        {"walls", nlohmann::json::array()}};
}

}  // namespace

core::Result<nlohmann::json> importPlan(std::string_view text, PlanFormat format, const std::string& source,
                                        const PlanImportOptions& options) {
  plan::Reporter report(source);
  checkOptions(options, report);
  if (text.size() > kMaxPlanBytes) {
    report.error(0, 0, "plan of " + std::to_string(text.size()) + " bytes", "at most " + std::to_string(kMaxPlanBytes) + " bytes");
  }
  if (report.failed()) return report.take();
  if (format == PlanFormat::Gltf) return importGltfFloor(text, source);
  const plan::Drawing drawing = format == PlanFormat::Dxf ? plan::readDxf(text, options, report) : plan::readWkt(text, options, report);
  if (report.failed()) return report.take();
  nlohmann::json fragment = Assembler(drawing, options, report).run();
  if (report.failed()) return report.take();
  return fragment;
}

}  // namespace throng::io
