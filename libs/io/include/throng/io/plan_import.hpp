// throng::io plan import — a floor plan (DXF or WKT text) → a scenario fragment
// {"walkable": [...], "obstacles": [...], "walls": [...]} in the units of docs/scenario-format.md
// (metres), for `throng import` and the scenario editor. Reads text; writes JSON or located
// diagnostics (DXF: file:line of the group code; WKT: file:line:column). docs/import.md.
#pragma once
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "throng/core/result.hpp"

namespace throng::io {

enum class PlanFormat : std::uint8_t {
  Dxf,  ///< AutoCAD DXF, ASCII (binary DXF is refused)
  Wkt,  ///< OGC well-known text (POLYGON, MULTIPOLYGON, LINESTRING, ..., GEOMETRYCOLLECTION)
  /// A flat glTF 2.0 world (docs/world-files.md: "walkable…" and "obstacle…" meshes): its floor as
  /// the world loader unites it (walkable outlines, holes and obstacle footprints as obstacles).
  /// A multi-level world is refused (the 2D plan has one floor). JSON .gltf, or .glb bytes.
  Gltf,
};

/// What a DXF layer's shapes become. Open lines and polylines are walls on every layer but an
/// ignored one; the role decides what a closed shape (closed polyline, circle) becomes.
enum class PlanRole : std::uint8_t { Walkable, Obstacle, Wall, Ignore };

struct PlanImportOptions {
  /// Multiplies every coordinate after the file's own unit conversion (DXF $INSUNITS) [Limit: > 0].
  double scale = 1.0;
  /// DXF layer name (compared without regard to case) → role, before the default rule: a layer whose
  /// name contains "wall" holds walls; "walk", "floor" or "room": walkable outlines; any other layer's
  /// closed shapes are obstacles.
  std::map<std::string, PlanRole> layers;
  /// Thickness given to every imported wall [m] [Limit: 0.01 .. 5] (the scenario default).
  double wallThickness = 0.2;
  /// Segments per full turn for circles, arcs and polyline bulges [Limit: 8 .. 1024]: 32 keeps the
  /// chord within 0.5 % of the radius (r (1 − cos(π/32))).
  int arcSegments = 32;
};

/// Limits against hostile input: each refused with a located diagnostic; reading is linear in the text.
inline constexpr std::size_t kMaxPlanBytes = std::size_t(64) << 20;
inline constexpr std::size_t kMaxPlanShapes = 200000;      ///< entities (DXF) or rings and lines (WKT)
inline constexpr std::size_t kMaxPlanVertices = 2000000;   ///< after arcs are approximated
inline constexpr int kMaxWktDepth = 32;                    ///< GEOMETRYCOLLECTIONs inside each other

/// The file's format from its extension (".dxf", ".wkt", ".gltf", ".glb", any case); none for another.
[[nodiscard]] std::optional<PlanFormat> planFormatOf(std::string_view path);

/// The plan as a scenario fragment {"walkable", "obstacles", "walls"} (each an array, in the shapes
/// of docs/scenario-format.md; coordinates in metres, rounded to the micrometre). Walkable: the
/// walkable outlines, or when there are none the bounding rectangle of everything. Every polygon is
/// simple with an area and every wall has 2 distinct points, as `throng check` wants them.
/// `source` names the file in diagnostics (a glTF's external buffers resolve against its directory).
/// A glTF floor has no walls; `scale` and the layer roles do not apply to it.
[[nodiscard]] core::Result<nlohmann::json> importPlan(std::string_view text, PlanFormat format, const std::string& source,
                                                      const PlanImportOptions& options = {});

}  // namespace throng::io
