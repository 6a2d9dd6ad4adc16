// throng::io scenario parser — walks the JSON tree of a "throng/1" scenario and fills a
// sim::ScenarioDesc. Every object's keys are checked against its schema (unknown keys get a
// "did you mean"), every value's type and range (with units), every polygon's shape, every id
// reference. Reads a JsonDocument; writes ParsedScenario and diagnostics; never stops early.
#include "scenario_parser.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <limits>
#include <map>

namespace throng::io {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kMinPolygonArea = 1e-6;  ///< [m²] below this a polygon is degenerate

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string quote(const std::string& s) {
  std::string q = "\"";
  for (const char c : s.substr(0, 80)) q += (static_cast<unsigned char>(c) < 0x20) ? '?' : c;
  if (s.size() > 80) q += "...";
  return q + "\"";
}

/// A closed or half-open interval of numbers with a unit ("s", "m", "m/s"; empty for counts).
struct Range {
  double lo = -kInf;
  double hi = kInf;
  bool loOpen = false;
  std::string unit;

  [[nodiscard]] bool contains(double v) const { return (loOpen ? v > lo : v >= lo) && v <= hi; }
  [[nodiscard]] std::string describe(const std::string& noun) const {
    const std::string u = unit.empty() ? "" : " " + unit;
    if (hi == kInf) return noun + (loOpen ? " > " : " >= ") + num(lo) + u;
    if (lo == -kInf) return noun + " <= " + num(hi) + u;
    if (loOpen) return noun + " > " + num(lo) + " and <= " + num(hi) + u;
    return noun + " from " + num(lo) + (loOpen ? " (exclusive)" : "") + " to " + num(hi) + u;
  }
};

/// Parser state shared by all the read functions: the document (for positions) and the output.
class Parser {
 public:
  Parser(const JsonDocument& doc, core::Diagnostics& diags) : doc_(doc), diags_(diags) {}

  ParsedScenario run();

 private:
  void error(const std::string& ptr, std::string what, std::string expected, std::string hint = {}, bool atKey = false) {
    diags_.push_back(doc_.diagnostic(ptr, std::move(what), std::move(expected), std::move(hint), atKey));
  }

  /// Reports unknown keys of `obj` (at the key's position, with a "did you mean").
  void checkKeys(const Json& obj, const std::string& ptr, const std::vector<std::string>& allowed, const std::string& what) {
    for (const auto& [key, value] : obj.items()) {
      if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      const std::string match = core::closestMatch(key, allowed);
      error(ptr + "/" + escapePointerToken(key), "unknown key " + quote(key) + " in " + what, "one of: " + list,
            match.empty() ? "" : "did you mean " + quote(match) + "?", true);
    }
  }

  bool isObject(const Json& v, const std::string& ptr, const std::string& expected) {
    if (v.is_object()) return true;
    error(ptr, "wrong type: " + describeType(v), expected);
    return false;
  }

  const Json* require(const Json& obj, const std::string& ptr, const std::string& key, const std::string& expected) {
    if (auto it = obj.find(key); it != obj.end()) return &*it;
    error(ptr, "missing required key " + quote(key), expected);
    return nullptr;
  }

  static const Json* optional(const Json& obj, const std::string& key) {
    auto it = obj.find(key);
    return it == obj.end() ? nullptr : &*it;
  }

  bool readNumber(const Json& v, const std::string& ptr, const Range& range, double& out) {
    if (!v.is_number()) {
      error(ptr, "wrong type: " + describeType(v), range.describe("a number"));
      return false;
    }
    const double d = v.get<double>();
    if (!range.contains(d)) {
      error(ptr, "value " + num(d) + (range.unit.empty() ? "" : " " + range.unit) + " is out of range",
            range.describe("a number"));
      return false;
    }
    out = d;
    return true;
  }

  bool readFloat(const Json& v, const std::string& ptr, const Range& range, float& out) {
    double d;
    if (!readNumber(v, ptr, range, d)) return false;
    out = static_cast<float>(d);
    return true;
  }

  /// An integer (JSON integers, or numbers with no fractional part) within [lo, hi].
  bool readInteger(const Json& v, const std::string& ptr, double lo, double hi, const std::string& unit, double& out) {
    const Range range{lo, hi, false, unit};
    if (!v.is_number()) {
      error(ptr, "wrong type: " + describeType(v), range.describe("an integer"));
      return false;
    }
    const double d = v.get<double>();
    if (d != std::floor(d)) {
      error(ptr, "value " + num(d) + " is not a whole number", range.describe("an integer"));
      return false;
    }
    if (!range.contains(d)) {
      error(ptr, "value " + num(d) + (unit.empty() ? "" : " " + unit) + " is out of range", range.describe("an integer"));
      return false;
    }
    out = d;
    return true;
  }

  bool readBool(const Json& v, const std::string& ptr, bool& out) {
    if (!v.is_boolean()) {
      error(ptr, "wrong type: " + describeType(v), "true or false");
      return false;
    }
    out = v.get<bool>();
    return true;
  }

  bool readString(const Json& v, const std::string& ptr, const std::string& expected, std::string& out) {
    if (!v.is_string()) {
      error(ptr, "wrong type: " + describeType(v), expected);
      return false;
    }
    out = v.get<std::string>();
    return true;
  }

