// throng::io scenario validator — cross-element checks on a parsed scenario, with Boost.Geometry
// for polygon sets (walkable union minus obstacles) and the navmesh for reachability. Multi-level
// worlds (a "terrain") are checked on their 3D navmesh only: points, spawns and guide waypoints
// snapped at their heights, goals reachable across floors. Reads a ParsedScenario; writes
// diagnostics (and the navmesh it built).
#include "scenario_validator.hpp"
#include "throng/core/text.hpp"

#include <boost/geometry.hpp>
#include <boost/geometry/geometries/multi_polygon.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>
#include <boost/geometry/algorithms/point_on_surface.hpp>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

namespace throng::io {

namespace {

namespace bg = boost::geometry;
using BPoint = bg::model::d2::point_xy<double>;
using BPolygon = bg::model::polygon<BPoint, false, true>;  // counter-clockwise, closed
using BMulti = bg::model::multi_polygon<BPolygon>;

std::string num(double v) {
  char buf[32];
  if (v == std::floor(v) && std::fabs(v) < 1e12) {
    std::snprintf(buf, sizeof buf, "%.0f", v);  // counts and whole metres: never "1e+03"
  } else {
    std::snprintf(buf, sizeof buf, "%.3g", v);
  }
  return buf;
}

BPolygon toBoost(const core::Polygon& poly) {
  BPolygon out;
  for (const core::Vec2 p : poly) out.outer().emplace_back(p.x, p.y);
  bg::correct(out);  // closes the ring and fixes the winding
  return out;
}

BPolygon disc(core::Vec2 c, double r) {
  constexpr int kSides = 24;
  core::Polygon poly;
  for (int i = 0; i < kSides; ++i) {
    const double a = 2.0 * std::numbers::pi * i / kSides;
    poly.emplace_back(static_cast<float>(c.x + r * std::cos(a)), static_cast<float>(c.y + r * std::sin(a)));
  }
  return toBoost(poly);
}

/// Where agents of one population appear: a region (polygon or disc) or one position.
struct SpawnRegion {
  bool isPosition = false;
  BPolygon region;
  core::Vec2 position;
  std::string pointer;  ///< the JSON value that defines it
};

class Validator {
 public:
  Validator(const JsonDocument& doc, const ParsedScenario& parsed, core::Diagnostics& diags)
      : doc_(doc), parsed_(parsed), desc_(parsed.desc), diags_(diags) {}

  /// Stop early (leaving diagnostics incomplete) once `*cancel` is non-zero.
  void cancelWith(const std::atomic<int>* cancel) { cancel_ = cancel; }

  /// A crowd file: points before `firstOwnPoint` are the world's; the world's navmesh is given.
  void useWorld(std::size_t firstOwnPoint, std::shared_ptr<const nav::NavMesh> navmesh) {
    firstOwnPoint_ = firstOwnPoint;
    worldNavmesh_ = std::move(navmesh);
  }

  void run(const LoadOptions& options, std::shared_ptr<const nav::NavMesh>& navmesh) {
    if (!desc_.terrain.empty() || !parsed_.terrainOk) {
      runTerrain(options, navmesh);
      return;
    }
    const bool geometryOk = !desc_.walkable.empty() &&
                            std::all_of(parsed_.walkableOk.begin(), parsed_.walkableOk.end(), [](bool b) { return b; }) &&
                            std::all_of(parsed_.obstaclesOk.begin(), parsed_.obstaclesOk.end(), [](bool b) { return b; }) &&
                            std::all_of(parsed_.wallsOk.begin(), parsed_.wallsOk.end(), [](bool b) { return b; });
    if (!geometryOk) return;  // the parser already said why
    if (!buildAreas()) return;
    std::vector<std::optional<core::Vec2>> starts(desc_.populations.size());
    for (std::size_t i = 0; i < desc_.populations.size(); ++i) {
      if (cancelled()) return;
      if (i < parsed_.populationsOk.size() && parsed_.populationsOk[i]) {
        starts[i] = checkSpawn(i);
        checkGuide(i);
      }
    }
    if (!cancelled()) checkSpawnCapacity(starts);
    if (options.checkReachability && diags_.empty() && !cancelled()) checkReachability(starts, navmesh);
  }

 private:
  [[nodiscard]] bool cancelled() const { return cancel_ != nullptr && cancel_->load(std::memory_order_relaxed) != 0; }

  void error(const std::string& ptr, std::string what, std::string expected, std::string hint = {}) {
    diags_.push_back(doc_.diagnostic(ptr, std::move(what), std::move(expected), std::move(hint)));
  }

  /// The union of `parts`, merged pairwise in rounds (a balanced tree): each polygon takes part in
  /// O(log n) merges of growing size, where adding one polygon at a time to the growing union
  /// made 4,000 small obstacles cost minutes. Empty when cancelled.
  BMulti unionAll(std::vector<BMulti> parts) const {
    while (parts.size() > 1) {
      std::vector<BMulti> next((parts.size() + 1) / 2);
      for (std::size_t k = 0; k + 1 < parts.size(); k += 2) {
        if (cancelled()) return {};
        bg::union_(parts[k], parts[k + 1], next[k / 2]);
      }
      if (parts.size() % 2 == 1) next.back() = std::move(parts.back());
      parts = std::move(next);
    }
    return parts.empty() ? BMulti{} : std::move(parts.front());
  }

