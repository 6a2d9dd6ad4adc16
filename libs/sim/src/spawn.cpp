// applyCommands — spawning. Populations due this tick enter the world in population order; groups
// are placed together (members near a group anchor) on free spots of the spawn area, on the
// navmesh, never closer than the sum of radii (plus a small gap) to anyone already there. Every
// draw comes from a stream keyed by (seed, stable group or agent id, purpose). When random spots
// run out (a crowded area), the populations sharing that area are laid out again on a packed
// lattice inside it, a deterministic layout; only what the area cannot hold at all goes around it.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <unordered_map>

#include "throng/core/assert.hpp"
#include "throng/core/rng.hpp"
#include "world_impl.hpp"

namespace throng::sim {
namespace {

constexpr float kSpawnGap = 0.02f;  // extra clearance between spawned bodies [m]
constexpr float kFloorGap = 1.5f;   // bodies further apart in height stand on different floors [m]

}  // namespace

/// Hash grid of occupied discs used while placing agents (only on ticks that spawn): open
/// addressing over cells, each cell's discs chained through one flat array. A few large blocks
/// (about 40 bytes per disc), freed whole when spawning ends, so placing a million agents leaves
/// no heap fragments behind.
class SpawnOccupancy {
 public:
  SpawnOccupancy(float cell, std::size_t expected) : cell_(cell) {
    std::size_t cap = 64;
    while (cap < 2 * expected) cap *= 2;
    keys_.resize(cap);
    heads_.assign(cap, kNone);
    entries_.reserve(expected);
  }
  /// A disc of radius `r` at `p` on the floor at height `z` (0 on flat worlds).
  void add(core::Vec2 p, float r, float z = 0.0f) {
    if (2 * (cells_ + 1) > keys_.size()) rehash(2 * keys_.size());
    const std::size_t slot = find(key(p));
    if (heads_[slot] == kNone) {
      keys_[slot] = key(p);
      ++cells_;
    }
    entries_.push_back({p, r, z, heads_[slot]});
    heads_[slot] = static_cast<std::uint32_t>(entries_.size() - 1);
  }
  /// Whether a disc of radius `r` at `p` on the floor at height `z` touches none (discs on other
  /// floors, more than kFloorGap above or below, do not count).
  [[nodiscard]] bool free(core::Vec2 p, float r, float z = 0.0f) const {
    const int cx = static_cast<int>(std::floor(p.x / cell_)), cy = static_cast<int>(std::floor(p.y / cell_));
    for (int y = cy - 1; y <= cy + 1; ++y) {
      for (int x = cx - 1; x <= cx + 1; ++x) {
        for (std::uint32_t i = heads_[find(pack(x, y))]; i != kNone; i = entries_[i].next) {
          const float d = r + entries_[i].r + kSpawnGap;
          if (core::lengthSq(p - entries_[i].p) < d * d && std::fabs(z - entries_[i].z) <= kFloorGap) return false;
        }
      }
    }
    return true;
  }

 private:
  static constexpr std::uint32_t kNone = 0xffffffffu;
  struct Entry {
    core::Vec2 p;
    float r;
    float z;
    std::uint32_t next;  ///< previous disc of the same cell, kNone at the end
  };
  static std::uint64_t pack(int x, int y) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(x)) << 32) | static_cast<std::uint32_t>(y);
  }
  [[nodiscard]] std::uint64_t key(core::Vec2 p) const {
    return pack(static_cast<int>(std::floor(p.x / cell_)), static_cast<int>(std::floor(p.y / cell_)));
  }
  /// The slot holding `k`, or the empty slot where it would go (linear probing; never full).
  [[nodiscard]] std::size_t find(std::uint64_t k) const {
    const std::size_t mask = keys_.size() - 1;
    std::size_t slot = core::mix64(k) & mask;
    while (heads_[slot] != kNone && keys_[slot] != k) slot = (slot + 1) & mask;
    return slot;
  }
  void rehash(std::size_t cap) {
    std::vector<std::uint64_t> keys = std::move(keys_);
    std::vector<std::uint32_t> heads = std::move(heads_);
    keys_.assign(cap, 0);
    heads_.assign(cap, kNone);
    for (std::size_t i = 0; i < keys.size(); ++i) {
      if (heads[i] == kNone) continue;
      const std::size_t slot = find(keys[i]);
      keys_[slot] = keys[i];
      heads_[slot] = heads[i];
    }
  }
  float cell_;
  std::vector<std::uint64_t> keys_;
  std::vector<std::uint32_t> heads_;  ///< last disc of the slot's cell, kNone: empty slot
  std::vector<Entry> entries_;
  std::size_t cells_ = 0;
};

