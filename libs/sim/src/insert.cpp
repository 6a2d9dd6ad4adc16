// Crowds inserted at run time — World::insertCrowd / removeCrowd and the scenario timeline — and
// agents removed by id (World::removeAgents); exits closed and opened by the timeline and
// World::setExitOpen (setExitClosedNow: exit choice and decide's closedExits).
// A crowd (CrowdDesc: new points and populations) is checked against the world when it is queued
// (CrowdCheck) and applied at the start of the next tick (applyCommands), before any population
// spawns that tick: its points and populations are appended to the description, the spawner
// schedules them and registers their groups as it did the scenario's own (Spawner::registerGroups:
// the next stable group ids), its agents get the next agent ids as they spawn, and the optional
// agent columns it needs (formation, sociological model) are created. A removal takes the crowd's
// agents out at the start of the tick (an Exit event each, a = kNoPoint; leaveWorld, phases.hpp);
// agents removed by id leave the same way, after the crowd commands (b = kNoIndex).
// Everything is serial and in command order, so trajectories never depend on the thread count.
// Reads and writes World::Impl (insertion edits the scenario itself).
#include <algorithm>
#include <cmath>
#include <set>
#include <system_error>

#include "throng/sim/animation.hpp"
#include "world_impl.hpp"

namespace throng::sim {
namespace {

/// Population indices are 16 bits in the agent store and the group table.
constexpr std::size_t kMaxPopulations = 0xffff;
/// Interests are a 64-bit mask over the point categories (Common Ground).
constexpr std::size_t kMaxCategories = 64;

std::uint64_t ticksOf(float time, float dt) {
  return static_cast<std::uint64_t>(std::ceil(static_cast<double>(time) / dt - 1e-6));
}

}  // namespace

namespace {

/// Checks a crowd against the world's scenario, the crowds queued before it and the Common Ground
/// categories; diagnostics in the order a reader meets the crowd: ids, points, populations, size.
class CrowdCheck {
 public:
  CrowdCheck(const CrowdDesc& crowd, const ScenarioDesc& desc, const CrowdInsertion& insertion,
             const CommonGroundState& commonGround)
      : crowd_(crowd), desc_(desc), insertion_(insertion), commonGround_(commonGround),
        source_("crowd " + (crowd.id.empty() ? std::string("(no id)") : "\"" + crowd.id + "\"")) {}

  core::Diagnostics run() {
    checkIds();
    if (crowd_.basePoints > desc_.points.size() || crowd_.basePopulations > desc_.populations.size()) {
      error("", "the crowd was resolved against a world with more points or populations than this one",
            "a crowd parsed against this world (io::parseCrowd with World::desc())");
      return std::move(out_);
    }
    checkActions();
    for (std::size_t i = 0; i < crowd_.populations.size(); ++i) checkPopulation(i);
    checkBudget();
    return std::move(out_);
  }

 private:
  void error(std::string pointer, std::string what, std::string expected) {
    out_.push_back({source_, 0, 0, std::move(pointer), std::move(what), std::move(expected), ""});
  }

  /// The crowd's id, its points' ids and the world's population count; fills the ids taken.
  void checkIds() {
    if (crowd_.id.empty()) error("/id", "empty crowd id", "a non-empty id");
    for (const CrowdState& c : insertion_.crowds) {
      if (c.info.id == crowd_.id) error("/id", "crowd id \"" + crowd_.id + "\" is already taken", "an id no crowd of this world has");
    }
    // Ids taken by the world and by every crowd queued so far.
    for (const PointDesc& p : desc_.points) pointIds_.insert(p.id);
    for (const PopulationDesc& p : desc_.populations) populationIds_.insert(p.id);
    for (const CrowdState& c : insertion_.crowds) {
      if (c.info.applied) continue;
      pointIds_.insert(c.pointIds.begin(), c.pointIds.end());
      populationIds_.insert(c.populationIds.begin(), c.populationIds.end());
    }
    for (std::size_t i = 0; i < crowd_.points.size(); ++i) {
      if (!pointIds_.insert(crowd_.points[i].id).second) {
        error("/points/" + std::to_string(i) + "/id", "point id \"" + crowd_.points[i].id + "\" is already taken",
              "an id no point of the world or of this crowd has");
      }
    }
    std::size_t populationsAfter = desc_.populations.size() + crowd_.populations.size();
    for (const CrowdState& c : insertion_.crowds) {
      if (!c.info.applied) populationsAfter += c.populationIds.size();
    }
    if (populationsAfter > kMaxPopulations) {
      error("/populations", "the world would have " + std::to_string(populationsAfter) + " populations",
            "at most " + std::to_string(kMaxPopulations) + " populations in a world");
    }
  }

