// throng::io DXF reader — ASCII DXF (AutoCAD's Drawing Interchange Format: group code and value on
// alternate lines) → plan shapes. Reads the HEADER's $INSUNITS and the ENTITIES section's LINE,
// LWPOLYLINE (closed flag, bulges), POLYLINE/VERTEX/SEQEND, CIRCLE and ARC; every other entity and
// section is skipped. Curves become segments (arcSegments per turn). Errors name file:line of the
// group code. Binary DXF is refused. Linear in the text.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>

#include "plan_shapes.hpp"
#include "throng/core/text.hpp"

namespace throng::io::plan {

namespace {

constexpr std::string_view kBinarySentinel = "AutoCAD Binary DXF";

/// One group: a code line and its value line.
struct Group {
  int code = -1;
  std::string_view value;
  int line = 0;  ///< 1-based line of the code
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::string printable(std::string_view s) { return "\"" + core::printable(std::string(s.substr(0, 80)), 80) + "\""; }

/// The text as groups, one at a time; the first error stops it.
class GroupReader {
 public:
  GroupReader(std::string_view text, Reporter& report) : text_(text), report_(report) {}

  /// The next group; false at the end of the text or after an error (`report_` says which).
  bool next(Group& g) {
    if (pending_) {
      g = *pending_;
      pending_.reset();
      return true;
    }
    std::string_view codeLine;
    if (!readLine(codeLine)) return false;
    g.line = line_;
    const std::string_view code = trim(codeLine);
    if (code.empty() && pos_ >= text_.size()) return false;  // a final empty line
    const auto [end, ec] = std::from_chars(code.data(), code.data() + code.size(), g.code);
    if (ec != std::errc() || end != code.data() + code.size() || g.code < 0 || g.code > 1071) {
      report_.error(line_, 0, "group code " + printable(code) + " is not a DXF group code",
                    "an integer group code (0 .. 1071) on its own line, its value on the next",
                    "is the file a DXF exported as ASCII text?");
      return false;
    }
    std::string_view value;
    if (!readLine(value)) {
      report_.error(g.line, 0, "the file ends after group code " + std::to_string(g.code), "its value on the next line");
      return false;
    }
    g.value = trim(value);
    return true;
  }
  /// Gives `g` back: the next call to next() returns it again.
  void unread(const Group& g) { pending_ = g; }

 private:
  bool readLine(std::string_view& out) {
    if (pos_ >= text_.size()) return false;
    const std::size_t end = std::min(text_.find('\n', pos_), text_.size());
    out = text_.substr(pos_, end - pos_);
    pos_ = end + 1;
    ++line_;
    return true;
  }

  std::string_view text_;
  Reporter& report_;
  std::size_t pos_ = 0;
  int line_ = 0;
  std::optional<Group> pending_;
};

/// Metres per drawing unit for $INSUNITS codes (AutoCAD DXF reference, HEADER section); 0: not a length.
double insunitsMetres(int code) {
  switch (code) {
    case 0: return 1.0;           // unitless: taken as metres (scale with --scale)
    case 1: return 0.0254;        // inches
    case 2: return 0.3048;        // feet
    case 3: return 1609.344;      // miles
    case 4: return 0.001;         // millimetres
    case 5: return 0.01;          // centimetres
    case 6: return 1.0;           // metres
    case 7: return 1000.0;        // kilometres
    case 8: return 0.0254e-6;     // microinches
    case 9: return 0.0254e-3;     // mils
    case 10: return 0.9144;       // yards
    case 13: return 1e-6;         // microns
    case 14: return 0.1;          // decimetres
    case 15: return 10.0;         // decametres
    case 16: return 100.0;        // hectometres
    case 21: return 1200.0 / 3937.0;  // US survey feet
    default: return 0.0;
  }
}

/// One entity's groups (after its "0 TYPE"), up to the next code 0.
struct Entity {
  std::string_view type;
  int line = 0;
  std::vector<Group> groups;
};

class DxfParser {
 public:
  DxfParser(std::string_view text, const PlanImportOptions& options, Reporter& report)
      : groups_(text, report), options_(options), report_(report) {}

