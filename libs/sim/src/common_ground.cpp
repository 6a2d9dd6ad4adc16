// common_ground — the Common Ground model of Park, Peng, Quek and Cao inside the World
// (docs/social-model.md), part 1 of 2: its state at creation, goals and the start of coordinations.
//   goal generator (decide, parallel; reads DecideInput, writes DecideOutput: phases.hpp): stochastic
//     needs at a rate per agent, and places of an interesting category the agent sees (vision cone,
//     range, walls), one draw per agent and place;
//   start (group pass, serial): the initiator assesses its group mates (sensing, relations), the
//     planner runs the grounding process into an action script for A, B and the companions, or a
//     lone visit when nobody else is there or Common Ground is off.
// Playing the scripts (run: entries, finishing, reunions) is in common_ground_play.cpp; the state
// both read and write is CommonGroundState (common_ground_state.hpp).
// Reads the scenario's social description and the agents; writes the agents' desires, the Scripted
// agents' rows, the group table and the new coordinations (startCoordinations: CommonGroundInput,
// CommonGroundOutput, group_pass.hpp). Serial parts visit rows in a fixed
// order, so the result never depends on threads.
#include <algorithm>
#include <cmath>

#include "throng/sim/animation.hpp"
#include "throng/common_ground/relations.hpp"
#include "group_pass.hpp"
#include "world_impl.hpp"

namespace throng::sim {
namespace {

/// Every actor is released this long after the planned end, times 3 for slow crowds [s].
constexpr double kDeadlineSlack = 120.0;

/// Effort for A to be perceived by a member in relation r: the respondent B is the hardest one.
int effort(common_ground::Relation r) {
  switch (r) {
    case common_ground::Relation::A1: return 0;
    case common_ground::Relation::A2: return 1;
    case common_ground::Relation::A4: return 2;
    case common_ground::Relation::A5: return 3;
    case common_ground::Relation::A3: return 4;
    case common_ground::Relation::A6: return 5;
  }
  return 5;
}

core::Vec2 facingOf(float x, float y) {
  const core::Vec2 f{x, y};
  return core::lengthSq(f) > 0.0f ? core::normalize(f) : core::Vec2{1.0f, 0.0f};
}

/// startCoordinations' steps over its contexts (CommonGroundInput, CommonGroundOutput: group_pass.hpp).
struct CoordinationStart : CommonGroundPass {
  using CommonGroundPass::CommonGroundPass;