  /// Action points play clips the world has; Common Ground's categories still fit the interest mask.
  void checkActions() {
    const std::vector<ClipInfo> clips = animationClips(desc_);
    for (std::size_t i = 0; i < crowd_.points.size(); ++i) {
      const PointDesc& p = crowd_.points[i];
      if (p.kind != PointKind::Action || !p.stop) continue;
      const std::string name = p.action.empty() ? "stand" : p.action;
      if (std::none_of(clips.begin(), clips.end(), [&](const ClipInfo& c) { return c.name == name; })) {
        error("/points/" + std::to_string(i) + "/action", "action \"" + name + "\" has no clip in this world",
              "an action some action point of the world already plays (the clip table is fixed when the world starts)");
      }
    }
    if (!desc_.social.enabled) return;
    std::set<std::string, std::less<>> categories(commonGround_.categories.begin(), commonGround_.categories.end());
    for (const PointDesc& p : crowd_.points) if (!p.category.empty()) categories.insert(p.category);
    if (categories.size() > kMaxCategories) {
      error("/points", std::to_string(categories.size()) + " point categories", "at most " + std::to_string(kMaxCategories));
    }
  }

  void checkPopulation(std::size_t i) {
    const PopulationDesc& pop = crowd_.populations[i];
    const std::string ptr = "/populations/" + std::to_string(i);
    const std::uint64_t pointCount = crowd_.basePoints + crowd_.points.size();
    const std::uint64_t populationCount = crowd_.basePopulations + crowd_.populations.size();
    if (!populationIds_.insert(pop.id).second) {
      error(ptr + "/id", "population id \"" + pop.id + "\" is already taken", "an id no population of the world or of this crowd has");
    }
    for (std::size_t g = 0; g < pop.goals.size(); ++g) {
      if (pop.goals[g] >= pointCount) error(ptr + "/goals/" + std::to_string(g), "point index out of range", "a point of the world or of the crowd");
    }
    for (const GoalChoiceDesc& c : pop.goalChoices) {
      const std::string cptr = ptr + "/goals/" + std::to_string(c.slot) + "/choose";
      if (c.slot >= pop.goals.size()) error(ptr + "/goals", "a choice past the last goal", "a choice at one of the goals");
      for (const std::uint32_t o : c.options) {
        if (o >= pointCount) error(cptr, "point index out of range", "points of the world or of the crowd");
      }
    }
    if (pop.spawn.kind == SpawnKind::Point && pop.spawn.point >= pointCount) {
      error(ptr + "/spawn/point", "point index out of range", "a point of the world or of the crowd");
    }
    if (pop.follow.mode != FollowMode::None) {
      const std::uint32_t f = pop.follow.population;
      const std::uint32_t groupsThere = f < crowd_.basePopulations ? (f < desc_.populations.size() ? desc_.populations[f].groups : 0)
                                        : f < populationCount ? crowd_.populations[f - crowd_.basePopulations].groups : 0;
      if (f >= populationCount || pop.follow.group >= groupsThere) {
        error(ptr + "/follow", "followed population or group out of range", "a group of a population of the world or of the crowd");
      }
    }
    if (pop.largestRadius() * pop.model.passageRatio() > insertion_.navRadius + 1e-6f) {
      error(ptr + "/radius",
            "body radius " + std::to_string(pop.radius) + " m (× passage ratio " + std::to_string(pop.model.passageRatio()) +
                ") exceeds the world's navmesh erosion radius " + std::to_string(insertion_.navRadius) + " m",
            "a radius × passage ratio <= the scenario's navmesh erosion radius");
    }
    if (pop.groups == 0 || pop.sizeMin == 0 || pop.sizeMin > pop.sizeMax) {
      error(ptr, "empty or inverted group sizes", "groups >= 1 and 1 <= size min <= size max");
    }
  }