  bool buildAreas() {
    try {
      std::vector<BMulti> walkable;
      for (const auto& poly : desc_.walkable) walkable.push_back(BMulti{toBoost(poly)});
      walk_ = unionAll(std::move(walkable));
      std::vector<BMulti> obstacles;
      for (const auto& poly : desc_.obstacles) {
        obstacles_.push_back(toBoost(poly));
        obstacles.push_back(BMulti{obstacles_.back()});
      }
      const BMulti blocked = unionAll(std::move(obstacles));
      if (cancelled()) return false;
      if (blocked.empty()) {
        free_ = walk_;
      } else {
        bg::difference(walk_, blocked, free_);
      }
    } catch (const std::exception& e) {
      error("/walkable", std::string("cannot combine the walkable and obstacle polygons: ") + e.what(),
            "simple polygons with well-separated vertices");
      return false;
    }
    if (bg::area(free_) < 1e-6) {
      error(desc_.obstacles.empty() ? "/walkable" : parsed_.listedObstacles > 0 ? "/obstacles" : "/walls", "nothing walkable remains after removing obstacles",
            "walkable area not entirely covered by /obstacles");
      return false;
    }
    return true;
  }

  SpawnRegion spawnRegion(std::size_t i) const {
    const sim::PopulationDesc& pop = desc_.populations[i];
    const std::string base = "/populations/" + std::to_string(i) + "/spawn";
    SpawnRegion s;
    switch (pop.spawn.kind) {
      case sim::SpawnKind::Polygon:
        s.region = toBoost(pop.spawn.polygon);
        s.pointer = base + "/polygon";
        break;
      case sim::SpawnKind::Position:
        s.isPosition = true;
        s.position = pop.spawn.position;
        s.pointer = base + "/position";
        break;
      case sim::SpawnKind::Point: {
        const sim::PointDesc& p = desc_.points[pop.spawn.point];
        s.pointer = base + "/point";
        if (!p.polygon.empty()) s.region = toBoost(p.polygon);
        else s.region = disc(p.position, p.radius);
        break;
      }
    }
    return s;
  }

  /// Empty when `p` lies strictly inside the walkable area and outside every obstacle; otherwise
  /// "(x, y) is outside the walkable area" or "(x, y) is inside obstacle /obstacles/k" (or "/walls/j").
  std::string positionProblem(core::Vec2 p) const {
    const BPoint b(p.x, p.y);
    const std::string where = "(" + num(p.x) + ", " + num(p.y) + ")";
    if (!bg::within(b, walk_)) return where + " is outside the walkable area";
    for (std::size_t k = 0; k < obstacles_.size(); ++k) {
      if (bg::within(b, obstacles_[k])) return where + " is inside obstacle " + obstaclePointer(parsed_, k);
    }
    return {};
  }

  /// A scripted guide (Musse et al. §3.2.6) walks where the group can follow: every waypoint
  /// inside the walkable area and clear of obstacles.
  void checkGuide(std::size_t i) {
    const auto& script = desc_.populations[i].guide.script;
    for (std::size_t k = 0; k < script.size(); ++k) {
      if (const std::string problem = positionProblem(script[k].position); !problem.empty()) {
        error("/populations/" + std::to_string(i) + "/guide/script/" + std::to_string(k) + "/position",
              "guide waypoint " + problem, "a waypoint inside /walkable and clear of /obstacles");
      }
    }
  }

  /// Checks one population's spawn; returns a point inside it to start reachability from.
  std::optional<core::Vec2> checkSpawn(std::size_t i) {
    const sim::PopulationDesc& pop = desc_.populations[i];
    if (pop.spawn.kind == sim::SpawnKind::Point &&
        (pop.spawn.point >= parsed_.pointsOk.size() || !parsed_.pointsOk[pop.spawn.point])) {
      return std::nullopt;  // the point's own diagnostic explains it
    }
    const SpawnRegion s = spawnRegion(i);
    const std::string expected = "a spawn inside /walkable and clear of /obstacles";
    if (s.isPosition) {
      if (const std::string problem = positionProblem(s.position); !problem.empty()) {
        error(s.pointer, "spawn position " + problem, expected);
        return std::nullopt;
      }
      return s.position;
    }
    BMulti inWalk, inFree;
    bg::intersection(s.region, walk_, inWalk);
    bg::intersection(s.region, free_, inFree);
    const double area = bg::area(s.region);
    const double walkArea = bg::area(inWalk);
    const double freeArea = bg::area(inFree);
    const double tolerance = std::max(1e-6, 0.01 * area);
    if (area - walkArea > tolerance) {
      error(s.pointer,
            "spawn area lies " + std::string(walkArea < 1e-6 ? "entirely" : "partly") + " outside the walkable area (" +
                num(area - walkArea) + " of " + num(area) + " m² outside)",
            expected);
    } else if (walkArea - freeArea > tolerance) {
      std::string which;
      for (std::size_t k = 0; k < obstacles_.size(); ++k) {
        BMulti overlap;
        bg::intersection(s.region, obstacles_[k], overlap);
        const std::string name = obstaclePointer(parsed_, k);  // a wall's segments name it once
        if (bg::area(overlap) > 1e-9 && !which.ends_with(name)) which += (which.empty() ? "" : ", ") + name;
      }
      error(s.pointer,
            "spawn area overlaps obstacle " + which + " (" + num(walkArea - freeArea) + " of " + num(area) + " m² covered)",
            expected);
    }
    if (freeArea < 1e-6) return std::nullopt;
    BPoint inside;
    try {
      bg::point_on_surface(inFree, inside);
    } catch (const std::exception&) {
      return std::nullopt;
    }
    return core::Vec2(static_cast<float>(inside.x()), static_cast<float>(inside.y()));
  }

