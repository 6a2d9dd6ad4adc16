// applyCommands — spawning. Populations due this tick enter the world in population order; groups
// are placed together (members near a group anchor) on free spots of the spawn region, on the
// navmesh, never closer than the sum of radii to anyone already there when room allows. Every
// draw comes from a stream keyed by (seed, stable group or agent id, purpose).
#include <algorithm>
#include <cmath>

#include "throng/core/assert.hpp"
#include "throng/core/rng.hpp"
#include "world_impl.hpp"

namespace throng::sim {
namespace {

constexpr float kSpawnGap = 0.02f;  // extra clearance between spawned bodies [m]

/// Hash grid of occupied discs used while placing agents (only on ticks that spawn): open
/// addressing over cells, each cell's discs chained through one flat array. A few large blocks
/// (about 40 bytes per disc), freed whole when spawning ends, so placing a million agents leaves
/// no heap fragments behind.
class Occupancy {
 public:
  Occupancy(float cell, std::size_t expected) : cell_(cell) {
    std::size_t cap = 64;
    while (cap < 2 * expected) cap *= 2;
    keys_.resize(cap);
    heads_.assign(cap, kNone);
    entries_.reserve(expected);
  }
  void add(core::Vec2 p, float r) {
    if (2 * (cells_ + 1) > keys_.size()) rehash(2 * keys_.size());
    const std::size_t slot = find(key(p));
    if (heads_[slot] == kNone) {
      keys_[slot] = key(p);
      ++cells_;
    }
    entries_.push_back({p, r, heads_[slot]});
    heads_[slot] = static_cast<std::uint32_t>(entries_.size() - 1);
  }
  [[nodiscard]] bool free(core::Vec2 p, float r) const {
    const int cx = static_cast<int>(std::floor(p.x / cell_)), cy = static_cast<int>(std::floor(p.y / cell_));
    for (int y = cy - 1; y <= cy + 1; ++y) {
      for (int x = cx - 1; x <= cx + 1; ++x) {
        for (std::uint32_t i = heads_[find(pack(x, y))]; i != kNone; i = entries_[i].next) {
          const float d = r + entries_[i].r + kSpawnGap;
          if (core::lengthSq(p - entries_[i].p) < d * d) return false;
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
  for (const PopulationDesc& pop : desc.populations) goalLists.push_back(pop.goals);
  std::size_t totalGroups = 0;
  for (const PopulationDesc& pop : desc.populations) totalGroups += pop.groups;
  groups.reserve(totalGroups);
  std::uint32_t scheduled = 0;
  std::uint32_t groupId = 0;
  for (std::size_t p = 0; p < desc.populations.size(); ++p) {
    const PopulationDesc& pop = desc.populations[p];
    firstGroupId.push_back(groupId);
    std::vector<std::uint32_t> sizes(pop.groups);
    for (std::uint32_t g = 0; g < pop.groups; ++g) {
      core::Rng rng(desc.seed, groupId + g, core::RngPurpose::GroupSize);
      sizes[g] = pop.sizeMin == pop.sizeMax ? pop.sizeMin : rng.uniformInt(pop.sizeMin, pop.sizeMax);
      scheduled += sizes[g];
      GroupState state;
      state.population = static_cast<std::uint16_t>(p);
      state.expected = sizes[g];
      state.goalList = static_cast<std::uint32_t>(p);
      groups.push_back(std::move(state));
    }
    groupId += pop.groups;
    groupSizes.push_back(std::move(sizes));
  }
  stats.scheduled = scheduled;
  // Optional agent columns: only the features some population (or the scenario) uses.
  for (const PopulationDesc& pop : desc.populations) {
    agents.formation = agents.formation || (pop.flocking && pop.sizeMax >= 2);
    agents.sociological = agents.sociological || pop.sociological.enabled;
  }
  agents.commonGround = desc.social.enabled;
  // Every agent that will ever exist is known: exact capacity, no doubling slack on the columns.
  agents.forEachColumn([&](auto& column) { column.reserve(scheduled); });
  // Cold group parts: at most one per busy group (a follower and the group it follows: two).
  std::size_t extras = 0;
  for (const GroupState& g : groups) {
    const PopulationDesc& pop = desc.populations[g.population];
    if (desc.social.enabled) ++extras;
    else extras += (pop.follow.mode != FollowMode::None ? 2 : 0) +
                   ((pop.flocking && g.expected >= 2) || !pop.guide.script.empty() || pop.sociological.enabled ? 1 : 0);
  }
  groupExtras.reserve(std::min(extras, groups.size()));
  for (std::uint32_t gid = 0; gid < groups.size(); ++gid) {
    GroupState& g = groups[gid];
    const PopulationDesc& pop = desc.populations[g.population];
    const FollowDesc& f = pop.follow;
    if (f.mode != FollowMode::None && f.population < firstGroupId.size() && f.group < desc.populations[f.population].groups) {
      const std::uint32_t followed = firstGroupId[f.population] + f.group;
      markBusy(followed);
      routeFor(gid).followGroup = followed;
    }
    if (!pop.guide.script.empty()) routeFor(gid);
    if ((pop.flocking && g.expected >= 2) || pop.sociological.enabled) markBusy(gid);
    // Common Ground may start a coordination in any group (a lone visit too).
    if (desc.social.enabled && g.extra == kNoAgent) {
      g.extra = static_cast<std::uint32_t>(groupExtras.size());
      groupExtras.emplace_back();
    }
  }
  busyDirty = true;
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
  for (std::size_t p = 0; p < desc.populations.size(); ++p) {
    if (!populationSpawned[p] && populationStartTick[p] <= tick) spawnPopulation(p);
  }
}

void World::Impl::spawnPopulation(std::size_t populationIndex) {
  const PopulationDesc& pop = desc.populations[populationIndex];
  populationSpawned[populationIndex] = 1;
  const nav::NavQuery& query = *mainQuery;

  // Region the population spawns in.
  const Polygon* regionPoly = nullptr;
  core::Vec2 regionCentre;
  float regionRadius = 0.0f;
  switch (pop.spawn.kind) {
    case SpawnKind::Polygon: regionPoly = &pop.spawn.polygon; break;
    case SpawnKind::Position: regionCentre = pop.spawn.position; break;
    case SpawnKind::Point: {
      const PointDesc& point = desc.points[pop.spawn.point];
      if (!point.polygon.empty()) regionPoly = &point.polygon;
      regionCentre = point.position;
      regionRadius = point.radius;
      break;
    }
  }
  const core::Aabb box = regionPoly ? core::bounds(*regionPoly) : core::Aabb{};
  std::uint32_t total = 0;
  for (std::uint32_t s : groupSizes[populationIndex]) total += s;
  // A position spawn grows a disc big enough for everyone at half packing density.
  if (pop.spawn.kind == SpawnKind::Position) {
    regionRadius = std::sqrt(static_cast<float>(total) * pop.radius * pop.radius / 0.5f) + pop.radius;
  }

  Occupancy occupancy(std::max(0.5f, 4.0f * desc.maxRadius()), agents.size() + total);
  for (std::size_t r = 0; r < agents.size(); ++r) occupancy.add({agents.posX[r], agents.posY[r]}, agents.radius[r]);

  // Multi-level worlds: the spawn's height picks the floor.
  const float spawnHeight = pop.spawn.kind == SpawnKind::Point ? desc.points[pop.spawn.point].height : pop.spawn.height;
  auto nearestAt = [&](core::Vec2 p, float r) -> std::optional<std::pair<core::Vec2, nav::PolyRef>> {
    if (!agents.levels) return query.nearest(p, r);
    const auto hit = query.snap(p, spawnHeight, r);
    if (!hit) return std::nullopt;
    return std::make_pair(hit->p, hit->ref);
  };
  auto onMesh = [&](core::Vec2 p) -> std::optional<std::pair<core::Vec2, nav::PolyRef>> {
    auto hit = nearestAt(p, 0.5f);
    if (!hit || core::lengthSq(hit->first - p) > 1e-4f) return std::nullopt;
    return hit;
  };
  auto sampleRegion = [&](core::Rng& rng) -> std::optional<core::Vec2> {
    if (regionPoly) return samplePolygon(*regionPoly, box, rng);
    return sampleDisc(regionCentre, regionRadius, rng);
  };

  const std::vector<std::uint32_t>& sizes = groupSizes[populationIndex];
  for (std::uint32_t g = 0; g < sizes.size(); ++g) {
    const std::uint32_t groupId = firstGroupId[populationIndex] + g;
    core::Rng groupRng(desc.seed, groupId, core::RngPurpose::Spawn);
    // Group anchor: a free point on the mesh inside the region.
    core::Vec2 anchor = regionCentre;
    for (int attempt = 0; attempt < 200; ++attempt) {
      auto p = sampleRegion(groupRng);
      if (p && onMesh(*p) && occupancy.free(*p, pop.radius)) { anchor = *p; break; }
    }
    if (pop.autoGoals) reconstructGoals(groupId, anchor);
    const float groupSpread = 0.4f + 0.5f * std::sqrt(static_cast<float>(sizes[g]));
    for (std::uint32_t m = 0; m < sizes[g]; ++m) {
      const std::uint32_t agentId = nextAgentId++;
      core::Rng rng(desc.seed, agentId, core::RngPurpose::Spawn);
      std::optional<std::pair<core::Vec2, nav::PolyRef>> placed;
      // Near the anchor first, then anywhere in the region, then (an overfull region) in a
      // widening disc around the anchor beyond the region, and only then wherever the mesh is.
      for (int attempt = 0; attempt < 700 && !placed; ++attempt) {
        std::optional<core::Vec2> p;
        if (attempt < 100) {
          p = sampleDisc(anchor, groupSpread * (1.0f + 0.02f * static_cast<float>(attempt)), rng);
          if (regionPoly && !core::pointInPolygon(*regionPoly, *p)) p.reset();
        } else if (attempt < 400) {
          p = sampleRegion(rng);
        } else {
          p = sampleDisc(anchor, groupSpread + 0.05f * static_cast<float>(attempt - 400), rng);
        }
        if (!p || !occupancy.free(*p, pop.radius)) continue;
        placed = onMesh(*p);
      }
      if (!placed) placed = nearestAt(sampleDisc(anchor, groupSpread, rng), 5.0f);
      if (!placed) placed = std::make_pair(anchor, nav::PolyRef{0});
      occupancy.add(placed->first, pop.radius);

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
  stats.active = static_cast<std::uint32_t>(agents.size());
  rowsChanged = true;
}

}  // namespace throng::sim