  void checkBudget() {
    const std::uint64_t agents = crowd_.maxAgents();
    if (agents > kMaxInsertAgents) {
      error("/populations", "the crowd may spawn " + std::to_string(agents) + " agents",
            "at most " + std::to_string(kMaxInsertAgents) + " agents per insertion");
    } else if (insertion_.insertedAgents + agents > kMaxInsertedAgents) {
      error("/populations",
            "the crowd may spawn " + std::to_string(agents) + " agents; " + std::to_string(insertion_.insertedAgents) +
                " were inserted into this world already",
            "at most " + std::to_string(kMaxInsertedAgents) + " inserted agents per world in all");
    }
  }

  const CrowdDesc& crowd_;
  const ScenarioDesc& desc_;
  const CrowdInsertion& insertion_;
  const CommonGroundState& commonGround_;
  std::string source_;
  core::Diagnostics out_;
  std::set<std::string, std::less<>> pointIds_, populationIds_;
};

}  // namespace

core::Diagnostics World::Impl::checkCrowd(const CrowdDesc& crowd) const {
  return CrowdCheck(crowd, desc, insertion, commonGround).run();
}

std::uint32_t World::Impl::queueCrowd(const CrowdDesc& crowd) {
  CrowdState c;
  c.desc = crowd;
  c.info.id = crowd.id;
  c.info.index = static_cast<std::uint32_t>(insertion.crowds.size());
  for (const PointDesc& p : crowd.points) c.pointIds.push_back(p.id);
  for (const PopulationDesc& p : crowd.populations) c.populationIds.push_back(p.id);
  insertion.insertedAgents += crowd.maxAgents();
  insertion.crowds.push_back(std::move(c));
  return insertion.crowds.back().info.index;
}

void World::Impl::initTimeline() {
  for (const TimelineEntry& e : desc.timeline) insertion.timelineTick.push_back(ticksOf(e.time, desc.dt));
}

void World::Impl::applyCrowdCommands() {
  while (insertion.timelineNext < desc.timeline.size() && insertion.timelineTick[insertion.timelineNext] <= tick) {
    const TimelineEntry& e = desc.timeline[insertion.timelineNext++];
    if (e.action == TimelineAction::Insert) {
      // io validated the whole timeline; a crowd that no longer fits is skipped, never half-applied.
      if (checkCrowd(e.crowd).empty()) {
        const std::uint32_t index = queueCrowd(e.crowd);
        insertCrowdNow(insertion.crowds[index]);
      }
    } else if (e.action == TimelineAction::CloseExit || e.action == TimelineAction::OpenExit) {
      setExitClosedNow(e.point, e.action == TimelineAction::CloseExit);
    } else {
      for (CrowdState& c : insertion.crowds) {
        if (c.info.id == e.crowdId) removeCrowdNow(c);
      }
    }
  }
  const std::vector<CrowdCommand> commands = std::move(insertion.commands);
  insertion.commands.clear();
  for (const CrowdCommand& c : commands) {
    if (c.insert) insertCrowdNow(insertion.crowds[c.crowd]);
    else removeCrowdNow(insertion.crowds[c.crowd]);
  }
  for (const auto& [point, closed] : insertion.exitCommands) setExitClosedNow(point, closed);
  insertion.exitCommands.clear();
  removeAgentsNow();
}

void World::Impl::setExitClosedNow(std::uint32_t point, bool closed) {
  exitChoice.setClosed(point, closed);
  if (closedExits.size() <= point) closedExits.resize(point + 1, 0);
  const bool changed = (closedExits[point] != 0) != closed;
  closedExits[point] = closed ? 1 : 0;
  if (changed) closeDoorFloor(point, closed);
}

namespace {

/// Whether the segment a → b touches `region`.
bool segmentTouches(const nav::CutRegion& region, core::Vec2 a, core::Vec2 b) {
  if (region.polygon.empty()) return core::distanceToSegmentSq(region.centre, a, b) <= region.radius * region.radius;
  if (region.contains(a) || region.contains(b)) return true;
  const core::Polygon& poly = region.polygon;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    if (core::segmentsIntersect(a, b, poly[j], poly[i])) return true;
  }
  return false;
}

}  // namespace

namespace {

bool sameRegion(const nav::CutRegion& a, const nav::CutRegion& b) {
  return a.centre.x == b.centre.x && a.centre.y == b.centre.y && a.radius == b.radius && a.height == b.height &&
         a.polygon.size() == b.polygon.size() &&
         std::equal(a.polygon.begin(), a.polygon.end(), b.polygon.begin(), [](core::Vec2 p, core::Vec2 q) { return p.x == q.x && p.y == q.y; });
}

}  // namespace