  /// Agents of a population at most (groups × largest group size).
  double maxAgents(std::size_t i) const {
    const sim::PopulationDesc& pop = desc_.populations[i];
    return double(pop.groups) * pop.sizeMax;
  }

  /// Populations spawning in areas that overlap, at the same time (and on multi-level worlds at
  /// the same floor), as clusters of population indices in ascending order; only those `use`
  /// admits. Position spawns grow a disc that fits their agents and are left out.
  std::vector<std::vector<std::size_t>> spawnClusters(const std::vector<bool>& use, bool levels) const {
    const std::size_t n = desc_.populations.size();
    std::vector<std::size_t> parent(n);
    for (std::size_t i = 0; i < n; ++i) parent[i] = i;
    auto root = [&](std::size_t i) {
      while (parent[i] != i) i = parent[i] = parent[parent[i]];
      return i;
    };
    std::vector<BPolygon> regions(n);
    std::vector<bg::model::box<BPoint>> boxes(n);
    for (std::size_t i = 0; i < n; ++i) {
      if (!use[i]) continue;
      regions[i] = spawnRegion(i).region;
      boxes[i] = bg::return_envelope<bg::model::box<BPoint>>(regions[i]);
    }
    const float halfTick = 0.5f * desc_.dt;
    for (std::size_t i = 0; i < n; ++i) {
      if (!use[i]) continue;
      for (std::size_t j = i + 1; j < n; ++j) {
        if (!use[j] || root(i) == root(j)) continue;
        if (std::fabs(desc_.populations[i].start - desc_.populations[j].start) > halfTick) continue;
        if (levels && std::fabs(spawnHeight(i) - spawnHeight(j)) > nav::kLevelSearch) continue;
        if (!bg::intersects(boxes[i], boxes[j])) continue;
        BMulti overlap;
        bg::intersection(regions[i], regions[j], overlap);
        if (bg::area(overlap) > 1e-6) parent[root(j)] = root(i);
      }
    }
    std::vector<std::vector<std::size_t>> clusters;
    std::vector<std::size_t> index(n, n);
    for (std::size_t i = 0; i < n; ++i) {
      if (!use[i]) continue;
      const std::size_t r = root(i);
      if (index[r] == n) {
        index[r] = clusters.size();
        clusters.emplace_back();
      }
      clusters[index[r]].push_back(i);
    }
    return clusters;
  }

  float spawnHeight(std::size_t i) const {
    const sim::SpawnDesc& spawn = desc_.populations[i].spawn;
    return spawn.kind == sim::SpawnKind::Point ? desc_.points[spawn.point].height : spawn.height;
  }

  /// One diagnostic when the walkable part of a cluster's spawn areas (`freeArea`) cannot hold its
  /// agents: agents × π r² / kSpawnPackingFactor, summed over the populations spawning there.
  void reportCapacity(const std::vector<std::size_t>& cluster, double freeArea) {
    double agents = 0.0, needed = 0.0;
    for (const std::size_t i : cluster) {
      const double r = desc_.populations[i].radius;
      agents += maxAgents(i);
      needed += maxAgents(i) * std::numbers::pi * r * r / kSpawnPackingFactor;
    }
    if (freeArea >= needed) return;
    const std::size_t last = cluster.back();
    const SpawnRegion s = spawnRegion(last);
    const sim::PopulationDesc& pop = desc_.populations[last];
    if (cluster.size() == 1) {
      error(s.pointer,
            "spawn area of " + num(freeArea) + " m² is too small for " + num(agents) + " agents of radius " +
                num(pop.radius) + " m",
            "at least " + num(needed) + " m² (agents × π r² / packing factor " + num(kSpawnPackingFactor) + ")",
            "enlarge the spawn area or spawn fewer groups");
      return;
    }
    std::string names;
    for (std::size_t k = 0; k < cluster.size(); ++k) {
      const std::size_t i = cluster[k];
      names += (k == 0 ? "" : k + 1 == cluster.size() ? " and " : ", ") + ("\"" + desc_.populations[i].id + "\" (" +
               num(maxAgents(i)) + " at " + spawnRegion(i).pointer + ")");
    }
    error(s.pointer,
          "spawn areas of populations " + names + " overlap and start at " + num(pop.start) + " s: " + num(freeArea) +
              " m² of walkable ground is too small for their " + num(agents) + " agents",
          "at least " + num(needed) + " m² (agents × π r² / packing factor " + num(kSpawnPackingFactor) +
              ", summed over the populations spawning there together)",
          "enlarge the spawn areas, spawn fewer groups, or start the populations at different times");
  }

  /// Spawn capacity on a flat world: the walkable part (clear of obstacles) of the union of the
  /// areas of populations that spawn together in overlapping areas must hold all their agents.
  void checkSpawnCapacity(const std::vector<std::optional<core::Vec2>>& starts) {
    std::vector<bool> use(desc_.populations.size(), false);
    for (std::size_t i = 0; i < use.size(); ++i) {
      use[i] = starts[i].has_value() && desc_.populations[i].spawn.kind != sim::SpawnKind::Position;
    }
    for (const auto& cluster : spawnClusters(use, false)) {
      BMulti all;
      for (const std::size_t i : cluster) {
        BMulti next;
        bg::union_(all, spawnRegion(i).region, next);
        all = std::move(next);
      }
      BMulti inFree;
      bg::intersection(all, free_, inFree);
      reportCapacity(cluster, bg::area(inFree));
    }
  }

