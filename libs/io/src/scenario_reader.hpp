// throng::io scenario reader — the scenario parser's shared state and typed value readers: the
// document (for line:column positions), the diagnostics sink, key checks with "did you mean",
// numbers, integers, booleans, strings, choices, intervals and points with their ranges and units,
// plus the point ids and pending "follow" references gathered while reading. The reading of each
// part of a scenario is split by concept: scenario_parser.cpp (structure, geometry, steering,
// points, spawn, speed, populations) and scenario_crowd_parser.cpp (the Musse et al. crowd-model
// keys of a population). Reads a JsonDocument; writes ParsedScenario fields and diagnostics.
// Private to throng_io.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <initializer_list>
#include <limits>
#include <string>
#include <unordered_map>
#include <vector>

#include "json_document.hpp"
#include "scenario_parser.hpp"
#include "throng/sim/animation.hpp"
#include "throng/core/text.hpp"

namespace throng::io::detail {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

inline std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

/// A string from the file echoed in a message: quoted, control characters escaped, at most 80
/// characters (core::printable).
inline std::string quote(const std::string& s) { return "\"" + core::printable(s, 80) + "\""; }

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

/// Reader state shared by all the read functions (defined in scenario_parser.cpp and
/// scenario_crowd_parser.cpp): the document (for positions) and the output.
class ScenarioReader {
 public:
  ScenarioReader(const JsonDocument& doc, core::Diagnostics& diags) : doc_(doc), diags_(diags) {}

  ParsedScenario run();
  /// A crowd file (crowd_parser.cpp) read against a world: the result's desc holds the world's
  /// geometry, social section and points followed by the crowd's points, and only the crowd's
  /// populations (indices into that point list; follow populations index the world's populations
  /// followed by the crowd's). `takenPoints`/`takenPopulations`: ids also in use (earlier crowds).
  ParsedScenario runCrowd(const sim::ScenarioDesc& world, const std::vector<std::string>& takenPoints,
                          const std::vector<std::string>& takenPopulations, std::string& crowdId);

 private:
  // The steps of run() (scenario_parser.cpp), in order.
  void readScenarioHeader(const Json& root, sim::ScenarioDesc& desc);  ///< format, $schema, name, seed
  void readTiming(const Json& root, sim::ScenarioDesc& desc);          ///< duration, dt, navCellSize, steering
  void readGeometry(const Json& root, ParsedScenario& out);            ///< walkable + obstacles, or terrain
  void readPointList(const Json& root, ParsedScenario& out);
  /// "walls" (scenario_walls_parser.cpp): read, then appended to desc.obstacles as footprints.
  void readWallList(const Json& root, ParsedScenario& out);
  bool readWall(const Json& v, const std::string& ptr, sim::WallDesc& w, std::size_t& segments);
  /// "measurements" (scenario_walls_parser.cpp): lines and areas for analysis.
  void readMeasurementList(const Json& root, ParsedScenario& out);
  bool readMeasurement(const Json& v, const std::string& ptr, sim::MeasurementDesc& m);
  void readSmokeList(const Json& root, sim::ScenarioDesc& desc);
  /// "transports" (scenario_walls_parser.cpp): lifts and escalators between points (after indexPoints).
  void readTransportList(const Json& root, sim::ScenarioDesc& desc);
  /// A transport's "kind"; true for an elevator (whose default speed it sets).
  bool readTransportKind(const Json& v, const std::string& ptr, sim::TransportDesc& t);
  /// Its "stops": resolved, different, interest points; false when not.
  bool readTransportStops(const Json& v, const std::string& ptr, bool elevator, const sim::ScenarioDesc& desc,
                          sim::TransportDesc& t);
  /// Its speed and the keys of its kind (a key of the other kind is an error).
  void readTransportNumbers(const Json& v, const std::string& ptr, bool elevator, sim::TransportDesc& t);
  /// The point ids and heights that goals and spawns resolve against (run and runCrowd).
  void indexPoints(const sim::ScenarioDesc& desc);
  void readPopulationList(const Json& root, ParsedScenario& out);
  // The steps of runCrowd() (crowd_parser.cpp), in order.
  void readCrowdHeader(const Json& root, std::string& crowdId);  ///< format, $schema, id
  void adoptWorld(const sim::ScenarioDesc& world, ParsedScenario& out);
  void readCrowdPointList(const Json& root, const sim::ScenarioDesc& world, const std::vector<std::string>& takenPoints,
                          ParsedScenario& out);
  /// A stopping action point of a crowd must play an action the world already has a clip for.
  void checkCrowdAction(const Json& v, const std::string& ptr, const sim::PointDesc& p,
                        const std::vector<sim::ClipInfo>& clips);
  void readCrowdPopulationList(const Json& root, const sim::ScenarioDesc& world,
                               const std::vector<std::string>& takenPopulations, ParsedScenario& out);
  /// "follow" names a population of the world or of the crowd file.
  void resolveCrowdFollows(const sim::ScenarioDesc& world, ParsedScenario& out);

