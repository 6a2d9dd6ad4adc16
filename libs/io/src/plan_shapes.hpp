// throng::io plan shapes — what the DXF and WKT readers hand to plan_import.cpp: outlines and
// polylines in the drawing's own units, each with where it starts in the file, its layer (DXF) or
// its fixed role (WKT), and the drawing's unit. Also the diagnostics they share and the arc
// approximation (DXF circles, arcs and bulges). Private to throng_io.
#pragma once
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "throng/core/diagnostic.hpp"
#include "throng/io/plan_import.hpp"

namespace throng::io::plan {

struct Point {
  double x = 0, y = 0;
  bool operator==(const Point&) const = default;
};

struct Shape {
  std::vector<Point> points;       ///< drawing units
  bool closed = false;             ///< an outline (last point joins the first)
  std::string layer;               ///< DXF layer ("0" when none); empty for WKT
  std::optional<PlanRole> role;    ///< fixed by the reader (WKT); none: decided by the layer (DXF)
  int line = 0, column = 0;        ///< where it starts in the file (column 0: DXF, lines only)
  std::string what;                ///< "LWPOLYLINE", "POLYGON ring 2", ... for messages
};

struct Drawing {
  std::vector<Shape> shapes;
  double metresPerUnit = 1.0;  ///< from DXF $INSUNITS (1 for WKT and unitless DXF)
};

/// Collects diagnostics for one file, with a running count of vertices against kMaxPlanVertices.
class Reporter {
 public:
  explicit Reporter(std::string source) : source_(std::move(source)) {}
  void error(int line, int column, std::string what, std::string expected, std::string hint = {}) {
    diags_.push_back({source_, line, column, "", std::move(what), std::move(expected), std::move(hint)});
  }
  [[nodiscard]] bool failed() const { return !diags_.empty(); }
  core::Diagnostics take() { return std::move(diags_); }
  /// Counts `n` more vertices; false (and one diagnostic at line:column) past kMaxPlanVertices.
  bool addVertices(std::size_t n, int line, int column) {
    vertices_ += n;
    if (vertices_ <= kMaxPlanVertices) return true;
    if (!overflowed_) {
      error(line, column, "more than " + std::to_string(kMaxPlanVertices) + " vertices (arcs counted as their segments)",
            "a plan of at most " + std::to_string(kMaxPlanVertices) + " vertices", "split the plan or simplify its curves");
    }
    overflowed_ = true;
    return false;
  }

 private:
  std::string source_;
  core::Diagnostics diags_;
  std::size_t vertices_ = 0;
  bool overflowed_ = false;
};

/// Points on the circle (centre c, radius r) from angle a0 over `sweep` radians (signed), the end
/// points included, with `segmentsPerTurn` segments for a full turn (at least one).
inline std::vector<Point> arcPoints(Point c, double r, double a0, double sweep, int segmentsPerTurn) {
  const double step = 2.0 * std::numbers::pi / segmentsPerTurn;
  const int n = std::max(1, static_cast<int>(std::ceil(std::abs(sweep) / step - 1e-9)));
  std::vector<Point> out;
  out.reserve(std::size_t(n) + 1);
  for (int k = 0; k <= n; ++k) {
    const double a = a0 + sweep * k / n;
    out.push_back({c.x + r * std::cos(a), c.y + r * std::sin(a)});
  }
  return out;
}

/// The drawing of a DXF file (dxf_reader.cpp); diagnostics go to `report`.
Drawing readDxf(std::string_view text, const PlanImportOptions& options, Reporter& report);
/// The drawing of a WKT text (wkt_reader.cpp); diagnostics go to `report`.
Drawing readWkt(std::string_view text, const PlanImportOptions& options, Reporter& report);

}  // namespace throng::io::plan