  Drawing run() {
    Group g;
    bool sawEntities = false;
    while (!report_.failed() && groups_.next(g)) {
      if (g.code == 999) continue;  // comment
      if (g.code != 0 || (g.value != "SECTION" && g.value != "EOF")) {
        report_.error(g.line, 0, "group " + std::to_string(g.code) + " " + printable(g.value) + " outside a section",
                      "0 / SECTION (or 0 / EOF at the end)");
        break;
      }
      if (g.value == "EOF") break;
      Group name;
      if (!groups_.next(name)) {
        if (!report_.failed()) report_.error(g.line, 0, "the file ends after 0 / SECTION", "2 / the section's name");
        break;
      }
      if (name.code != 2) {
        report_.error(name.line, 0, "section without a name (group code " + std::to_string(name.code) + ")",
                      "2 / the section's name (HEADER, ENTITIES, ...) after 0 / SECTION");
        break;
      }
      if (name.value == "HEADER") readHeader(g.line);
      else if (name.value == "ENTITIES") sawEntities = readEntities(g.line) || sawEntities;
      else skipSection(name.value, g.line);
    }
    if (!report_.failed() && !sawEntities) {
      report_.error(0, 0, "no ENTITIES section", "a DXF drawing with an ENTITIES section (0 / SECTION, 2 / ENTITIES)");
    }
    return std::move(drawing_);
  }

 private:
  /// The groups up to "0 / ENDSEC"; false (with a diagnostic) when the file ends first.
  template <class F>
  bool forEachInSection(std::string_view name, int openedAt, F&& onGroup) {
    Group g;
    while (groups_.next(g)) {
      if (g.code == 0 && g.value == "ENDSEC") return true;
      if (g.code == 0 && g.value == "EOF") break;
      if (!onGroup(g) || report_.failed()) return false;
    }
    if (!report_.failed()) {
      report_.error(openedAt, 0, "section " + printable(name) + " has no end", "0 / ENDSEC before the end of the file");
    }
    return false;
  }

  void skipSection(std::string_view name, int openedAt) {
    forEachInSection(name, openedAt, [](const Group&) { return true; });
  }

  void readHeader(int openedAt) {
    bool units = false;
    forEachInSection("HEADER", openedAt, [&](const Group& g) {
      if (g.code == 9) units = g.value == "$INSUNITS";
      else if (units && g.code == 70) {
        units = false;
        int code = -1;
        const auto [end, ec] = std::from_chars(g.value.data(), g.value.data() + g.value.size(), code);
        const double m = ec == std::errc() && end == g.value.data() + g.value.size() ? insunitsMetres(code) : 0.0;
        if (m <= 0.0) {
          report_.error(g.line + 1, 0, "$INSUNITS " + printable(g.value) + " is not a length unit this importer knows",
                        "0 (unitless), 1 (in), 2 (ft), 4 (mm), 5 (cm), 6 (m) or another length unit code",
                        "set the drawing's units in the CAD program, or give --scale");
          return false;
        }
        drawing_.metresPerUnit = m;
      }
      return true;
    });
  }

  /// Reads every entity; true when the section was read to its end.
  bool readEntities(int openedAt) {
    Entity e;
    bool inEntity = false;
    const bool ok = forEachInSection("ENTITIES", openedAt, [&](const Group& g) {
      if (g.code != 0) {
        if (!inEntity) {
          report_.error(g.line, 0, "group " + std::to_string(g.code) + " before the first entity", "0 / an entity type (LINE, ...)");
          return false;
        }
        e.groups.push_back(g);
        return true;
      }
      if (inEntity) entity(e);
      e = Entity{g.value, g.line, {}};
      inEntity = true;
      return !report_.failed();
    });
    if (ok && inEntity) entity(e);
    if (ok && polyline_ && !report_.failed()) {
      report_.error(polyline_->entity.line, 0, "POLYLINE without SEQEND", "VERTEX entities, then 0 / SEQEND");
    }
    return ok;
  }

  void entity(const Entity& e) {
    if (++entities_ > kMaxPlanShapes) {
      report_.error(e.line, 0, "more than " + std::to_string(kMaxPlanShapes) + " entities",
                    "a plan of at most " + std::to_string(kMaxPlanShapes) + " entities", "split the plan");
      return;
    }
    if (polyline_ && e.type != "VERTEX" && e.type != "SEQEND") {
      report_.error(e.line, 0, "entity " + printable(e.type) + " inside the POLYLINE at line " + std::to_string(polyline_->entity.line),
                    "VERTEX entities, then 0 / SEQEND");
      return;
    }
    if (e.type == "LINE") line(e);
    else if (e.type == "LWPOLYLINE") lwpolyline(e);
    else if (e.type == "POLYLINE") polylineStart(e);
    else if (e.type == "VERTEX") vertex(e);
    else if (e.type == "SEQEND") seqend(e);
    else if (e.type == "CIRCLE" || e.type == "ARC") circle(e);
    // Anything else (TEXT, INSERT, DIMENSION, HATCH, SPLINE, ...) carries no plan geometry here.
  }

  bool number(const Group& g, double& out) {
    const auto [end, ec] = std::from_chars(g.value.data(), g.value.data() + g.value.size(), out);
    if (ec == std::errc() && end == g.value.data() + g.value.size() && std::isfinite(out) && std::abs(out) < 1e12) return true;
    report_.error(g.line + 1, 0, "value " + printable(g.value) + " of group code " + std::to_string(g.code) + " is not a number",
                  "a finite number below 1e12 in magnitude");
    return false;
  }