  /// Spawn capacity on a multi-level world: the walkable part of the spawn areas at their floor,
  /// measured on the navmesh (ground within one body radius of it, sampled on a grid).
  void checkTerrainCapacity(const std::vector<std::optional<nav::MeshPoint>>& starts, const nav::NavQuery& query,
                            float agentRadius) {
    std::vector<bool> use(desc_.populations.size(), false);
    for (std::size_t i = 0; i < use.size(); ++i) {
      use[i] = starts[i].has_value() && desc_.populations[i].spawn.kind != sim::SpawnKind::Position;
    }
    for (const auto& cluster : spawnClusters(use, true)) {
      std::vector<BPolygon> regions;
      bg::model::box<BPoint> box;
      bg::assign_inverse(box);
      for (const std::size_t i : cluster) {
        regions.push_back(spawnRegion(i).region);
        bg::expand(box, bg::return_envelope<bg::model::box<BPoint>>(regions.back()));
      }
      const double w = box.max_corner().x() - box.min_corner().x(), h = box.max_corner().y() - box.min_corner().y();
      const double step = std::max(0.1, std::sqrt(w * h / 10000.0));  // at most 10,000 samples
      const float height = spawnHeight(cluster.front());
      const float reach = agentRadius + 0.02f;
      std::size_t walkable = 0;
      for (double y = box.min_corner().y() + 0.5 * step; y < box.max_corner().y(); y += step) {
        for (double x = box.min_corner().x() + 0.5 * step; x < box.max_corner().x(); x += step) {
          const BPoint b(x, y);
          if (std::none_of(regions.begin(), regions.end(), [&](const BPolygon& r) { return bg::within(b, r); })) continue;
          const core::Vec2 p(static_cast<float>(x), static_cast<float>(y));
          const auto m = snapAt(query, p, height, reach);
          if (m && core::lengthSq(m->p - p) <= reach * reach) ++walkable;
        }
      }
      reportCapacity(cluster, static_cast<double>(walkable) * step * step);
    }
  }

  /// A point inside a goal's region to route to.
  core::Vec2 goalTarget(const sim::PointDesc& p) const {
    if (p.polygon.empty() || core::pointInPolygon(p.polygon, p.position)) return p.position;
    BPoint inside;
    try {
      bg::point_on_surface(toBoost(p.polygon), inside);
    } catch (const std::exception&) {
      return p.position;
    }
    return core::Vec2(static_cast<float>(inside.x()), static_cast<float>(inside.y()));
  }

  /// The navmesh for reachability: the world's (crowd files) or built from the scenario's
  /// polygons or terrain; null after diagnostics (mapped to /walkable, /terrain or /navCellSize).
  std::shared_ptr<const nav::NavMesh> navmeshFor(nav::NavMeshConfig& config) {
    config = desc_.navMeshConfig();
    config.cancel = cancel_;
    if (worldNavmesh_) {
      config.agentRadius = worldNavmesh_->config().agentRadius;
      return worldNavmesh_;
    }
    const bool terrain = !desc_.terrain.empty();
    auto built = terrain ? nav::NavMesh::buildFromTerrain(desc_.terrain, config)
                         : nav::NavMesh::build(desc_.walkable, desc_.obstacles, config);
    if (built.ok()) return built.value();
    for (core::Diagnostic d : built.errors()) {
      // The navmesh names its own inputs ("navmesh", "/cellSize", "/terrain/walkable"); in a
      // scenario the problem is the walkable geometry (or navCellSize), so point there.
      std::string pointer = terrain ? "/terrain" : "/walkable";
      if (d.pointer == "/cellSize") pointer = "/navCellSize";
      else if (d.pointer == "/stairSlopeDeg") pointer = "/terrain/stairSlope";
      else if (terrain && d.pointer.rfind("/terrain", 0) == 0) pointer = d.pointer;
      const SourcePos pos = doc_.position(pointer);
      d.source = doc_.source();
      d.line = pos.line;
      d.column = pos.column;
      d.pointer = pointer;
      diags_.push_back(std::move(d));
    }
    return nullptr;
  }

  /// How far around a point's position its region reaches [m].
  static float regionReach(const sim::PointDesc& p) {
    if (p.polygon.empty()) return p.radius;
    const core::Aabb box = core::bounds(p.polygon);
    return 0.5f * core::length(box.max - box.min);
  }

  /// NavQuery::snap, keeping only points within the height band: Detour picks polygons by their
  /// bounding boxes, and a polygon spanning a ramp and the floor above it reaches into the band of
  /// the floor below.
  static std::optional<nav::MeshPoint> snapAt(const nav::NavQuery& query, core::Vec2 p, float height, float radius) {
    auto m = query.snap(p, height, radius);
    if (m && query.mesh().layered() && std::fabs(m->height - height) > nav::kLevelSearch) return std::nullopt;
    return m;
  }

  /// The height band a snap searches (nav::kLevelSearch).
  static std::string levelsText() { return " at heights within ±" + num(nav::kLevelSearch) + " m"; }

  /// Why an opening must be that wide: the navmesh keeps body centres half of it from walls.
  std::string clearanceText(float width) const {
    return " (the navmesh keeps body centres " + num(0.5f * width) + " m from walls: body radius " + num(desc_.maxRadius()) +
           " m × the model's passage ratio, rounded up to navmesh cells)";
  }