namespace {

/// Uniform point in a polygon by rejection from its bounding box (nullopt after many misses).
std::optional<core::Vec2> samplePolygon(const Polygon& poly, const core::Aabb& box, core::Rng& rng) {
  for (int i = 0; i < 64; ++i) {
    const core::Vec2 p{static_cast<float>(rng.uniform(box.min.x, box.max.x)),
                       static_cast<float>(rng.uniform(box.min.y, box.max.y))};
    if (core::pointInPolygon(poly, p)) return p;
  }
  return std::nullopt;
}

core::Vec2 sampleDisc(core::Vec2 centre, float radius, core::Rng& rng) {
  const double r = radius * std::sqrt(rng.uniform());
  const double a = 6.283185307179586 * rng.uniform();
  return {centre.x + static_cast<float>(r * std::cos(a)), centre.y + static_cast<float>(r * std::sin(a))};
}

}  // namespace

void World::Impl::planPopulations() {
  const std::uint32_t scheduled = registerGroups(0);
  // Optional agent columns: only the features some population (or the scenario) uses.
  for (const PopulationDesc& pop : desc.populations) {
    agents.formation = agents.formation || (pop.flocking && pop.sizeMax >= 2);
    agents.sociological = agents.sociological || pop.sociological.enabled;
  }
  agents.commonGround = desc.social.enabled;
  // Every agent that will ever exist is known: exact capacity, no doubling slack on the columns.
  agents.forEachColumn([&](auto& column) { column.reserve(scheduled); });
}

std::uint32_t World::Impl::registerGroups(std::uint32_t firstPopulation) {
  // Group sizes are drawn per stable group id, so a group is the same whether its population came
  // with the scenario or with a crowd.
  THRONG_ASSERT(groupSizes.size() == firstPopulation && firstGroupId.size() == firstPopulation);
  const std::uint32_t firstGroup = groups.size();
  std::uint32_t gid = firstGroup, scheduled = 0;
  std::size_t extras = 0;  // cold parts: at most one per busy group (a follower and the group it follows: two)
  for (std::size_t p = firstPopulation; p < desc.populations.size(); ++p) {
    const PopulationDesc& pop = desc.populations[p];
    std::vector<std::uint32_t> sizes(pop.groups);
    for (std::uint32_t& size : sizes) {
      core::Rng rng(desc.seed, gid++, core::RngPurpose::GroupSize);
      size = pop.sizeMin == pop.sizeMax ? pop.sizeMin : rng.uniformInt(pop.sizeMin, pop.sizeMax);
      scheduled += size;
      if (desc.social.enabled) ++extras;
      else extras += (pop.follow.mode != FollowMode::None ? 2 : 0) +
                     ((pop.flocking && size >= 2) || !pop.guide.script.empty() || pop.sociological.enabled ? 1 : 0);
    }
    groupSizes.push_back(std::move(sizes));
  }
  groups.reserve(gid, std::min<std::size_t>(extras, gid));
  // One goal list per population (automatic goals add one per group when it spawns), then its groups.
  for (std::size_t p = firstPopulation; p < desc.populations.size(); ++p) {
    const auto goalList = static_cast<std::uint32_t>(goalLists.size());
    goalLists.push_back(desc.populations[p].goals);
    firstGroupId.push_back(groups.size());
    for (const std::uint32_t size : groupSizes[p]) {
      GroupState state;
      state.population = static_cast<std::uint16_t>(p);
      state.expected = size;
      state.goalList = goalList;
      groups.add(std::move(state));
    }
  }
  stats.scheduled += scheduled;
  // Busy groups, routes and cold parts.
  for (std::uint32_t gid = firstGroup; gid < groups.size(); ++gid) {
    const PopulationDesc& pop = desc.populations[groups[gid].population];
    const FollowDesc& f = pop.follow;
    if (f.mode != FollowMode::None && f.population < firstGroupId.size() && f.group < desc.populations[f.population].groups) {
      const std::uint32_t followed = firstGroupId[f.population] + f.group;
      groups.markBusy(followed);
      groups.routeFor(gid).followGroup = followed;
    }
    if (!pop.guide.script.empty()) groups.routeFor(gid);
    if ((pop.flocking && groups[gid].expected >= 2) || pop.sociological.enabled) groups.markBusy(gid);
    // Common Ground may start a coordination in any group (a lone visit too).
    if (desc.social.enabled) groups.giveExtra(gid);
  }
  return scheduled;
}

float World::Impl::groupSpeed(std::uint32_t gid) const {
  const PopulationDesc& pop = desc.populations[groups[gid].population];
  core::Rng speedRng(desc.seed, gid, core::RngPurpose::Speed);
  const double v = pop.speedSd > 0 ? speedRng.normal(pop.speedMean, pop.speedSd) : pop.speedMean;
  return static_cast<float>(std::clamp(v, static_cast<double>(pop.speedMin), static_cast<double>(pop.speedMax)));
}

