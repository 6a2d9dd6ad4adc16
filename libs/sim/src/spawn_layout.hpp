// Spawn layout — where agents appear (the spawn phase, spawn.cpp, places them): the occupied discs
// while placing (SpawnOccupancy), a population's spawn area (SpawnArea), the samplers, and the two
// layouts of one population (LayoutInput, LayoutJob → SpawnPlan): random free spots around group
// anchors (planRandomSpawn) and the packed lattice over the area (planPackedSpawn), both in
// spawn_layout.cpp. Private to throng_sim.
#pragma once
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "throng/core/geometry.hpp"
#include "throng/core/rng.hpp"
#include "throng/nav/navmesh.hpp"
#include "throng/sim/scenario.hpp"

namespace throng::sim {

inline constexpr float kSpawnGap = 0.02f;  ///< extra clearance between spawned bodies [m]
inline constexpr float kFloorGap = 1.5f;   ///< bodies further apart in height stand on different floors [m]

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
    return !anyNear(p, z, [&](const Entry& e) {
      const float d = r + e.r + kSpawnGap;
      return core::lengthSq(p - e.p) < d * d;
    });
  }
  /// How much room a disc of radius `r` at `p` (height `z`) has: the smallest gap to a disc within
  /// a cell of it [m], negative when it overlaps one, `cell` when none is that near.
  [[nodiscard]] float room(core::Vec2 p, float r, float z = 0.0f) const {
    float best = cell_;
    anyNear(p, z, [&](const Entry& e) {
      best = std::min(best, core::length(p - e.p) - r - e.r);
      return false;
    });
    return best;
  }

 private:
  static constexpr std::uint32_t kNone = 0xffffffffu;
  struct Entry {
    core::Vec2 p;
    float r;
    float z;
    std::uint32_t next;  ///< previous disc of the same cell, kNone at the end
  };
  /// Calls f(entry) for the discs on p's floor (within kFloorGap of z) in the 3 × 3 cells round p,
  /// until it returns true; whether one did.
  template <class F>
  bool anyNear(core::Vec2 p, float z, F&& f) const {
    const int cx = static_cast<int>(std::floor(p.x / cell_)), cy = static_cast<int>(std::floor(p.y / cell_));
    for (int y = cy - 1; y <= cy + 1; ++y) {
      for (int x = cx - 1; x <= cx + 1; ++x) {
        for (std::uint32_t i = heads_[find(pack(x, y))]; i != kNone; i = entries_[i].next) {
          if (std::fabs(z - entries_[i].z) <= kFloorGap && f(entries_[i])) return true;
        }
      }
    }
    return false;
  }
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

/// Uniform point in a polygon by rejection from its bounding box (nullopt after many misses).
std::optional<core::Vec2> samplePolygon(const Polygon& poly, const core::Aabb& box, core::Rng& rng);
/// Uniform point in a disc.
core::Vec2 sampleDisc(core::Vec2 centre, float radius, core::Rng& rng);


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

/// The spawn area of `pop`, for `total` agents (a position's disc grows with them).
SpawnArea spawnArea(const ScenarioDesc& desc, const PopulationDesc& pop, std::uint32_t total, bool levels);
/// Whether two boxes overlap (touching counts).
bool boxesOverlap(const core::Aabb& a, const core::Aabb& b);

/// What laying out a population reads.
struct LayoutInput {
  const ScenarioDesc& desc;    ///< seed, populations (spawn area, radius), points (spawn points)
  const nav::NavQuery& query;  ///< spots must lie on the navmesh
  bool levels = false;         ///< a multi-level world: spots on the spawn area's floor
};

/// One population to lay out: its groups (stable ids from firstGroup, in order) and agents (stable
/// ids from firstAgent, group by group). Every draw comes from a stream keyed by (seed, stable
/// group or agent id, purpose).
struct LayoutJob {
  std::size_t population = 0;
  std::span<const std::uint32_t> groupSizes;
  std::uint32_t firstGroup = 0;
  std::uint32_t firstAgent = 0;
};

/// Where one population's agents appear: planned for every population due in a tick before any of
/// them is added, so a crowded area can be laid out again as a whole.
struct SpawnPlan {
  std::size_t population = 0;
  std::uint32_t firstAgent = 0;                            ///< stable id of its first agent
  std::vector<core::Vec2> anchors;                         ///< per group: where it gathers
  std::vector<std::pair<core::Vec2, nav::PolyRef>> spots;  ///< per agent, in spawn order
  bool placed = true;  ///< every agent found a free spot on the navmesh inside the spawn area
};

/// Random layout: per group an anchor (a free spot on the navmesh inside the area), its members
/// on free spots near it, then anywhere in the area. Occupies the spots it takes. Stops early with
/// placed = false when the area is crowded (a polygon without a free anchor, or a member without
/// a spot).
[[nodiscard]] SpawnPlan planRandomSpawn(const LayoutInput& in, const LayoutJob& job, SpawnOccupancy& occupancy);
/// Packed layout: free spots of the densest lattice over the area that holds everyone (sorted
/// along a Hilbert curve, each group on neighbouring spots); agents the area cannot hold go around
/// it (placed = false). Occupies the spots it takes.
[[nodiscard]] SpawnPlan planPackedSpawn(const LayoutInput& in, const LayoutJob& job, SpawnOccupancy& occupancy);

}  // namespace throng::sim