  static std::string at3(core::Vec2 p, float h) { return "(" + num(p.x) + ", " + num(p.y) + ", " + num(h) + ")"; }

  /// A multi-level world (ScenarioDesc::terrain): every check snaps to the navmesh at the given
  /// heights, so it needs the mesh; spawn capacity is measured on it (checkTerrainCapacity); the 2D
  /// polygon checks (spawn areas inside /walkable) have no counterpart yet.
  void runTerrain(const LoadOptions& options, std::shared_ptr<const nav::NavMesh>& navmesh) {
    if (!parsed_.terrainOk || !options.checkReachability) return;  // the parser said why / no mesh wanted
    nav::NavMeshConfig config;
    const auto mesh = navmeshFor(config);
    if (!mesh) return;
    navmesh = mesh;
    nav::NavQuery query(mesh);
    const std::string levels = " m" + levelsText();
    for (std::size_t i = firstOwnPoint_; i < desc_.points.size(); ++i) {
      if (i < parsed_.pointsOk.size() && !parsed_.pointsOk[i]) continue;
      const sim::PointDesc& point = desc_.points[i];
      const float reach = regionReach(point) + 1.0f;
      const auto snapped = snapAt(query, goalTarget(point), point.height, reach);
      if (!snapped) {
        error("/points/" + std::to_string(i - firstOwnPoint_),
              "point \"" + point.id + "\" at " + at3(point.position, point.height) +
                  " lies off the walkable surface (nothing walkable within " + num(reach) + levels + ")",
              "a region on a floor, stair or ramp of /terrain/walkable, at that floor's height (z)");
      } else {
        checkTerrainArrival(i, *snapped, config.agentRadius);
      }
    }
    std::vector<std::optional<nav::MeshPoint>> starts(desc_.populations.size());
    for (std::size_t i = 0; i < desc_.populations.size(); ++i) {
      if (i >= parsed_.populationsOk.size() || !parsed_.populationsOk[i]) continue;
      starts[i] = terrainSpawn(i, query, levels);
      const auto& script = desc_.populations[i].guide.script;
      for (std::size_t k = 0; k < script.size(); ++k) {
        if (snapAt(query, script[k].position, script[k].height, 1.0f)) continue;
        error("/populations/" + std::to_string(i) + "/guide/script/" + std::to_string(k) + "/position",
              "guide waypoint " + at3(script[k].position, script[k].height) +
                  " is off the walkable surface (nothing walkable within 1" + levels + ")",
              "a waypoint on a floor, stair or ramp of /terrain/walkable, at that floor's height (z)");
      }
    }
    checkTerrainCapacity(starts, query, config.agentRadius);
    if (!diags_.empty()) return;
    const float width = mesh->narrowestOpening();
    for (std::size_t i = 0; i < desc_.populations.size(); ++i) {
      if (!starts[i]) continue;
      const sim::PopulationDesc& pop = desc_.populations[i];
      for (const auto& [point, pointer, from] : destinations(i)) {
        const sim::PointDesc& goal = desc_.points[point];
        const auto target = snapAt(query, goalTarget(goal), goal.height, regionReach(goal) + 1.0f);
        std::optional<nav::MeshPoint> source = starts[i];
        if (from != kFromSpawn) {
          const sim::PointDesc& stop = desc_.points[from];
          source = snapAt(query, goalTarget(stop), stop.height, regionReach(stop) + 1.0f);
        }
        const auto locate = [&](std::uint32_t p) {
          return snapAt(query, goalTarget(desc_.points[p]), desc_.points[p].height, regionReach(desc_.points[p]) + 1.0f);
        };
        const auto walk = [&](const nav::MeshPoint& a, const nav::MeshPoint& b) { return query.reachable(a.p, a.height, b.p, b.height); };
        if (!target || !source || !reachableRiding(pop, *source, *target, locate, walk)) {
          error(pointer,
                "point \"" + goal.id + "\" cannot be reached from " +
                    (from == kFromSpawn ? "the spawn area of population \"" + pop.id + "\""
                                        : "transport stop \"" + desc_.points[from].id + "\" (population \"" + pop.id + "\")"),
                "a goal connected to the spawn" + std::string(ridesAny(pop) ? " (or to a lift's or escalator's stop)" : "") +
                    " by floors, stairs or ramps at least " + num(width) +
                    " m wide" + clearanceText(width) + ", steps at most " + num(config.maxClimb) + " m high, slopes at most " +
                    num(config.maxSlopeDeg) + "°",
                "check /terrain/walkable for a missing stair or ramp, and /terrain/obstacles for walls closing the way");
        }
      }
    }
  }

  /// Whether population `pop` may ride lifts and escalators of its own accord (useTransports).
  [[nodiscard]] bool ridesAny(const sim::PopulationDesc& pop) const { return pop.useTransports && !desc_.transports.empty(); }