void World::Impl::recordSpawn(std::uint32_t population, std::uint32_t agent, std::uint32_t group, std::uint32_t member) {
  if (!spawnRuns.empty()) {
    SpawnRun& run = spawnRuns.back();
    // The same run goes on while nothing else happened in between.
    if (run.at == pendingEvents.size() && run.tick == tick && run.population == population && run.firstAgent + run.count == agent) {
      ++run.count;
      return;
    }
  }
  spawnRuns.push_back({pendingEvents.size(), tick, population, agent, 1, group, member});
}

std::vector<Event> World::Impl::takeEvents() {
  if (spawnRuns.empty()) return std::move(pendingEvents);
  std::size_t total = pendingEvents.size();
  for (const SpawnRun& run : spawnRuns) total += run.count;
  std::vector<Event> out;
  out.reserve(total);
  std::size_t next = 0;
  for (const SpawnRun& run : spawnRuns) {
    out.insert(out.end(), pendingEvents.begin() + static_cast<std::ptrdiff_t>(next), pendingEvents.begin() + static_cast<std::ptrdiff_t>(run.at));
    next = run.at;
    // Walk the population's groups from the run's first agent (groups in id order, members in
    // spawn order; empty groups spawn nobody).
    const std::vector<std::uint32_t>& sizes = groupSizes[run.population];
    std::uint32_t group = run.group, member = run.member;
    for (std::uint32_t i = 0; i < run.count; ++i) {
      while (member >= sizes[group - firstGroupId[run.population]]) {
        ++group;
        member = 0;
      }
      out.push_back({run.tick, run.firstAgent + i, EventKind::Spawn, run.population, group});
      ++member;
    }
  }
  out.insert(out.end(), pendingEvents.begin() + static_cast<std::ptrdiff_t>(next), pendingEvents.end());
  spawnRuns.clear();
  std::vector<Event>().swap(pendingEvents);  // as if moved out
  return out;
}

void World::Impl::applyCommands() {
  applyCrowdCommands();  // inserted crowds' populations starting now spawn below
  std::vector<std::size_t> due;
  for (std::size_t p = 0; p < desc.populations.size(); ++p) {
    if (!populationSpawned[p] && populationStartTick[p] <= tick) due.push_back(p);
  }
  if (!due.empty()) spawnPopulations(due);
}

namespace {

/// Where one population appears: a polygon, or a disc (a point's radius; a position's disc grown
/// big enough for everyone at half packing density), at one floor's height on multi-level worlds.
struct SpawnArea {
  const Polygon* poly = nullptr;
  core::Vec2 centre;  ///< a spawn polygon's centroid, a point's or position's centre (never an unset origin)
  float radius = 0.0f;
  core::Aabb box;
  float height = 0.0f;  ///< its floor on multi-level worlds (0 on flat ones) [m]
  double area = 0.0;  ///< [m²]