bool World::Impl::exitCut(std::uint32_t point) const {
  const nav::CutRegion region = cutRegion(desc.points[point]);
  const std::vector<nav::CutRegion>& cuts = navmesh->config().cuts;
  return std::any_of(cuts.begin(), cuts.end(), [&](const nav::CutRegion& c) { return sameRegion(c, region); });
}

nav::NavMeshConfig World::Impl::configWithEveryExit() const {
  nav::NavMeshConfig config = navmesh->config();
  config.cancel = nullptr;
  for (std::uint32_t p = 0; p < desc.points.size(); ++p) {
    if (desc.points[p].kind == PointKind::Exit && !exitCut(p)) config.cuts.push_back(cutRegion(desc.points[p]));
  }
  return config;
}

namespace {

/// The same build as the world's first (World::create), so the same mesh on every rank and run,
/// whichever thread builds it and whenever.
core::Result<std::shared_ptr<const nav::NavMesh>> buildMesh(const std::vector<core::Polygon>& walkable,
                                                            const std::vector<core::Polygon>& obstacles,
                                                            const nav::TerrainMesh& terrain, const nav::NavMeshConfig& config) {
  return terrain.empty() ? nav::NavMesh::build(walkable, obstacles, config) : nav::NavMesh::buildFromTerrain(terrain, config);
}

bool sameRegions(const std::vector<nav::CutRegion>& a, const std::vector<nav::CutRegion>& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), sameRegion);
}

}  // namespace

void World::Impl::startCutBuild() {
  if (!meshRebuildable()) return;
  nav::NavMeshConfig config = configWithEveryExit();
  if (config.cuts.size() == navmesh->config().cuts.size()) return;
  if (cutBuild.mesh.valid()) cutBuild.mesh.wait();  // an earlier crowd's: superseded
  cutBuild.cuts = config.cuts;
  try {
    // The build reads copies: the world's description changes while it runs (more crowds).
    cutBuild.mesh = std::async(std::launch::async, [walkable = desc.walkable, obstacles = desc.obstacles,
                                                    terrain = desc.terrain, config = std::move(config)] {
      return buildMesh(walkable, obstacles, terrain, config);
    });
  } catch (const std::system_error&) {
    cutBuild = {};  // no thread to spare: cutExitsIntoMesh builds it when a door closes
  }
}

bool World::Impl::cutExitsIntoMesh() {
  if (!meshRebuildable()) return false;
  const nav::NavMeshConfig config = configWithEveryExit();
  if (config.cuts.size() == navmesh->config().cuts.size()) return false;
  // Built in the background since the crowd came, when it was built for these very exits.
  const bool ready = cutBuild.mesh.valid() && sameRegions(cutBuild.cuts, config.cuts);
  auto built = ready ? cutBuild.mesh.get() : buildMesh(desc.walkable, desc.obstacles, desc.terrain, config);
  cutBuild = {};  // a superseded build is waited for here
  if (!built) return false;
  std::shared_ptr<nav::NavMesh> mesh = built.value()->clone();
  if (mesh->layered() != navmesh->layered()) return false;
  retiredMeshes.push_back(navmesh);
  ownMesh = mesh;
  navmesh = mesh;
  mainQuery = std::make_unique<nav::NavQuery>(navmesh);
  for (WorkerScratch& ws : scratch) ws.query = std::make_unique<nav::NavQuery>(navmesh);
  pathQueue->setMesh(navmesh);
  buildWalls();
  // Doors closed so far close again on the new polygons.
  doorPolys.clear();
  for (std::uint32_t p = 0; p < closedExits.size(); ++p) {
    if (closedExits[p] == 0) continue;
    auto& polys = doorPolys.emplace(p, ownMesh->cutPolygons(cutRegion(desc.points[p]))).first->second;
    ownMesh->setClosed(polys, true);
  }
  exitChoice.setMesh(*navmesh);
  transportRoutes.prepare(desc, *navmesh, *mainQuery);
  // Every polygon reference agents hold is of the old mesh (a fresh build reuses reference values
  // for other polygons): each agent finds its polygon again where it stands, on its floor.
  const bool levels = agents.levels;
  for (std::size_t row = 0; row < agents.size(); ++row) {
    const core::Vec2 pos{agents.posX[row], agents.posY[row]};
    const auto at = mainQuery->snap(pos, levels ? agents.posZ[row] : 0.0f, 2.0f);
    agents.polyRef[row] = at ? static_cast<std::uint32_t>(at->ref) : 0;
  }
  return true;
}

