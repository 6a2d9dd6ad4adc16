// throng::io scenario walls and measurements — the scenario keys "walls" (polylines with a
// thickness, turned into obstacle rectangles before the navmesh is built, exactly as if they were
// listed in "obstacles") and "measurements" (lines and areas for analysis, never read by the
// simulation). Reads the JSON tree; writes ScenarioDesc::walls, ::measurements, the walls'
// footprints appended to ::obstacles, and diagnostics.
#include <cmath>
#include <map>

#include "scenario_reader.hpp"
#include "throng/core/polygon_check.hpp"

namespace throng::io {

namespace detail {

namespace {

/// Wall thickness [m]: 0.2 m is a plastered interior masonry wall (DIN 4172 brick courses give 11.5,
/// 17.5 and 24 cm walls; 17.5 cm plus 1.5 cm of plaster on each side ≈ 0.2 m).
const Range kThickness{0.01, 5, false, "m"};

/// Consecutive duplicate points dropped (a wall's line keeps its order; no closing rule).
std::vector<core::Vec2> distinctRun(const std::vector<core::Vec2>& line) {
  std::vector<core::Vec2> out;
  for (const core::Vec2 p : line) {
    if (out.empty() || out.back() != p) out.push_back(p);
  }
  return out;
}

/// Ids unique within one list: claim gives the id's first index, or `index` when it is new.
class IdRegistry {
 public:
  std::size_t claim(const std::string& id, std::size_t index) { return seen_.emplace(id, index).first->second; }