  void startCoordination(std::uint32_t row);
  [[nodiscard]] std::vector<std::uint32_t> availableMates(const GroupState& g, std::uint32_t initiator) const;
  [[nodiscard]] common_ground::Goal coordinationGoal(std::uint32_t point, GoalTrigger trigger, const std::vector<std::uint32_t>& mates) const;
  /// The grounding planner's script for A, B and the companions; false when it has none.
  bool planGrounding(ActiveCoordination& c, std::uint32_t row, const std::vector<std::uint32_t>& mates,
                     const common_ground::Goal& goal, core::Vec2 destination, double now);
  void planLoneVisit(ActiveCoordination& c, std::uint32_t row, const common_ground::Goal& goal, core::Vec2 destination,
                     double now) const;
  void beginCoordination(ActiveCoordination c, bool alone, double now);
};

}  // namespace

void World::Impl::initCommonGround() {
  commonGround.addPoints(desc.points, 0);
  commonGround.refreshInterests(desc);
  const std::vector<ClipInfo> clips = animationClips(desc);
  for (std::size_t i = 0; i < clips.size(); ++i) {
    commonGround.clipDuration.push_back(std::max(1e-3f, clips[i].duration));
    commonGround.clipIndex.emplace(clips[i].name, static_cast<std::uint16_t>(i));
  }
}

void generateGoal(const DecideInput& in, const DecideOutput& out, std::size_t row, ChunkOutput& chunk,
                  const nav::NavQuery& query) {
  const CommonGroundDesc& social = in.desc.social;
  const AgentStore& agents = in.agents;
  const CommonGroundState& commonGround = in.commonGround;
  const std::uint64_t tick = in.tick;
  if (!social.enabled || out.desirePoint[row] != kNoPoint || tick < agents.socialReady[row]) return;
  const GroupState& g = in.groups[agents.group[row]];
  if (in.groups.extraOf(g).coordination != kNoIndex || g.guided || g.following || agents.followedAgent(row) != kNoAgent) return;
  const std::uint32_t id = agents.id[row];
  const core::Vec2 pos{agents.posX[row], agents.posY[row]};
  auto want = [&](std::uint32_t point, GoalTrigger trigger) {
    out.desirePoint[row] = point;
    out.desireTrigger[row] = static_cast<std::uint8_t>(trigger);
    chunk.desireRows.push_back(static_cast<std::uint32_t>(row));
  };
  // Stochastic needs (a restroom visit): rate × dt per tick; the nearest place of the category.
  for (std::size_t i = 0; i < social.needs.size(); ++i) {
    const NeedDesc& need = social.needs[i];
    const std::int32_t c = commonGround.needCategory[i];
    if (c < 0 || need.rate <= 0.0f) continue;
    core::Rng rng(in.desc.seed, core::mix64((static_cast<std::uint64_t>(id) << 32) ^ tick) ^ i, core::RngPurpose::Social);
    if (rng.uniform() >= static_cast<double>(need.rate) * in.desc.dt) continue;
    std::uint32_t best = kNoPoint;
    float bestD = 1e30f;
    for (const std::uint32_t p : commonGround.categoryPoints[static_cast<std::size_t>(c)]) {
      const float d = core::lengthSq(in.desc.points[p].position - pos);
      if (d < bestD) { bestD = d; best = p; }
    }
    if (best != kNoPoint) {
      want(best, GoalTrigger::Need);
      return;
    }
  }
  // Environmentally driven goals: a place of an interesting category in view (cone, range, walls).
  const std::uint64_t mask = agents.interests[row];
  if (mask == 0 || commonGround.attractionPoints.empty()) return;
  const auto period = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::lround(social.attraction.checkPeriod / in.desc.dt)));
  if ((tick + id) % period != 0) return;
  const common_ground::Body me{pos, facingOf(out.oriX[row], out.oriY[row]), agents.radius[row]};
  const common_ground::NavMeshOcclusion walls(query);
  const std::vector<std::uint32_t>& seen = agents.visited[row];
  for (const std::uint32_t p : commonGround.attractionPoints) {
    if (!((mask >> static_cast<unsigned>(commonGround.pointCategory[p])) & 1u)) continue;
    if (std::find(seen.begin(), seen.end(), p) != seen.end()) continue;
    const common_ground::Body place{in.desc.points[p].position, {0.0f, 0.0f}, 0.0f};
    if (!common_ground::perceive(me, place, social.senses, walls).see) continue;
    // One draw per agent and place: the same place never tempts the same agent twice.
    core::Rng rng(in.desc.seed, (static_cast<std::uint64_t>(id) << 32) ^ p, core::RngPurpose::Social);
    if (rng.uniform() < social.attraction.probability) {
      want(p, GoalTrigger::Attraction);
      return;
    }
  }
}

void startCoordinations(const CommonGroundInput& in, const CommonGroundOutput& out, std::span<ChunkOutput> chunks) {
  CoordinationStart start(in, out);
  for (ChunkOutput& chunk : chunks) {
    for (const std::uint32_t row : chunk.desireRows) start.startCoordination(row);
    chunk.desireRows.clear();
  }
}