  /// Whether `walk(a, b)` links `source` to `target`, or, for a population that rides of its own
  /// accord (ridesAny; sim::TransportRoutes), a chain of walks and rides does: from a place, to a
  /// boarding stop reachable on foot, carried to any other stop of a lift or to an escalator's head,
  /// and on from there. `locate(point)` is where a stop is on the navmesh (empty: nowhere).
  template <class Place, class Locate, class Walk>
  bool reachableRiding(const sim::PopulationDesc& pop, const Place& source, const Place& target, Locate locate, Walk walk) const {
    if (walk(source, target)) return true;
    if (!ridesAny(pop)) return false;
    std::vector<Place> places{source};
    std::vector<std::uint8_t> reached(desc_.points.size(), 0);
    for (std::size_t i = 0; i < places.size(); ++i) {
      for (const sim::TransportDesc& t : desc_.transports) {
        const bool lift = t.kind == sim::TransportKind::Elevator;
        for (std::size_t k = 0; k < (lift ? t.stops.size() : 1); ++k) {
          const auto board = locate(t.stops[k]);
          if (!board || !walk(places[i], *board)) continue;
          for (std::size_t m = lift ? 0 : 1; m < t.stops.size(); ++m) {
            if (m == k || reached[t.stops[m]] != 0) continue;
            reached[t.stops[m]] = 1;
            const auto off = locate(t.stops[m]);
            if (!off) continue;
            if (walk(*off, target)) return true;
            places.push_back(*off);
          }
        }
      }
    }
    return false;
  }

  /// The points population i walks to, with their JSON pointers: its goals (every option of a
  /// waypoint choice), then its exits.
  /// Each also with the point it is walked from: kFromSpawn, or the stop a lift or escalator took
  /// the population to (a goal that is a transport's boarding stop is followed by a ride).
  struct Destination {
    std::uint32_t point;
    std::string pointer;
    std::uint32_t from;
  };
  static constexpr std::uint32_t kFromSpawn = 0xffffffffu;
  [[nodiscard]] std::vector<Destination> destinations(std::size_t i) const {
    const sim::PopulationDesc& pop = desc_.populations[i];
    const std::string ptr = "/populations/" + std::to_string(i);
    std::vector<Destination> out;
    std::vector<std::uint32_t> fromAt(pop.goals.size());
    std::uint32_t from = kFromSpawn;
    for (std::size_t g = 0; g < pop.goals.size(); ++g) {
      fromAt[g] = from;
      out.push_back({pop.goals[g], ptr + "/goals/" + std::to_string(g), from});
      for (const sim::TransportDesc& t : desc_.transports) {  // ridden from there to the stop rideTo says
        const std::size_t boarding = t.kind == sim::TransportKind::Elevator ? t.stops.size() : 1;
        for (std::size_t k = 0; k < boarding; ++k) {
          if (t.stops[k] != pop.goals[g]) continue;
          const std::uint32_t next = g + 1 < pop.goals.size() ? pop.goals[g + 1] : 0xffffffffu;  // none
          from = t.stops[sim::rideTo(desc_, t, k, next)];
        }
      }
    }
    for (const sim::GoalChoiceDesc& c : pop.goalChoices) {
      out[c.slot].pointer += "/choose/0";
      for (std::size_t k = 1; k < c.options.size(); ++k) {
        out.push_back({c.options[k], ptr + "/goals/" + std::to_string(c.slot) + "/choose/" + std::to_string(k), fromAt[c.slot]});
      }
    }
    for (std::size_t e = 0; e < pop.exits.size(); ++e) out.push_back({pop.exits[e], ptr + "/exits/" + std::to_string(e), from});
    return out;
  }

  /// checkPointArrival on a multi-level world, for disc regions: the ground nearest the disc's
  /// centre at its floor's height (`snapped`) must lie within its radius.
  void checkTerrainArrival(std::size_t i, const nav::MeshPoint& snapped, float agentRadius) {
    const sim::PointDesc& point = desc_.points[i];
    if ((point.kind == sim::PointKind::Action && point.stop) || !point.polygon.empty()) return;
    const float distance = core::length(snapped.p - point.position);
    if (distance <= point.radius) return;
    error("/points/" + std::to_string(i - firstOwnPoint_) + "/position",
          kindName(point) + " \"" + core::printable(point.id, 80) + "\" cannot be reached: " + at3(point.position, point.height) +
              " is off the walkable surface and its radius " + num(point.radius) + " m reaches no ground where agents can stand (their centres keep " +
              num(agentRadius) + " m from walls); the nearest walkable point is " + centimetres(snapped.p) + " at height " +
              num(std::round(snapped.height * 100.0f) / 100.0f) + " m, " + num(std::round(distance * 100.0f) / 100.0f) + " m away",
          "a point whose disc reaches a floor, stair or ramp of /terrain/walkable",
          "move it to " + centimetres(snapped.p) + " or enlarge \"radius\" to at least " +
              num(std::ceil(distance * 100.0 - 1e-3) / 100.0) + " m");
  }

  static std::string kindName(const sim::PointDesc& point) {
    return point.kind == sim::PointKind::Exit ? "exit" : point.kind == sim::PointKind::Action ? "action point" : "interest point";
  }