  [[nodiscard]] bool contains(core::Vec2 p) const {
    return poly ? core::pointInPolygon(*poly, p) : core::lengthSq(p - centre) <= radius * radius;
  }
  [[nodiscard]] std::optional<core::Vec2> sample(core::Rng& rng) const {
    if (poly) return samplePolygon(*poly, box, rng);
    return sampleDisc(centre, radius, rng);
  }
};

SpawnArea spawnArea(const ScenarioDesc& desc, const PopulationDesc& pop, std::uint32_t total, bool levels) {
  SpawnArea a;
  switch (pop.spawn.kind) {
    case SpawnKind::Polygon: a.poly = &pop.spawn.polygon; break;
    case SpawnKind::Position:
      a.centre = pop.spawn.position;
      a.radius = std::sqrt(static_cast<float>(total) * pop.radius * pop.radius / 0.5f) + pop.radius;
      break;
    case SpawnKind::Point: {
      const PointDesc& point = desc.points[pop.spawn.point];
      if (!point.polygon.empty()) a.poly = &point.polygon;
      a.centre = point.position;
      a.radius = point.radius;
      break;
    }
  }
  if (a.poly) {
    a.box = core::bounds(*a.poly);
    if (pop.spawn.kind == SpawnKind::Polygon) a.centre = core::centroid(*a.poly);
    a.area = std::fabs(core::signedArea(*a.poly));
  } else {
    a.box = {{a.centre.x - a.radius, a.centre.y - a.radius}, {a.centre.x + a.radius, a.centre.y + a.radius}};
    a.area = 3.141592653589793 * static_cast<double>(a.radius) * a.radius;
  }
  if (levels) a.height = pop.spawn.kind == SpawnKind::Point ? desc.points[pop.spawn.point].height : pop.spawn.height;
  return a;
}

/// The navmesh near `p` (on multi-level worlds at the area's floor).
std::optional<std::pair<core::Vec2, nav::PolyRef>> nearestAt(const nav::NavQuery& query, bool levels, const SpawnArea& area,
                                                             core::Vec2 p, float r) {
  if (!levels) return query.nearest(p, r);
  const auto hit = query.snap(p, area.height, r);
  if (!hit) return std::nullopt;
  return std::make_pair(hit->p, hit->ref);
}

/// `p` itself when it lies on the navmesh.
std::optional<std::pair<core::Vec2, nav::PolyRef>> onMesh(const nav::NavQuery& query, bool levels, const SpawnArea& area,
                                                          core::Vec2 p) {
  auto hit = nearestAt(query, levels, area, p, 0.5f);
  if (!hit || core::lengthSq(hit->first - p) > 1e-4f) return std::nullopt;
  return hit;
}

bool boxesOverlap(const core::Aabb& a, const core::Aabb& b) {
  return a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y;
}

/// Position of cell (x, y) along the Hilbert curve over a 65536 x 65536 grid.
std::uint64_t hilbertIndex(std::uint32_t x, std::uint32_t y) {
  constexpr std::uint32_t n = 1u << 16;
  std::uint64_t d = 0;
  for (std::uint32_t s = n / 2; s > 0; s /= 2) {
    const std::uint32_t rx = (x & s) ? 1 : 0, ry = (y & s) ? 1 : 0;
    d += static_cast<std::uint64_t>(s) * s * ((3 * rx) ^ ry);
    if (ry == 0) {  // rotate the quadrant
      if (rx == 1) {
        x = n - 1 - x;
        y = n - 1 - y;
      }
      std::swap(x, y);
    }
  }
  return d;
}

/// Spots handed out once each (and given back): the first free one in their order, or the one
/// nearest a point (ties: the earlier). Buckets of 1 m cells, searched ring by ring.
class NearestSpots {
 public:
  explicit NearestSpots(const std::vector<std::pair<core::Vec2, nav::PolyRef>>& spots) : spots_(spots), used_(spots.size(), 0) {
    for (std::size_t i = 0; i < spots.size(); ++i) {
      const auto [x, y] = cellOf(spots[i].first);
      buckets_[key(x, y)].push_back(static_cast<std::uint32_t>(i));
      minX_ = std::min(minX_, x), maxX_ = std::max(maxX_, x), minY_ = std::min(minY_, y), maxY_ = std::max(maxY_, y);
    }
  }
  /// The first free spot at or after `from`.
  std::optional<std::size_t> firstFree(std::size_t from) {
    while (cursor_ < used_.size() && used_[cursor_]) ++cursor_;  // every spot before the cursor is taken
    for (std::size_t i = std::max(from, cursor_); i < used_.size(); ++i) {
      if (!used_[i]) return i;
    }
    return std::nullopt;
  }
  void take(std::size_t i) { used_[i] = 1; }
  void release(std::size_t i) {
    used_[i] = 0;
    cursor_ = std::min(cursor_, i);
  }
  std::optional<std::size_t> takeNearest(core::Vec2 p) {
    const auto [cx, cy] = cellOf(p);
    std::optional<std::size_t> best;
    float bestD = 0.0f;
    const int reach = std::max({cx - minX_, maxX_ - cx, cy - minY_, maxY_ - cy, 0});
    for (int k = 0; k <= reach; ++k) {
      if (best && bestD <= static_cast<float>(k - 1) * static_cast<float>(k - 1)) break;  // ring k is farther
      for (int y = cy - k; y <= cy + k; ++y) {
        for (int x = cx - k; x <= cx + k; ++x) {
          if (std::max(std::abs(x - cx), std::abs(y - cy)) != k) continue;
          const auto it = buckets_.find(key(x, y));
          if (it == buckets_.end()) continue;
          for (const std::uint32_t i : it->second) {
            if (used_[i]) continue;
            const float d = core::lengthSq(spots_[i].first - p);
            if (!best || d < bestD || (d == bestD && i < *best)) {
              best = i;
              bestD = d;
            }
          }
        }
      }
    }
    if (best) used_[*best] = 1;
    return best;
  }

 private:
  static std::pair<int, int> cellOf(core::Vec2 p) {
    return {static_cast<int>(std::floor(p.x)), static_cast<int>(std::floor(p.y))};
  }
  static std::uint64_t key(int x, int y) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(x)) << 32) | static_cast<std::uint32_t>(y);
  }
  const std::vector<std::pair<core::Vec2, nav::PolyRef>>& spots_;
  std::vector<std::uint8_t> used_;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> buckets_;
  std::size_t cursor_ = 0;
  int minX_ = std::numeric_limits<int>::max(), maxX_ = std::numeric_limits<int>::min();
  int minY_ = std::numeric_limits<int>::max(), maxY_ = std::numeric_limits<int>::min();
};

}  // namespace