  /// A motion clip path: a non-empty relative path (resolved against the scenario's directory).
  void readClipPath(const Json& v, const std::string& ptr, std::string& out) {
    const std::string expected = "a BVH file path relative to the scenario (\"motions/look.bvh\")";
    std::string path;
    if (!readString(v, ptr, expected, path)) return;
    if (path.empty()) error(ptr, "empty clip path", expected);
    else if (path.front() == '/' || path.front() == '\\' || (path.size() > 1 && path[1] == ':'))
      error(ptr, "absolute clip path " + quote(path), expected, "scenarios stay portable with relative paths");
    else if (path.find('\0') != std::string::npos) error(ptr, "clip path contains a NUL character", expected);
    else out = path;
  }

  /// One of `options` (a string); an unknown one gets a "did you mean". `out` is its index.
  bool readChoice(const Json& v, const std::string& ptr, const std::vector<std::string>& options, const std::string& noun,
                  std::size_t& out) {
    std::string expected;
    for (std::size_t i = 0; i < options.size(); ++i) {
      expected += (i == 0 ? "" : i + 1 == options.size() ? " or " : ", ") + quote(options[i]);
    }
    std::string s;
    if (!readString(v, ptr, expected, s)) return false;
    if (const auto it = std::find(options.begin(), options.end(), s); it != options.end()) {
      out = static_cast<std::size_t>(it - options.begin());
      return true;
    }
    const std::string match = core::closestMatch(s, options);
    error(ptr, "unknown " + noun + " " + quote(s), expected, match.empty() ? "" : "did you mean " + quote(match) + "?");
    return false;
  }

  /// An interval [min, max] of two numbers, each within `range`, with min <= max.
  bool readInterval(const Json& v, const std::string& ptr, const Range& range, float& lo, float& hi) {
    const std::string expected = "[min, max] with min <= max, each " + range.describe("a number");
    if (!v.is_array() || v.size() != 2) {
      error(ptr, v.is_array() ? "interval has " + std::to_string(v.size()) + " entries" : "wrong type: " + describeType(v),
            expected);
      return false;
    }
    float a = lo, b = hi;
    const bool aOk = readFloat(v[0], ptr + "/0", range, a);
    const bool bOk = readFloat(v[1], ptr + "/1", range, b);
    if (!aOk || !bOk) return false;
    if (a > b) {
      error(ptr, "interval [" + num(a) + ", " + num(b) + "] " + range.unit + " is empty", expected);
      return false;
    }
    lo = a;
    hi = b;
    return true;
  }

  /// A float field of an object, read only when present.
  struct FloatKey {
    const char* key;
    Range range;
    float* out;
  };
  bool readFloatKeys(const Json& obj, const std::string& ptr, std::initializer_list<FloatKey> keys) {
    bool ok = true;
    for (const FloatKey& k : keys) {
      if (auto* x = optional(obj, k.key)) ok = readFloat(*x, ptr + "/" + k.key, k.range, *k.out) && ok;
    }
    return ok;
  }

  bool readVec2(const Json& v, const std::string& ptr, core::Vec2& out) {
    const std::string expected = "a point [x, y] of two numbers in metres, |x|, |y| <= " + num(kMaxCoordinate);
    if (!v.is_array() || v.size() != 2) {
      error(ptr, v.is_array() ? "point has " + std::to_string(v.size()) + " coordinates" : "wrong type: " + describeType(v),
            expected);
      return false;
    }
    bool ok = true;
    double c[2] = {0, 0};
    const Range r{-kMaxCoordinate, kMaxCoordinate, false, "m"};
    for (int i = 0; i < 2; ++i) ok = readNumber(v[static_cast<std::size_t>(i)], ptr + "/" + std::to_string(i), r, c[i]) && ok;
    out = core::Vec2(static_cast<float>(c[0]), static_cast<float>(c[1]));
    return ok;
  }

  bool readPolygon(const Json& v, const std::string& ptr, core::Polygon& out);
  void readSteering(const Json& v, const std::string& ptr, sim::SteeringDesc& s);
  bool readPoint(const Json& v, const std::string& ptr, sim::PointDesc& p);
  bool readPopulation(const Json& v, const std::string& ptr, std::size_t index, sim::PopulationDesc& p);
  bool readSpawn(const Json& v, const std::string& ptr, sim::SpawnDesc& s);
  bool readSpeed(const Json& v, const std::string& ptr, sim::PopulationDesc& p);
  bool readGoals(const Json& v, const std::string& ptr, sim::PopulationDesc& p);
  bool readCrowdKeys(const Json& v, const std::string& ptr, std::size_t index, sim::PopulationDesc& p);
  bool readFollow(const Json& v, const std::string& ptr, std::size_t index, sim::FollowDesc& f);
  bool readGuide(const Json& v, const std::string& ptr, sim::GuideDesc& g);
  bool readGuideScript(const Json& v, const std::string& ptr, std::vector<sim::GuideWaypoint>& out, bool& firstTimeOk);
  bool readSociological(const Json& v, const std::string& ptr, sim::SociologicalDesc& s);
  void resolveFollows(ParsedScenario& out);
  bool resolvePoint(const Json& v, const std::string& ptr, std::uint32_t& out);
  void readPolygonList(const Json& root, const std::string& key, bool required, std::vector<core::Polygon>& out,
                       std::vector<bool>& ok);