  /// A population's spawn on a multi-level world: its centre (a position, a point's region) or,
  /// for a polygon, its vertices pulled halfway to the centre and the centre itself, snapped to the
  /// navmesh at the spawn's height. Returns the first point that snaps (reachability starts there).
  std::optional<nav::MeshPoint> terrainSpawn(std::size_t i, const nav::NavQuery& query, const std::string& levels) {
    const sim::SpawnDesc& spawn = desc_.populations[i].spawn;
    const std::string base = "/populations/" + std::to_string(i) + "/spawn";
    const std::string expected = "a spawn on a floor, stair or ramp of /terrain/walkable, at that floor's height (z)";
    switch (spawn.kind) {
      case sim::SpawnKind::Position: {
        if (auto m = snapAt(query, spawn.position, spawn.height, 1.0f)) return m;
        error(base + "/position",
              "spawn position " + at3(spawn.position, spawn.height) + " is off the walkable surface (nothing walkable within 1" +
                  levels + ")",
              expected);
        return std::nullopt;
      }
      case sim::SpawnKind::Point: {
        if (spawn.point >= parsed_.pointsOk.size() || !parsed_.pointsOk[spawn.point]) return std::nullopt;
        const sim::PointDesc& p = desc_.points[spawn.point];
        return snapAt(query, goalTarget(p), p.height, regionReach(p) + 1.0f);  // the point's own check reports a miss
      }
      case sim::SpawnKind::Polygon: break;
    }
    const core::Polygon& poly = spawn.polygon;
    sim::PointDesc region;
    region.polygon = poly;
    region.position = core::centroid(poly);
    const core::Vec2 centre = goalTarget(region);
    const std::size_t step = std::max<std::size_t>(1, poly.size() / 8);
    for (std::size_t k = 0; k < poly.size(); k += step) {
      if (auto m = snapAt(query, 0.5f * (poly[k] + centre), spawn.height, 1.0f)) return m;
    }
    const float reach = std::max(1.0f, regionReach(region));
    if (auto m = snapAt(query, centre, spawn.height, reach)) return m;
    error(base + "/polygon",
          "spawn area at height " + num(spawn.height) + " m is off the walkable surface (nothing walkable within " + num(reach) +
              " m of its centre " + at3(centre, spawn.height) + levelsText() + ")",
          expected, "give the floor's height as \"height\" next to \"polygon\"");
    return std::nullopt;
  }

  /// An agent arrives at an interest point, an exit or a non-stopping action point when its centre
  /// is inside the point's region (a stopping action point: near a target snapped to the navmesh,
  /// always reachable). Agents' centres stay on the navmesh (the walkable area minus obstacles,
  /// eroded by the agent radius), so a region that holds no navmesh ground — a disc drawn inside a
  /// wall — is never reached, and the run ends with every agent stuck in front of it. Says where
  /// the point is, why it cannot be reached and the nearest ground agents can stand on.
  void checkPointArrival(const nav::NavQuery& query, std::size_t i, float agentRadius) {
    const sim::PointDesc& point = desc_.points[i];
    if (point.kind == sim::PointKind::Action && point.stop) return;
    const std::string ptr = "/points/" + std::to_string(i - firstOwnPoint_);
    const std::string kind = kindName(point);
    if (!point.polygon.empty()) {
      const core::Vec2 target = goalTarget(point);
      const auto near = query.nearest(target, regionReach(point) + 1.0f);
      if (near && core::pointInPolygon(point.polygon, near->first)) return;
      BMulti overlap;
      bg::intersection(toBoost(point.polygon), free_, overlap);
      if (bg::area(overlap) > 1e-6) return;
      error(ptr + "/polygon",
            kind + " \"" + core::printable(point.id, 80) + "\" cannot be reached: its polygon covers no walkable ground (" +
                positionText(target) + ")" + nearestText(near, target),
            "a region that overlaps /walkable clear of /obstacles", "move the polygon onto walkable ground");
      return;
    }
    const auto near = query.nearest(point.position, point.radius + 3.0f);
    const float distance = near ? core::length(near->first - point.position) : std::numeric_limits<float>::infinity();
    if (distance <= point.radius) return;
    std::string hint = "move it onto walkable ground";
    if (near) {
      hint = "move it to " + centimetres(near->first) + " or enlarge \"radius\" to at least " +
             num(std::ceil(distance * 100.0 - 1e-3) / 100.0) + " m";
    }
    error(ptr + "/position",
          kind + " \"" + core::printable(point.id, 80) + "\" cannot be reached: " + positionText(point.position) +
              " and its radius " + num(point.radius) + " m reaches no ground where agents can stand (their centres keep " + num(agentRadius) +
              " m from walls)" + nearestText(near, point.position),
          "a point whose disc reaches walkable ground clear of /obstacles", hint);
  }

  /// "(x, y) is inside obstacle /obstacles/k", "(x, y) is outside the walkable area" or
  /// "(x, y) is too close to a wall".
  std::string positionText(core::Vec2 p) const {
    std::string problem = positionProblem(p);
    if (problem.empty()) problem = "(" + num(p.x) + ", " + num(p.y) + ") is too close to a wall or obstacle";
    return problem;
  }

  /// "; the nearest walkable point is (x, y), d m away" (or that there is none nearby).
  static std::string nearestText(const std::optional<std::pair<core::Vec2, nav::PolyRef>>& near, core::Vec2 from) {
    if (!near) return "; no walkable ground nearby";
    return "; the nearest walkable point is " + centimetres(near->first) + ", " +
           num(std::round(core::length(near->first - from) * 100.0f) / 100.0f) + " m away";
  }

  /// "(19.75, 0)": a point to the centimetre (num() keeps 3 significant digits).
  static std::string centimetres(core::Vec2 p) {
    const auto one = [](float v) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.2f", std::round(double(v) * 100.0) / 100.0);
      std::string s = buf;
      while (s.back() == '0') s.pop_back();
      if (s.back() == '.') s.pop_back();
      return s == "-0" ? std::string("0") : s;
    };
    return "(" + one(p.x) + ", " + one(p.y) + ")";
  }