 private:
  std::map<std::string, std::size_t> seen_;
};

}  // namespace

bool ScenarioReader::readWall(const Json& v, const std::string& ptr, sim::WallDesc& w, std::size_t& segments) {
  if (!isObject(v, ptr, "a wall object {\"id\", \"line\": [[x, y], ...], \"thickness\"}")) return false;
  checkKeys(v, ptr, {"id", "line", "thickness"}, "a wall");
  bool ok = true;
  if (auto* x = optional(v, "id")) {
    if (readString(*x, ptr + "/id", "a non-empty string id, unique among the walls", w.id) && w.id.empty()) {
      error(ptr + "/id", "empty id", "a non-empty string id, unique among the walls (or no \"id\")");
      ok = false;
    }
  }
  if (auto* x = optional(v, "thickness")) ok = readFloat(*x, ptr + "/thickness", kThickness, w.thickness) && ok;
  const std::string expected = "a polyline: an array of at least 2 distinct points [x, y] (metres)";
  const Json* line = require(v, ptr, "line", expected);
  if (line == nullptr) return false;
  const std::string lptr = ptr + "/line";
  if (!line->is_array()) {
    error(lptr, "wrong type: " + describeType(*line), expected);
    return false;
  }
  if (line->size() > kMaxPolygonVertices) {
    error(lptr, "line of " + std::to_string(line->size()) + " points",
          "at most " + std::to_string(kMaxPolygonVertices) + " points per wall", "split it into several walls");
    return false;
  }
  w.line.resize(line->size());
  for (std::size_t i = 0; i < line->size(); ++i) ok = readVec2((*line)[i], lptr + "/" + std::to_string(i), w.line[i]) && ok;
  if (!ok) return false;
  const std::vector<core::Vec2> run = distinctRun(w.line);
  if (run.size() < 2) {
    error(lptr, "degenerate wall: " + std::to_string(run.size()) + " distinct point" + (run.size() == 1 ? "" : "s"), expected);
    return false;
  }
  segments = run.size() - 1;
  return true;
}

void ScenarioReader::readWallList(const Json& root, ParsedScenario& out) {
  sim::ScenarioDesc& desc = out.desc;
  out.listedObstacles = desc.obstacles.size();
  const Json* x = optional(root, "walls");
  if (x == nullptr) return;
  const std::string expected = "an array of walls {\"line\": [[x, y], ...], \"thickness\"}";
  if (!x->is_array()) {
    error("/walls", "wrong type: " + describeType(*x), expected);
    return;
  }
  if (multiLevel_) {
    if (!x->empty()) refuseOnLevels("/walls", "\"walls\"", "no \"walls\" next to \"terrain\" (walls as /terrain/obstacles triangles)", true);
    return;
  }
  desc.walls.resize(x->size());
  out.wallsOk.resize(x->size());
  IdRegistry ids;
  std::size_t total = 0;
  for (std::size_t i = 0; i < x->size(); ++i) {
    const std::string ptr = "/walls/" + std::to_string(i);
    std::size_t segments = 0;
    out.wallsOk[i] = readWall((*x)[i], ptr, desc.walls[i], segments);
    const std::string& id = desc.walls[i].id;
    if (!id.empty()) {
      if (const std::size_t first = ids.claim(id, i); first != i) {
        error(ptr + "/id", "duplicate wall id " + quote(id), "ids unique within /walls", "first used at /walls/" + std::to_string(first));
      }
    }
    if (!out.wallsOk[i]) continue;
    total += segments;
    if (total > kMaxWallSegments) {
      error(ptr + "/line", std::to_string(total) + " wall segments so far",
            "at most " + std::to_string(kMaxWallSegments) + " wall segments in all", "simplify the walls");
      out.wallsOk[i] = false;
      return;
    }
    for (core::Polygon& rect : wallFootprints(desc.walls[i])) {
      if (std::abs(core::signedArea(rect)) < 1e-6 || core::checkSimple(rect, 64).crossing) {
        error(ptr + "/thickness", "a segment of this wall is too thin to represent at its coordinates",
              "a thickness well above the float precision at the wall's coordinates (about 1e-7 × |x|)");
        out.wallsOk[i] = false;
        break;
      }
      desc.obstacles.push_back(std::move(rect));
      out.obstaclesOk.push_back(true);
      out.obstacleWall.push_back(static_cast<std::uint32_t>(i));
    }
  }
}

bool ScenarioReader::readMeasurement(const Json& v, const std::string& ptr, sim::MeasurementDesc& m) {
  const std::string regionExpected = "either \"line\": [[x, y], [x, y]] or \"polygon\": [[x, y], ...]";
  if (!isObject(v, ptr, "a measurement {\"id\", \"line\": [[x, y], [x, y]]} or {\"id\", \"polygon\": [...]}")) return false;
  checkKeys(v, ptr, {"id", "line", "polygon"}, "a measurement");
  bool ok = true;
  if (auto* id = require(v, ptr, "id", "a non-empty string id, unique among the measurements")) {
    if (readString(*id, ptr + "/id", "a non-empty string id, unique among the measurements", m.id) && m.id.empty()) {
      error(ptr + "/id", "empty id", "a non-empty string id, unique among the measurements");
      ok = false;
    }
  } else {
    ok = false;
  }
  const Json* line = optional(v, "line");
  const Json* polygon = optional(v, "polygon");
  if (line != nullptr && polygon != nullptr) {
    error(ptr + "/polygon", "a measurement given as a line and an area", regionExpected, "", true);
    return false;
  }
  if (polygon != nullptr) return readPolygon(*polygon, ptr + "/polygon", m.polygon) && ok;
  if (line == nullptr) {
    error(ptr, "measurement has no \"line\" or \"polygon\"", regionExpected);
    return false;
  }
  const std::string lptr = ptr + "/line";
  const std::string expected = "a measurement line: exactly 2 distinct points [[x, y], [x, y]] (metres)";
  if (!line->is_array() || line->size() != 2) {
    error(lptr, line->is_array() ? "line of " + std::to_string(line->size()) + " points" : "wrong type: " + describeType(*line),
          expected);
    return false;
  }
  m.line.resize(2);
  for (std::size_t i = 0; i < 2; ++i) ok = readVec2((*line)[i], lptr + "/" + std::to_string(i), m.line[i]) && ok;
  if (ok && core::length(m.line[1] - m.line[0]) < 1e-6f) {
    error(lptr, "zero-length measurement line", expected);
    return false;
  }
  return ok;
}

void ScenarioReader::readSmokeList(const Json& root, sim::ScenarioDesc& desc) {
  const Json* x = optional(root, "smoke");
  if (x == nullptr) return;
  const std::string expected =
      "an array of smoke regions {\"polygon\": [[x, y], ...], \"extinction\": K (1/m, 0 to 30), \"co\": ppm (optional, 0 to "
      "100000)}";
  if (multiLevel_) {
    refuseOnLevels("/smoke", "smoke", "no \"smoke\" next to \"terrain\"", true);
    return;
  }
  if (!x->is_array()) {
    error("/smoke", "wrong type: " + describeType(*x), expected);
    return;
  }
  if (x->size() > kMaxSmoke) {
    error("/smoke", std::to_string(x->size()) + " smoke regions", "at most " + std::to_string(kMaxSmoke));
    return;
  }
  desc.smoke.resize(x->size());
  for (std::size_t i = 0; i < x->size(); ++i) {
    const std::string ptr = "/smoke/" + std::to_string(i);
    const Json& v = (*x)[i];
    sim::SmokeDesc& smoke = desc.smoke[i];
    if (!isObject(v, ptr, expected)) continue;
    checkKeys(v, ptr, {"polygon", "extinction", "co"}, "a smoke region");
    if (auto* p = require(v, ptr, "polygon", "a polygon [[x, y], ...] (metres)")) readPolygon(*p, ptr + "/polygon", smoke.polygon);
    if (auto* k = require(v, ptr, "extinction", "the extinction coefficient K, a number from 0 to 30 (1/m)")) {
      readFloat(*k, ptr + "/extinction", {0, 30, false, "1/m"}, smoke.extinction);
    }
    if (auto* c = optional(v, "co")) readFloat(*c, ptr + "/co", {0, 100000, false, "ppm"}, smoke.co);
  }
}

void ScenarioReader::readTransportList(const Json& root, sim::ScenarioDesc& desc) {
  const Json* x = optional(root, "transports");
  if (x == nullptr) return;
  const std::string expected =
      "an array of lifts and escalators {\"id\", \"kind\": \"elevator\" or \"escalator\", \"stops\": [point id, ...], ...}";
  if (!x->is_array()) {
    error("/transports", "wrong type: " + describeType(*x), expected);
    return;
  }
  if (x->size() > kMaxTransports) {
    error("/transports", std::to_string(x->size()) + " transports", "at most " + std::to_string(kMaxTransports));
    return;
  }
  desc.transports.resize(x->size());
  IdRegistry ids;
  std::map<std::uint32_t, std::size_t> stopOf;  // point -> the transport it is a stop of
  for (std::size_t i = 0; i < x->size(); ++i) {
    const std::string ptr = "/transports/" + std::to_string(i);
    const Json& v = (*x)[i];
    sim::TransportDesc& t = desc.transports[i];
    if (!isObject(v, ptr, expected)) continue;
    checkKeys(v, ptr,
              {"id", "kind", "stops", "speed", "headway", "capacity", "acceleration", "doorOpenTime", "doorCloseTime",
               "transferTime"},
              "a transport");
    if (auto* id = require(v, ptr, "id", "a non-empty string id, unique among the transports")) {
      if (readString(*id, ptr + "/id", "a non-empty string id, unique among the transports", t.id) && t.id.empty()) {
        error(ptr + "/id", "empty id", "a non-empty string id, unique among the transports");
      } else if (!t.id.empty()) {
        if (const std::size_t first = ids.claim(t.id, i); first != i) {
          error(ptr + "/id", "duplicate transport id " + quote(t.id), "ids unique within /transports",
                "first used at /transports/" + std::to_string(first));
        }
      }
    }
    const bool elevator = readTransportKind(v, ptr, t);
    if (readTransportStops(v, ptr, elevator, desc, t)) {
      for (std::size_t k = 0; k < t.stops.size(); ++k) {
        if (auto [it, fresh] = stopOf.emplace(t.stops[k], i); !fresh && it->second != i) {
          error(ptr + "/stops/" + std::to_string(k), "point " + quote(desc.points[t.stops[k]].id) +
                " is already a stop of /transports/" + std::to_string(it->second), "each point the stop of one transport at most");
        }
      }
    }
    readTransportNumbers(v, ptr, elevator, t);
  }
}

bool ScenarioReader::readTransportKind(const Json& v, const std::string& ptr, sim::TransportDesc& t) {
  const Json* k = require(v, ptr, "kind", "\"elevator\" or \"escalator\"");
  std::string kind;
  if (k == nullptr || !readString(*k, ptr + "/kind", "\"elevator\" or \"escalator\"", kind)) return false;
  if (kind == "elevator") {
    t.kind = sim::TransportKind::Elevator;
    t.speed = 1.0f;  // a lift's default rated speed (sim::TransportDesc::speed)
    return true;
  }
  if (kind == "escalator") {
    t.kind = sim::TransportKind::Escalator;
    return false;
  }
  const std::string match = core::closestMatch(kind, {"elevator", "escalator"});
  error(ptr + "/kind", "unknown transport kind " + quote(kind), "\"elevator\" or \"escalator\"",
        match.empty() ? "" : "did you mean " + quote(match) + "?");
  return false;
}

bool ScenarioReader::readTransportStops(const Json& v, const std::string& ptr, bool elevator, const sim::ScenarioDesc& desc,
                                        sim::TransportDesc& t) {
  const std::string expected =
      elevator ? "2 to " + std::to_string(sim::kMaxElevatorStops) + " different point ids from /points (the floors it serves)"
               : "two different point ids [from, to] from /points (an escalator carries from the first to the second)";
  const Json* st = require(v, ptr, "stops", expected);
  if (st == nullptr) return false;
  const std::size_t most = elevator ? sim::kMaxElevatorStops : 2;
  if (!st->is_array() || st->size() < 2 || st->size() > most) {
    error(ptr + "/stops", st->is_array() ? std::to_string(st->size()) + " stops" : "wrong type: " + describeType(*st), expected);
    return false;
  }
  t.stops.assign(st->size(), 0);
  bool ok = true;
  for (std::size_t k = 0; k < st->size(); ++k) ok = resolvePoint((*st)[k], ptr + "/stops/" + std::to_string(k), t.stops[k]) && ok;
  for (std::size_t k = 1; ok && k < t.stops.size(); ++k) {
    const auto earlier = t.stops.begin() + static_cast<std::ptrdiff_t>(k);
    if (std::find(t.stops.begin(), earlier, t.stops[k]) != earlier) {
      error(ptr + "/stops/" + std::to_string(k), "the same point as an earlier stop", expected);
      ok = false;
    }
  }
  for (std::size_t k = 0; ok && k < t.stops.size(); ++k) {
    if (desc.points[t.stops[k]].kind != sim::PointKind::Interest) {
      error(ptr + "/stops/" + std::to_string(k), "point " + quote(desc.points[t.stops[k]].id) + " is no interest point",
            "a point of kind \"interest\" (where people board and alight)");
      ok = false;
    }
  }
  return ok;
}

void ScenarioReader::readTransportNumbers(const Json& v, const std::string& ptr, bool elevator, sim::TransportDesc& t) {
  if (auto* y = optional(v, "speed")) {
    readFloat(*y, ptr + "/speed", elevator ? Range{0.1, 10, false, "m/s"} : Range{0.1, 2, false, "m/s"}, t.speed);
  }
  // A key of the other kind is an error at the key.
  const auto only = [&](const char* key, bool forElevator) -> const Json* {
    const Json* y = optional(v, key);
    if (y != nullptr && forElevator != elevator) {
      error(ptr + "/" + key, std::string("\"") + key + "\" is for " + (forElevator ? "an elevator" : "an escalator"),
            "no \"" + std::string(key) + "\" on an " + (forElevator ? "escalator" : "elevator"), "", true);
      return nullptr;
    }
    return y;
  };
  if (auto* y = only("headway", false)) readFloat(*y, ptr + "/headway", {0.2, 60, false, "s"}, t.headway);
  if (auto* y = only("capacity", true)) {
    double c = 0;
    if (readInteger(*y, ptr + "/capacity", 1, 100, "persons", c)) t.capacity = static_cast<std::uint32_t>(c);
  }
  if (auto* y = only("acceleration", true)) readFloat(*y, ptr + "/acceleration", {0.1, 5, false, "m/s²"}, t.acceleration);
  if (auto* y = only("doorOpenTime", true)) readFloat(*y, ptr + "/doorOpenTime", {0, 60, false, "s"}, t.doorOpenTime);
  if (auto* y = only("doorCloseTime", true)) readFloat(*y, ptr + "/doorCloseTime", {0, 60, false, "s"}, t.doorCloseTime);
  if (auto* y = only("transferTime", true)) readFloat(*y, ptr + "/transferTime", {0, 60, false, "s"}, t.transferTime);
}

void ScenarioReader::readMeasurementList(const Json& root, ParsedScenario& out) {
  const Json* x = optional(root, "measurements");
  if (x == nullptr) return;
  const std::string expected = "an array of measurement lines {\"id\", \"line\"} and areas {\"id\", \"polygon\"}";
  if (!x->is_array()) {
    error("/measurements", "wrong type: " + describeType(*x), expected);
    return;
  }
  if (x->size() > kMaxMeasurements) {
    error("/measurements", std::to_string(x->size()) + " measurements", "at most " + std::to_string(kMaxMeasurements));
    return;
  }
  sim::ScenarioDesc& desc = out.desc;
  desc.measurements.resize(x->size());
  out.measurementsOk.resize(x->size());
  IdRegistry ids;
  for (std::size_t i = 0; i < x->size(); ++i) {
    const std::string ptr = "/measurements/" + std::to_string(i);
    out.measurementsOk[i] = readMeasurement((*x)[i], ptr, desc.measurements[i]);
    const std::string& id = desc.measurements[i].id;
    if (id.empty()) continue;
    if (const std::size_t first = ids.claim(id, i); first != i) {
      error(ptr + "/id", "duplicate measurement id " + quote(id), "ids unique within /measurements",
            "first used at /measurements/" + std::to_string(first));
    }
  }
}

}  // namespace detail

std::vector<core::Polygon> wallFootprints(const sim::WallDesc& wall) {
  std::vector<core::Polygon> out;
  const std::vector<core::Vec2> run = detail::distinctRun(wall.line);
  const double h = 0.5 * double(wall.thickness);
  for (std::size_t i = 0; i + 1 < run.size(); ++i) {
    const double ax = run[i].x, ay = run[i].y, bx = run[i + 1].x, by = run[i + 1].y;
    const double len = std::hypot(bx - ax, by - ay);
    const double dx = (bx - ax) / len * h, dy = (by - ay) / len * h;  // along, half a thickness long
    const double nx = -dy, ny = dx;                                    // to the left, likewise
    const auto corner = [](double x, double y) { return core::Vec2(static_cast<float>(x), static_cast<float>(y)); };
    out.push_back({corner(ax - dx - nx, ay - dy - ny), corner(bx + dx - nx, by + dy - ny), corner(bx + dx + nx, by + dy + ny),
                   corner(ax - dx + nx, ay - dy + ny)});
  }
  return out;
}

std::string obstaclePointer(const ParsedScenario& parsed, std::size_t k) {
  if (k >= parsed.listedObstacles && k - parsed.listedObstacles < parsed.obstacleWall.size()) {
    return "/walls/" + std::to_string(parsed.obstacleWall[k - parsed.listedObstacles]);
  }
  return "/obstacles/" + std::to_string(k);
}

}  // namespace throng::io