void CoordinationStart::startCoordination(std::uint32_t row) {
  const std::uint32_t point = agents.desirePoint[row];
  const auto trigger = static_cast<GoalTrigger>(agents.desireTrigger[row]);
  agents.desirePoint[row] = kNoPoint;
  if (point == kNoPoint || agents.goalState[row] != GoalState::Seeking || agents.coordination[row] != kNoIndex) return;
  const std::uint32_t gid = agents.group[row];
  GroupState& g = groups[gid];
  if (groups.extraOf(g).coordination != kNoIndex) return;  // a mate got there first this tick
  const std::uint32_t aId = agents.id[row];
  const double now = static_cast<double>(tick) * desc.dt;
  const std::vector<std::uint32_t> mates = availableMates(g, aId);
  common_ground::Goal goal = coordinationGoal(point, trigger, mates);
  // x_s: a spot in the place's region (sub-regions spread visitors), on the navmesh.
  goal.position = goals.drawTarget(row, desc.points[point]);
  const core::Vec2 destination{agents.targetX[row], agents.targetY[row]};

  ActiveCoordination c;
  c.record.id = commonGround.nextCoordinationId++;
  c.record.group = gid;
  c.record.initiator = aId;
  c.record.goalPoint = point;
  c.record.goalKind = static_cast<std::uint8_t>(goal.kind);
  c.record.trigger = trigger;
  c.record.start = now;
  c.actors.push_back(aId);
  bool alone = !desc.social.commonGround || mates.empty();
  if (!alone) alone = !planGrounding(c, row, mates, goal, destination, now);  // no clip length: alone
  if (alone) planLoneVisit(c, row, goal, destination, now);
  beginCoordination(std::move(c), alone, now);
}

std::vector<std::uint32_t> CoordinationStart::availableMates(const GroupState& g, std::uint32_t initiator) const {
  // Group mates that can take part: present, not busy at an action point or in another script.
  std::vector<std::uint32_t> mates;
  for (const std::uint32_t m : g.members) {
    if (m == initiator) continue;
    const std::uint32_t r = rowOfId[m];
    const GoalState s = agents.goalState[r];
    if (agents.coordination[r] != kNoIndex) continue;
    if (s == GoalState::Seeking || s == GoalState::WaitingForGroup || s == GoalState::Done) mates.push_back(m);
  }
  return mates;
}

common_ground::Goal CoordinationStart::coordinationGoal(std::uint32_t point, GoalTrigger trigger, const std::vector<std::uint32_t>& mates) const {
  // The goal: what the macro-plan rules read.
  const CommonGroundDesc& social = desc.social;
  const PointDesc& place = desc.points[point];
  common_ground::Goal goal;
  goal.kind = common_ground::GoalKind::Personal;
  goal.expectedVisit = social.attraction.expectedVisit;
  if (trigger == GoalTrigger::Need) {
    for (const NeedDesc& need : social.needs) {
      if (need.category == place.category) { goal.kind = need.kind; goal.expectedVisit = need.expectedVisit; break; }
    }
  }
  if (trigger == GoalTrigger::Attraction && !mates.empty()) {
    // A place every mate is interested in too is a shared goal (detour together).
    const int cat = commonGround.pointCategory[point];
    const bool all = std::all_of(mates.begin(), mates.end(), [&](std::uint32_t m) {
      return ((agents.interests[rowOfId[m]] >> static_cast<unsigned>(cat)) & 1u) != 0;
    });
    if (all) goal.kind = common_ground::GoalKind::Shared;
  }
  return goal;
}

namespace {

common_ground::ActorBody actorBody(const AgentStore& agents, std::uint32_t r) {
  common_ground::ActorBody b;
  b.position = {agents.posX[r], agents.posY[r]};
  b.heading = std::atan2(agents.oriY[r], agents.oriX[r]);
  b.walkSpeed = std::clamp(agents.speed[r], 0.1f, 10.0f);
  b.id = agents.id[r];
  return b;
}

common_ground::Body sensedBody(const AgentStore& agents, std::uint32_t r) {
  return common_ground::Body{{agents.posX[r], agents.posY[r]}, facingOf(agents.oriX[r], agents.oriY[r]), agents.radius[r]};
}

}  // namespace