  const JsonDocument& doc_;
  core::Diagnostics& diags_;
  std::vector<std::string> pointIds_;
  bool hasActionPoint_ = false;  ///< "goals": "auto" draws its final goal among the action points
  /// A "follow" whose population id is resolved once every population has been read.
  struct PendingFollow {
    std::size_t population;  ///< the following population
    std::string target;      ///< id of the followed one
    std::string pointer;     ///< of the "follow" object
  };
  std::vector<PendingFollow> follows_;
};

bool Parser::readPolygon(const Json& v, const std::string& ptr, core::Polygon& out) {
  const std::string expected = "a polygon: an array of at least 3 points [x, y] (metres, any winding)";
  if (!v.is_array()) {
    error(ptr, "wrong type: " + describeType(v), expected);
    return false;
  }
  bool ok = true;
  core::Polygon raw(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) ok = readVec2(v[i], ptr + "/" + std::to_string(i), raw[i]) && ok;
  if (!ok) return false;
  std::vector<std::size_t> original;
  out = normalizePolygon(raw, original);
  if (out.size() < 3) {
    error(ptr, "degenerate polygon: " + std::to_string(out.size()) + " distinct point" + (out.size() == 1 ? "" : "s"),
          "at least 3 distinct points");
    return false;
  }
  const auto zeroArea = [&] {
    error(ptr, "degenerate polygon: zero area (all points on one line)", "a polygon enclosing an area > 0 m²");
    return false;
  };
  bool collinear = true;
  for (std::size_t i = 2; i < out.size() && collinear; ++i) {
    collinear = std::abs(core::cross(out[1] - out[0], out[i] - out[0])) < 1e-9f;
  }
  if (collinear) return zeroArea();
  if (const auto hit = core::findSelfIntersection(out)) {
    const std::size_t n = out.size();
    const auto edge = [&](std::size_t e) {
      return std::to_string(original[e]) + "→" + std::to_string(original[(e + 1) % n]);
    };
    error(ptr + "/" + std::to_string(original[hit->second]),
          "self-intersecting polygon: edge " + edge(hit->second) + " crosses edge " + edge(hit->first),
          "a simple polygon (edges meet only at consecutive vertices)",
          "split it into several polygons or reorder the points");
    return false;
  }
  if (std::abs(core::signedArea(out)) < kMinPolygonArea) return zeroArea();
  return true;
}

void Parser::readPolygonList(const Json& root, const std::string& key, bool required, std::vector<core::Polygon>& out,
                             std::vector<bool>& ok) {
  const std::string ptr = "/" + key;
  const std::string expected = "an array of polygons (each an array of [x, y] points in metres)";
  const Json* v = required ? require(root, "", key, expected) : optional(root, key);
  if (v == nullptr) return;
  if (!v->is_array()) {
    error(ptr, "wrong type: " + describeType(*v), expected);
    return;
  }
  if (required && v->empty()) error(ptr, "no walkable polygon", "at least one polygon");
  out.resize(v->size());
  ok.resize(v->size());
  for (std::size_t i = 0; i < v->size(); ++i) ok[i] = readPolygon((*v)[i], ptr + "/" + std::to_string(i), out[i]);
}

void Parser::readSteering(const Json& v, const std::string& ptr, sim::SteeringDesc& s) {
  if (!isObject(v, ptr, "an object of steering parameters")) return;
  checkKeys(v, ptr,
            {"timeHorizon", "timeHorizonObstacle", "neighbourDistance", "maxNeighbours", "accelerationTime",
             "denseNeighbourDistance", "denseThreshold", "lodDistance"},
            "steering");
  const bool rangeOk = readFloatKeys(v, ptr, {{"timeHorizon", {0, 60, true, "s"}, &s.timeHorizon},
                                              {"timeHorizonObstacle", {0, 60, true, "s"}, &s.timeHorizonObstacle},
                                              {"neighbourDistance", {0, 100, true, "m"}, &s.neighbourDistance},
                                              {"accelerationTime", {0, 60, true, "s"}, &s.accelerationTime}});
  if (auto* x = optional(v, "maxNeighbours")) {
    double d;
    if (readInteger(*x, ptr + "/maxNeighbours", 1, 1000, "agents", d)) s.maxNeighbours = static_cast<std::uint32_t>(d);
  }
  // The crowd model's density-dependent range and multiresolution (Musse et al. §3.2.4).
  readFloatKeys(v, ptr, {{"denseThreshold", {0, 100, true, "agents/m²"}, &s.denseThreshold},
                         {"lodDistance", {0, 1e6, false, "m"}, &s.lodDistance}});
  if (auto* x = optional(v, "denseNeighbourDistance")) {
    const std::string dptr = ptr + "/denseNeighbourDistance";
    if (readFloat(*x, dptr, {0, 100, false, "m"}, s.denseNeighbourDistance) && rangeOk &&
        s.denseNeighbourDistance > s.neighbourDistance) {
      error(dptr,
            "dense neighbour distance " + num(s.denseNeighbourDistance) + " m exceeds neighbourDistance " +
                num(s.neighbourDistance) + " m",
            "a number from 0 (off) to neighbourDistance (" + num(s.neighbourDistance) + " m)",
            "the dense range d shrinks the normal range D where the crowd is dense: d <= D");
    }
  }
}

bool Parser::readPoint(const Json& v, const std::string& ptr, sim::PointDesc& p) {
  if (!isObject(v, ptr, "a point object {\"id\", \"kind\", \"position\"+\"radius\" or \"polygon\"}")) return false;
  checkKeys(v, ptr,
            {"id", "kind", "position", "radius", "polygon", "stop", "orientation", "action", "duration", "clip"},
            "a point");
  bool ok = true;
  if (auto* id = require(v, ptr, "id", "a unique non-empty string id")) {
    if (readString(*id, ptr + "/id", "a unique non-empty string id", p.id) && p.id.empty()) {
      error(ptr + "/id", "empty id", "a unique non-empty string id");
    }
  }
  if (auto* kind = require(v, ptr, "kind", "\"interest\", \"action\" or \"exit\"")) {
    std::string k;
    if (readString(*kind, ptr + "/kind", "\"interest\", \"action\" or \"exit\"", k)) {
      if (k == "interest") p.kind = sim::PointKind::Interest;
      else if (k == "action") p.kind = sim::PointKind::Action;
      else if (k == "exit") p.kind = sim::PointKind::Exit;
      else {
        const std::string match = core::closestMatch(k, {"interest", "action", "exit"});
        error(ptr + "/kind", "unknown point kind " + quote(k), "\"interest\", \"action\" or \"exit\"",
              match.empty() ? "" : "did you mean " + quote(match) + "?");
      }
    }
  }
  const Json* position = optional(v, "position");
  const Json* radius = optional(v, "radius");
  const Json* polygon = optional(v, "polygon");
  const std::string regionExpected = "either \"position\" (with optional \"radius\") or \"polygon\"";
  if (polygon != nullptr && (position != nullptr || radius != nullptr)) {
    error(ptr + (position ? "/position" : "/radius"), "a point's region given twice (polygon and disc)", regionExpected,
          "", true);
    ok = false;
  } else if (polygon != nullptr) {
    ok = readPolygon(*polygon, ptr + "/polygon", p.polygon) && ok;
    if (ok) p.position = core::centroid(p.polygon);
  } else if (position != nullptr) {
    ok = readVec2(*position, ptr + "/position", p.position) && ok;
    p.radius = 0.5f;
    if (radius != nullptr) ok = readFloat(*radius, ptr + "/radius", {0, 1000, true, "m"}, p.radius) && ok;
  } else {
    error(ptr, "point has no region", regionExpected);
    ok = false;
  }
  // Action-only keys: stop, orientation, action, duration, clip (loaded by scenario_clips).
  const bool action = p.kind == sim::PointKind::Action;
  if (action) p.stop = true;
  for (const char* key : {"stop", "orientation", "action", "duration", "clip"}) {
    const Json* x = optional(v, key);
    if (x == nullptr) continue;
    const std::string kptr = ptr + "/" + key;
    if (!action) {
      error(kptr, std::string("\"") + key + "\" only applies to action points", std::string("\"kind\": \"action\" or no \"") + key + "\"",
            "", true);
      continue;
    }
    const std::string k = key;
    if (k == "stop") readBool(*x, kptr, p.stop);
    else if (k == "action") readString(*x, kptr, "the name of an action (a string)", p.action);
    else if (k == "duration") readFloat(*x, kptr, {0, 86400, false, "s"}, p.actionDuration);
    else if (k == "clip") readClipPath(*x, kptr, p.clip);
    else if (readVec2(*x, kptr, p.orientation)) {
      if (core::length(p.orientation) < 1e-6f) error(kptr, "zero orientation vector", "a non-zero direction [x, y]");
      else p.orientation = core::normalize(p.orientation);
    }
  }
  return ok;
}

bool Parser::resolvePoint(const Json& v, const std::string& ptr, std::uint32_t& out) {
  std::string id;
  if (!readString(v, ptr, "the id of a point in /points (a string)", id)) return false;
  for (std::size_t i = 0; i < pointIds_.size(); ++i) {
    if (pointIds_[i] == id) {
      out = static_cast<std::uint32_t>(i);
      return true;
    }
  }
  const std::string match = core::closestMatch(id, pointIds_);
  error(ptr, "unknown point " + quote(id), "an id from /points", match.empty() ? "" : "did you mean " + quote(match) + "?");
  return false;
}

bool Parser::readSpawn(const Json& v, const std::string& ptr, sim::SpawnDesc& s) {
  const std::string expected = "an object with one of \"polygon\", \"position\" or \"point\"";
  if (!isObject(v, ptr, expected)) return false;
  checkKeys(v, ptr, {"polygon", "position", "point"}, "a spawn");
  if (v.size() != 1) {
    if (v.empty()) error(ptr, "empty spawn", expected);
    else error(ptr, "spawn has " + std::to_string(v.size()) + " forms", "exactly one of \"polygon\", \"position\" or \"point\"");
    return false;
  }
  if (auto* x = optional(v, "polygon")) {
    s.kind = sim::SpawnKind::Polygon;
    return readPolygon(*x, ptr + "/polygon", s.polygon);
  }
  if (auto* x = optional(v, "position")) {
    s.kind = sim::SpawnKind::Position;
    return readVec2(*x, ptr + "/position", s.position);
  }
  if (auto* x = optional(v, "point")) {
    s.kind = sim::SpawnKind::Point;
    return resolvePoint(*x, ptr + "/point", s.point);
  }
  return false;  // the unknown key was reported by checkKeys
}

bool Parser::readSpeed(const Json& v, const std::string& ptr, sim::PopulationDesc& p) {
  const Range speedRange{0, 10, true, "m/s"};
  if (v.is_number()) {
    if (!readFloat(v, ptr, speedRange, p.speedMean)) return false;
    p.speedSd = 0.0f;
    p.speedMin = std::min(p.speedMin, p.speedMean);  // a fixed speed is never clipped
    p.speedMax = std::max(p.speedMax, p.speedMean);
    return true;
  }
  if (!v.is_object()) {
    error(ptr, "wrong type: " + describeType(v), "a speed in m/s, or {\"mean\", \"sd\", \"min\", \"max\"} in m/s");
    return false;
  }
  checkKeys(v, ptr, {"mean", "sd", "min", "max"}, "a speed distribution");
  bool ok = true;
  if (auto* x = require(v, ptr, "mean", speedRange.describe("a number"))) ok = readFloat(*x, ptr + "/mean", speedRange, p.speedMean) && ok;
  if (auto* x = optional(v, "sd")) ok = readFloat(*x, ptr + "/sd", {0, 5, false, "m/s"}, p.speedSd) && ok;
  if (auto* x = optional(v, "min")) ok = readFloat(*x, ptr + "/min", speedRange, p.speedMin) && ok;
  if (auto* x = optional(v, "max")) ok = readFloat(*x, ptr + "/max", speedRange, p.speedMax) && ok;
  if (ok && p.speedMin > p.speedMax) {
    error(ptr + "/min", "min speed " + num(p.speedMin) + " m/s exceeds max speed " + num(p.speedMax) + " m/s",
          "min <= max");
    ok = false;
  }
  if (ok && (p.speedMean < p.speedMin || p.speedMean > p.speedMax)) {
    error(ptr + "/mean", "mean speed " + num(p.speedMean) + " m/s lies outside [min, max] = [" + num(p.speedMin) + ", " +
                             num(p.speedMax) + "] m/s",
          "min <= mean <= max");
    ok = false;
  }
  return ok;
}

bool Parser::readPopulation(const Json& v, const std::string& ptr, std::size_t index, sim::PopulationDesc& p) {
  if (!isObject(v, ptr, "a population object {\"id\", \"groups\", \"size\", \"spawn\", \"goals\", ...}")) return false;
  checkKeys(v, ptr,
            {"id", "groups", "size", "spawn", "start", "goals", "speed", "radius", "wander", "paths", "autoNearDistance",
             "flocking", "waitTimeout", "groupSpacing", "follow", "guide", "sociological"},
            "a population");
  bool ok = true;
  p.id = "population" + std::to_string(index);
  if (auto* x = optional(v, "id")) ok = readString(*x, ptr + "/id", "a string id", p.id) && ok;
  double d;
  if (auto* x = optional(v, "groups")) {
    if (readInteger(*x, ptr + "/groups", 1, kMaxAgents, "groups", d)) p.groups = static_cast<std::uint32_t>(d);
    else ok = false;
  }
  if (auto* x = optional(v, "size")) {
    const std::string sp = ptr + "/size";
    if (x->is_array()) {
      if (x->size() != 2) {
        error(sp, "size range has " + std::to_string(x->size()) + " entries", "[min, max] with 1 <= min <= max <= 1000 agents");
        ok = false;
      } else {
        double lo = 1, hi = 1;
        const bool a = readInteger((*x)[0], sp + "/0", 1, 1000, "agents", lo);
        const bool b = readInteger((*x)[1], sp + "/1", 1, 1000, "agents", hi);
        if (a && b && lo > hi) {
          error(sp, "size range [" + num(lo) + ", " + num(hi) + "] is empty", "[min, max] with min <= max");
          ok = false;
        } else if (a && b) {
          p.sizeMin = static_cast<std::uint32_t>(lo);
          p.sizeMax = static_cast<std::uint32_t>(hi);
        } else {
          ok = false;
        }
      }
    } else if (x->is_number()) {
      if (readInteger(*x, sp, 1, 1000, "agents", d)) p.sizeMin = p.sizeMax = static_cast<std::uint32_t>(d);
      else ok = false;
    } else {
      error(sp, "wrong type: " + describeType(*x), "a group size (integer, agents) or a range [min, max]");
      ok = false;
    }
  }
  if (double(p.groups) * double(p.sizeMax) > kMaxAgents) {
    error(ptr + "/groups", num(double(p.groups) * p.sizeMax) + " agents", "at most " + num(kMaxAgents) + " agents per population");
    ok = false;
  }
  if (auto* x = require(v, ptr, "spawn", "{\"polygon\": [...]}, {\"position\": [x, y]} or {\"point\": \"id\"}")) {
    ok = readSpawn(*x, ptr + "/spawn", p.spawn) && ok;
  } else {
    ok = false;
  }
  if (auto* x = optional(v, "start")) ok = readFloat(*x, ptr + "/start", {0, 1e6, false, "s"}, p.start) && ok;
  if (auto* x = optional(v, "goals")) ok = readGoals(*x, ptr + "/goals", p) && ok;
  if (auto* x = optional(v, "speed")) ok = readSpeed(*x, ptr + "/speed", p) && ok;
  if (auto* x = optional(v, "radius")) ok = readFloat(*x, ptr + "/radius", {0.05, 1.0, false, "m"}, p.radius) && ok;
  if (auto* x = optional(v, "wander")) ok = readBool(*x, ptr + "/wander", p.wander) && ok;
  return readCrowdKeys(v, ptr, index, p) && ok;
}

bool Parser::readGoals(const Json& v, const std::string& ptr, sim::PopulationDesc& p) {
  const std::string expected = "an array of point ids from /points, or \"auto\"";
  if (v.is_string()) {
    // Automatic goals (Musse et al. §3.1.2): a final action point drawn per group, the interest
    // points near a curve to it on the way.
    const std::string s = v.get<std::string>();
    if (s != "auto") {
      std::string hint;
      if (std::find(pointIds_.begin(), pointIds_.end(), s) != pointIds_.end()) hint = "for one goal write [" + quote(s) + "]";
      else if (!core::closestMatch(s, {"auto"}).empty()) hint = "did you mean \"auto\"?";
      error(ptr, "unknown goals mode " + quote(s), expected, hint);
      return false;
    }
    if (!hasActionPoint_) {
      error(ptr, "\"goals\": \"auto\" needs at least one point of kind \"action\"",
            "an action point in /points (each group's final goal is drawn among them)",
            "add a point with \"kind\": \"action\", or list the goals");
      return false;
    }
    p.autoGoals = true;
    p.goals.clear();
    return true;
  }
  if (!v.is_array()) {
    error(ptr, "wrong type: " + describeType(v), expected);
    return false;
  }
  bool ok = true;
  for (std::size_t g = 0; g < v.size(); ++g) {
    std::uint32_t index = 0;
    if (resolvePoint(v[g], ptr + "/" + std::to_string(g), index)) p.goals.push_back(index);
    else ok = false;
  }
  return ok;
}

/// The Musse et al. crowd-model keys of a population (group behaviour, paths, following,
/// guidance, sociological effects); see docs/scenario-format.md "Crowd model".
bool Parser::readCrowdKeys(const Json& v, const std::string& ptr, std::size_t index, sim::PopulationDesc& p) {
  bool ok = readFloatKeys(v, ptr, {{"autoNearDistance", {0, 1000, true, "m"}, &p.autoNearDistance},
                                   {"waitTimeout", {0, 1e6, true, "s"}, &p.waitTimeout},
                                   {"groupSpacing", {0.3, 3, false, "m"}, &p.groupSpacing}});
  if (auto* x = optional(v, "paths")) {
    std::size_t kind = 0;
    if (readChoice(*x, ptr + "/paths", {"navmesh", "bezier"}, "path kind", kind)) p.bezierPaths = kind == 1;
    else ok = false;
  }
  if (auto* x = optional(v, "flocking")) ok = readBool(*x, ptr + "/flocking", p.flocking) && ok;
  if (auto* x = optional(v, "follow")) ok = readFollow(*x, ptr + "/follow", index, p.follow) && ok;
  if (auto* x = optional(v, "guide")) ok = readGuide(*x, ptr + "/guide", p.guide) && ok;
  if (auto* x = optional(v, "sociological")) ok = readSociological(*x, ptr + "/sociological", p.sociological) && ok;
  return ok;
}

bool Parser::readFollow(const Json& v, const std::string& ptr, std::size_t index, sim::FollowDesc& f) {
  if (!isObject(v, ptr, "a follow object {\"population\", \"group\", \"mode\", \"on\", \"off\"}")) return false;
  checkKeys(v, ptr, {"population", "group", "mode", "on", "off"}, "follow");
  bool ok = true;
  const std::string popExpected = "the id of another population in /populations (a string)";
  if (auto* x = require(v, ptr, "population", popExpected)) {
    std::string target;
    if (readString(*x, ptr + "/population", popExpected, target)) follows_.push_back({index, target, ptr});
    else ok = false;
  } else {
    ok = false;
  }
  f.mode = sim::FollowMode::Permanent;
  bool modeOk = true;
  if (auto* x = optional(v, "mode")) {
    std::size_t mode = 0;
    modeOk = readChoice(*x, ptr + "/mode", {"permanent", "temporary"}, "follow mode", mode);
    if (mode == 1) f.mode = sim::FollowMode::Temporary;
    ok = modeOk && ok;
  }
  if (auto* x = optional(v, "group")) {
    double d;
    // Checked against the followed population's "groups" by resolveFollows.
    if (readInteger(*x, ptr + "/group", 0, kMaxAgents, "", d)) f.group = static_cast<std::uint32_t>(d);
    else ok = false;
  }
  const Range period{0, 1e6, true, "s"};
  for (const char* key : {"on", "off"}) {
    const Json* x = optional(v, key);
    if (x == nullptr || !modeOk) continue;
    const std::string kptr = ptr + "/" + key;
    if (f.mode != sim::FollowMode::Temporary) {
      error(kptr, std::string("\"") + key + "\" only applies to temporary following",
            std::string("\"mode\": \"temporary\" or no \"") + key + "\"", "", true);
      ok = false;
    } else if (std::string(key) == "on") {
      ok = readInterval(*x, kptr, period, f.onMin, f.onMax) && ok;
    } else {
      ok = readInterval(*x, kptr, period, f.offMin, f.offMax) && ok;
    }
  }
  return ok;
}

void Parser::resolveFollows(ParsedScenario& out) {
  std::vector<std::string> ids;
  for (const auto& p : out.desc.populations) ids.push_back(p.id);
  for (const PendingFollow& pf : follows_) {
    sim::PopulationDesc& pop = out.desc.populations[pf.population];
    const std::string pptr = pf.pointer + "/population";
    const auto it = std::find(ids.begin(), ids.end(), pf.target);
    const std::size_t target = static_cast<std::size_t>(it - ids.begin());
    bool ok = true;
    if (it == ids.end()) {
      std::vector<std::string> others = ids;
      others.erase(others.begin() + static_cast<std::ptrdiff_t>(pf.population));
      const std::string match = core::closestMatch(pf.target, others);
      error(pptr, "unknown population " + quote(pf.target), "an id from /populations",
            match.empty() ? "" : "did you mean " + quote(match) + "?");
      ok = false;
    } else if (target == pf.population) {
      error(pptr, "a population cannot follow itself", "the id of another population in /populations");
      ok = false;
    } else if (out.populationsOk[target] && pop.follow.group >= out.desc.populations[target].groups) {
      const std::uint32_t groups = out.desc.populations[target].groups;
      error(pf.pointer + "/group",
            "group " + std::to_string(pop.follow.group) + " is out of range: population " + quote(pf.target) + " has " +
                std::to_string(groups) + (groups == 1 ? " group" : " groups"),
            "a group index from 0 to " + std::to_string(groups - 1) + " (0-based)");
      ok = false;
    }
    if (ok) {
      pop.follow.population = static_cast<std::uint32_t>(target);
    } else {
      pop.follow = {};
      out.populationsOk[pf.population] = false;
    }
  }
}

bool Parser::readGuide(const Json& v, const std::string& ptr, sim::GuideDesc& g) {
  if (!isObject(v, ptr, "a guide object {\"script\", \"distance\", \"release\"}")) return false;
  checkKeys(v, ptr, {"script", "distance", "release"}, "a guide");
  bool ok = readFloatKeys(v, ptr, {{"distance", {0, 100, false, "m"}, &g.distance}});
  const Json* script = optional(v, "script");
  bool firstTimeOk = false;  // the release is checked against the first waypoint whenever it parsed
  if (script != nullptr) ok = readGuideScript(*script, ptr + "/script", g.script, firstTimeOk) && ok;
  if (auto* x = optional(v, "release")) {
    const std::string rptr = ptr + "/release";
    float release = 0.0f;
    if (!readFloat(*x, rptr, {0, 1e6, false, "s"}, release)) {
      ok = false;
    } else if (script == nullptr) {
      error(rptr, "\"release\" without a \"script\"", "a \"script\" of timed waypoints, or no \"release\"", "", true);
      ok = false;
    } else if (firstTimeOk && release < g.script.front().time) {
      error(rptr,
            "release at " + num(release) + " s is before the first waypoint at " + num(g.script.front().time) + " s",
            "a time >= " + num(g.script.front().time) + " s (the first waypoint's time)");
      ok = false;
    } else {
      g.release = release;
    }
  }
  if (!ok) g.script.clear();
  return ok;
}

bool Parser::readGuideScript(const Json& v, const std::string& ptr, std::vector<sim::GuideWaypoint>& out,
                             bool& firstTimeOk) {
  const std::string waypoint = "a waypoint {\"time\": seconds >= 0, \"position\": [x, y] in metres}";
  if (!v.is_array()) {
    error(ptr, "wrong type: " + describeType(v), "an array of waypoints, times strictly ascending");
    return false;
  }
  if (v.empty()) {
    error(ptr, "empty guide script", "at least one " + waypoint);
    return false;
  }
  out.assign(v.size(), {});  // indices equal JSON indices: the validator points at /script/k
  bool ok = true, previousOk = false;
  for (std::size_t k = 0; k < v.size(); ++k) {
    const std::string wptr = ptr + "/" + std::to_string(k);
    bool timeOk = false;
    if (isObject(v[k], wptr, waypoint)) {
      checkKeys(v[k], wptr, {"time", "position"}, "a guide waypoint");
      if (auto* t = require(v[k], wptr, "time", "a time in seconds >= 0")) {
        timeOk = readFloat(*t, wptr + "/time", {0, 1e6, false, "s"}, out[k].time);
      }
      if (auto* p = require(v[k], wptr, "position", "a point [x, y] in metres")) {
        ok = readVec2(*p, wptr + "/position", out[k].position) && ok;
      } else {
        ok = false;
      }
    }
    if (timeOk && previousOk && out[k].time <= out[k - 1].time) {
      error(wptr + "/time",
            "waypoint time " + num(out[k].time) + " s is not after the previous waypoint's " + num(out[k - 1].time) + " s",
            "times strictly ascending along the script");
      ok = false;
    }
    ok = timeOk && ok;
    previousOk = timeOk;
    if (k == 0) firstTimeOk = timeOk;
  }
  return ok;
}

bool Parser::readSociological(const Json& v, const std::string& ptr, sim::SociologicalDesc& s) {
  if (!isObject(v, ptr, "an object of sociological-model parameters")) return false;
  checkKeys(v, ptr,
            {"enabled", "meetDistance", "changeGroupRate", "followAgentRate", "followDuration", "leaderChangeRate",
             "sociability", "domination"},
            "sociological");
  s.enabled = true;  // giving the object turns the model on
  bool ok = true;
  if (auto* x = optional(v, "enabled")) ok = readBool(*x, ptr + "/enabled", s.enabled) && ok;
  const Range rate{0, 100, false, "1/s"};
  return readFloatKeys(v, ptr, {{"meetDistance", {0, 100, true, "m"}, &s.meetDistance},
                                {"changeGroupRate", rate, &s.changeGroupRate},
                                {"followAgentRate", rate, &s.followAgentRate},
                                {"followDuration", {0, 1e6, true, "s"}, &s.followDuration},
                                {"leaderChangeRate", rate, &s.leaderChangeRate},
                                {"sociability", {0, 100, false, ""}, &s.sociability},
                                {"domination", {0, 1, false, ""}, &s.domination}}) &&
         ok;
}

ParsedScenario Parser::run() {
  ParsedScenario out;
  sim::ScenarioDesc& desc = out.desc;
  const std::size_t before = diags_.size();
  const Json& root = doc_.root();
  if (!isObject(root, "", "a scenario object {\"format\": \"throng/1\", ...}")) return out;
  checkKeys(root, "",
            {"$schema", "format", "name", "seed", "duration", "dt", "walkable", "obstacles", "points", "populations",
             "steering", "navCellSize"},
            "the scenario");
  if (auto* x = require(root, "", "format", "\"throng/1\"")) {
    if (readString(*x, "/format", "\"throng/1\"", desc.format) && desc.format != "throng/1") {
      error("/format", "unsupported format " + quote(desc.format), "\"throng/1\"");
    }
  }
  if (auto* x = optional(root, "$schema")) {
    std::string ignored;
    readString(*x, "/$schema", "a schema URI (a string)", ignored);
  }
  if (auto* x = optional(root, "name")) readString(*x, "/name", "a string", desc.name);
  if (auto* x = optional(root, "seed")) {
    if (!x->is_number_integer()) {
      error("/seed", x->is_number() ? "value " + num(x->get<double>()) + " is not an integer" : "wrong type: " + describeType(*x),
            "an integer from 0 to 18446744073709551615");
    } else if (x->is_number_unsigned()) {
      desc.seed = x->get<std::uint64_t>();
    } else if (x->get<std::int64_t>() < 0) {
      error("/seed", "value " + std::to_string(x->get<std::int64_t>()) + " is negative", "an integer from 0 to 18446744073709551615");
    } else {
      desc.seed = static_cast<std::uint64_t>(x->get<std::int64_t>());
    }
  }
  if (auto* x = optional(root, "duration")) readFloat(*x, "/duration", {0, 1e6, true, "s"}, desc.duration);
  if (auto* x = optional(root, "dt")) readFloat(*x, "/dt", {0.001, 0.5, false, "s"}, desc.dt);
  if (auto* x = optional(root, "navCellSize")) {
    if (readFloat(*x, "/navCellSize", {0, 1, false, "m"}, desc.navCellSize) && desc.navCellSize > 0.0f &&
        desc.navCellSize < 0.01f) {
      error("/navCellSize", "value " + num(desc.navCellSize) + " m is out of range", "0 (automatic) or a number from 0.01 to 1 m");
    }
  }
  if (auto* x = optional(root, "steering")) readSteering(*x, "/steering", desc.steering);
  if (desc.steering.accelerationTime < desc.dt) {
    error("/steering/accelerationTime",
          "acceleration time " + num(desc.steering.accelerationTime) + " s is shorter than dt " + num(desc.dt) + " s",
          "a number >= dt");
  }
  if (desc.duration < desc.dt) {
    error("/duration", "duration " + num(desc.duration) + " s is shorter than one step (dt " + num(desc.dt) + " s)",
          "a number >= dt");
  }
  readPolygonList(root, "walkable", true, desc.walkable, out.walkableOk);
  readPolygonList(root, "obstacles", false, desc.obstacles, out.obstaclesOk);

  if (auto* x = optional(root, "points")) {
    if (!x->is_array()) {
      error("/points", "wrong type: " + describeType(*x), "an array of point objects");
    } else {
      desc.points.resize(x->size());
      out.pointsOk.resize(x->size());
      std::map<std::string, std::size_t> seen;
      for (std::size_t i = 0; i < x->size(); ++i) {
        const std::string ptr = "/points/" + std::to_string(i);
        out.pointsOk[i] = readPoint((*x)[i], ptr, desc.points[i]);
        const std::string& id = desc.points[i].id;
        if (id.empty()) continue;
        if (auto [it, fresh] = seen.emplace(id, i); !fresh) {
          error(ptr + "/id", "duplicate point id " + quote(id), "ids unique within /points",
                "first used at /points/" + std::to_string(it->second));
        }
      }
    }
  }
  pointIds_.clear();
  for (const auto& p : desc.points) {
    pointIds_.push_back(p.id);
    hasActionPoint_ = hasActionPoint_ || p.kind == sim::PointKind::Action;
  }

  const std::string popExpected = "an array of population objects";
  if (auto* x = require(root, "", "populations", popExpected)) {
    if (!x->is_array()) {
      error("/populations", "wrong type: " + describeType(*x), popExpected);
    } else {
      desc.populations.resize(x->size());
      out.populationsOk.resize(x->size());
      std::map<std::string, std::size_t> seen;
      for (std::size_t i = 0; i < x->size(); ++i) {
        const std::string ptr = "/populations/" + std::to_string(i);
        out.populationsOk[i] = readPopulation((*x)[i], ptr, i, desc.populations[i]);
        if (auto [it, fresh] = seen.emplace(desc.populations[i].id, i); !fresh) {
          error(ptr + "/id", "duplicate population id " + quote(desc.populations[i].id), "ids unique within /populations",
                "first used at /populations/" + std::to_string(it->second));
        }
      }
      resolveFollows(out);
    }
  }
  out.structureOk = diags_.size() == before;
  return out;
}

}  // namespace

core::Polygon normalizePolygon(const core::Polygon& poly, std::vector<std::size_t>& original) {
  core::Polygon out;
  original.clear();
  for (std::size_t i = 0; i < poly.size(); ++i) {
    if (!out.empty() && out.back() == poly[i]) continue;
    out.push_back(poly[i]);
    original.push_back(i);
  }
  while (out.size() > 1 && out.back() == out.front()) {  // closing vertex (GeoJSON style)
    out.pop_back();
    original.pop_back();
  }
  return out;
}

ParsedScenario parseScenarioJson(const JsonDocument& doc, core::Diagnostics& diagnostics) {
  return Parser(doc, diagnostics).run();
}

}  // namespace throng::io