void World::Impl::closeDoorFloor(std::uint32_t point, bool closed) {
  if (point >= desc.points.size()) return;
  // An exit of a crowd World::insertCrowd brought is cut into the mesh when it first closes.
  if (closed && !exitCut(point)) cutExitsIntoMesh();
  if (!ownMesh) return;
  const nav::CutRegion region = cutRegion(desc.points[point]);
  auto it = doorPolys.find(point);
  if (it == doorPolys.end()) it = doorPolys.emplace(point, ownMesh->cutPolygons(region)).first;
  if (it->second.empty()) return;  // no floor in its region (or a mesh that could not be rebuilt: exitIsWall)
  ownMesh->setClosed(it->second, closed);
  if (!closed) {
    // Polygons shared with another exit that is still closed stay closed.
    for (const auto& [other, polys] : doorPolys) {
      if (other != point && other < closedExits.size() && closedExits[other] != 0) ownMesh->setClosed(polys, true);
    }
  }
  pathQueue->restart();
  exitChoice.meshChanged();  // exit choice measures round the closed doors (ExitChoice::refresh)
  transportRoutes.meshChanged();  // so does the choice of a lift, an escalator or the stairs
  const bool levels = agents.levels;
  for (std::size_t row = 0; row < agents.size(); ++row) {
    const core::Vec2 pos{agents.posX[row], agents.posY[row]};
    const bool sameFloor = !levels || std::abs(agents.posZ[row] - region.height) <= nav::kLevelSearch;
    if (!closed) {
      if (agents.goalState[row] == GoalState::Seeking && currentGoalPoint(row) == point) {
        // Heading for this exit: its target was drawn on the open floor in front while it was
        // closed (the waiting place); now it lies in the exit again.
        const core::Vec2 t = goalWriter().drawTarget(row, desc.points[point]);
        agents.targetX[row] = t.x;
        agents.targetY[row] = t.y;
        agents.needPath[row] = 1;
      } else if (!agents.corners[row].empty()) {
        agents.needPath[row] = 1;  // the door may be the shorter way now
      }
      continue;
    }
    if (!sameFloor) continue;
    if (region.contains(pos)) {
      // Caught in the doorway: out to the nearest open floor (within 2 m; a wider region keeps them).
      const auto out = mainQuery->snap(pos, levels ? agents.posZ[row] : 0.0f, 2.0f);
      if (out) {
        agents.posX[row] = out->p.x;
        agents.posY[row] = out->p.y;
        agents.polyRef[row] = static_cast<std::uint32_t>(out->ref);
        if (levels) agents.posZ[row] = out->height;
      }
      agents.needPath[row] = 1;
      continue;
    }
    // Re-plan when the way ahead (the path's remaining corners, or straight at the target) enters it.
    const CornerPath& path = agents.corners[row];
    core::Vec2 from = pos;
    bool crosses = false;
    if (path.empty()) {
      crosses = segmentTouches(region, pos, {agents.targetX[row], agents.targetY[row]});
    } else {
      for (std::size_t i = path.index; i < path.size() && !crosses; ++i) {
        crosses = segmentTouches(region, from, path[i]);
        from = path[i];
      }
    }
    if (crosses) agents.needPath[row] = 1;
  }
}

void World::Impl::insertCrowdNow(CrowdState& c) {
  if (c.info.applied) return;
  const CrowdDesc& cd = c.desc;
  const auto firstPoint = static_cast<std::uint32_t>(desc.points.size());
  const auto firstPopulation = static_cast<std::uint32_t>(desc.populations.size());
  const auto firstGroup = static_cast<std::uint32_t>(groups.size());
  const double now = static_cast<double>(tick) * desc.dt;

  // Points: geometry, sub-regions, clips, categories.
  for (const PointDesc& p : cd.points) {
    desc.points.push_back(p);
    pointRegions.add(p);
  }
  pointClip = pointClips(desc);  // the crowd's actions are the world's (checkCrowd): old indices stay
  commonGround.addPoints(desc.points, firstPoint);

  addCrowdPopulations(cd, firstPoint, firstPopulation, now);
  // Its exits are cut into the mesh when the first of them closes: the mesh for that is built now.
  if (std::any_of(cd.points.begin(), cd.points.end(), [](const PointDesc& p) { return p.kind == PointKind::Exit; })) startCutBuild();
  exitChoice.prepare(desc, *navmesh, firstPopulation);
  configureModels();  // a crowd may walk with a model the world had no use for
  if (desc.social.enabled) commonGround.refreshInterests(desc);

  stats.scheduled += spawner.registerGroups(desc, firstPopulation, groups, goalLists);  // as the scenario's own groups

  addColumnsFor(firstPopulation);

  c.info.applied = true;
  c.info.insertTick = tick;
  c.info.firstPopulation = firstPopulation;
  c.info.populations = static_cast<std::uint32_t>(cd.populations.size());
  c.info.firstPoint = firstPoint;
  c.info.points = static_cast<std::uint32_t>(cd.points.size());
  c.info.firstGroup = firstGroup;
  c.info.groups = static_cast<std::uint32_t>(groups.size()) - firstGroup;
  c.desc = {};  // its parts live in desc now
}

