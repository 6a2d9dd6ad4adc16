// decideGroups — the serial group pass that runs after the parallel, per-agent part of `decide`.
// It owns everything that couples agents of a group (Musse et al. §3.2):
//   API commands (guide / release) → guidance (dynamic goals, §3.2.6) → following (§3.2.5) →
//   sociological effects (§3.2.1 iii) → the wait rule (flocking rule 4, §3.2.3) → leaders →
//   formation (members walk abreast; the cohesion behind flocking rules 1–3).
// Groups are visited in stable-id order and agents in row order, so the result never depends on
// threads. Effects on agents go through GoalWriter::setGoal (goals.hpp) or their own columns
// (dynamic targets, needPath); paths are then planned by `plan`. Every step but Common Ground's is a
// function of its contexts: applyGroupCommands, updateGuidance, updateFollowing, applySocialEffects
// and updateWaiting (…Input/…Output: group_pass.hpp), updateLeaders and formGroups (phases.hpp),
// and Common Ground's startCoordinations, runCoordinations and checkReunions (CommonGroundInput,
// CommonGroundOutput: group_pass.hpp; common_ground*.cpp). World::Impl::decideGroups builds the
// contexts.
#include <algorithm>
#include <cmath>

#include "throng/crowd/bezier_path.hpp"
#include "throng/crowd/path_reconstruction.hpp"
#include "throng/crowd/walkable.hpp"
#include "throng/core/assert.hpp"
#include "world_impl.hpp"