World::Impl::SpawnPlan World::Impl::planRandomSpawn(std::size_t populationIndex, std::uint32_t firstAgent,
                                                    SpawnOccupancy& occupancy) {
  const PopulationDesc& pop = desc.populations[populationIndex];
  const nav::NavQuery& query = *mainQuery;
  const std::vector<std::uint32_t>& sizes = groupSizes[populationIndex];
  std::uint32_t total = 0;
  for (std::uint32_t s : sizes) total += s;
  const SpawnArea area = spawnArea(desc, pop, total, agents.levels);
  const bool levels = agents.levels;
  SpawnPlan plan;
  plan.population = populationIndex;
  plan.firstAgent = firstAgent;
  plan.spots.reserve(total);
  std::uint32_t agentId = firstAgent;
  for (std::uint32_t g = 0; g < sizes.size(); ++g) {
    const std::uint32_t groupId = firstGroupId[populationIndex] + g;
    core::Rng groupRng(desc.seed, groupId, core::RngPurpose::Spawn);
    // Group anchor: a free point on the mesh inside the area.
    std::optional<core::Vec2> anchor;
    for (int attempt = 0; attempt < 200 && !anchor; ++attempt) {
      auto p = area.sample(groupRng);
      if (p && onMesh(query, levels, area, *p) && occupancy.free(*p, pop.radius, area.height)) anchor = *p;
    }
    if (!anchor && pop.spawn.kind == SpawnKind::Polygon) {
      plan.placed = false;  // the area is crowded: laid out again on a lattice
      return plan;
    }
    plan.anchors.push_back(anchor.value_or(area.centre));
    const float groupSpread = 0.4f + 0.5f * std::sqrt(static_cast<float>(sizes[g]));
    for (std::uint32_t m = 0; m < sizes[g]; ++m, ++agentId) {
      core::Rng rng(desc.seed, agentId, core::RngPurpose::Spawn);
      std::optional<std::pair<core::Vec2, nav::PolyRef>> placed;
      // Near the anchor first, then anywhere in the area.
      for (int attempt = 0; attempt < 400 && !placed; ++attempt) {
        std::optional<core::Vec2> p;
        if (attempt < 100) {
          p = sampleDisc(plan.anchors.back(), groupSpread * (1.0f + 0.02f * static_cast<float>(attempt)), rng);
          if (area.poly && !core::pointInPolygon(*area.poly, *p)) p.reset();
        } else {
          p = area.sample(rng);
        }
        if (!p || !occupancy.free(*p, pop.radius, area.height)) continue;
        placed = onMesh(query, levels, area, *p);
      }
      if (!placed) {
        plan.placed = false;
        return plan;
      }
      occupancy.add(placed->first, pop.radius, area.height);
      plan.spots.push_back(*placed);
    }
  }
  return plan;
}