bool CoordinationStart::planGrounding(ActiveCoordination& c, std::uint32_t row, const std::vector<std::uint32_t>& mates,
                                const common_ground::Goal& goal, core::Vec2 destination, double now) {
  const CommonGroundDesc& social = desc.social;
  const nav::NavQuery& query = goals.query;
  const core::Vec2 aPos{agents.posX[row], agents.posY[row]};
  const common_ground::NavMeshOcclusion walls(query);
  const common_ground::Body aBody = sensedBody(agents, row);
  std::vector<std::pair<common_ground::Relation, std::uint32_t>> rel;
  for (const std::uint32_t m : mates) rel.emplace_back(common_ground::assess(aBody, sensedBody(agents, rowOfId[m]), social.senses, walls), m);
  // B: the mate hardest to reach (ties: nearest, then lowest id); the others are companions.
  std::size_t bi = 0;
  for (std::size_t i = 1; i < rel.size(); ++i) {
    const int ei = effort(rel[i].first), eb = effort(rel[bi].first);
    const std::uint32_t ri = rowOfId[rel[i].second], rb = rowOfId[rel[bi].second];
    const float di = core::lengthSq(core::Vec2{agents.posX[ri], agents.posY[ri]} - aPos);
    const float db = core::lengthSq(core::Vec2{agents.posX[rb], agents.posY[rb]} - aPos);
    if (ei > eb || (ei == eb && (di < db || (di == db && rel[i].second < rel[bi].second)))) bi = i;
  }
  const std::uint32_t bRow = rowOfId[rel[bi].second];
  common_ground::CoordinationInput in;
  in.initiator = actorBody(agents, row);
  in.respondent = actorBody(agents, bRow);
  in.relation = rel[bi].first;
  for (std::size_t i = 0; i < rel.size(); ++i) {
    if (i != bi) in.companions.push_back({actorBody(agents, rowOfId[rel[i].second]), rel[i].first});
  }
  const common_ground::Body bBody = sensedBody(agents, bRow);
  const auto snap = [&](common_ground::Approach a) -> std::optional<core::Vec2> {
    if (!a.reachable) return std::nullopt;
    if (auto hit = query.nearest(a.point, 2.0f)) return hit->first;
    return std::nullopt;
  };
  in.viewPoint = snap(common_ground::pointInView(aBody, bBody, social.senses, walls));
  in.hearingPoint = snap(common_ground::pointInHearing(aBody, bBody, social.senses));
  in.goal = goal;
  in.destination = destination;
  in.startTime = now;
  in.seed = desc.seed;
  // Per-actor preferences (the population's, seeded draws in the planner); companions use B's.
  in.initiatorStyle.preference = desc.populations[agents.population[row]].preferences;
  in.respondentStyle.preference = desc.populations[agents.population[bRow]].preferences;
  // Responses B misses (it did not notice): drawn per coordination, consumed in order.
  core::Rng miss(desc.seed, c.record.id, core::RngPurpose::Social);
  for (int k = 0; k < 32; ++k) in.lostResponses.push_back(miss.uniform() < social.missProbability);
  auto planned = common_ground::planCoordination(in, {&social.micro, &social.macro}, social.clipLengths, social.coordination);
  if (!planned.ok()) return false;
  c.script = std::move(planned).value();
  c.actors.push_back(rel[bi].second);
  for (std::size_t i = 0; i < rel.size(); ++i) {
    if (i != bi) c.actors.push_back(rel[i].second);
  }
  c.record.relation = static_cast<std::uint8_t>(rel[bi].first);
  c.record.plan = static_cast<std::uint8_t>(c.script.plan);
  c.record.outcome = c.script.outcome == common_ground::Outcome::Grounded ? CoordinationOutcome::Grounded : CoordinationOutcome::Failed;
  return true;
}