namespace throng::sim {
namespace {

/// Gain of the formation correction: how fast a member closes the gap to its slot [1/s].
constexpr float kFormationGain = 0.8f;
/// Largest formation correction added to a member's desired velocity [m/s].
constexpr float kFormationMaxSpeed = 0.5f;
/// Members walking abreast per row; larger groups form rows behind each other.
constexpr std::size_t kAbreast = 3;
/// Distance between rows of a large group [m].
constexpr float kRowSpacing = 0.8f;
/// A guided group re-plans when its guide has moved this far since the last plan [m].
constexpr float kGuideReplan = 1.0f;
/// Agents following another agent (sociological model) keep this far behind it [m].
constexpr float kFollowAgentGap = 1.0f;

/// The guide script's position (and floor height) at time t: linear between waypoints, held
/// before the first and after the last.
GuideWaypoint interpolateGuide(const std::vector<GuideWaypoint>& script, float t) {
  if (t <= script.front().time) return script.front();
  for (std::size_t i = 1; i < script.size(); ++i) {
    if (t <= script[i].time) {
      const GuideWaypoint& a = script[i - 1];
      const GuideWaypoint& b = script[i];
      const float span = b.time - a.time;
      const float u = span > 0.0f ? (t - a.time) / span : 1.0f;
      return {t, a.position + (b.position - a.position) * u, a.height + (b.height - a.height) * u};
    }
  }
  return script.back();
}

}  // namespace

void World::Impl::decideGroups(const core::TaskSystem& tasks) {
  refreshRowOfId();
  GoalWriter goals = goalWriter();
  goals.applyPendingGoals(chunks);
  applyGroupCommands(commands, groups);
  commands.clear();
  const CommonGroundInput commonGroundIn{desc, tick, rowOfId};
  const CommonGroundOutput commonGroundOut{agents, groups, commonGround, goals, pendingEvents};
  if (desc.social.enabled) {
    startCoordinations(commonGroundIn, commonGroundOut, chunks);
    runCoordinations(commonGroundIn, commonGroundOut);
  }
  groups.refreshBusy();
  const auto dt = desc.dt;
  updateGuidance(GuidanceInput{desc.populations, dt, tick, rowOfId},
                 GuidanceOutput{groups, agents.goalState, agents.mode, agents.targetX, agents.targetY, agents.targetZ,
                                agents.dynamicTarget, agents.needPath, agents.corners, goals, pendingEvents});
  updateFollowing(FollowingInput{desc.populations, desc.seed, dt, tick, rowOfId, agents.goalState},
                  FollowingOutput{groups, goals, pendingEvents});
  if (anySociological) {
    const SocialEffectsInput in{desc, tick, rowOfId, agents.id, agents.population, agents.posX, agents.posY,
                                agents.posZ, agents.sociologicalOther, agents.goalCursor};
    applySocialEffects(in, SocialEffectsOutput{groups, agents.followAgent, agents.followUntil, agents.sociologicalEffect,
                                               agents.group, agents.groupSize, agents.speed, agents.targetX, agents.targetY,
                                               agents.targetZ, agents.dynamicTarget, agents.needPath, agents.goalState,
                                               agents.mode, goals, pendingEvents});
  }
  updateWaiting(WaitingInput{desc.populations, dt, tick, rowOfId, agents.goalCursor, agents.goalState},
                WaitingOutput{groups, goals, pendingEvents});
  if (desc.social.enabled) checkReunions(commonGroundIn, commonGroundOut);
  updateLeaders();
  updateGroupShapes(tasks);
}

void applyGroupCommands(std::span<const GroupCommand> commands, GroupTable& groups) {
  for (const GroupCommand& c : commands) {
    GroupRoute& x = groups.routeFor(c.group);
    if (c.guide) {
      x.guidedByApi = true;
      x.guide = c.position;
      x.guideHeight = c.height;
    } else {
      x.guidedByApi = false;
    }
  }
}

namespace {

/// Whether a member's goal may be set by its group (not gone, not holding a target of its own).
bool groupSetsGoal(GoalState s) { return s != GoalState::Exited && !holdsOwnTarget(s); }

/// A member's dynamic target: `target` snapped onto the navmesh (onto the guide's floor on a
/// multi-level world), approached slowing down.
void setDynamicTarget(const GuidanceOutput& out, std::uint32_t r, core::Vec2 target, float guideHeight) {
  const nav::NavQuery& query = out.goals.query;
  if (!out.targetZ.empty()) {
    const auto hit = query.snap(target, guideHeight, 3.0f);
    if (hit) target = hit->p;
    out.targetZ[r] = hit ? hit->height : guideHeight;
  } else if (auto hit = query.nearest(target, 3.0f)) {
    target = hit->first;
  }
  out.targetX[r] = target.x;
  out.targetY[r] = target.y;
  out.dynamicTarget[r] = 1;
  out.goalState[r] = GoalState::Seeking;
  out.mode[r] = AgentMode::Walking;
  out.needPath[r] = 1;
  out.corners[r].clear();
}

/// Whether group `gid` is guided now (by the API, or by its population's script — which then
/// moves the guide); on a change, the event, and when guidance ends its members go back to the
/// group's own goals where they left them.
void updateGuided(const GuidanceInput& in, const GuidanceOutput& out, std::uint32_t gid, float now) {
  GroupState& g = out.groups[gid];
  GroupRoute& x = out.groups.routeFor(gid);
  const GuideDesc& script = in.populations[g.population].guide;
  bool guided = x.guidedByApi;
  if (!guided && !script.script.empty() && now >= script.script.front().time && (script.release < 0.0f || now < script.release)) {
    guided = true;
    const GuideWaypoint at = interpolateGuide(script.script, now);
    x.guide = at.position;
    x.guideHeight = at.height;
  }
  if (guided == g.guided) return;
  g.guided = guided;
  const std::uint32_t leader = g.leader == kNoAgent ? 0 : g.leader;
  out.events.push_back({in.tick, leader, guided ? EventKind::GuideStart : EventKind::GuideEnd, gid, 0});
  x.guidePlanned = {1e30f, 1e30f};
  if (guided) return;
  for (std::uint32_t id : g.members) {
    const std::uint32_t r = in.rowOfId[id];
    if (groupSetsGoal(out.goalState[r])) out.goals.setGoal(r, g.cursor);
  }
}

}  // namespace

void updateGuidance(const GuidanceInput& in, const GuidanceOutput& out) {
  const float now = static_cast<float>(static_cast<double>(in.tick) * in.dt);
  for (const std::uint32_t gid : out.groups.busy()) {
    const GroupState& g = out.groups[gid];
    if (!out.groups.hasRoute(g)) continue;  // never guided
    updateGuided(in, out, gid, now);
    if (!g.guided || g.members.empty()) continue;
    GroupRoute& x = out.groups.routeFor(gid);
    if (core::lengthSq(x.guide - x.guidePlanned) < kGuideReplan * kGuideReplan) continue;
    // Dynamic goal: a spot `distance` behind the guide (on the side the group comes from), one
    // lateral slot per member so they stand beside each other.
    x.guidePlanned = x.guide;
    const GroupExtra& shape = out.groups.extraOf(g);
    const PopulationDesc& pop = in.populations[g.population];
    core::Vec2 back = core::normalize(shape.centroid - x.guide);
    if (core::lengthSq(back) == 0.0f) back = -shape.heading;
    const core::Vec2 lateral = core::perp(back);
    const float n = static_cast<float>(g.members.size());
    for (std::size_t i = 0; i < g.members.size(); ++i) {
      const std::uint32_t r = in.rowOfId[g.members[i]];
      if (!groupSetsGoal(out.goalState[r])) continue;
      const float slot = (static_cast<float>(i) - 0.5f * (n - 1.0f)) * pop.groupSpacing;
      setDynamicTarget(out, r, x.guide + back * pop.guide.distance + lateral * slot, x.guideHeight);
    }
  }
}

void updateFollowing(const FollowingInput& in, const FollowingOutput& out) {
  GroupTable& groups = out.groups;
  for (const std::uint32_t gid : groups.busy()) {
    GroupState& g = groups[gid];
    if (!groups.hasRoute(g)) continue;  // follows nobody
    GroupRoute& x = groups.routeFor(gid);
    if (x.followGroup == kNoGroup || g.guided) continue;
    const FollowDesc& f = in.populations[g.population].follow;
    const GroupState& leader = groups[x.followGroup];
    bool following = g.following;
    if (f.mode == FollowMode::Permanent) {
      following = !leader.members.empty() || leader.cursor > 0;
    } else if (in.tick >= x.followToggle) {
      // Temporary following: alternate periods on and off, lengths drawn per group and period.
      core::Rng rng(in.seed, (static_cast<std::uint64_t>(gid) << 24) ^ in.tick, core::RngPurpose::Behaviour);
      following = !g.following && (!leader.members.empty() || leader.cursor > 0);
      const float lo = following ? f.onMin : f.offMin, hi = following ? f.onMax : f.offMax;
      x.followToggle = static_cast<std::uint32_t>(in.tick + static_cast<std::uint64_t>(std::lround(rng.uniform(lo, hi) / in.dt)));
    }
    if (following == g.following) continue;
    const std::uint32_t who = g.leader == kNoAgent ? 0 : g.leader;
    out.events.push_back({in.tick, who, following ? EventKind::FollowStart : EventKind::FollowEnd, gid, x.followGroup});
    if (following) {
      // Adopt the followed group's goal list from where that group is now.
      x.ownCursor = g.cursor;
      g.following = true;
      g.cursor = leader.cursor;
    } else {
      g.following = false;
      g.cursor = x.ownCursor;
    }
    groups.extraOf(g).waiting = false;
    for (std::uint32_t id : g.members) {
      const std::uint32_t r = in.rowOfId[id];
      if (groupSetsGoal(in.goalState[r])) out.goals.setGoal(r, g.cursor);
    }
  }
}

namespace {

/// Row r's ongoing following of another agent: chase it; end it when time is up or it left.
void chaseFollowed(const SocialEffectsInput& in, const SocialEffectsOutput& out, std::uint32_t r) {
  const std::uint32_t other = out.followAgent[r] < in.rowOfId.size() ? in.rowOfId[out.followAgent[r]] : kNoRow;
  if (other == kNoRow || in.tick >= out.followUntil[r] || out.goalState[r] == GoalState::Exited) {
    out.events.push_back({in.tick, in.id[r], EventKind::FollowAgentEnd, out.followAgent[r], 0});
    out.followAgent[r] = kNoAgent;
    if (out.goalState[r] != GoalState::Exited) out.goals.setGoal(r, in.goalCursor[r]);
    return;
  }
  const core::Vec2 them{in.posX[other], in.posY[other]};
  const core::Vec2 me{in.posX[r], in.posY[r]};
  const core::Vec2 target = them + core::normalize(me - them) * kFollowAgentGap;
  if (core::lengthSq(target - core::Vec2{out.targetX[r], out.targetY[r]}) <= 1.0f) return;
  out.targetX[r] = target.x;
  out.targetY[r] = target.y;
  if (!out.targetZ.empty()) out.targetZ[r] = in.posZ[other];
  out.dynamicTarget[r] = 1;
  out.needPath[r] = 1;
}

/// Row r joins the group of row `other`: adopts its goals and speed.
void joinGroup(const SocialEffectsInput& in, const SocialEffectsOutput& out, std::uint32_t r, std::uint32_t other) {
  GroupTable& groups = out.groups;
  const std::uint32_t from = out.group[r], to = out.group[other];
  if (from == to || groups[to].guided) return;
  const std::uint32_t id = in.id[r];
  groups[from].members.erase(id);
  if (groups[from].leader == id) groups[from].leader = groups[from].members.empty() ? kNoAgent : groups[from].members.front();
  auto& members = groups[to].members;
  members.insert(std::upper_bound(members.begin(), members.end(), id), id);
  out.group[r] = to;
  out.groupSize[r] = static_cast<std::uint16_t>(std::min<std::size_t>(members.size(), 0xffff));
  groups.markBusy(to);
  if (groups[to].flocks(in.desc.populations[groups[to].population])) out.speed[r] = groupSpeed(in.desc, groups, to);
  out.events.push_back({in.tick, id, EventKind::JoinGroup, from, to});
  if (out.goalState[r] != GoalState::Acting) out.goals.setGoal(r, groups[to].cursor);
}

}  // namespace

void applySocialEffects(const SocialEffectsInput& in, const SocialEffectsOutput& out) {
  const std::size_t n = in.id.size();
  for (std::uint32_t r = 0; r < n; ++r) {
    if (out.followAgent[r] == kNoAgent && out.sociologicalEffect[r] == SocialEffect::None) continue;
    if (out.followAgent[r] != kNoAgent) chaseFollowed(in, out, r);
    const SocialEffect effect = out.sociologicalEffect[r];
    if (effect == SocialEffect::None) continue;
    out.sociologicalEffect[r] = SocialEffect::None;
    const std::uint32_t other = in.sociologicalOther[r] < in.rowOfId.size() ? in.rowOfId[in.sociologicalOther[r]] : kNoRow;
    if (other == kNoRow) continue;
    if (effect == SocialEffect::JoinGroup) {
      joinGroup(in, out, r, other);
    } else if (effect == SocialEffect::FollowAgent) {
      const SociologicalDesc& social = in.desc.populations[in.population[r]].sociological;
      out.followAgent[r] = in.id[other];
      out.followUntil[r] = static_cast<std::uint32_t>(in.tick + static_cast<std::uint64_t>(std::lround(social.followDuration / in.desc.dt)));
      out.goalState[r] = GoalState::Seeking;
      out.mode[r] = AgentMode::Walking;
      out.events.push_back({in.tick, in.id[r], EventKind::FollowAgent, in.id[other], 0});
    }
  }
}

void updateWaiting(const WaitingInput& in, const WaitingOutput& out) {
  GroupTable& groups = out.groups;
  for (const std::uint32_t gid : groups.busy()) {
    GroupState& g = groups[gid];
    GroupExtra& x = groups.extraOf(g);
    const PopulationDesc& pop = in.populations[g.population];
    if (x.coordination != kNoIndex) continue;  // members are playing a script: nobody waits or leaves
    if (!g.flocks(pop) || g.guided) {
      // Without flocking the group's position in its goal list is its leader's.
      if (g.leader != kNoAgent && in.rowOfId[g.leader] != kNoRow) g.cursor = in.goalCursor[in.rowOfId[g.leader]];
      continue;
    }
    std::uint32_t waiting = 0;
    for (std::uint32_t id : g.members) waiting += in.goalState[in.rowOfId[id]] == GoalState::WaitingForGroup;
    if (waiting == 0) continue;
    const std::uint32_t point = out.goals.view().groupGoalPoint(g);
    if (!x.waiting) {
      x.waiting = true;
      x.waitStart = static_cast<std::uint32_t>(in.tick);
      out.events.push_back({in.tick, g.members.front(), EventKind::GroupWaitStart, point, gid});
    }
    const bool everyone = waiting == g.members.size();
    const bool timedOut = static_cast<double>(in.tick - x.waitStart) * in.dt >= pop.waitTimeout;
    if (!everyone && !timedOut) continue;
    // A following group never overtakes: it leaves a goal only once the followed group has left it.
    const std::uint32_t followed = groups.routeOf(g).followGroup;
    if (g.following && !groups[followed].members.empty() && groups[followed].cursor <= g.cursor) continue;
    const std::uint32_t missing = static_cast<std::uint32_t>(g.expected > waiting ? g.expected - waiting : 0);
    out.events.push_back({in.tick, g.members.front(), everyone ? EventKind::GroupRelease : EventKind::GroupTimeout, point,
                          everyone ? gid : missing});
    x.waiting = false;
    ++g.cursor;
    for (std::uint32_t id : g.members) {
      const std::uint32_t r = in.rowOfId[id];
      if (in.goalState[r] == GoalState::WaitingForGroup) out.goals.setGoal(r, g.cursor);
    }
  }
}

void World::Impl::updateLeaders() {
  sim::updateLeaders(LeaderInput{desc.populations, desc.seed, desc.dt, tick, rowOfId, agents.population},
                     LeaderOutput{groups, pendingEvents});
}

void updateLeaders(const LeaderInput& in, const LeaderOutput& out) {
  GroupTable& groups = out.groups;
  for (const std::uint32_t gid : groups.busy()) {
    GroupState& g = groups[gid];
    if (g.members.empty()) {
      g.leader = kNoAgent;
      continue;
    }
    if (g.leader == kNoAgent || !std::binary_search(g.members.begin(), g.members.end(), g.leader)) g.leader = g.members.front();
    const SociologicalDesc& social = in.populations[g.population].sociological;
    if (!social.enabled || g.members.size() < 2) continue;
    core::Rng rng(in.seed, (static_cast<std::uint64_t>(gid) << 24) ^ in.tick, core::RngPurpose::Behaviour);
    if (rng.uniform() >= social.leaderChangeRate * in.dt) continue;
    // Leadership passes to the most dominant member (members of other populations may have joined);
    // among equals, one drawn at random — never the current leader.
    float best = -1.0f;
    std::vector<std::uint32_t> candidates;
    for (std::uint32_t id : g.members) {
      if (id == g.leader) continue;
      const float d = in.populations[in.population[in.rowOfId[id]]].sociological.domination;
      if (d > best + 1e-6f) { best = d; candidates.clear(); }
      if (std::fabs(d - best) <= 1e-6f) candidates.push_back(id);
    }
    if (candidates.empty()) continue;
    g.leader = candidates[rng.uniformInt(0, static_cast<std::uint32_t>(candidates.size() - 1))];
    out.events.push_back({in.tick, g.leader, EventKind::LeaderChange, gid, 0});
  }
}

void World::Impl::updateGroupShapes(const core::TaskSystem& tasks) {
  const FormationInput in{desc.populations, rowOfId, agents.posX, agents.posY, agents.velX, agents.velY,
                          agents.goalState, agents.goalCursor, agents.followAgent};
  formGroups(in, FormationOutput{groups, agents.formVelX, agents.formVelY, scratch}, tasks);
}

namespace {

/// One busy group's formation: its centroid and heading, its members' corrections.
struct GroupFormation {
  const FormationInput& in;
  const FormationOutput& out;
  WorkerScratch& ws;