World::Impl::SpawnPlan World::Impl::planPackedSpawn(std::size_t populationIndex, std::uint32_t firstAgent,
                                                    SpawnOccupancy& occupancy) {
  const PopulationDesc& pop = desc.populations[populationIndex];
  const nav::NavQuery& query = *mainQuery;
  const std::vector<std::uint32_t>& sizes = groupSizes[populationIndex];
  std::uint32_t total = 0;
  for (std::uint32_t s : sizes) total += s;
  const SpawnArea area = spawnArea(desc, pop, total, agents.levels);
  const bool levels = agents.levels;
  SpawnPlan plan;
  plan.population = populationIndex;
  plan.firstAgent = firstAgent;
  if (total == 0) {
    plan.anchors.assign(sizes.size(), area.centre);
    return plan;
  }
  const float width = area.box.max.x - area.box.min.x, depth = area.box.max.y - area.box.min.y;
  // Free spots on a lattice over the area, row by row, each kept clear of everyone placed.
  auto scan = [&](SpawnOccupancy& occ, float dx, float dy, bool staggered, std::size_t want,
                  std::vector<std::pair<core::Vec2, nav::PolyRef>>& out) {
    const auto rows = static_cast<std::int64_t>(std::floor(depth / dy)) + 1;
    const auto cols = static_cast<std::int64_t>(std::floor(width / dx)) + 1;
    for (std::int64_t j = 0; j < rows && out.size() < want; ++j) {
      const float y = area.box.min.y + 0.5f * (depth - static_cast<float>(rows - 1) * dy) + static_cast<float>(j) * dy;
      const float shift = staggered && (j & 1) ? 0.5f * dx : 0.0f;
      for (std::int64_t i = 0; i < cols && out.size() < want; ++i) {
        const core::Vec2 p{area.box.min.x + 0.5f * (width - static_cast<float>(cols - 1) * dx) + shift + static_cast<float>(i) * dx, y};
        if (!area.contains(p) || !occ.free(p, pop.radius, area.height)) continue;
        if (auto hit = onMesh(query, levels, area, p)) {
          occ.add(hit->first, pop.radius, area.height);
          out.push_back(*hit);
        }
      }
    }
  };
  // A hexagonal lattice a little looser than the closest packing allowed (bodies kSpawnGap apart),
  // or spread over the whole area when that is tighter; tightened step by step while the area
  // holds too few spots, then a fine grid fills what is left. A few spots more than agents are
  // gathered when there is room, so groups need not take scattered leftovers.
  const float closest = 2.0f * pop.radius + kSpawnGap + 1e-3f;
  float spacing = std::clamp(static_cast<float>(std::sqrt(area.area / (0.8660254 * total))), closest, 1.15f * closest);
  const std::size_t want = total + total / 4 + 8;
  const double cells = static_cast<double>(width) * depth;
  std::vector<std::pair<core::Vec2, nav::PolyRef>> spots;
  std::optional<SpawnOccupancy> best;
  for (int attempt = 0; attempt < 24; ++attempt) {
    if (cells / (static_cast<double>(spacing) * spacing) > 4e6) break;  // a sliver in a huge box: the grid below
    SpawnOccupancy trial = occupancy;
    std::vector<std::pair<core::Vec2, nav::PolyRef>> found;
    found.reserve(want);
    scan(trial, spacing, 0.8660254f * spacing, true, want, found);
    if (found.size() >= spots.size()) {
      spots = std::move(found);
      best = std::move(trial);
    }
    if (spots.size() >= total || spacing <= closest) break;
    spacing = std::max(closest, spacing * 0.93f);
  }
  if (spots.size() < total) {
    SpawnOccupancy trial = best ? std::move(*best) : occupancy;
    const float step = std::max({pop.radius / 3.0f, 0.02f, static_cast<float>(std::sqrt(cells / 4e6))});
    scan(trial, step, step, false, total, spots);
  }
  plan.placed = spots.size() >= total;

  // Along a Hilbert curve over the area: spots next to each other in this order are close. Each
  // group starts at the first free spot in this order and its other members take the free spots
  // nearest to it; a start whose group would stand far apart is passed over (up to 32 tries).
  {
    const float cellSize = std::max({width, depth, 1e-3f}) / 65535.0f;
    std::vector<std::pair<std::uint64_t, std::uint32_t>> order(spots.size());
    for (std::size_t i = 0; i < spots.size(); ++i) {
      const auto qx = static_cast<std::uint32_t>(std::clamp((spots[i].first.x - area.box.min.x) / cellSize, 0.0f, 65535.0f));
      const auto qy = static_cast<std::uint32_t>(std::clamp((spots[i].first.y - area.box.min.y) / cellSize, 0.0f, 65535.0f));
      order[i] = {hilbertIndex(qx, qy), static_cast<std::uint32_t>(i)};
    }
    std::sort(order.begin(), order.end());
    std::vector<std::pair<core::Vec2, nav::PolyRef>> sorted;
    sorted.reserve(spots.size());
    for (const auto& entry : order) sorted.push_back(spots[entry.second]);
    spots = std::move(sorted);
  }
  NearestSpots nearest(spots);
  std::vector<std::optional<std::size_t>> chosen;  // per agent
  chosen.reserve(total);
  for (std::uint32_t g = 0; g < sizes.size(); ++g) {
    if (sizes[g] == 0) continue;  // an empty group takes no spot
    const float tolerated = spacing * (1.5f + std::sqrt(static_cast<float>(sizes[g])));
    std::vector<std::size_t> bestTry;
    float bestSpread = 0.0f;
    std::size_t from = 0;
    for (int attempt = 0; attempt < 32; ++attempt) {
      const std::optional<std::size_t> leader = nearest.firstFree(from);
      if (!leader) break;
      std::vector<std::size_t> members{*leader};
      nearest.take(*leader);
      float spread = 0.0f;
      for (std::uint32_t m = 1; m < sizes[g]; ++m) {
        const auto next = nearest.takeNearest(spots[*leader].first);
        if (!next) break;
        members.push_back(*next);
        spread = std::max(spread, core::length(spots[*next].first - spots[*leader].first));
      }
      for (const std::size_t i : members) nearest.release(i);
      if (bestTry.empty() || members.size() > bestTry.size() || (members.size() == bestTry.size() && spread < bestSpread)) {
        bestTry = members;
        bestSpread = spread;
      }
      if (members.size() == sizes[g] && spread <= tolerated) break;
      from = *leader + 1;
    }
    for (const std::size_t i : bestTry) nearest.take(i);
    for (std::uint32_t m = 0; m < sizes[g]; ++m) chosen.push_back(m < bestTry.size() ? std::optional<std::size_t>(bestTry[m]) : std::nullopt);
  }

  // The spots taken become occupied; agents the area cannot hold go around it (widening discs),
  // or to the navmesh nearest the area.
  for (const auto& c : chosen) {
    if (c) occupancy.add(spots[*c].first, pop.radius, area.height);
  }
  std::uint32_t agentId = firstAgent;
  std::size_t k = 0;
  for (std::uint32_t g = 0; g < sizes.size(); ++g) {
    plan.anchors.push_back(sizes[g] > 0 && chosen[k] ? spots[*chosen[k]].first : area.centre);
    const float groupSpread = 0.4f + 0.5f * std::sqrt(static_cast<float>(sizes[g]));
    for (std::uint32_t m = 0; m < sizes[g]; ++m, ++agentId, ++k) {
      if (chosen[k]) {
        plan.spots.push_back(spots[*chosen[k]]);
        continue;
      }
      plan.placed = false;
      const core::Vec2 anchor = plan.anchors.back();
      core::Rng rng(desc.seed, agentId, core::RngPurpose::Spawn);
      std::optional<std::pair<core::Vec2, nav::PolyRef>> placed;
      for (int attempt = 0; attempt < 300 && !placed; ++attempt) {
        const core::Vec2 p = sampleDisc(anchor, groupSpread + 0.05f * static_cast<float>(attempt), rng);
        if (occupancy.free(p, pop.radius, area.height)) placed = onMesh(query, levels, area, p);
      }
      if (!placed) placed = nearestAt(query, levels, area, anchor, std::max(5.0f, 0.5f * (width + depth)));
      if (!placed) placed = std::make_pair(anchor, nav::PolyRef{0});
      occupancy.add(placed->first, pop.radius, area.height);
      plan.spots.push_back(*placed);
    }
  }
  return plan;
}

