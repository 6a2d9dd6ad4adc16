// throng::io scenario terrain parser — a multi-level world's "terrain": {"vertices": [[x, y, z],
// ...], "walkable": [[i, j, k], ...], "obstacles": [[i, j, k], ...]} (scenario coordinates: ground
// x, y and height z, metres; "stairSlope": the stair threshold in degrees) → nav::TerrainMesh and
// ScenarioDesc::stairSlopeDeg. Checks types, finite coordinates within
// ±kMaxCoordinate, indices in range, three different vertices per triangle, at least one walkable
// triangle and at most kMaxTerrainTriangles in all. Whether the triangles make a walkable navmesh
// (slope, climb, clearance) is the validator's question (nav::NavMesh::buildFromTerrain).
// Reads the JSON value; writes the TerrainMesh and diagnostics. Private to throng_io.
#include <string>

#include "scenario_reader.hpp"

namespace throng::io::detail {

namespace {

/// Bad vertices or triangles reported one by one per array; the rest are counted in one line, so
/// that a broken exporter's 100 000 bad triangles do not bury the first messages.
constexpr std::size_t kMaxListedProblems = 20;
/// The steepest stair threshold a scenario may set (terrain.stairSlope) [deg].
constexpr double kMaxStairSlopeDeg = 89.0;

}  // namespace

bool ScenarioReader::readTriangles(const Json& v, const std::string& ptr, std::size_t vertexCount,
                                   std::vector<std::uint32_t>& out) {
  const std::string last = vertexCount == 0 ? "-" : std::to_string(vertexCount - 1);
  const std::string expected = "a triangle [i, j, k]: three different vertex indices from 0 to " + last + " (into /terrain/vertices)";
  if (!v.is_array()) {
    error(ptr, "wrong type: " + describeType(v), "an array of triangles [i, j, k] (indices into /terrain/vertices)");
    return false;
  }
  out.clear();
  out.reserve(3 * v.size());
  std::size_t problems = 0;
  const auto report = [&](const std::string& p, std::string what) {
    if (++problems <= kMaxListedProblems) error(p, std::move(what), expected);
  };
  for (std::size_t t = 0; t < v.size(); ++t) {
    const Json& tri = v[t];
    if (!tri.is_array() || tri.size() != 3) {
      report(ptr + "/" + std::to_string(t),
             tri.is_array() ? "triangle has " + std::to_string(tri.size()) + " indices" : "wrong type: " + describeType(tri));
      continue;
    }
    std::uint32_t idx[3] = {0, 0, 0};
    bool ok = true;
    for (std::size_t k = 0; k < 3 && ok; ++k) {
      const Json& i = tri[k];
      const std::string ip = ptr + "/" + std::to_string(t) + "/" + std::to_string(k);
      if (!i.is_number()) {
        report(ip, "wrong type: " + describeType(i));
        ok = false;
        break;
      }
      const double d = i.get<double>();
      if (d != std::floor(d)) {
        report(ip, "index " + num(d) + " is not a whole number");
        ok = false;
      } else if (d < 0 || d >= static_cast<double>(vertexCount)) {
        report(ip, "index " + num(d) + " is out of range: /terrain/vertices has " + std::to_string(vertexCount) +
                       (vertexCount == 1 ? " vertex" : " vertices"));
        ok = false;
      } else {
        idx[k] = static_cast<std::uint32_t>(d);
      }
    }
    if (!ok) continue;
    if (idx[0] == idx[1] || idx[1] == idx[2] || idx[0] == idx[2]) {
      const std::uint32_t twice = idx[0] == idx[1] || idx[0] == idx[2] ? idx[0] : idx[1];
      report(ptr + "/" + std::to_string(t), "degenerate triangle: vertex " + std::to_string(twice) + " used twice");
      continue;
    }
    out.insert(out.end(), idx, idx + 3);
  }
  if (problems > kMaxListedProblems) {
    error(ptr, "and " + std::to_string(problems - kMaxListedProblems) + " more bad triangles in " + ptr, expected);
  }
  return problems == 0;
}

bool ScenarioReader::readTerrain(const Json& v, const std::string& ptr, nav::TerrainMesh& out, float& stairSlopeDeg) {
  if (!isObject(v, ptr, "a terrain object {\"vertices\": [[x, y, z], ...], \"walkable\": [[i, j, k], ...], \"obstacles\": [...]}")) {
    return false;
  }
  checkKeys(v, ptr, {"vertices", "walkable", "obstacles", "stairSlope"}, "the terrain");
  bool ok = true;
  // The slope above which ground is a stair (nav::NavMeshConfig::stairSlopeDeg): above 0, and at
  // most 89° (Recast walks nothing steeper than 45°, but a stair's treads are flat, so its mean
  // slope over kStairBaseline may be steeper than any walkable triangle).
  if (const Json* x = optional(v, "stairSlope")) {
    ok = readFloat(*x, ptr + "/stairSlope", {0.0, kMaxStairSlopeDeg, true, "degrees"}, stairSlopeDeg) && ok;
  }
  std::size_t vertexCount = 0;
  const std::string vexpected = "an array of vertices [x, y, z] (metres: ground x, y and height z, each within ±" +
                                num(kMaxCoordinate) + ")";
  if (const Json* x = require(v, ptr, "vertices", vexpected)) {
    const std::string vptr = ptr + "/vertices";
    if (!x->is_array()) {
      error(vptr, "wrong type: " + describeType(*x), vexpected);
      ok = false;
    } else if (x->size() > 3 * kMaxTerrainTriangles) {
      error(vptr, std::to_string(x->size()) + " vertices", "at most " + std::to_string(3 * kMaxTerrainTriangles) + " vertices",
            "simplify the meshes");
      ok = false;
    } else {
      vertexCount = x->size();
      out.vertices.assign(3 * vertexCount, 0.0f);
      const std::string expected = "a vertex [x, y, z] of three finite numbers in metres, each within ±" + num(kMaxCoordinate);
      std::size_t problems = 0;
      const auto report = [&](const std::string& p, std::string what) {
        if (++problems <= kMaxListedProblems) error(p, std::move(what), expected);
      };
      for (std::size_t i = 0; i < vertexCount; ++i) {
        const Json& p = (*x)[i];
        if (!p.is_array() || p.size() != 3) {
          report(vptr + "/" + std::to_string(i),
                 p.is_array() ? "vertex has " + std::to_string(p.size()) + " coordinates" : "wrong type: " + describeType(p));
          continue;
        }
        for (std::size_t k = 0; k < 3; ++k) {
          const std::string cp = vptr + "/" + std::to_string(i) + "/" + std::to_string(k);
          if (!p[k].is_number()) {
            report(cp, "wrong type: " + describeType(p[k]));
            continue;
          }
          const double d = p[k].get<double>();
          if (!std::isfinite(d) || std::abs(d) > kMaxCoordinate) {
            report(cp, "value " + num(d) + " m is out of range");
            continue;
          }
          out.vertices[3 * i + k] = static_cast<float>(d);
        }
      }
      if (problems > kMaxListedProblems) {
        error(vptr, "and " + std::to_string(problems - kMaxListedProblems) + " more bad vertices in " + vptr, expected);
      }
      ok = problems == 0 && ok;
    }
  } else {
    ok = false;
  }
  const std::string wexpected = "an array of at least one triangle [i, j, k] (indices into /terrain/vertices)";
  if (const Json* x = require(v, ptr, "walkable", wexpected)) {
    ok = readTriangles(*x, ptr + "/walkable", vertexCount, out.walkable) && ok;
    if (x->is_array() && x->empty()) {
      error(ptr + "/walkable", "no walkable triangle", wexpected);
      ok = false;
    }
  } else {
    ok = false;
  }
  if (const Json* x = optional(v, "obstacles")) ok = readTriangles(*x, ptr + "/obstacles", vertexCount, out.obstacles) && ok;
  const std::size_t triangles = (out.walkable.size() + out.obstacles.size()) / 3;
  if (triangles > kMaxTerrainTriangles) {
    error(ptr, std::to_string(triangles) + " triangles", "at most " + std::to_string(kMaxTerrainTriangles) +
                                                            " triangles (walkable and obstacles together)",
          "simplify the meshes");
    ok = false;
  }
  return ok;
}

}  // namespace throng::io::detail