void World::Impl::removeCrowdNow(CrowdState& c) {
  if (!c.info.applied || c.info.removed) return;
  c.info.removed = true;
  const std::uint32_t first = c.info.firstPopulation, last = first + c.info.populations;
  for (std::uint32_t p = first; p < last; ++p) {
    stats.scheduled -= spawner.cancel(p);  // spawns nobody any more
  }
  std::vector<std::uint8_t> keep(agents.size(), 1);
  bool any = false;
  GoalWriter goals = goalWriter();
  for (std::size_t r = 0; r < agents.size(); ++r) {
    if (agents.population[r] < first || agents.population[r] >= last) continue;
    keep[r] = 0;
    any = true;
    pendingEvents.push_back({tick, agents.id[r], EventKind::Exit, kNoPoint, c.info.index});
    ++stats.removed;
    leaveWorld(r, goals, groups);
  }
  if (!any) return;
  agents.compact(keep);
  rowsChanged = true;
  stats.active = static_cast<std::uint32_t>(agents.size());
}

void World::Impl::removeAgentsNow() {
  if (agentRemovals.empty()) return;
  std::vector<std::uint8_t> keep(agents.size(), 1);
  bool any = false;
  GoalWriter goals = goalWriter();
  refreshRowOfId();
  for (const std::uint32_t id : agentRemovals) {
    const std::uint32_t found = id < rowOfId.size() ? rowOfId[id] : kNoRow;
    if (found == kNoRow) continue;  // gone with a crowd removed this tick
    const std::size_t r = found;
    if (!keep[r]) continue;
    keep[r] = 0;
    any = true;
    pendingEvents.push_back({tick, id, EventKind::Exit, kNoPoint, kNoIndex});
    ++stats.removed;
    leaveWorld(r, goals, groups);
  }
  agentRemovals.clear();
  if (!any) return;
  agents.compact(keep);
  rowsChanged = true;
  stats.active = static_cast<std::uint32_t>(agents.size());
}

core::Status World::removeAgents(std::span<const std::uint32_t> ids) {
  Impl& w = *impl_;
  core::Diagnostics problems;
  std::set<std::uint32_t> listed;
  const std::set<std::uint32_t> queued(w.agentRemovals.begin(), w.agentRemovals.end());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const std::uint32_t id = ids[i];
    std::string what;
    if (w.rowOf(id) == kNoRow) {
      what = "no agent with id " + std::to_string(id) + " in the world (not spawned yet, or left)";
    } else if (!listed.insert(id).second) {
      what = "agent " + std::to_string(id) + " is listed twice";
    } else if (queued.contains(id)) {
      what = "agent " + std::to_string(id) + " is already queued for removal";
    }
    if (!what.empty()) problems.push_back({"removeAgents", 0, 0, "/" + std::to_string(i), what, "the id of an agent present now", ""});
  }
  if (!problems.empty()) return problems;
  w.agentRemovals.insert(w.agentRemovals.end(), ids.begin(), ids.end());
  return core::Ok{};
}

core::Result<std::uint32_t> World::insertCrowd(const CrowdDesc& crowd) {
  Impl& w = *impl_;
  core::Diagnostics problems = w.checkCrowd(crowd);
  if (!problems.empty()) return problems;
  const std::uint32_t index = w.queueCrowd(crowd);
  w.insertion.commands.push_back({index, true});
  return index;
}

