// throng::io scenario parser — walks the JSON tree of a "throng/1" scenario and fills a
// sim::ScenarioDesc. Every object's keys are checked against its schema (unknown keys get a
// "did you mean"), every value's type and range (with units), every polygon's shape, every id
// reference. Reads a JsonDocument; writes ParsedScenario and diagnostics; never stops early.
// A population's own keys are read here (its speed and pre-movement distributions too), its
// crowd-model keys by scenario_crowd_parser.cpp; the shared readers live in scenario_reader.hpp.
#include "scenario_parser.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "scenario_reader.hpp"
#include "throng/core/polygon_check.hpp"

namespace throng::io {

namespace detail {

namespace {

constexpr double kMinPolygonArea = 1e-6;  ///< [m²] below this a polygon is degenerate

}  // namespace

bool ScenarioReader::readPolygon(const Json& v, const std::string& ptr, core::Polygon& out) {
  const std::string expected = "a polygon: an array of at least 3 points [x, y] (metres, any winding)";
  if (!v.is_array()) {
    error(ptr, "wrong type: " + describeType(v), expected);
    return false;
  }
  if (v.size() > kMaxPolygonVertices) {
    error(ptr, "polygon of " + std::to_string(v.size()) + " points",
          "at most " + std::to_string(kMaxPolygonVertices) + " points per polygon", "simplify the outline or split it");
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
  // Ordinary outlines take a few edge-pair tests per edge; a hostile shape whose long edges all
  // cross one another (a star of 250,000 spikes) would take every pair: give up past the budget.
  const std::uint64_t budget = kSelfIntersectionTests + 64 * std::uint64_t(out.size());
  const core::SimplicityCheck simple = core::checkSimple(out, budget);
  if (simple.tooComplex) {
    error(ptr, "polygon of " + std::to_string(out.size()) + " points is too complex to check for self-intersections (" +
                   std::to_string(budget) + " pairs of edges tested; its long edges cross much of its area)",
          "a simple polygon of fewer points or shorter edges", "split it into several polygons");
    return false;
  }
  if (const auto hit = simple.crossing) {
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

void ScenarioReader::readPolygonList(const Json& root, const std::string& key, bool required, std::vector<core::Polygon>& out,
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

void ScenarioReader::readSteering(const Json& v, const std::string& ptr, sim::SteeringDesc& s) {
  if (!isObject(v, ptr, "an object of steering parameters")) return;
  checkKeys(v, ptr,
            {"timeHorizon", "timeHorizonObstacle", "neighbourDistance", "maxNeighbours", "accelerationTime",
             "denseNeighbourDistance", "denseThreshold", "lodDistance", "cornerReach", "levelLookAhead", "arrivalTime",
             "formationSpeedUp", "stuckPatience", "stuckAttempt"},
            "steering");
  const bool rangeOk = readFloatKeys(v, ptr, {{"timeHorizon", {0, 60, true, "s"}, &s.timeHorizon},
                                              {"timeHorizonObstacle", {0, 60, true, "s"}, &s.timeHorizonObstacle},
                                              {"neighbourDistance", {0, 100, true, "m"}, &s.neighbourDistance},
                                              {"accelerationTime", {0, 60, true, "s"}, &s.accelerationTime}});
  if (auto* x = optional(v, "maxNeighbours")) {
    double d;
    if (readInteger(*x, ptr + "/maxNeighbours", 1, 1000, "agents", d)) s.maxNeighbours = static_cast<std::uint32_t>(d);
  }
  // The preferred velocity (steer phase): path corners, arrival, formation, deadlock breaking.
  readFloatKeys(v, ptr, {{"cornerReach", {0, 5, true, "m"}, &s.cornerReach},
                         {"arrivalTime", {0, 10, true, "s"}, &s.arrivalTime},
                         {"formationSpeedUp", {1, 3, false, ""}, &s.formationSpeedUp},
                         {"stuckPatience", {0, 60, true, "s"}, &s.stuckPatience},
                         {"stuckAttempt", {0, 60, true, "s"}, &s.stuckAttempt}});
  if (auto* x = optional(v, "levelLookAhead")) {
    double d;
    if (readInteger(*x, ptr + "/levelLookAhead", 1, 16, "corners", d)) s.levelLookAhead = static_cast<std::uint32_t>(d);
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

bool ScenarioReader::readPoint(const Json& v, const std::string& ptr, sim::PointDesc& p) {
  if (!isObject(v, ptr, "a point object {\"id\", \"kind\", \"position\"+\"radius\" or \"polygon\"}")) return false;
  checkKeys(v, ptr,
            {"id", "kind", "position", "radius", "polygon", "height", "stop", "orientation", "action", "duration", "clip",
             "category", "width", "aim"},
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
    if (auto* h = optional(v, "height")) ok = readHeight(*h, ptr + "/height", p.height) && ok;
  } else if (position != nullptr) {
    ok = readPosition(*position, ptr + "/position", p.position, p.height) && ok;
    p.radius = 0.5f;
    if (radius != nullptr) ok = readFloat(*radius, ptr + "/radius", {0, 1000, true, "m"}, p.radius) && ok;
  } else {
    error(ptr, "point has no region", regionExpected);
    ok = false;
  }
  if (polygon == nullptr && optional(v, "height") != nullptr) {
    error(ptr + "/height", "\"height\" only applies to a polygon region", "the height as the position's z: [x, y, z]", "", true);
    ok = false;
  }
  if (auto* x = optional(v, "category")) ok = readCategory(*x, ptr + "/category", p.category) && ok;
  if (auto* x = optional(v, "width")) {
    if (p.kind != sim::PointKind::Exit) {
      error(ptr + "/width", "\"width\" only applies to exit points", "\"kind\": \"exit\" or no \"width\"", "", true);
      ok = false;
    } else {
      ok = readFloat(*x, ptr + "/width", {0.1, 100, false, "m"}, p.width) && ok;
    }
  }
  if (auto* x = optional(v, "aim")) {
    const char* expected = "\"spread\" (a spot spread over the region) or \"lane\" (where the way from the previous goal crosses it)";
    std::string aim;
    if (p.kind == sim::PointKind::Action) {
      error(ptr + "/aim", "\"aim\" only applies to interest and exit points", "\"kind\": \"interest\" or \"exit\", or no \"aim\"", "", true);
      ok = false;
    } else if (readString(*x, ptr + "/aim", expected, aim)) {
      if (aim == "spread") p.aim = sim::PointAim::Spread;
      else if (aim == "lane") p.aim = sim::PointAim::Lane;
      else {
        const std::string match = core::closestMatch(aim, {"spread", "lane"});
        error(ptr + "/aim", "unknown aim " + quote(aim), expected, match.empty() ? "" : "did you mean " + quote(match) + "?");
        ok = false;
      }
    } else {
      ok = false;
    }
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

bool ScenarioReader::resolvePoint(const Json& v, const std::string& ptr, std::uint32_t& out) {
  std::string id;
  if (!readString(v, ptr, "the id of a point in /points (a string)", id)) return false;
  if (pointIndex_.size() != pointIds_.size() || indexedIds_ != pointIds_.data()) {
    // Hashed once per id list: a file with 100,000 points and as many goals stays linear.
    pointIndex_.clear();
    for (std::size_t i = pointIds_.size(); i-- > 0;) pointIndex_[pointIds_[i]] = static_cast<std::uint32_t>(i);  // first wins
    pointIndex_.reserve(pointIds_.size());
    indexedIds_ = pointIds_.data();
  }
  if (auto it = pointIndex_.find(id); it != pointIndex_.end()) {
    out = it->second;
    return true;
  }
  // "Did you mean" compares with every id: offered while the comparisons stay few.
  std::string match;
  if (suggestionWork_ < kSuggestionWork) {
    suggestionWork_ += pointIds_.size();
    match = core::closestMatch(id, pointIds_);
  }
  error(ptr, "unknown point " + quote(id), "an id from /points", match.empty() ? "" : "did you mean " + quote(match) + "?");
  return false;
}

bool ScenarioReader::readSpawn(const Json& v, const std::string& ptr, sim::SpawnDesc& s) {
  const std::string expected = "an object with one of \"polygon\", \"position\" or \"point\"";
  if (!isObject(v, ptr, expected)) return false;
  checkKeys(v, ptr, {"polygon", "position", "point", "height"}, "a spawn");
  const Json* height = optional(v, "height");
  const std::size_t forms = v.size() - (height != nullptr ? 1 : 0);
  if (forms != 1) {
    if (forms == 0) error(ptr, "empty spawn", expected);
    else error(ptr, "spawn has " + std::to_string(forms) + " forms", "exactly one of \"polygon\", \"position\" or \"point\"");
    return false;
  }
  if (height != nullptr && optional(v, "polygon") == nullptr) {
    error(ptr + "/height", "\"height\" only applies to a polygon spawn",
          optional(v, "position") != nullptr ? "the height as the position's z: [x, y, z]"
                                             : "no \"height\" (a spawn at a point takes the point's height)",
          "", true);
    return false;
  }
  if (auto* x = optional(v, "polygon")) {
    s.kind = sim::SpawnKind::Polygon;
    bool ok = readPolygon(*x, ptr + "/polygon", s.polygon);
    if (height != nullptr) ok = readHeight(*height, ptr + "/height", s.height) && ok;
    return ok;
  }
  if (auto* x = optional(v, "position")) {
    s.kind = sim::SpawnKind::Position;
    return readPosition(*x, ptr + "/position", s.position, s.height);
  }
  if (auto* x = optional(v, "point")) {
    s.kind = sim::SpawnKind::Point;
    if (!resolvePoint(*x, ptr + "/point", s.point)) return false;
    s.height = pointHeights_[s.point];
    return true;
  }
  return false;  // the unknown key was reported by checkKeys
}

bool ScenarioReader::readSpeed(const Json& v, const std::string& ptr, sim::PopulationDesc& p) {
  const Range speedRange{0, 10, true, "m/s"};
  if (v.is_number()) {
    if (!readFloat(v, ptr, speedRange, p.speedMean)) return false;
    p.speedSd = 0.0f;
    p.speedMin = std::min(p.speedMin, p.speedMean);  // a fixed speed is never clipped
    p.speedMax = std::max(p.speedMax, p.speedMean);
    return true;
  }
  if (!v.is_object()) {
    error(ptr, "wrong type: " + describeType(v), "a speed in m/s, {\"mean\", \"sd\", \"min\", \"max\"} in m/s, or {\"demographics\": \"weidmann-age\", ...}");
    return false;
  }
  checkKeys(v, ptr, {"mean", "sd", "min", "max", "demographics", "age", "impaired", "impairedRadius"}, "a speed distribution");
  if (optional(v, "demographics") != nullptr) return readDemographics(v, ptr, p);
  bool ok = true;
  for (const char* key : {"age", "impaired", "impairedRadius"}) {
    if (optional(v, key) == nullptr) continue;
    error(ptr + "/" + key, quote(key) + " needs a demographic table", "\"demographics\": \"weidmann-age\" next to it", "", true);
    ok = false;
  }
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

bool ScenarioReader::readPreMovement(const Json& v, const std::string& ptr, sim::PreMovementDesc& d) {
  const std::vector<std::string> names{"uniform", "normal", "lognormal"};
  if (!isObject(v, ptr, "{\"distribution\": \"uniform\", \"min\", \"max\"}, {\"distribution\": \"normal\", \"mean\", \"sd\"} "
                        "or {\"distribution\": \"lognormal\", \"mu\", \"sigma\"}")) {
    return false;
  }
  checkKeys(v, ptr, {"distribution", "min", "max", "mean", "sd", "mu", "sigma"}, "a pre-movement distribution");
  std::size_t kind = 0;
  const Json* name = require(v, ptr, "distribution", "\"uniform\", \"normal\" or \"lognormal\"");
  if (name == nullptr || !readChoice(*name, ptr + "/distribution", names, "pre-movement distribution", kind)) return false;
  const Range time{0, sim::kMaxPreMovement, false, "s"};
  const std::vector<FloatKey> keys[] = {{{"min", time, &d.min}, {"max", time, &d.max}},
                                        {{"mean", time, &d.mean}, {"sd", time, &d.sd}},
                                        {{"mu", {-10, 14, false, "(ln s)"}, &d.mu}, {"sigma", {0, 3, false, "(ln s)"}, &d.sigma}}};
  const std::vector<FloatKey>& mine = keys[kind];
  std::string list;
  for (const FloatKey& k : mine) list += (list.empty() ? "\"" : ", \"") + std::string(k.key) + "\"";
  bool ok = true;
  for (const auto& item : v.items()) {
    const std::string key = item.key();
    const bool known = key == "distribution" || std::any_of(mine.begin(), mine.end(), [&](const FloatKey& k) { return key == k.key; });
    const bool other = key == "min" || key == "max" || key == "mean" || key == "sd" || key == "mu" || key == "sigma";
    if (known || !other) continue;  // an unknown key was reported by checkKeys
    error(ptr + "/" + key, quote(key) + " does not belong to a " + names[kind] + " distribution",
          "the keys of a " + names[kind] + " distribution: " + list, "", true);
    ok = false;
  }
  for (const FloatKey& k : mine) {
    if (auto* x = require(v, ptr, k.key, k.range.describe("a number"))) ok = readFloat(*x, ptr + "/" + k.key, k.range, *k.out) && ok;
    else ok = false;
  }
  if (ok && kind == 0 && d.min > d.max) {
    error(ptr + "/min", "min pre-movement time " + num(d.min) + " s exceeds max " + num(d.max) + " s", "min <= max");
    ok = false;
  }
  if (ok) d.distribution = static_cast<sim::PreMovementDistribution>(kind + 1);
  return ok;
}

bool ScenarioReader::readDemographics(const Json& v, const std::string& ptr, sim::PopulationDesc& p) {
  bool ok = true;
  for (const char* key : {"mean", "sd", "min", "max"}) {
    if (optional(v, key) == nullptr) continue;
    error(ptr + "/" + key, quote(key) + " next to \"demographics\": the table gives the speeds",
          "either {\"mean\", \"sd\", \"min\", \"max\"} or {\"demographics\", \"age\", \"impaired\", \"impairedRadius\"}", "",
          true);
    ok = false;
  }
  sim::DemographicsDesc& d = p.demographics;
  std::size_t table = 0;
  if (!readChoice(*optional(v, "demographics"), ptr + "/demographics", {"weidmann-age"}, "speed table", table)) return false;
  d.table = sim::SpeedTable::WeidmannAge;
  if (auto* x = optional(v, "age")) {
    ok = readInterval(*x, ptr + "/age", {sim::kMinAge, sim::kMaxAge, false, "years"}, d.ageMin, d.ageMax) && ok;
  }
  ok = readFloatKeys(v, ptr, {{"impaired", {0, 1, false, ""}, &d.impaired},
                              {"impairedRadius", {0.05, 1, false, "m"}, &d.impairedRadius}}) && ok;
  return ok;
}

bool ScenarioReader::readStairs(const Json& v, const std::string& ptr, sim::PopulationDesc& p) {
  if (!isObject(v, ptr, "{\"up\", \"down\", \"climb\"}: factors of the desired speed on stairs, each > 0 and <= 1")) return false;
  checkKeys(v, ptr, {"up", "down", "climb"}, "the stair speed factors and \"climb\"");
  const Range factor{0, 1, true, ""};
  bool ok = readFloatKeys(v, ptr, {{"up", factor, &p.stairUp}, {"down", factor, &p.stairDown}});
  if (const Json* climb = optional(v, "climb")) {
    const std::string at = ptr + "/climb";
    if (!isObject(*climb, at, "{\"up\", \"down\"}: the shares of groups who take the stairs over a lift or escalator when quicker, each 0 to 1")) return false;
    checkKeys(*climb, at, {"up", "down"}, "the shares who take the stairs");
    const Range share{0, 1, false, ""};
    ok = readFloatKeys(*climb, at, {{"up", share, &p.stairClimbUp}, {"down", share, &p.stairClimbDown}}) && ok;
  }
  return ok;
}

bool ScenarioReader::readPopulation(const Json& v, const std::string& ptr, std::size_t index, sim::PopulationDesc& p) {
  if (!isObject(v, ptr, "a population object {\"id\", \"groups\", \"size\", \"spawn\", \"goals\", ...}")) return false;
  checkKeys(v, ptr,
            {"id", "groups", "size", "spawn", "start", "goals", "speed", "radius", "wander", "paths", "autoNearDistance",
             "flocking", "waitTimeout", "groupSpacing", "follow", "guide", "sociological", "interests", "interestsPerAgent", "preferences",
             "model", "preMovement", "stairs", "exits", "exitChoice", "incapacitationDose", "useTransports"},
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
  if (auto* x = require(v, ptr, "spawn", "{\"polygon\": [...]}, {\"position\": [x, y] or [x, y, z]} or {\"point\": \"id\"}")) {
    ok = readSpawn(*x, ptr + "/spawn", p.spawn) && ok;
  } else {
    ok = false;
  }
  if (auto* x = optional(v, "start")) ok = readFloat(*x, ptr + "/start", {0, 1e6, false, "s"}, p.start) && ok;
  if (auto* x = optional(v, "goals")) ok = readGoals(*x, ptr + "/goals", p) && ok;
  if (auto* x = optional(v, "exits")) ok = readExits(*x, ptr + "/exits", p) && ok;
  if (auto* x = optional(v, "exitChoice")) {
    if (optional(v, "exits") == nullptr) {
      error(ptr + "/exitChoice", "\"exitChoice\" without \"exits\"", "the exits to choose among: \"exits\": [\"exit id\", ...]", "", true);
      ok = false;
    } else {
      ok = readExitChoice(*x, ptr + "/exitChoice", p) && ok;
    }
  }
  if (auto* x = optional(v, "speed")) ok = readSpeed(*x, ptr + "/speed", p) && ok;
  if (auto* x = optional(v, "stairs")) ok = readStairs(*x, ptr + "/stairs", p) && ok;
  if (auto* x = optional(v, "useTransports")) ok = readBool(*x, ptr + "/useTransports", p.useTransports) && ok;
  if (auto* x = optional(v, "incapacitationDose")) {
    ok = readFloat(*x, ptr + "/incapacitationDose", {0, 10, true, ""}, p.incapacitationDose) && ok;
  }
  if (auto* x = optional(v, "radius")) ok = readFloat(*x, ptr + "/radius", {0.05, 1.0, false, "m"}, p.radius) && ok;
  if (auto* x = optional(v, "preMovement")) ok = readPreMovement(*x, ptr + "/preMovement", p.preMovement) && ok;
  if (auto* x = optional(v, "wander")) ok = readBool(*x, ptr + "/wander", p.wander) && ok;
  if (auto* x = optional(v, "model")) ok = readModel(*x, ptr + "/model", p.model) && ok;
  ok = readInterests(v, ptr, p) && ok;
  return readCrowdKeys(v, ptr, index, p) && ok;
}

ParsedScenario ScenarioReader::run() {
  ParsedScenario out;
  const std::size_t before = diags_.size();
  const Json& root = doc_.root();
  if (!isObject(root, "", "a scenario object {\"format\": \"throng/1\", ...}")) return out;
  checkKeys(root, "",
            {"$schema", "format", "name", "description", "seed", "duration", "dt", "walkable", "obstacles", "terrain", "points",
             "populations", "steering", "navCellSize", "social", "timeline", "walls", "measurements", "smoke", "transports"},
            "the scenario");
  readScenarioHeader(root, out.desc);
  readTiming(root, out.desc);
  readGeometry(root, out);
  readWallList(root, out);
  readMeasurementList(root, out);
  readSmokeList(root, out.desc);
  readPointList(root, out);
  indexPoints(out.desc);
  readTransportList(root, out.desc);
  readPopulationList(root, out);
  if (auto* x = optional(root, "social")) {
    if (multiLevel_) {
      refuseOnLevels("/social", "the \"social\" section (Common Ground)", "no \"social\" section next to \"terrain\"", true);
    } else {
      readSocial(*x, "/social", out.desc.social);
    }
  }
  if (auto* x = optional(root, "timeline")) readTimeline(*x, "/timeline", out.desc.timeline);
  checkCategories(out);
  out.structureOk = diags_.size() == before;
  return out;
}

void ScenarioReader::readScenarioHeader(const Json& root, sim::ScenarioDesc& desc) {
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
  if (auto* x = optional(root, "description")) {
    const std::string expected = "a string of at most " + std::to_string(sim::kMaxDescription) + " bytes";
    if (readString(*x, "/description", expected, desc.description) && desc.description.size() > sim::kMaxDescription) {
      error("/description", std::to_string(desc.description.size()) + " bytes", expected);
      desc.description.clear();
    }
  }
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
}

void ScenarioReader::readTiming(const Json& root, sim::ScenarioDesc& desc) {
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
}

void ScenarioReader::readGeometry(const Json& root, ParsedScenario& out) {
  sim::ScenarioDesc& desc = out.desc;
  const Json* terrain = optional(root, "terrain");
  if (terrain == nullptr) {
    readPolygonList(root, "walkable", true, desc.walkable, out.walkableOk);
    readPolygonList(root, "obstacles", false, desc.obstacles, out.obstaclesOk);
    return;
  }
  // A multi-level world: its geometry is the terrain's triangles, never 2D polygons.
  multiLevel_ = true;
  out.terrainOk = readTerrain(*terrain, "/terrain", desc.terrain, desc.stairSlopeDeg);
  for (const char* key : {"walkable", "obstacles"}) {
    const Json* x = optional(root, key);
    if (x == nullptr || (x->is_array() && x->empty())) continue;
    error(std::string("/") + key,
          std::string("a multi-level world takes its ") + (key[0] == 'w' ? "walkable surface" : "obstacles") +
              " from /terrain/" + key,
          std::string("no \"") + key + "\" (or an empty array) next to \"terrain\"",
          std::string("move the ") + (key[0] == 'w' ? "floors" : "obstacles") + " into /terrain/" + key + " as triangles",
          true);
  }
}

void ScenarioReader::readPointList(const Json& root, ParsedScenario& out) {
  sim::ScenarioDesc& desc = out.desc;
  auto* x = optional(root, "points");
  if (x == nullptr) return;
  if (!x->is_array()) {
    error("/points", "wrong type: " + describeType(*x), "an array of point objects");
    return;
  }
  if (x->size() > kMaxPoints) {
    error("/points", std::to_string(x->size()) + " points", "at most " + std::to_string(kMaxPoints) + " points");
    return;
  }
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

void ScenarioReader::indexPoints(const sim::ScenarioDesc& desc) {
  pointIds_.clear();
  indexedIds_ = nullptr;  // resolvePoint re-hashes the new list
  pointHeights_.clear();
  pointIsExit_.clear();
  for (const auto& p : desc.points) {
    pointIds_.push_back(p.id);
    pointHeights_.push_back(p.height);
    pointIsExit_.push_back(p.kind == sim::PointKind::Exit ? 1 : 0);
    hasActionPoint_ = hasActionPoint_ || p.kind == sim::PointKind::Action;
  }
}

void ScenarioReader::readPopulationList(const Json& root, ParsedScenario& out) {
  sim::ScenarioDesc& desc = out.desc;
  const std::string popExpected = "an array of population objects";
  auto* x = require(root, "", "populations", popExpected);
  if (x == nullptr) return;
  if (!x->is_array()) {
    error("/populations", "wrong type: " + describeType(*x), popExpected);
    return;
  }
  if (x->size() > kMaxPopulations) {
    error("/populations", std::to_string(x->size()) + " populations",
          "at most " + std::to_string(kMaxPopulations) + " populations (give one population more groups)");
    return;
  }
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

}  // namespace detail

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
  return detail::ScenarioReader(doc, diagnostics).run();
}

}  // namespace throng::io