  void checkReachability(const std::vector<std::optional<core::Vec2>>& starts, std::shared_ptr<const nav::NavMesh>& navmesh) {
    nav::NavMeshConfig config;
    const auto mesh = navmeshFor(config);
    if (!mesh) return;
    navmesh = mesh;
    nav::NavQuery query(navmesh);
    const float width = mesh->narrowestOpening();
    // Every point must touch the walkable area, used as a goal or not: a point out in the void is
    // a typo in its coordinates.
    for (std::size_t i = firstOwnPoint_; i < desc_.points.size(); ++i) {
      if (cancelled()) return;
      const sim::PointDesc& point = desc_.points[i];
      float reach = point.radius;
      if (!point.polygon.empty()) {
        const core::Aabb box = core::bounds(point.polygon);
        reach = 0.5f * core::length(box.max - box.min);
      }
      if (!query.nearest(goalTarget(point), reach + 1.0f)) {
        error("/points/" + std::to_string(i - firstOwnPoint_),
              "point \"" + point.id + "\" at (" + num(point.position.x) + ", " + num(point.position.y) +
                  ") lies outside the walkable area (no walkable ground within " + num(reach + 1.0f) + " m)",
              "a region that overlaps /walkable");
      } else {
        checkPointArrival(query, i, config.agentRadius);
      }
    }
    for (std::size_t i = 0; i < desc_.populations.size(); ++i) {
      if (cancelled()) return;
      if (!starts[i]) continue;
      const sim::PopulationDesc& pop = desc_.populations[i];
      const std::string ptr = "/populations/" + std::to_string(i);
      const SpawnRegion s = spawnRegion(i);
      double searchRadius = 1.0;
      if (!s.isPosition) {
        const auto box = bg::return_envelope<bg::model::box<BPoint>>(s.region);
        searchRadius = std::max(searchRadius, bg::distance(box.min_corner(), box.max_corner()));
      }
      const auto start = query.nearest(*starts[i], static_cast<float>(searchRadius));
      if (!start) {
        error(s.pointer, "no walkable area at least " + num(width) + " m wide" + clearanceText(width) + " near the spawn",
              "a spawn on or next to walkable area wide enough for the agents");
        continue;
      }
      for (const auto& [point, gptr, from] : destinations(i)) {
        const sim::PointDesc& goal = desc_.points[point];
        // Search around the goal as far as its region extends, plus a margin for the erosion.
        float reach = goal.radius;
        if (!goal.polygon.empty()) {
          const core::Aabb box = core::bounds(goal.polygon);
          reach = 0.5f * core::length(box.max - box.min);
        }
        const auto target = query.nearest(goalTarget(goal), reach + 1.0f);
        auto source = start;
        if (from != kFromSpawn) source = query.nearest(goalTarget(desc_.points[from]), regionReach(desc_.points[from]) + 1.0f);
        const auto locate = [&](std::uint32_t p) { return query.nearest(goalTarget(desc_.points[p]), regionReach(desc_.points[p]) + 1.0f); };
        const auto walk = [&](const auto& a, const auto& b) { return query.reachable(a.first, b.first); };
        if (!target || !source || !reachableRiding(pop, *source, *target, locate, walk)) {
          error(gptr,
                "point \"" + goal.id + "\" cannot be reached from " +
                    (from == kFromSpawn ? "the spawn area of population \"" + pop.id + "\""
                                        : "transport stop \"" + desc_.points[from].id + "\" (population \"" + pop.id + "\")"),
                "a goal connected to the spawn" + std::string(ridesAny(pop) ? " (or to a lift's or escalator's stop)" : "") +
                    " by walkable area at least " + num(width) + " m wide" + clearanceText(width),
                "check /obstacles for walls closing the way");
        }
      }
    }
  }

  const JsonDocument& doc_;
  const ParsedScenario& parsed_;
  const sim::ScenarioDesc& desc_;
  core::Diagnostics& diags_;
  BMulti walk_;
  BMulti free_;
  std::vector<BPolygon> obstacles_;
  std::size_t firstOwnPoint_ = 0;
  std::shared_ptr<const nav::NavMesh> worldNavmesh_;
  const std::atomic<int>* cancel_ = nullptr;
};

}  // namespace

void validateScenario(const JsonDocument& doc, const ParsedScenario& parsed, const LoadOptions& options,
                      core::Diagnostics& diagnostics, std::shared_ptr<const nav::NavMesh>& navmesh) {
  core::Diagnostics own;
  try {
    Validator v(doc, parsed, own);
    v.cancelWith(options.cancel);
    v.run(options, navmesh);
  } catch (const std::exception& e) {
    own.push_back(doc.diagnostic("", std::string("cannot validate the geometry: ") + e.what(), "simple polygons"));
  }
  diagnostics.insert(diagnostics.end(), own.begin(), own.end());
}

void validateCrowd(const JsonDocument& doc, const ParsedScenario& parsed, std::size_t firstOwnPoint,
                   std::shared_ptr<const nav::NavMesh> navmesh, core::Diagnostics& diagnostics) {
  core::Diagnostics own;
  try {
    Validator v(doc, parsed, own);
    const bool check = navmesh != nullptr;
    v.useWorld(firstOwnPoint, std::move(navmesh));
    std::shared_ptr<const nav::NavMesh> unused;
    LoadOptions options;
    options.checkReachability = check;
    v.run(options, unused);
  } catch (const std::exception& e) {
    own.push_back(doc.diagnostic("", std::string("cannot validate the crowd's geometry: ") + e.what(), "simple polygons"));
  }
  diagnostics.insert(diagnostics.end(), own.begin(), own.end());
}

}  // namespace throng::io
