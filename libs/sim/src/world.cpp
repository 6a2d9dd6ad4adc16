// World — creation (planPopulations), the tick's phase order, the phases' contexts (spawner.hpp,
// phases.hpp: spawning, sense, decide, plan, steer, integrate, emit, the frame), the avoidance
// models in use (configureModels) and the World API's queries and commands.
#include "throng/sim/world.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "throng/core/assert.hpp"
#include "throng/sim/animation.hpp"
#include "world_impl.hpp"

namespace throng::sim {
namespace {

// Groups are never removed, so a group's handle is fixed: {stable id + 1, generation 1} (what a
// SlotMap filled in id order hands out) and needs no table.
GroupId handleOf(std::uint32_t gid) { return GroupId{gid + 1, 1}; }

std::optional<std::uint32_t> groupOf(const GroupTable& groups, GroupId handle) {
  if (handle.index == 0 || handle.index > groups.size() || handle.generation != 1) return std::nullopt;
  return handle.index - 1;
}

/// Per population, the route cost of a metre of stairs (nav::kStairArea) against one of level
/// ground: the mean time a metre of stairs takes, up and down, over a level one's (its speed factors).
std::vector<float> stairCosts(std::span<const PopulationDesc> populations) {
  std::vector<float> costs;
  for (const PopulationDesc& p : populations) costs.push_back(0.5f * (1.0f / p.stairUp + 1.0f / p.stairDown));
  return costs;
}

}  // namespace

World::World() : impl_(std::make_unique<Impl>()) {}
World::~World() = default;

core::Result<std::unique_ptr<World>> World::create(const ScenarioDesc& desc,
                                                    std::shared_ptr<const nav::NavMesh> navmesh) {
  // Lifts and escalators: different points (an escalator two, an elevator 2 to kMaxElevatorStops),
  // none the stop of another transport (io reports these with the file's location; a host building
  // a ScenarioDesc gets this).
  std::vector<std::uint8_t> isStop(desc.points.size(), 0);
  for (std::size_t t = 0; t < desc.transports.size(); ++t) {
    const TransportDesc& d = desc.transports[t];
    const std::string at = "/transports/" + std::to_string(t) + "/stops";
    const std::size_t most = d.kind == TransportKind::Elevator ? kMaxElevatorStops : 2;
    if (d.stops.size() < 2 || d.stops.size() > most) {
      return core::Diagnostic{"", 0, 0, at, std::to_string(d.stops.size()) + " stops",
                              d.kind == TransportKind::Elevator ? "2 to " + std::to_string(kMaxElevatorStops) : "2", ""};
    }
    for (const std::uint32_t p : d.stops) {
      if (p >= desc.points.size()) return core::Diagnostic{"", 0, 0, at, "no point " + std::to_string(p), "indices into /points", ""};
      if (isStop[p] != 0) {
        return core::Diagnostic{"", 0, 0, at, "point \"" + desc.points[p].id + "\" is a stop twice, or of another transport",
                                "each point the stop of one transport at most, once", ""};
      }
      isStop[p] = 1;
    }
  }
  if (!navmesh) {
    const nav::NavMeshConfig config = desc.navMeshConfig();
    auto built = desc.terrain.empty() ? nav::NavMesh::build(desc.walkable, desc.obstacles, config)
                                      : nav::NavMesh::buildFromTerrain(desc.terrain, config);
    if (!built) return std::move(built).takeErrors();
    navmesh = std::move(built).value();
  }
  std::unique_ptr<World> world(new World());
  Impl& w = *world->impl_;
  // Closing an exit takes its floor out of the navmesh (setExitClosedNow): a world with exits
  // edits a copy of its own, never the mesh other worlds built from the same scenario share.
  if (desc.hasExit() || !navmesh->config().cuts.empty()) {  // its own exits or its timeline crowds'
    w.ownMesh = navmesh->clone();
    navmesh = w.ownMesh;
  }
  w.desc = desc;
  w.navmesh = navmesh;
  w.pathQueue = std::make_unique<nav::PathQueue>(navmesh);
  w.mainQuery = std::make_unique<nav::NavQuery>(navmesh);
  w.agents.levels = navmesh->layered();  // heights per agent: before any row exists
  const SteeringDesc& s = desc.steering;
  w.buildWalls();
  core::Aabb gridBounds = navmesh->bounds();
  // ~1 m cells searched ring by ring (SpatialGrid::nearest): a handful of agents per cell at
  // pedestrian densities, and the search stops at the k-th neighbour.
  w.grid.configure(gridBounds, std::clamp(s.neighbourDistance / 3.0f, 0.5f, 2.0f));
  for (const PopulationDesc& pop : desc.populations) {
    w.spawner.addPopulation(static_cast<std::uint64_t>(std::ceil(pop.start / desc.dt - 1e-6)));
  }
  for (const PointDesc& p : desc.points) w.pointRegions.add(p);
  w.exitChoice.prepare(desc, *navmesh, 0);
  w.pointClip = pointClips(desc);
  w.initCommonGround();
  w.planPopulations();
  for (const PopulationDesc& pop : desc.populations) w.anySociological = w.anySociological || pop.sociological.enabled;
  w.insertion.navRadius = desc.navRadius();
  w.configureModels();
  w.transports.configure(desc);
  w.transportRoutes.prepare(desc, *navmesh, *w.mainQuery);
  w.initTimeline();
  w.applyCommands();  // populations starting at t = 0 are present in the first frame
  return world;
}

void World::step(const core::TaskSystem& tasks, PhaseObserver* observer) {
  Impl& w = *impl_;
  w.ensureScratch(tasks);
  struct Scope {
    PhaseObserver* o;
    std::string_view name;
    Scope(PhaseObserver* obs, std::string_view n) : o(obs), name(n) { if (o) o->phaseBegin(name); }
    ~Scope() { if (o) o->phaseEnd(name); }
  };
  {
    Scope s(observer, "applyCommands");
    if (w.tick > 0 || w.crowdsPending()) w.applyCommands(&tasks);
    w.chooseExits(tasks);
  }
  { Scope s(observer, "sense"); w.sense(tasks); }
  { Scope s(observer, "decide"); w.decide(tasks); }
  { Scope s(observer, "plan"); w.plan(tasks); }
  { Scope s(observer, "steer"); w.steer(tasks); }
  if (w.partition.exchange != nullptr) { Scope s(observer, "exchange"); w.exchangeSteer(); }
  {
    Scope s(observer, "integrate");
    w.integrate(tasks);
    w.separate(tasks);
    w.transports.step(w.desc, w.tick, *w.mainQuery, w.goalWriter());
  }
  { Scope s(observer, "emit"); w.emit(); }
  {
    Scope s(observer, "order");
    w.sortRows(tasks);
    w.refreshRowOfId();  // current between ticks (agentInfo, removeAgents)
  }
}

void World::Impl::planPopulations() {
  const std::uint32_t scheduled = spawner.registerGroups(desc, 0, groups, goalLists);
  stats.scheduled += scheduled;
  // Optional agent columns: only the features some population (or the scenario) uses.
  for (const PopulationDesc& pop : desc.populations) {
    agents.formation = agents.formation || (pop.flocking && pop.sizeMax >= 2);
    agents.sociological = agents.sociological || pop.sociological.enabled;
  }
  agents.commonGround = desc.social.enabled;
  for (const SmokeDesc& smoke : desc.smoke) agents.toxic = agents.toxic || smoke.co > 0.0f;
  // Every agent that will ever exist is known: exact capacity, no doubling slack on the columns.
  agents.forEachColumn([&](auto& column) { column.reserve(scheduled); });
}

// The phases' contexts (spawner.hpp, phases.hpp): what each phase reads and what it may write,
// taken from the world's state.

void World::Impl::applyCommands(const core::TaskSystem* tasks) {
  applyCrowdCommands();  // inserted crowds' populations starting now spawn below
  // Doors closed or opened just now: exit choice measures round them before anyone chooses.
  if (exitChoice.stale()) exitChoice.refresh(goalWriter(), tasks);
  const std::vector<std::size_t> due = spawner.due(tick);
  if (due.empty()) return;
  GoalWriter goals = goalWriter();
  spawnDue(SpawnInput{desc, *mainQuery, tick, commonGround}, SpawnOutput{spawner, agents, groups, goals, stats, &exitChoice},
           due);
  rowsChanged = true;
}

void World::Impl::chooseExits(const core::TaskSystem& tasks) {
  if (!exitChoice.active()) return;
  refreshRowOfId();
  GoalWriter goals = goalWriter();
  exitChoice.step(tick, rowOfId, goals, tasks);
}

void World::Impl::sense(const core::TaskSystem& tasks) {
  const bool carrying = !transports.empty();
  // The models' per-tick preparation (OperationalModel::beginStep: the avm's crowd grid, serial)
  // beside the neighbour search: it reads the positions and last tick's preferred velocities,
  // which nothing changes before steer, and not the neighbour lists.
  tasks.invoke(
      [&] {
        sim::sense(SenseInput{agents.posX, agents.posY, agents.posZ, desc.steering,
                              carrying ? std::span<const GoalState>(agents.goalState) : std::span<const GoalState>(),
                              carrying ? std::span<const AgentMode>(agents.mode) : std::span<const AgentMode>()},
                   SenseOutput{grid, agents.neighbours, agents.neighbourCount}, tasks);
      },
      [&] {
        const bool prior = modelsReadPrior();
        const ModelInput model{agents, walls, desc, viewers, tick, prior ? std::span<const float>(agents.prefVelX) : std::span<const float>(),
                               prior ? std::span<const float>(agents.prefVelY) : std::span<const float>()};
        for (auto& m : models) {
          if (m) m->beginStep(model);
        }
      });
}

void World::Impl::decide(const core::TaskSystem& tasks) {
  const std::size_t n = agents.size();
  chunks.resize(std::max(chunks.size(), core::TaskSystem::chunkCount(n, grainFor(n, tasks))));
  const DecideInput in{agents, desc, tick, groups, goalView(), commonGround, scratch, closedExits};
  const DecideOutput out{agents.goalState, agents.mode, agents.targetX, agents.targetY, agents.targetZ,
                         agents.corners, agents.needPath, agents.goalPending, agents.progressDistance,
                         agents.actionEndTick, agents.oriX, agents.oriY, agents.sociologicalEffect,
                         agents.sociologicalOther, agents.desirePoint, agents.desireTrigger, chunks, agents.dose};
  sim::decide(in, out, tasks);
  decideGroups(tasks);
}

void World::Impl::plan(const core::TaskSystem& tasks) {
  // Route costs per population (stairs: multi-level worlds), populations inserted at run time too.
  if (navmesh->layered() && pathQueue->costClasses() < desc.populations.size()) {
    pathQueue->setStairCosts(stairCosts(desc.populations));
  }
  sim::plan(PlanInput{tick, agents.id, agents.population, agents.posX, agents.posY, agents.targetX, agents.targetY, agents.posZ,
                      agents.targetZ, goalView(), &tasks},
            PlanOutput{agents.needPath, agents.ticket, agents.corners, *pathQueue, pendingEvents, agents.cornerZ});
}

void World::Impl::steer(const core::TaskSystem& tasks) {
  // Partitioned (partition.cpp): only the rows this rank owns; exchangeSteer brings the rest.
  const bool partitioned = partition.exchange != nullptr;
  if (partitioned) assignOwners();
  const std::uint32_t* list = partitioned ? partition.ownedRows.data() : nullptr;
  const std::size_t n = partitioned ? partition.ownedRows.size() : agents.size();
  std::array<const OperationalModel*, kModelCount> inUse{};
  for (std::size_t m = 0; m < kModelCount; ++m) inUse[m] = models[m].get();
  // The preferred velocities of the last tick become the models' priorDesired; steer writes every
  // row's anew (the rows other ranks own through exchangeSteer) over what separate left.
  std::span<const float> priorX, priorY;
  if (modelsReadPrior()) {
    std::swap(agents.prefVelX, spareX);
    std::swap(agents.prefVelY, spareY);
    agents.prefVelX.resize(agents.size());
    agents.prefVelY.resize(agents.size());
    priorX = spareX;
    priorY = spareY;
  }
  const ModelInput model{agents, walls, desc, viewers, tick, priorX, priorY};  // beginStep ran in sense
  const SteerInput in{desc.steering, desc.seed, desc.populations, desc.points, agents.id, agents.population,
                      agents.posX, agents.posY, agents.posZ, agents.polyRef, agents.speed, agents.targetX, agents.targetY,
                      agents.goalState, agents.scriptWalk, agents.dynamicTarget, agents.formVelX, agents.formVelY,
                      agents.stuckTime, goalView(), RowRange{list, 0, n}, inUse, model};
  const SteerOutput out{agents.prefVelX, agents.prefVelY, agents.corners, {agents.newVelX, agents.newVelY, agents.holdHeading, agents.lookTurn}, scratch};
  sim::steer(in, out, tasks);
}

bool World::Impl::modelsReadPrior() const {
  return std::ranges::any_of(models, [](const auto& m) { return m && m->readsPriorDesired(); });
}

void World::Impl::configureModels() {
  for (const PopulationDesc& pop : desc.populations) {
    const auto m = static_cast<std::size_t>(pop.model.kind);
    if (!models[m]) models[m] = makeModel(pop.model.kind);
  }
  for (auto& model : models) {
    if (model) model->configure(desc);
  }
  separationPasses = 0;
  for (std::size_t p = 0; p < desc.populations.size(); ++p) {
    const OperationalModel& m = *models[static_cast<std::size_t>(desc.populations[p].model.kind)];
    separationPasses = std::max(separationPasses, m.separationPasses(static_cast<std::uint16_t>(p)));
  }
  for (WorkerScratch& ws : scratch) addModelScratch(ws);
}

void World::Impl::addModelScratch(WorkerScratch& ws) const {
  for (std::size_t m = 0; m < models.size(); ++m) {
    if (models[m] && !ws.modelScratch[m]) ws.modelScratch[m] = models[m]->makeScratch();
  }
}

void World::Impl::integrate(const core::TaskSystem& tasks) {
  const IntegrateInput in{desc.dt, tick, agents.newVelX, agents.newVelY, agents.holdHeading, agents.prefVelX, agents.prefVelY,
                          agents.goalState, agents.mode, agents.speed, agents.actionEndTick, agents.scriptWalk, agents.scriptClip, goalView(), desc.points,
                          pointClip, commonGround.clipDuration, scratch};
  const IntegrateOutput out{agents.posX, agents.posY, agents.posZ, agents.polyRef, agents.velX, agents.velY,
                            agents.stuckTime, agents.animClip, agents.animPhase, agents.oriX, agents.oriY, chunks};
  sim::integrate(in, out, tasks);
}

void World::Impl::separate(const core::TaskSystem& tasks) {
  if (separationPasses <= 0) return;
  const std::size_t n = agents.size();
  std::vector<float>& sepX = spareX;  // every row's is written in each pass before any is read
  std::vector<float>& sepY = spareY;
  sepX.resize(n);
  sepY.resize(n);
  const ModelInput model{agents, walls, desc, viewers, tick, {}, {}};  // no priorDesired: spare holds the displacements
  const std::size_t grain = phaseGrain(n, tasks);
  const auto modelOf = [&](std::size_t row) {
    return models[static_cast<std::size_t>(desc.populations[agents.population[row]].model.kind)].get();
  };
  sepMoved.assign(n, 1);
  const std::size_t k = desc.steering.maxNeighbours;
  // Whether a pass after the first may give row another correction than the last: only when the
  // last moved it or one of the neighbours its correction reads (else it reads the same positions).
  const auto stirred = [&](std::size_t row) {
    if (sepMoved[row] != 0) return true;
    const std::uint32_t* nb = &agents.neighbours[row * k];
    unsigned any = 0;
    for (std::size_t j = 0; j < agents.neighbourCount[row]; ++j) any |= sepMoved[nb[j]];
    return any != 0;
  };
  for (int pass = 0; pass < separationPasses; ++pass) {
    // Every row's share from the same positions (Jacobi): the same for any thread or rank count.
    tasks.parallelFor(n, grain, [&](std::size_t begin, std::size_t end) {
      for (std::size_t row = begin; row < end; ++row) {
        if (pass > 0 && !stirred(row)) {  // the last pass's correction again: too small to apply
          sepX[row] = 0.0f;
          sepY[row] = 0.0f;
          continue;
        }
        const OperationalModel* m = modelOf(row);
        const bool carried = agents.goalState[row] == GoalState::Riding && agents.mode[row] == AgentMode::Acting;
        const bool corrects = agents.goalState[row] != GoalState::Exited && !carried &&
                              m->separationPasses(agents.population[row]) > pass;
        const core::Vec2 d = corrects ? m->separation(model, row) : core::Vec2{};
        sepX[row] = d.x;
        sepY[row] = d.y;
      }
    });
    tasks.parallelFor(n, grain, [&](std::size_t begin, std::size_t end) {
      const nav::NavQuery& query = *scratch[static_cast<std::size_t>(tasks.workerIndex())].query;
      for (std::size_t row = begin; row < end; ++row) {
        const core::Vec2 d{sepX[row], sepY[row]};
        sepMoved[row] = core::lengthSq(d) < 1e-12f ? 0 : 1;
        if (sepMoved[row] == 0) continue;
        const core::Vec2 pos{agents.posX[row], agents.posY[row]};
        nav::PolyRef ref = agents.polyRef[row];
        const core::Vec2 next = query.moveAlongSurface(pos, pos + d, ref);  // nobody through a wall
        agents.polyRef[row] = static_cast<std::uint32_t>(ref);
        if (!agents.posZ.empty() && ref != 0) agents.posZ[row] = query.heightAt(ref, next);
        agents.posX[row] = next.x;
        agents.posY[row] = next.y;
      }
    });
  }
}

void World::Impl::buildWalls() {
  walls.build(*navmesh, std::max(2.0f, desc.steering.timeHorizonObstacle * 2.5f + 0.5f));
}

void World::Impl::ensureScratch(const core::TaskSystem& tasks) {
  const std::size_t needed = static_cast<std::size_t>(tasks.threads());
  while (scratch.size() < needed) {
    WorkerScratch ws;
    ws.query = std::make_unique<nav::NavQuery>(navmesh);
    addModelScratch(ws);
    scratch.push_back(std::move(ws));
  }
}

void World::Impl::emit() {
  GoalWriter goals = goalWriter();
  if (sim::emit(EmitInput{tick, desc.dt}, EmitOutput{chunks, pendingEvents, stats, agents, groups, goals})) rowsChanged = true;
  ++tick;
}

FramePtr World::takeFrame() {
  Impl& w = *impl_;
  return sim::takeFrame(FrameInput{w.agents, w.tick, w.desc.dt, w.rowsInIdOrder()}, FrameOutput{w.spawner, w.pendingEvents, w.commonGround});
}

AgentColumns World::agentColumns() const {
  const AgentStore& a = impl_->agents;
  return {a.id, a.group, a.posX, a.posY, a.posZ, a.velX, a.velY, a.oriX, a.oriY, a.mode, a.animClip, a.animPhase};
}

void World::keepRetiredColumns(bool on) { impl_->agents.keepRetired = on; }

std::vector<std::shared_ptr<const void>> World::takeRetiredColumns() {
  std::vector<std::shared_ptr<const void>> out = std::move(impl_->agents.retired);
  impl_->agents.retired.clear();
  return out;
}

bool World::finished() const {
  const Impl& w = *impl_;
  if (w.stats.scheduled > 0 || w.crowdsPending()) return false;
  if (!w.spawner.allSpawned()) return false;
  for (std::size_t r = 0; r < w.agents.size(); ++r) {
    // Done, or incapacitated (nothing more will happen to it).
    if (w.agents.goalState[r] != GoalState::Done && w.agents.goalState[r] != GoalState::Incapacitated) return false;
  }
  return true;
}

GroupId World::group(std::string_view population, std::uint32_t index) const {
  const Impl& w = *impl_;
  for (std::size_t p = 0; p < w.desc.populations.size(); ++p) {
    if (w.desc.populations[p].id == population && index < w.desc.populations[p].groups) {
      return handleOf(w.spawner.firstGroupId(p) + index);
    }
  }
  return {};
}

GroupId World::groupById(std::uint32_t id) const {
  return id < impl_->groups.size() ? handleOf(id) : GroupId{};
}

std::size_t World::groupCount() const { return impl_->groups.size(); }

std::optional<GroupInfo> World::groupInfo(GroupId handle) const {
  const Impl& w = *impl_;
  const auto id = groupOf(w.groups, handle);
  if (!id) return std::nullopt;
  const GroupState& g = w.groups[*id];
  const GroupExtra& x = w.groups.extraOf(g);
  const GroupRoute& route = w.groups.routeOf(g);
  GroupInfo info;
  info.id = *id;
  info.population = g.population;
  info.members = g.members.toVector();
  info.leader = g.leader;
  info.goalIndex = g.cursor;
  info.goalPoint = w.groupGoalPoint(g);
  info.waiting = x.waiting;
  info.guided = g.guided;
  info.guide = route.guide;
  info.following = g.following;
  info.followedGroup = g.following ? route.followGroup : kNoGroup;
  return info;
}

bool World::guide(GroupId handle, core::Vec2 position) { return guide(handle, position, 0.0f); }

bool World::guide(GroupId handle, core::Vec2 position, float height) {
  const auto id = groupOf(impl_->groups, handle);
  if (!id) return false;
  impl_->commands.push_back({*id, true, position, height});
  return true;
}

bool World::release(GroupId handle) {
  const auto id = groupOf(impl_->groups, handle);
  if (!id) return false;
  impl_->commands.push_back({*id, false, {}});
  return true;
}

std::optional<AgentInfo> World::agentInfo(std::uint32_t id) const {
  const Impl& w = *impl_;
  const AgentStore& a = w.agents;
  const std::uint32_t found = w.rowOf(id);
  if (found == kNoRow) return std::nullopt;
  const std::size_t row = found;
  AgentInfo info;
  info.id = id;
  info.group = a.group[row];
  info.population = a.population[row];
  info.mode = a.mode[row];
  info.position = {a.posX[row], a.posY[row]};
  info.target = {a.targetX[row], a.targetY[row]};
  info.height = a.height(row);
  info.targetHeight = a.targetHeight(row);
  info.clip = a.animClip[row];
  info.speed = a.speed[row];
  if (row < a.coordination.size()) info.coordination = a.coordination[row];
  if (row < a.followAgent.size()) info.followedAgent = a.followAgent[row];
  const GroupState& g = w.groups[a.group[row]];
  info.guided = g.guided;
  if (const std::uint32_t goal = w.currentGoalPoint(row); goal != kNoPoint) info.goalPoint = goal;
  switch (a.goalState[row]) {
    case GoalState::Seeking:
      // Heading for a lift's or escalator's stop: in its queue, when that reaches out this far.
      info.state = info.goalPoint != kNoPoint && !w.desc.transports.empty() && VerticalTransports::boardingAt(w.desc, info.goalPoint) != kNoIndex
                       ? "walking to a lift or escalator"
                       : "walking to its goal";
      break;
    case GoalState::Acting: info.state = "at an action point"; break;
    case GoalState::Done: info.state = "done"; break;
    case GoalState::Exited: info.state = "left"; break;
    case GoalState::WaitingForGroup: info.state = "waiting for its group"; break;
    case GoalState::Scripted: info.state = "playing a Common Ground script"; break;
    case GoalState::PreMovement: info.state = "waiting to leave (pre-movement time)"; break;
    case GoalState::Incapacitated: info.state = "incapacitated (its carbon monoxide dose)"; break;
    case GoalState::Riding: info.state = "at or on a lift or escalator"; break;
  }
  return info;
}

void World::setViewers(std::vector<core::Vec2> viewers) { impl_->viewers = std::move(viewers); }

const WorldStats& World::stats() const { return impl_->stats; }
const ScenarioDesc& World::desc() const { return impl_->desc; }
const nav::NavMesh& World::navMesh() const { return *impl_->navmesh; }

std::uint64_t World::stateHash() const {
  const AgentStore& a = impl_->agents;
  std::uint64_t h = 14695981039346656037ull;
  auto mix = [&](const void* p, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) { h ^= b[i]; h *= 1099511628211ull; }
  };
  // By ascending id, whatever the row order (ScenarioDesc::rowOrder): sorted rows are walked
  // through rowOfId, current between ticks (step ends by refreshing it).
  const Impl& w = *impl_;
  THRONG_ASSERT(w.rowsById || !w.rowsChanged);
  const auto hashRow = [&](std::size_t r) {
    mix(&a.id[r], sizeof(std::uint32_t));
    mix(&a.posX[r], sizeof(float));
    mix(&a.posY[r], sizeof(float));
    mix(&a.velX[r], sizeof(float));
    mix(&a.velY[r], sizeof(float));
  };
  if (w.rowsById) {
    for (std::size_t r = 0; r < a.size(); ++r) hashRow(r);
  } else {
    for (const std::uint32_t r : w.rowOfId) {
      if (r != kNoRow) hashRow(r);
    }
  }
  return h;
}

}  // namespace throng::sim
