// Spawn layout (spawn_layout.hpp): the random layout of a population (groups around anchors, random
// free spots) and the packed lattice laid out instead when random spots run out in a crowded area.
// Reads the scenario, the navmesh and the occupied discs (LayoutInput, LayoutJob); writes a
// SpawnPlan. Deterministic: every draw comes from a stream keyed by (seed, stable group or agent
// id, purpose).
#include "spawn_layout.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <unordered_map>

#include "hilbert.hpp"
#include "throng/core/assert.hpp"

namespace throng::sim {

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

bool boxesOverlap(const core::Aabb& a, const core::Aabb& b) {
  return a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y;
}

namespace {

using Spot = std::pair<core::Vec2, nav::PolyRef>;

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

SpawnPlan planRandomSpawn(const LayoutInput& in, const LayoutJob& job, SpawnOccupancy& occupancy) {
  const ScenarioDesc& desc = in.desc;
  const PopulationDesc& pop = desc.populations[job.population];
  const nav::NavQuery& query = in.query;
  const std::span<const std::uint32_t> sizes = job.groupSizes;
  std::uint32_t total = 0;
  for (std::uint32_t s : sizes) total += s;
  const bool levels = in.levels;
  const SpawnArea area = spawnArea(desc, pop, total, levels);
  SpawnPlan plan;
  plan.population = job.population;
  plan.firstAgent = job.firstAgent;
  plan.spots.reserve(total);
  std::uint32_t agentId = job.firstAgent;
  for (std::uint32_t g = 0; g < sizes.size(); ++g) {
    const std::uint32_t groupId = job.firstGroup + g;
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

namespace {

/// What a packed layout works on: the area, its box, the navmesh and the body radius.
struct Lattice {
  const SpawnArea& area;
  const nav::NavQuery& query;
  bool levels = false;
  float radius = 0.0f;
  [[nodiscard]] float width() const { return area.box.max.x - area.box.min.x; }
  [[nodiscard]] float depth() const { return area.box.max.y - area.box.min.y; }

  /// Free spots on a lattice of steps dx, dy over the area, row by row (odd rows shifted by half a
  /// step when staggered), each kept clear of everyone placed, until `want` are found.
  void scan(SpawnOccupancy& occ, float dx, float dy, bool staggered, std::size_t want, std::vector<Spot>& out) const {
    const float w = width(), d = depth();
    const auto rows = static_cast<std::int64_t>(std::floor(d / dy)) + 1;
    const auto cols = static_cast<std::int64_t>(std::floor(w / dx)) + 1;
    for (std::int64_t j = 0; j < rows && out.size() < want; ++j) {
      const float y = area.box.min.y + 0.5f * (d - static_cast<float>(rows - 1) * dy) + static_cast<float>(j) * dy;
      const float shift = staggered && (j & 1) ? 0.5f * dx : 0.0f;
      for (std::int64_t i = 0; i < cols && out.size() < want; ++i) {
        const core::Vec2 p{area.box.min.x + 0.5f * (w - static_cast<float>(cols - 1) * dx) + shift + static_cast<float>(i) * dx, y};
        if (!area.contains(p) || !occ.free(p, radius, area.height)) continue;
        if (auto hit = onMesh(query, levels, area, p)) {
          occ.add(hit->first, radius, area.height);
          out.push_back(*hit);
        }
      }
    }
  }
};

/// Spots for `total` agents: a hexagonal lattice a little looser than the closest packing allowed
/// (bodies kSpawnGap apart), or spread over the whole area when that is tighter; tightened step by
/// step while the area holds too few spots, then a fine grid fills what is left. A few spots more
/// than agents are gathered when there is room, so groups need not take scattered leftovers.
/// `spacing` receives the lattice step used [m].
std::vector<Spot> packedSpots(const Lattice& lattice, const SpawnOccupancy& occupancy, std::uint32_t total, float& spacing) {
  const float closest = 2.0f * lattice.radius + kSpawnGap + 1e-3f;
  spacing = std::clamp(static_cast<float>(std::sqrt(lattice.area.area / (0.8660254 * total))), closest, 1.15f * closest);
  const std::size_t want = total + total / 4 + 8;
  const double cells = static_cast<double>(lattice.width()) * lattice.depth();
  std::vector<Spot> spots;
  std::optional<SpawnOccupancy> best;
  for (int attempt = 0; attempt < 24; ++attempt) {
    if (cells / (static_cast<double>(spacing) * spacing) > 4e6) break;  // a sliver in a huge box: the grid below
    SpawnOccupancy trial = occupancy;
    std::vector<Spot> found;
    found.reserve(want);
    lattice.scan(trial, spacing, 0.8660254f * spacing, true, want, found);
    if (found.size() >= spots.size()) {
      spots = std::move(found);
      best = std::move(trial);
    }
    if (spots.size() >= total || spacing <= closest) break;
    spacing = std::max(closest, spacing * 0.93f);
  }
  if (spots.size() < total) {
    SpawnOccupancy trial = best ? std::move(*best) : occupancy;
    const float step = std::max({lattice.radius / 3.0f, 0.02f, static_cast<float>(std::sqrt(cells / 4e6))});
    lattice.scan(trial, step, step, false, total, spots);
  }
  return spots;
}

/// Orders spots along a Hilbert curve over the box: spots next to each other in this order are close.
void sortAlongHilbertCurve(std::vector<Spot>& spots, const core::Aabb& box) {
  const float cellSize = std::max({box.max.x - box.min.x, box.max.y - box.min.y, 1e-3f}) / 65535.0f;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> order(spots.size());
  for (std::size_t i = 0; i < spots.size(); ++i) {
    const auto qx = static_cast<std::uint32_t>(std::clamp((spots[i].first.x - box.min.x) / cellSize, 0.0f, 65535.0f));
    const auto qy = static_cast<std::uint32_t>(std::clamp((spots[i].first.y - box.min.y) / cellSize, 0.0f, 65535.0f));
    order[i] = {hilbertIndex(qx, qy), static_cast<std::uint32_t>(i)};
  }
  std::sort(order.begin(), order.end());
  std::vector<Spot> sorted;
  sorted.reserve(spots.size());
  for (const auto& entry : order) sorted.push_back(spots[entry.second]);
  spots = std::move(sorted);
}

/// The spots of one group: it starts at the first free spot in curve order and its other members
/// take the free spots nearest to it; a start whose group would stand far apart is passed over (up
/// to 32 tries; the best try wins). Takes the spots it returns.
std::vector<std::size_t> groupSpots(NearestSpots& nearest, const std::vector<Spot>& spots, std::uint32_t size, float spacing) {
  const float tolerated = spacing * (1.5f + std::sqrt(static_cast<float>(size)));
  std::vector<std::size_t> bestTry;
  float bestSpread = 0.0f;
  std::size_t from = 0;
  for (int attempt = 0; attempt < 32; ++attempt) {
    const std::optional<std::size_t> leader = nearest.firstFree(from);
    if (!leader) break;
    std::vector<std::size_t> members{*leader};
    nearest.take(*leader);
    float spread = 0.0f;
    for (std::uint32_t m = 1; m < size; ++m) {
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
    if (members.size() == size && spread <= tolerated) break;
    from = *leader + 1;
  }
  for (const std::size_t i : bestTry) nearest.take(i);
  return bestTry;
}

/// A spot for an agent the area cannot hold (another population or an inserted crowd already stands
/// in it): a free one of the area in discs widening round its group's anchor up to kOverflowReach
/// beyond the group's spread; else the roomiest of kOverflowSamples random spots of the area, where
/// the bodies step apart in the first ticks — not a free spot metres outside it (up to 15 m before
/// session 34: spawned 3.6 m beyond their sector, people in the validation's 5 /m² ring walked back
/// to their first waypoint for seconds); or the navmesh nearest the area (occupied once chosen).
constexpr float kOverflowReach = 1.0f;  ///< [m]
constexpr int kOverflowSamples = 32;

Spot placeOutside(const Lattice& lattice, SpawnOccupancy& occupancy, core::Vec2 anchor, std::uint32_t groupSize,
                  std::uint32_t agentId, std::uint64_t seed) {
  const float groupSpread = 0.4f + 0.5f * std::sqrt(static_cast<float>(groupSize));
  core::Rng rng(seed, agentId, core::RngPurpose::Spawn);
  std::optional<Spot> placed;
  constexpr float kWiden = 0.05f;  // [m] per attempt
  for (int attempt = 0; kWiden * static_cast<float>(attempt) <= kOverflowReach && !placed; ++attempt) {
    const core::Vec2 p = sampleDisc(anchor, groupSpread + kWiden * static_cast<float>(attempt), rng);
    if (lattice.area.contains(p) && occupancy.free(p, lattice.radius, lattice.area.height)) placed = onMesh(lattice.query, lattice.levels, lattice.area, p);
  }
  if (!placed) {
    float roomiest = -1e30f;
    for (int k = 0; k < kOverflowSamples; ++k) {
      const std::optional<core::Vec2> p = lattice.area.sample(rng);
      if (!p) continue;
      const float room = occupancy.room(*p, lattice.radius, lattice.area.height);
      if (room <= roomiest) continue;
      if (const auto spot = onMesh(lattice.query, lattice.levels, lattice.area, *p)) {
        roomiest = room;
        placed = spot;
      }
    }
  }
  if (!placed) placed = nearestAt(lattice.query, lattice.levels, lattice.area, anchor, std::max(5.0f, 0.5f * (lattice.width() + lattice.depth())));
  if (!placed) placed = std::make_pair(anchor, nav::PolyRef{0});
  occupancy.add(placed->first, lattice.radius, lattice.area.height);
  return *placed;
}

}  // namespace

SpawnPlan planPackedSpawn(const LayoutInput& in, const LayoutJob& job, SpawnOccupancy& occupancy) {
  const PopulationDesc& pop = in.desc.populations[job.population];
  const std::span<const std::uint32_t> sizes = job.groupSizes;
  std::uint32_t total = 0;
  for (std::uint32_t s : sizes) total += s;
  const SpawnArea area = spawnArea(in.desc, pop, total, in.levels);
  SpawnPlan plan;
  plan.population = job.population;
  plan.firstAgent = job.firstAgent;
  if (total == 0) {
    plan.anchors.assign(sizes.size(), area.centre);
    return plan;
  }
  const Lattice lattice{area, in.query, in.levels, pop.radius};
  float spacing = 0.0f;
  std::vector<Spot> spots = packedSpots(lattice, occupancy, total, spacing);
  plan.placed = spots.size() >= total;
  sortAlongHilbertCurve(spots, area.box);
  NearestSpots nearest(spots);
  std::vector<std::optional<std::size_t>> chosen;  // per agent
  chosen.reserve(total);
  for (std::uint32_t g = 0; g < sizes.size(); ++g) {
    if (sizes[g] == 0) continue;  // an empty group takes no spot
    const std::vector<std::size_t> taken = groupSpots(nearest, spots, sizes[g], spacing);
    for (std::uint32_t m = 0; m < sizes[g]; ++m) chosen.push_back(m < taken.size() ? std::optional<std::size_t>(taken[m]) : std::nullopt);
  }
  // The spots taken become occupied; agents the area cannot hold go around it.
  for (const auto& c : chosen) {
    if (c) occupancy.add(spots[*c].first, pop.radius, area.height);
  }
  std::uint32_t agentId = job.firstAgent;
  std::size_t k = 0;
  for (std::uint32_t g = 0; g < sizes.size(); ++g) {
    plan.anchors.push_back(sizes[g] > 0 && chosen[k] ? spots[*chosen[k]].first : area.centre);
    for (std::uint32_t m = 0; m < sizes[g]; ++m, ++agentId, ++k) {
      if (chosen[k]) {
        plan.spots.push_back(spots[*chosen[k]]);
        continue;
      }
      plan.placed = false;
      plan.spots.push_back(placeOutside(lattice, occupancy, plan.anchors.back(), sizes[g], agentId, in.desc.seed));
    }
  }
  return plan;
}

}  // namespace throng::sim