  bool integer(const Group& g, int& out) {
    const auto [end, ec] = std::from_chars(g.value.data(), g.value.data() + g.value.size(), out);
    if (ec == std::errc() && end == g.value.data() + g.value.size()) return true;
    report_.error(g.line + 1, 0, "value " + printable(g.value) + " of group code " + std::to_string(g.code) + " is not an integer",
                  "an integer (flags)");
    return false;
  }

  /// The groups every entity may have: layer (8) and extrusion z (230, mirrors x when negative).
  struct Common {
    std::string layer = "0";
    bool mirrored = false;
  };
  bool common(const Group& g, Common& c) {
    if (g.code == 8) {
      c.layer = std::string(g.value);
      return true;
    }
    if (g.code == 230) {
      double z = 0;
      if (number(g, z)) c.mirrored = z < 0;
      return true;
    }
    return false;
  }

  Shape shape(const Entity& e, const Common& c, bool closed) {
    Shape s;
    s.closed = closed;
    s.layer = c.layer;
    s.line = e.line;
    s.what = std::string(e.type);
    return s;
  }

  void add(Shape s, bool mirrored) {
    if (mirrored) {  // the arbitrary axis algorithm for extrusion (0, 0, -1): OCS x = −WCS x
      for (Point& p : s.points) p.x = -p.x;
    }
    if (!report_.addVertices(s.points.size(), s.line, 0)) return;
    drawing_.shapes.push_back(std::move(s));
  }

  void line(const Entity& e) {
    Common c;
    double v[4] = {0, 0, 0, 0};
    bool have[4] = {false, false, false, false};
    for (const Group& g : e.groups) {
      const int k = g.code == 10 ? 0 : g.code == 20 ? 1 : g.code == 11 ? 2 : g.code == 21 ? 3 : -1;
      if (k >= 0) have[k] = number(g, v[k]);
      else common(g, c);
    }
    if (!std::all_of(have, have + 4, [](bool b) { return b; })) {
      if (!report_.failed()) report_.error(e.line, 0, "LINE without both end points", "10/20 (start x, y) and 11/21 (end x, y)");
      return;
    }
    Shape s = shape(e, c, false);
    s.points = {{v[0], v[1]}, {v[2], v[3]}};
    add(std::move(s), false);  // LINE coordinates are in world coordinates
  }

  /// A polyline vertex with the bulge of the segment that leaves it (tan of a quarter of its angle).
  struct Vertex {
    Point p;
    double bulge = 0;
    bool hasX = false, hasY = false;
  };

  void lwpolyline(const Entity& e) {
    Common c;
    int flags = 0;
    std::vector<Vertex> vs;
    for (const Group& g : e.groups) {
      if (g.code == 10) {
        vs.push_back({});
        vs.back().hasX = number(g, vs.back().p.x);
      } else if (g.code == 20 || g.code == 42) {
        if (vs.empty()) {
          report_.error(g.line, 0, "group code " + std::to_string(g.code) + " before the first vertex", "10 (x) to start a vertex");
          return;
        }
        if (g.code == 20) vs.back().hasY = number(g, vs.back().p.y);
        else number(g, vs.back().bulge);
      } else if (g.code == 70) {
        integer(g, flags);
      } else {
        common(g, c);
      }
    }
    polyline(e, c, vs, (flags & 1) != 0);
  }

  /// A polyline's vertices → a shape, bulges approximated by arcs.
  void polyline(const Entity& e, const Common& c, const std::vector<Vertex>& vs, bool closed) {
    if (report_.failed()) return;
    for (const Vertex& v : vs) {
      if (!v.hasX || !v.hasY) {
        report_.error(e.line, 0, e.type == "POLYLINE" ? "a VERTEX without x or y" : "LWPOLYLINE vertex without x or y",
                      "each vertex with 10 (x) and 20 (y)");
        return;
      }
    }
    Shape s = shape(e, c, closed);
    const std::size_t n = vs.size();
    for (std::size_t i = 0; i < n; ++i) {
      s.points.push_back(vs[i].p);
      const bool last = i + 1 == n;
      if (vs[i].bulge == 0.0 || (last && !closed)) continue;
      const std::vector<Point> arc = bulgeArc(vs[i].p, vs[last ? 0 : i + 1].p, vs[i].bulge);
      if (!report_.addVertices(arc.size(), e.line, 0)) return;
      s.points.insert(s.points.end(), arc.begin() + 1, arc.end() - 1);
    }
    add(std::move(s), c.mirrored);
  }