bool World::removeCrowd(std::string_view id) {
  Impl& w = *impl_;
  for (const CrowdState& c : w.insertion.crowds) {
    if (c.info.id != id || c.info.removed) continue;
    for (const CrowdCommand& cmd : w.insertion.commands) {
      if (!cmd.insert && cmd.crowd == c.info.index) return false;  // already queued
    }
    w.insertion.commands.push_back({c.info.index, false});
    return true;
  }
  return false;
}

bool World::exitIsWall(std::string_view pointId) const {
  const Impl& w = *impl_;
  for (std::uint32_t p = 0; p < w.desc.points.size(); ++p) {
    const PointDesc& point = w.desc.points[p];
    if (point.id != pointId || point.kind != PointKind::Exit) continue;
    if (w.exitCut(p)) return w.ownMesh && !w.ownMesh->cutPolygons(cutRegion(point)).empty();
    // Not cut yet (a crowd World::insertCrowd brought): it is when it first closes, when the mesh
    // can be built again and some floor lies in its region.
    return w.meshRebuildable() && w.navmesh->floorIn(cutRegion(point));
  }
  return false;
}

bool World::setExitOpen(std::string_view pointId, bool open) {
  Impl& w = *impl_;
  for (std::size_t p = 0; p < w.desc.points.size(); ++p) {
    if (w.desc.points[p].id != pointId || w.desc.points[p].kind != PointKind::Exit) continue;
    w.insertion.exitCommands.emplace_back(static_cast<std::uint32_t>(p), !open);
    return true;
  }
  return false;
}

std::vector<CrowdInfo> World::crowds() const {
  const Impl& w = *impl_;
  std::vector<CrowdInfo> out;
  for (const CrowdState& c : w.insertion.crowds) out.push_back(c.info);
  for (std::size_t r = 0; r < w.agents.size(); ++r) {
    const std::uint32_t p = w.agents.population[r];
    for (CrowdInfo& info : out) {
      if (info.applied && p >= info.firstPopulation && p < info.firstPopulation + info.populations) ++info.present;
    }
  }
  return out;
}

void World::Impl::addCrowdPopulations(const CrowdDesc& cd, std::uint32_t firstPoint, std::uint32_t firstPopulation,
                                      double now) {
  // Indices into the world's point and population lists; times count from the insertion.
  auto mapPoint = [&](std::uint32_t i) { return i < cd.basePoints ? i : firstPoint + (i - cd.basePoints); };
  auto mapPopulation = [&](std::uint32_t i) { return i < cd.basePopulations ? i : firstPopulation + (i - cd.basePopulations); };
  for (const PopulationDesc& source : cd.populations) {
    PopulationDesc pop = source;
    for (std::uint32_t& g : pop.goals) g = mapPoint(g);
    for (std::uint32_t& e : pop.exits) e = mapPoint(e);
    for (GoalChoiceDesc& c : pop.goalChoices) {
      for (std::uint32_t& o : c.options) o = mapPoint(o);
    }
    if (pop.spawn.kind == SpawnKind::Point) pop.spawn.point = mapPoint(pop.spawn.point);
    if (pop.follow.mode != FollowMode::None) pop.follow.population = mapPopulation(pop.follow.population);
    // Times in a crowd count from its insertion: spawn, guide script and release.
    for (GuideWaypoint& w : pop.guide.script) w.time += static_cast<float>(now);
    if (pop.guide.release >= 0.0f) pop.guide.release += static_cast<float>(now);
    spawner.addPopulation(tick + ticksOf(pop.start, desc.dt));
    anySociological = anySociological || pop.sociological.enabled;
    desc.populations.push_back(std::move(pop));
  }
}

void World::Impl::addColumnsFor(std::uint32_t firstPopulation) {
  bool formation = false, sociological = false;
  for (std::uint32_t p = firstPopulation; p < desc.populations.size(); ++p) {
    formation = formation || (desc.populations[p].flocking && desc.populations[p].sizeMax >= 2);
    sociological = sociological || desc.populations[p].sociological.enabled;
  }
  const std::size_t rows = agents.size();
  if (formation && !agents.formation) {
    agents.formation = true;
    agents.formVelX.assign(rows, 0.0f);
    agents.formVelY.assign(rows, 0.0f);
  }
  if (sociological && !agents.sociological) {
    agents.sociological = true;
    agents.followAgent.assign(rows, kNoAgent);
    agents.followUntil.assign(rows, 0);
    agents.sociologicalEffect.assign(rows, SocialEffect::None);
    agents.sociologicalOther.assign(rows, 0);
  }
}

}  // namespace throng::sim