void CoordinationStart::planLoneVisit(ActiveCoordination& c, std::uint32_t row, const common_ground::Goal& goal, core::Vec2 destination,
                                double now) const {
  // A lone visit: walk to the goal, stay the plan's visit duration, walk on (no grounding).
  const CommonGroundDesc& social = desc.social;
  const core::Vec2 aPos{agents.posX[row], agents.posY[row]};
  const auto chosen = common_ground::selectPlan(social.macro, goal, core::distance(goal.position, aPos));
  const common_ground::PlanKind kind = chosen ? social.macro.plans[*chosen].kind : common_ground::PlanKind::DivideAndProceed;
  const double visit = chosen ? social.macro.plans[*chosen].visitDuration : 30.0;
  const double speed = std::max(0.1f, agents.speed[row]);
  common_ground::ActionScript s;
  s.actors.resize(1);
  s.plan = kind;
  s.startTime = s.executeTime = now;
  auto add = [&](const char* motion, const char* behaviour, double start, double duration, core::Vec2 target) {
    common_ground::ScriptEntry e;
    e.start = start;
    e.duration = duration;
    e.motion = motion;
    e.behaviour = behaviour;
    e.targetType = common_ground::ScriptEntry::Target::Point;
    e.targetPoint = target;
    e.step = common_ground::GroundingStep::Execute;
    e.plan = kind;
    s.actors[0].push_back(e);
    return start + duration;
  };
  double t = add("walk", "walk_to_goal", now, core::distance(aPos, goal.position) / speed, goal.position);
  t = add("idle", "stay", t, visit, goal.position);
  t = add("walk", "walk_to_next", t, core::distance(goal.position, destination) / speed, destination);
  s.endTime = t;
  c.script = std::move(s);
  c.record.plan = static_cast<std::uint8_t>(kind);
  c.record.outcome = CoordinationOutcome::Alone;
}

void CoordinationStart::beginCoordination(ActiveCoordination c, bool alone, double now) {
  // Its record, its deadline, and every actor's row handed to the script.
  const std::uint32_t gid = c.record.group;
  GroupState& g = groups[gid];
  for (std::size_t i = 1; i < c.actors.size(); ++i) c.record.respondents.push_back(c.actors[i]);
  for (const auto& list : c.script.actors) {
    for (const auto& e : list) c.record.retries += e.attempt > 0 && e.step != common_ground::GroundingStep::Execute ? 1u : 0u;
  }
  const std::size_t n = c.actors.size();
  c.cursor.assign(n, 0);
  c.started.assign(n, -1.0);
  c.left.assign(n, 0);
  c.deadline = now + 3.0 * std::max(0.0, c.script.endTime - now) + kDeadlineSlack;
  c.divides = g.members.size() >= 2 && (c.script.plan == common_ground::PlanKind::DivideAndProceed ||
                                        c.script.plan == common_ground::PlanKind::DivideAndWait);
  for (const std::uint32_t actor : c.actors) {
    const std::uint32_t r = rowOfId[actor];
    agents.coordination[r] = c.record.id;
    agents.goalState[r] = GoalState::Scripted;
    agents.mode[r] = AgentMode::Waiting;
    agents.scriptWalk[r] = 0;
    agents.scriptClip[r] = kNoClip;
    agents.targetSelf(r);
    agents.corners[r].clear();
    agents.needPath[r] = 0;
    agents.ticket[r] = 0;
  }
  if (!alone) groups.extraOf(g).coordination = c.record.id;
  groups.markBusy(gid);
  pendingEvents.push_back({tick, c.record.initiator, EventKind::GoalGenerated, c.record.goalPoint,
                           static_cast<std::uint32_t>(c.record.trigger)});
  pendingEvents.push_back({tick, c.record.initiator, EventKind::CoordinationStart, c.record.id, gid});
  const std::uint32_t id = c.record.id;
  commonGround.coordinations.emplace(id, std::move(c));
}

}  // namespace throng::sim