void World::Impl::spawnPopulations(const std::vector<std::size_t>& due) {
  std::size_t expected = agents.size();
  std::vector<std::uint32_t> firstAgent;
  std::uint32_t nextId = nextAgentId;
  for (const std::size_t p : due) {
    firstAgent.push_back(nextId);
    for (const std::uint32_t s : groupSizes[p]) nextId += s;
    expected += nextId - firstAgent.back();
  }
  const float cell = std::max(0.5f, 4.0f * desc.maxRadius());
  auto occupied = [&] {
    SpawnOccupancy occupancy(cell, expected);
    for (std::size_t r = 0; r < agents.size(); ++r) {
      occupancy.add({agents.posX[r], agents.posY[r]}, agents.radius[r], agents.levels ? agents.posZ[r] : 0.0f);
    }
    return occupancy;
  };
  SpawnOccupancy occupancy = occupied();
  std::vector<SpawnPlan> plans;
  plans.reserve(due.size());
  bool allPlaced = true;
  for (std::size_t k = 0; k < due.size(); ++k) {
    plans.push_back(planRandomSpawn(due[k], firstAgent[k], occupancy));
    allPlaced = allPlaced && plans.back().placed;
  }
  if (!allPlaced) {
    // Random spots ran out in some area. Every population whose area overlaps such an area (and
    // so on, transitively) is laid out again on the lattice, in population order; the others keep
    // their spots.
    std::vector<core::Aabb> boxes;
    std::vector<std::uint8_t> redo(due.size(), 0);
    for (std::size_t k = 0; k < due.size(); ++k) {
      std::uint32_t total = 0;
      for (const std::uint32_t s : groupSizes[due[k]]) total += s;
      boxes.push_back(spawnArea(desc, desc.populations[due[k]], total, agents.levels).box);
      redo[k] = plans[k].placed ? 0 : 1;
    }
    for (bool grew = true; grew;) {
      grew = false;
      for (std::size_t k = 0; k < due.size(); ++k) {
        if (redo[k]) continue;
        for (std::size_t o = 0; o < due.size() && !redo[k]; ++o) {
          if (redo[o] && boxesOverlap(boxes[k], boxes[o])) redo[k] = grew = true;
        }
      }
    }
    occupancy = occupied();
    for (std::size_t k = 0; k < due.size(); ++k) {
      if (redo[k]) continue;
      const PopulationDesc& pop = desc.populations[due[k]];
      const float height = spawnArea(desc, pop, 0, agents.levels).height;
      for (const auto& spot : plans[k].spots) occupancy.add(spot.first, pop.radius, height);
    }
    for (std::size_t k = 0; k < due.size(); ++k) {
      if (redo[k]) plans[k] = planPackedSpawn(due[k], firstAgent[k], occupancy);
    }
  }
  for (const SpawnPlan& plan : plans) addSpawnedAgents(plan);
  stats.active = static_cast<std::uint32_t>(agents.size());
  rowsChanged = true;
}