  void error(const std::string& ptr, std::string what, std::string expected, std::string hint = {}, bool atKey = false) {
    diags_.push_back(doc_.diagnostic(ptr, std::move(what), std::move(expected), std::move(hint), atKey));
  }

  /// Reports unknown keys of `obj` (at the key's position, with a "did you mean").
  void checkKeys(const Json& obj, const std::string& ptr, const std::vector<std::string>& allowed, const std::string& what) {
    for (const auto& [key, value] : obj.items()) {
      if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      // "Did you mean" for the first unknown keys only: a hostile file has 300,000 of them.
      const std::string match = suggestionWork_ < kSuggestionWork ? core::closestMatch(key, allowed) : std::string();
      suggestionWork_ += allowed.size() * 16;
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
    readRelativePath(v, ptr, "a BVH file path relative to the scenario (\"motions/look.bvh\")", out);
  }

  /// A non-empty path relative to the scenario's directory.
  void readRelativePath(const Json& v, const std::string& ptr, const std::string& expected, std::string& out) {
    std::string path;
    if (!readString(v, ptr, expected, path)) return;
    if (path.empty()) error(ptr, "empty path", expected);
    else if (path.front() == '/' || path.front() == '\\' || (path.size() > 1 && path[1] == ':'))
      error(ptr, "absolute path " + quote(path), expected, "scenarios stay portable with relative paths");
    else if (path.find('\0') != std::string::npos) error(ptr, "path contains a NUL character", expected);
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

  /// A single position: [x, y] or [x, y, z] (z: height of the floor it is on). A z other than 0
  /// needs a multi-level world (a "/terrain"); `height` is 0 for [x, y].
  bool readPosition(const Json& v, const std::string& ptr, core::Vec2& out, float& height) {
    const std::string expected = "a position [x, y] or [x, y, z] of numbers in metres (z: the floor's height, " +
                                 std::string("multi-level worlds only), each within ±") + num(kMaxCoordinate);
    if (!v.is_array() || (v.size() != 2 && v.size() != 3)) {
      error(ptr, v.is_array() ? "point has " + std::to_string(v.size()) + " coordinates" : "wrong type: " + describeType(v),
            expected);
      return false;
    }
    bool ok = true;
    double c[3] = {0, 0, 0};
    const Range r{-kMaxCoordinate, kMaxCoordinate, false, "m"};
    for (std::size_t i = 0; i < v.size(); ++i) ok = readNumber(v[i], ptr + "/" + std::to_string(i), r, c[i]) && ok;
    out = core::Vec2(static_cast<float>(c[0]), static_cast<float>(c[1]));
    height = 0.0f;
    if (v.size() == 3 && ok) ok = acceptHeight(c[2], ptr + "/2", height);
    return ok;
  }

  /// A "height" key [m] (polygon spawns and polygon points).
  bool readHeight(const Json& v, const std::string& ptr, float& height) {
    double h = 0;
    if (!readNumber(v, ptr, {-kMaxCoordinate, kMaxCoordinate, false, "m"}, h)) return false;
    return acceptHeight(h, ptr, height);
  }

  /// Heights belong to multi-level worlds: in a flat one only 0 is accepted.
  bool acceptHeight(double h, const std::string& ptr, float& height) {
    if (!multiLevel_ && h != 0.0) {
      error(ptr, "height " + num(h) + " m in a flat world: heights need a multi-level world (/terrain)",
            "no height (or 0) in a world of /walkable polygons", "describe the floors, stairs and ramps in \"terrain\"");
      return false;
    }
    height = static_cast<float>(h);
    return true;
  }

  /// A 2D-only feature used on a multi-level world: one diagnostic naming the key.
  void refuseOnLevels(const std::string& ptr, const std::string& what, const std::string& expected, bool atKey = false) {
    error(ptr, what + " is not supported on multi-level worlds yet", expected, "", atKey);
  }

  /// "terrain" (scenario_terrain_parser.cpp): vertices and walkable/obstacle triangles.
  bool readTerrain(const Json& v, const std::string& ptr, nav::TerrainMesh& out, float& stairSlopeDeg);
  bool readTriangles(const Json& v, const std::string& ptr, std::size_t vertexCount, std::vector<std::uint32_t>& out);

  bool readPolygon(const Json& v, const std::string& ptr, core::Polygon& out);
  void readSteering(const Json& v, const std::string& ptr, sim::SteeringDesc& s);
  bool readPoint(const Json& v, const std::string& ptr, sim::PointDesc& p);
  bool readPopulation(const Json& v, const std::string& ptr, std::size_t index, sim::PopulationDesc& p);
  bool readSpawn(const Json& v, const std::string& ptr, sim::SpawnDesc& s);
  bool readSpeed(const Json& v, const std::string& ptr, sim::PopulationDesc& p);
  /// "preMovement": {"distribution": "uniform" | "normal" | "lognormal", and that distribution's keys}.
  bool readPreMovement(const Json& v, const std::string& ptr, sim::PreMovementDesc& d);
  /// The demographic form of "speed": {"demographics": "weidmann-age", "age", "impaired", "impairedRadius"}.
  bool readDemographics(const Json& v, const std::string& ptr, sim::PopulationDesc& p);
  /// "stairs": {"up", "down"}, factors of the desired speed along a stair's slope.
  bool readStairs(const Json& v, const std::string& ptr, sim::PopulationDesc& p);
  bool readGoals(const Json& v, const std::string& ptr, sim::PopulationDesc& p);
  bool readExits(const Json& v, const std::string& ptr, sim::PopulationDesc& p);
  bool readGoalChoice(const Json& v, const std::string& ptr, sim::PopulationDesc& p);
  bool readChoiceShares(const Json& v, const std::string& ptr, sim::GoalChoiceDesc& c);
  bool readExitChoice(const Json& v, const std::string& ptr, sim::PopulationDesc& p);
  bool readFamiliar(const Json& v, const std::string& ptr, sim::PopulationDesc& p);
  bool readCrowdKeys(const Json& v, const std::string& ptr, std::size_t index, sim::PopulationDesc& p);
  /// "model" (scenario_model_parser.cpp): a model name, or {"name", parameters of that model}.
  bool readModel(const Json& v, const std::string& ptr, sim::ModelDesc& m);
  bool readFollow(const Json& v, const std::string& ptr, std::size_t index, sim::FollowDesc& f);
  bool readGuide(const Json& v, const std::string& ptr, sim::GuideDesc& g);
  bool readGuideScript(const Json& v, const std::string& ptr, std::vector<sim::GuideWaypoint>& out, bool& firstTimeOk);
  bool readSociological(const Json& v, const std::string& ptr, sim::SociologicalDesc& s);
  // Common Ground (scenario_social_parser.cpp).
  bool readCategory(const Json& v, const std::string& ptr, std::string& out);
  bool readInterests(const Json& v, const std::string& ptr, sim::PopulationDesc& p);
  void readSocial(const Json& v, const std::string& ptr, sim::CommonGroundDesc& s);
  /// Needs and interests name categories some point has.
  void checkCategories(const ParsedScenario& out);
  void resolveFollows(ParsedScenario& out);
  /// The scenario's "timeline" (crowd_parser.cpp): entries parsed, crowd files not read yet.
  void readTimeline(const Json& v, const std::string& ptr, std::vector<sim::TimelineEntry>& out);
  bool resolvePoint(const Json& v, const std::string& ptr, std::uint32_t& out);
  void readPolygonList(const Json& root, const std::string& key, bool required, std::vector<core::Polygon>& out,
                       std::vector<bool>& ok);

  const JsonDocument& doc_;
  core::Diagnostics& diags_;
  std::vector<std::string> pointIds_;
  /// pointIds_ hashed (id → first index), rebuilt when pointIds_ changes (size or storage).
  std::unordered_map<std::string, std::uint32_t> pointIndex_;
  const std::string* indexedIds_ = nullptr;
  /// Candidate comparisons spent on "did you mean" hints for unknown keys and point ids; past the
  /// budget no hint is offered (a hostile file with 300,000 unknown keys, or 100,000 unknown ids
  /// and as many points).
  std::size_t suggestionWork_ = 0;
  static constexpr std::size_t kSuggestionWork = 1000000;
  std::vector<float> pointHeights_;  ///< per point id: its floor height (spawns at a point take it)
  std::vector<std::uint8_t> pointIsExit_;  ///< per point id: kind "exit" (a population's "exits" must be)
  /// The world has a "terrain" (multi-level): positions may carry heights; 2D-only features are refused.
  bool multiLevel_ = false;
  bool hasActionPoint_ = false;  ///< "goals": "auto" draws its final goal among the action points
  /// A "follow" whose population id is resolved once every population has been read.
  struct PendingFollow {
    std::size_t population;  ///< the following population
    std::string target;      ///< id of the followed one
    std::string pointer;     ///< of the "follow" object
  };
  std::vector<PendingFollow> follows_;
};

}  // namespace throng::io::detail