  void setFormVel(std::uint32_t r, float x, float y) const {
    if (!out.formVelX.empty()) {
      out.formVelX[r] = x;
      out.formVelY[r] = y;
    }
  }
  [[nodiscard]] core::Vec2 pos(std::uint32_t r) const { return {in.posX[r], in.posY[r]}; }
  void shape(GroupState& g) const;
  void takeSlots(const GroupState& g, const GroupExtra& x, const PopulationDesc& pop) const;
};

void GroupFormation::shape(GroupState& g) const {
  const PopulationDesc& pop = in.populations[g.population];
  if (g.members.empty()) return;
  GroupExtra& x = out.groups.extraOf(g);
  const bool flocking = g.flocks(pop) && g.members.size() >= 2 && x.coordination == kNoIndex;
  if (!flocking && !g.guided) {
    for (std::uint32_t id : g.members) setFormVel(in.rowOfId[id], 0.0f, 0.0f);
    return;
  }
  // Centroid and heading of the members.
  core::Vec2 sum, vel;
  for (std::uint32_t id : g.members) {
    const std::uint32_t r = in.rowOfId[id];
    sum += pos(r);
    vel += core::Vec2{in.velX[r], in.velY[r]};
    setFormVel(r, 0.0f, 0.0f);
  }
  const auto count = static_cast<float>(g.members.size());
  x.centroid = sum / count;
  if (core::lengthSq(vel) > 0.04f * count * count) x.heading = core::normalize(vel);
  if (flocking) takeSlots(g, x, pop);
}

void GroupFormation::takeSlots(const GroupState& g, const GroupExtra& x, const PopulationDesc& pop) const {
  // Members walking toward the group's goal take slots abreast (Moussaïd et al. 2010: small groups
  // walk side by side, larger ones in rows), ordered by where they already are so nobody crosses.
  auto& order = ws.order;
  order.clear();
  for (std::uint32_t id : g.members) {
    const std::uint32_t r = in.rowOfId[id];
    const bool followsAgent = !in.followAgent.empty() && in.followAgent[r] != kNoAgent;
    if (in.goalState[r] != GoalState::Seeking || followsAgent) continue;
    if (in.goalCursor[r] != g.cursor && !g.guided) continue;
    order.push_back({core::dot(pos(r) - x.centroid, x.heading), r});
  }
  if (order.size() < 2) return;
  std::sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first > b.first || (a.first == b.first && a.second < b.second); });
  const core::Vec2 lateral = core::perp(x.heading);
  const std::size_t rows = (order.size() + kAbreast - 1) / kAbreast;
  auto& line = ws.line;
  for (std::size_t row0 = 0; row0 < rows; ++row0) {
    const std::size_t first = row0 * kAbreast, last = std::min(order.size(), first + kAbreast);
    line.assign(order.begin() + static_cast<std::ptrdiff_t>(first), order.begin() + static_cast<std::ptrdiff_t>(last));
    for (auto& e : line) e.first = core::dot(pos(e.second) - x.centroid, lateral);
    std::sort(line.begin(), line.end());
    const float along = (0.5f * static_cast<float>(rows - 1) - static_cast<float>(row0)) * kRowSpacing;
    for (std::size_t i = 0; i < line.size(); ++i) {
      const std::uint32_t r = line[i].second;
      const float slot = (static_cast<float>(i) - 0.5f * static_cast<float>(line.size() - 1)) * pop.groupSpacing;
      const core::Vec2 rel = pos(r) - x.centroid;
      const float lat = core::dot(rel, lateral), lon = core::dot(rel, x.heading);
      core::Vec2 corr = lateral * ((slot - lat) * kFormationGain) + x.heading * ((along - lon) * kFormationGain);
      const float m = core::length(corr);
      if (m > kFormationMaxSpeed) corr *= kFormationMaxSpeed / m;
      setFormVel(r, corr.x, corr.y);
    }
  }
}

}  // namespace

void formGroups(const FormationInput& in, const FormationOutput& out, const core::TaskSystem& tasks) {
  // Parallel over groups: a group writes its own centroid and heading and its members' rows only.
  const std::vector<std::uint32_t>& busy = out.groups.busy();
  tasks.parallelFor(busy.size(), tasks.grain(512), [&](std::size_t begin, std::size_t end) {
    const auto worker = static_cast<std::size_t>(tasks.workerIndex());
    THRONG_ASSERT(worker < out.workers.size());
    const GroupFormation formation{in, out, out.workers[worker]};
    for (std::size_t i = begin; i < end; ++i) formation.shape(out.groups[busy[i]]);
  });
}

}  // namespace throng::sim