  /// The arc from a to b whose bulge is tan(θ/4) (θ: its signed included angle, positive counter-clockwise).
  std::vector<Point> bulgeArc(Point a, Point b, double bulge) const {
    const double dx = b.x - a.x, dy = b.y - a.y;
    const double chord = std::hypot(dx, dy);
    if (chord == 0.0 || !std::isfinite(bulge) || std::abs(bulge) > 1e6) return {a, b};
    const double h = chord * (1.0 - bulge * bulge) / (4.0 * bulge);  // chord midpoint → centre, to the left
    const Point centre{(a.x + b.x) / 2 - dy / chord * h, (a.y + b.y) / 2 + dx / chord * h};
    const double r = std::hypot(a.x - centre.x, a.y - centre.y);
    std::vector<Point> out = arcPoints(centre, r, std::atan2(a.y - centre.y, a.x - centre.x), 4.0 * std::atan(bulge),
                                       options_.arcSegments);
    out.back() = b;
    return out;
  }

  void polylineStart(const Entity& e) {
    Common c;
    int flags = 0;
    for (const Group& g : e.groups) {
      if (g.code == 70) integer(g, flags);
      else common(g, c);
    }
    if ((flags & (16 | 64)) != 0) {
      report_.error(e.line, 0, std::string("a POLYLINE ") + ((flags & 64) ? "polyface mesh" : "polygon mesh") + " (flags " +
                                   std::to_string(flags) + ")",
                    "a 2D or 3D polyline (flags without 16 or 64)", "explode the mesh into lines or polylines");
      return;
    }
    polyline_ = OpenPolyline{e, c, (flags & 1) != 0, {}};
  }

  void vertex(const Entity& e) {
    if (!polyline_) {
      report_.error(e.line, 0, "VERTEX outside a POLYLINE", "0 / POLYLINE before its VERTEX entities");
      return;
    }
    Vertex v;
    for (const Group& g : e.groups) {
      if (g.code == 10) v.hasX = number(g, v.p.x);
      else if (g.code == 20) v.hasY = number(g, v.p.y);
      else if (g.code == 42) number(g, v.bulge);
    }
    polyline_->vertices.push_back(v);
  }

  void seqend(const Entity& e) {
    if (!polyline_) {
      report_.error(e.line, 0, "SEQEND outside a POLYLINE", "0 / POLYLINE, its VERTEX entities, then 0 / SEQEND");
      return;
    }
    const OpenPolyline p = std::move(*polyline_);
    polyline_.reset();
    polyline(p.entity, p.common, p.vertices, p.closed);
  }

  void circle(const Entity& e) {
    Common c;
    double v[5] = {0, 0, 0, 0, 360};  // x, y, radius, start and end angle [degrees]
    bool have[3] = {false, false, false};
    for (const Group& g : e.groups) {
      const int k = g.code == 10 ? 0 : g.code == 20 ? 1 : g.code == 40 ? 2 : g.code == 50 ? 3 : g.code == 51 ? 4 : -1;
      if (k < 0) common(g, c);
      else if (number(g, v[k]) && k < 3) have[k] = true;
    }
    if (report_.failed()) return;
    if (!have[0] || !have[1] || !have[2] || !(v[2] > 0)) {
      report_.error(e.line, 0, std::string(e.type) + (have[2] ? " with radius " + std::to_string(v[2]) : " without a radius"),
                    "10/20 (centre x, y) and 40 (radius > 0)");
      return;
    }
    const bool full = e.type == "CIRCLE";
    Shape s = shape(e, c, full);
    const double deg = std::numbers::pi / 180.0;
    double sweep = full ? 360.0 : std::fmod(v[4] - v[3], 360.0);
    if (sweep <= 0) sweep += 360.0;  // arcs run counter-clockwise from start to end
    s.points = arcPoints({v[0], v[1]}, v[2], full ? 0.0 : v[3] * deg, sweep * deg, options_.arcSegments);
    if (full) s.points.pop_back();  // the closing point repeats the first
    add(std::move(s), c.mirrored);
  }

  struct OpenPolyline {
    Entity entity;
    Common common;
    bool closed = false;
    std::vector<Vertex> vertices;
  };

  GroupReader groups_;
  const PlanImportOptions& options_;
  Reporter& report_;
  Drawing drawing_;
  std::size_t entities_ = 0;
  std::optional<OpenPolyline> polyline_;
};

}  // namespace

Drawing readDxf(std::string_view text, const PlanImportOptions& options, Reporter& report) {
  if (text.substr(0, kBinarySentinel.size()) == kBinarySentinel) {
    report.error(1, 0, "a binary DXF file", "an ASCII DXF file", "save the drawing as ASCII DXF (DXFOUT, format ASCII)");
    return {};
  }
  return DxfParser(text, options, report).run();
}

}  // namespace throng::io::plan