void World::Impl::addSpawnedAgents(const SpawnPlan& plan) {
  const std::size_t populationIndex = plan.population;
  const PopulationDesc& pop = desc.populations[populationIndex];
  populationSpawned[populationIndex] = 1;
  const nav::NavQuery& query = *mainQuery;
  const std::vector<std::uint32_t>& sizes = groupSizes[populationIndex];
  const float spawnHeight = pop.spawn.kind == SpawnKind::Point ? desc.points[pop.spawn.point].height : pop.spawn.height;
  THRONG_ASSERT(nextAgentId == plan.firstAgent);
  std::size_t spot = 0;
  for (std::uint32_t g = 0; g < sizes.size(); ++g) {
    const std::uint32_t groupId = firstGroupId[populationIndex] + g;
    if (pop.autoGoals) reconstructGoals(groupId, plan.anchors[g]);
    for (std::uint32_t m = 0; m < sizes[g]; ++m) {
      const std::uint32_t agentId = nextAgentId++;
      const std::pair<core::Vec2, nav::PolyRef>* placed = &plan.spots[spot++];
      const std::size_t row = agents.addRow();
      agents.id[row] = agentId;
      agents.group[row] = groupId;
      agents.population[row] = static_cast<std::uint16_t>(populationIndex);
      agents.groupSize[row] = static_cast<std::uint16_t>(std::min<std::uint32_t>(sizes[g], 0xffff));
      agents.posX[row] = placed->first.x;
      agents.posY[row] = placed->first.y;
      agents.polyRef[row] = static_cast<std::uint32_t>(placed->second);  // 32-bit Detour references
      if (agents.levels) agents.posZ[row] = placed->second != 0 ? query.heightAt(placed->second, placed->first) : spawnHeight;
      agents.radius[row] = pop.radius;
      core::Rng speedRng(desc.seed, agentId, core::RngPurpose::Speed);
      const double v = pop.speedSd > 0 ? speedRng.normal(pop.speedMean, pop.speedSd) : pop.speedMean;
      agents.speed[row] = static_cast<float>(std::clamp(v, static_cast<double>(pop.speedMin), static_cast<double>(pop.speedMax)));
      agents.oriX[row] = 1.0f;
      agents.oriY[row] = 0.0f;
      agents.mode[row] = AgentMode::Waiting;
      agents.goalState[row] = GoalState::Seeking;
      agents.goalCursor[row] = 0;
      recordSpawn(static_cast<std::uint32_t>(populationIndex), agentId, groupId, m);
      ++stats.spawned;
      --stats.scheduled;
      agents.targetSub[row] = -1;
      if (agents.sociological) agents.followAgent[row] = kNoAgent;
      if (agents.commonGround) {
        agents.coordination[row] = kNoAgent;
        agents.desirePoint[row] = kNoAgent;
        agents.scriptClip[row] = kNoClip;
      }
      // Interests matter only to the goal generator (Common Ground on).
      if (agents.commonGround && !pop.interests.empty() && pop.interestsPerAgent > 0) {
        // Common Ground: this agent's interests, drawn from its population's without repetition.
        core::Rng interestRng(desc.seed, agentId, core::RngPurpose::Social);
        std::vector<std::string> pool = pop.interests;
        for (std::uint32_t k = 0; k < pop.interestsPerAgent && !pool.empty(); ++k) {
          const std::uint32_t pick = interestRng.uniformInt(0, static_cast<std::uint32_t>(pool.size() - 1));
          const auto c = std::find(categories.begin(), categories.end(), pool[pick]);
          if (c != categories.end() && c - categories.begin() < 64) agents.interests[row] |= std::uint64_t{1} << (c - categories.begin());
          pool.erase(pool.begin() + pick);
        }
      }
      // Join the group (flocking: everyone walks at the group's speed) and head for its current goal.
      GroupState& group = groups[groupId];
      group.members.push_back(agentId);
      if (group.leader == kNoAgent) group.leader = agentId;
      if (group.flocks(pop)) agents.speed[row] = groupSpeed(groupId);
      setGoal(row, group.cursor, query);
      // Face the first target.
      const core::Vec2 dir = core::normalize(core::Vec2{agents.targetX[row] - agents.posX[row], agents.targetY[row] - agents.posY[row]});
      if (core::lengthSq(dir) > 0.0f) { agents.oriX[row] = dir.x; agents.oriY[row] = dir.y; }
      agents.progressDistance[row] = 1e30f;
    }
  }
}

}  // namespace throng::sim
