// common_ground_play — the Common Ground model of Park, Peng, Quek and Cao inside the World
// (docs/social-model.md), part 2 of 2: playing the action scripts.
//   run (group pass, serial): every actor plays its script entry by entry — walks go through the
//     navmesh and ORCA like any walk, clips and turns hold the agent in place — and each finished
//     entry is published with its planned and actual times; divided groups reunite.
// Goals and the start of coordinations (goal generator, grounding) are in common_ground.cpp.
// Reads the active coordinations and the agents; writes the Scripted agents' rows, the group table
// and the frame's script and coordination records (runCoordinations, checkReunions:
// CommonGroundInput, CommonGroundOutput, group_pass.hpp). Serial parts visit rows and coordinations in a
// fixed order, so the result never depends on threads.
#include <algorithm>
#include <cmath>

#include "group_pass.hpp"

namespace throng::sim {
namespace {

/// A scripted walk is done within this distance of its target [m].
constexpr float kScriptArrive = 0.35f;
/// Followers of a detour stop this close to the goal (they gather around the leader) [m].
constexpr float kFollowArrive = 1.5f;
/// A walker that stands still this long this close to its target counts as arrived [s], [m].
constexpr float kStuckArrive = 1.5f;
constexpr float kStuckArriveDistance = 2.0f;
/// A walk gives up after max(kWalkGiveUpMin, kWalkGiveUpFactor × its planned duration) [s].
constexpr double kWalkGiveUpMin = 20.0;
constexpr double kWalkGiveUpFactor = 3.0;
/// Times within this of each other count as equal [s].
constexpr double kTimeEpsilon = 1e-9;

bool leavesScript(const common_ground::ScriptEntry& e) {
  return e.step == common_ground::GroundingStep::Execute &&
         (e.behaviour == "resume" || e.behaviour == "walk_to_destination" || e.behaviour == "walk_to_next");
}

/// runCoordinations' steps over its contexts (CommonGroundInput, CommonGroundOutput: group_pass.hpp).
struct CoordinationPlay : CommonGroundPass {
  using CommonGroundPass::CommonGroundPass;

  void playCoordination(ActiveCoordination& c, double now);
  void playActor(ActiveCoordination& c, std::size_t actor, std::uint32_t row, double now);
  /// Whether the actor's current entry is over (walks: arrived, stuck near, or given up; others:
  /// their time is up); turns it toward the entry's target meanwhile.
  bool entryComplete(ActiveCoordination& c, std::size_t actor, std::uint32_t row, const common_ground::ScriptEntry& e, double now);
  void turnToward(const ActiveCoordination& c, std::uint32_t row, const common_ground::ScriptEntry& e);
  void publishEntry(const ActiveCoordination& c, std::size_t actor, const common_ground::ScriptEntry& e, double start, double duration);
  /// The actor leaves the script and goes back to its group's navigation.
  void leaveScript(ActiveCoordination& c, std::size_t actor);
  void beginEntry(ActiveCoordination& c, std::size_t actor, std::size_t row, double now);
  void finishCoordination(ActiveCoordination& c, double now);
};

}  // namespace

void CoordinationPlay::beginEntry(ActiveCoordination& c, std::size_t actor, std::size_t row, double now) {
  const common_ground::ScriptEntry& e = c.script.actor(actor)[c.cursor[actor]];
  if (e.step == common_ground::GroundingStep::Execute && c.record.executeTime <= 0.0 && actor == 0) c.record.executeTime = now;
  const core::Vec2 pos{agents.posX[row], agents.posY[row]};
  agents.scriptWalk[row] = 0;
  agents.scriptClip[row] = kNoClip;
  agents.targetX[row] = pos.x;
  agents.setTargetHeight(row, agents.height(row));  // Common Ground runs on flat worlds only (io refuses it on levels)
  agents.targetY[row] = pos.y;
  agents.corners[row].clear();
  agents.needPath[row] = 0;
  agents.ticket[row] = 0;
  agents.mode[row] = AgentMode::Waiting;
  if (e.motion == common_ground::kWalkMotion) {
    core::Vec2 target = e.targetPoint;
    if (e.behaviour == "walk_to_partner" && e.targetType == common_ground::ScriptEntry::Target::Agent &&
        e.targetActor < c.actors.size()) {
      // Back to where the partner stands now (it may have been nudged), touch distance short of it.
      const std::uint32_t pr = rowOfId[c.actors[e.targetActor]];
      if (pr != kNoRow) {
        const core::Vec2 partner{agents.posX[pr], agents.posY[pr]};
        const core::Vec2 away = core::normalize(pos - partner);
        target = partner + away * static_cast<float>(desc.social.coordination.touchDistance);
      }
    }
    if (auto hit = goals.query.nearest(target, 3.0f)) target = hit->first;
    agents.targetX[row] = target.x;
    agents.setTargetHeight(row, agents.height(row));
    agents.targetY[row] = target.y;
    agents.needPath[row] = 1;
    agents.scriptWalk[row] = 1;
    agents.dynamicTarget[row] = 1;
    agents.progressDistance[row] = 1e30f;
    agents.stuckTime[row] = 0.0f;
    agents.mode[row] = AgentMode::Walking;
  } else if (e.motion == common_ground::kIdleMotion) {
    if (e.behaviour == "stay") {
      agents.mode[row] = AgentMode::Acting;
      if (actor == 0) pendingEvents.push_back({tick, c.actors[0], EventKind::VisitStart, c.record.goalPoint, c.record.id});
    }
  } else if (e.motion != common_ground::kTurnMotion) {
    const auto clip = commonGround.clipIndex.find(e.motion);
    if (clip != commonGround.clipIndex.end()) agents.scriptClip[row] = clip->second;
    agents.mode[row] = AgentMode::Acting;
  }
}

void runCoordinations(const CommonGroundInput& in, const CommonGroundOutput& out) {
  CoordinationPlay play(in, out);
  const double now = static_cast<double>(in.tick) * in.desc.dt;
  auto& active = out.state.coordinations;
  for (auto it = active.begin(); it != active.end();) {
    ActiveCoordination& c = it->second;
    play.playCoordination(c, now);
    if (std::all_of(c.left.begin(), c.left.end(), [](std::uint8_t l) { return l != 0; })) {
      play.finishCoordination(c, now);
      it = active.erase(it);
    } else {
      ++it;
    }
  }
}

void CoordinationPlay::playCoordination(ActiveCoordination& c, double now) {
  const bool overdue = now >= c.deadline;
  for (std::size_t i = 0; i < c.actors.size(); ++i) {
    if (c.left[i]) continue;
    const std::uint32_t row = c.actors[i] < rowOfId.size() ? rowOfId[c.actors[i]] : kNoRow;
    if (row == kNoRow) {  // gone from the world
      c.left[i] = 1;
      continue;
    }
    if (overdue) {
      leaveScript(c, i);
      continue;
    }
    playActor(c, i, row, now);
  }
}

void CoordinationPlay::publishEntry(const ActiveCoordination& c, std::size_t actor, const common_ground::ScriptEntry& e, double start,
                               double duration) {
  ScriptRecord r;
  r.coordination = c.record.id;
  r.agent = c.actors[actor];
  r.seq = c.cursor[actor];
  r.role = static_cast<std::uint8_t>(std::min<std::size_t>(actor, 2));
  r.step = static_cast<std::uint8_t>(e.step);
  r.part = static_cast<std::uint8_t>(e.part);
  r.attempt = static_cast<std::uint8_t>(std::min(e.attempt, 255));
  r.plan = static_cast<std::uint8_t>(e.plan);
  r.targetType = static_cast<std::uint8_t>(e.targetType);
  if (e.targetType == common_ground::ScriptEntry::Target::Agent && e.targetActor < c.actors.size()) r.targetAgent = c.actors[e.targetActor];
  r.targetX = e.targetPoint.x;
  r.targetY = e.targetPoint.y;
  r.plannedStart = e.start;
  r.plannedDuration = e.duration;
  r.start = start;
  r.duration = duration;
  r.motion = e.motion;
  r.behaviour = e.behaviour;
  commonGround.pendingScript.push_back(std::move(r));
}

void CoordinationPlay::leaveScript(ActiveCoordination& c, std::size_t actor) {
  c.left[actor] = 1;
  const std::uint32_t row = c.actors[actor] < rowOfId.size() ? rowOfId[c.actors[actor]] : kNoRow;
  if (row == kNoRow) return;
  agents.coordination[row] = kNoIndex;
  agents.scriptWalk[row] = 0;
  agents.scriptClip[row] = kNoClip;
  if (actor == 0) {
    agents.socialReady[row] = static_cast<std::uint32_t>(tick + static_cast<std::uint64_t>(std::lround(desc.social.cooldown / desc.dt)));
    agents.visited[row].push_back(c.record.goalPoint);
  }
  // Back to the group's navigation, where the group is now.
  goals.setGoal(row, groups[agents.group[row]].cursor);
}

namespace {

/// A walk of another actor that should be over by `until` must really be over: the response to a
/// motion never starts before it (walking times are only estimates in a crowd).
bool waitsForWalk(const ActiveCoordination& c, std::size_t actor, double until) {
  for (std::size_t j = 0; j < c.actors.size(); ++j) {
    if (j == actor || c.left[j]) continue;
    const auto& other = c.script.actor(j);
    if (c.cursor[j] >= other.size()) continue;
    const common_ground::ScriptEntry& w = other[c.cursor[j]];
    if (w.motion == common_ground::kWalkMotion && w.duration > 0.0 && w.end() <= until + kTimeEpsilon) return true;
  }
  return false;
}

}  // namespace

void CoordinationPlay::playActor(ActiveCoordination& c, std::size_t i, std::uint32_t row, double now) {
  const auto& entries = c.script.actor(i);
  while (!c.left[i]) {
    if (c.cursor[i] >= entries.size()) {
      leaveScript(c, i);
      break;
    }
    const common_ground::ScriptEntry& e = entries[c.cursor[i]];
    if (c.started[i] < 0.0) {
      if (now + kTimeEpsilon < e.start + c.slip) break;  // waits for its activation time
      if (waitsForWalk(c, i, e.start)) break;
      if (leavesScript(e)) {
        publishEntry(c, i, e, now, e.duration);
        leaveScript(c, i);
        break;
      }
      beginEntry(c, i, row, now);
      c.started[i] = now;
    }
    if (!entryComplete(c, i, row, e, now)) break;
    publishEntry(c, i, e, c.started[i], now - c.started[i]);
    if (e.behaviour == "stay" && i == 0) {
      pendingEvents.push_back({tick, c.actors[0], EventKind::VisitEnd, c.record.goalPoint, c.record.id});
    }
    if (e.behaviour == "walk_to_partner" && i == 0) {
      c.reunitedOnReturn = true;
      pendingEvents.push_back({tick, c.actors[0], EventKind::Reunited, c.record.group, c.record.id});
    }
    ++c.cursor[i];
    c.started[i] = -1.0;
    agents.scriptWalk[row] = 0;
    agents.scriptClip[row] = kNoClip;
    agents.targetSelf(row);
    agents.corners[row].clear();
    agents.mode[row] = AgentMode::Waiting;
  }
}

bool CoordinationPlay::entryComplete(ActiveCoordination& c, std::size_t i, std::uint32_t row, const common_ground::ScriptEntry& e,
                                double now) {
  if (e.motion == common_ground::kWalkMotion) {
    const float dx = agents.targetX[row] - agents.posX[row], dy = agents.targetY[row] - agents.posY[row];
    const float d2 = dx * dx + dy * dy;
    const float reach = e.behaviour == "follow" ? kFollowArrive : kScriptArrive;
    const bool complete = d2 < reach * reach ||
                          (agents.stuckTime[row] > kStuckArrive && d2 < kStuckArriveDistance * kStuckArriveDistance) ||
                          now - c.started[i] > std::max(kWalkGiveUpMin, kWalkGiveUpFactor * e.duration);
    if (complete) c.slip += std::max(0.0, now - (e.end() + c.slip));  // a late walk delays what follows
    return complete;
  }
  const bool complete = now + kTimeEpsilon >= e.end() + c.slip && !waitsForWalk(c, i, e.end());
  if (!complete && e.targetType != common_ground::ScriptEntry::Target::None) turnToward(c, row, e);
  return complete;
}

void CoordinationPlay::turnToward(const ActiveCoordination& c, std::uint32_t row, const common_ground::ScriptEntry& e) {
  // Turn toward the target at the turning rate (turns, and clips aimed at something).
  const float turnStep = static_cast<float>(desc.social.coordination.turnRate * desc.dt);
  core::Vec2 aim = e.targetPoint;
  if (e.targetType == common_ground::ScriptEntry::Target::Agent && e.targetActor < c.actors.size()) {
    const std::uint32_t tr = rowOfId[c.actors[e.targetActor]];
    if (tr != kNoRow) aim = {agents.posX[tr], agents.posY[tr]};
  }
  const core::Vec2 want = aim - core::Vec2{agents.posX[row], agents.posY[row]};
  if (core::lengthSq(want) <= 1e-6f) return;
  const float have = std::atan2(agents.oriY[row], agents.oriX[row]);
  float delta = std::atan2(want.y, want.x) - have;
  while (delta > 3.14159265f) delta -= 6.28318531f;
  while (delta < -3.14159265f) delta += 6.28318531f;
  const float step = std::clamp(delta, -turnStep, turnStep);
  agents.oriX[row] = std::cos(have + step);
  agents.oriY[row] = std::sin(have + step);
}

void CoordinationPlay::finishCoordination(ActiveCoordination& c, double now) {
  c.record.end = now;
  if (c.record.executeTime <= 0.0) c.record.executeTime = now;
  GroupExtra& x = groups.extraOf(groups[c.record.group]);
  if (x.coordination == c.record.id) x.coordination = kNoIndex;
  if (c.divides && !c.reunitedOnReturn) {
    x.reunite = c.record.id;
    groups.markBusy(c.record.group);
  }
  pendingEvents.push_back({tick, c.record.initiator, EventKind::CoordinationEnd, c.record.id,
                           static_cast<std::uint32_t>(c.record.outcome)});
  commonGround.pendingCoordinations.push_back(std::move(c.record));
}

void checkReunions(const CommonGroundInput& in, const CommonGroundOutput& out) {
  const std::span<const std::uint32_t> rowOfId = in.rowOfId;
  const AgentStore& agents = out.agents;
  GroupTable& groups = out.groups;
  for (const std::uint32_t gid : groups.busy()) {
    GroupState& g = groups[gid];
    GroupExtra& x = groups.extraOf(g);
    if (x.reunite == kNoIndex || x.coordination != kNoIndex) continue;
    if (g.members.size() < 2) {
      x.reunite = kNoIndex;
      continue;
    }
    // Whole again: nobody in a script, everybody within the group's width of the centroid.
    core::Vec2 sum;
    bool busy = false;
    for (const std::uint32_t id : g.members) {
      const std::uint32_t r = rowOfId[id];
      busy = busy || agents.coordination[r] != kNoIndex;
      sum += core::Vec2{agents.posX[r], agents.posY[r]};
    }
    if (busy) continue;
    const core::Vec2 centroid = sum / static_cast<float>(g.members.size());
    const float reach = 1.5f + in.desc.populations[g.population].groupSpacing * static_cast<float>(g.members.size()) * 0.5f;
    const bool together = std::all_of(g.members.begin(), g.members.end(), [&](std::uint32_t id) {
      const std::uint32_t r = rowOfId[id];
      return core::lengthSq(core::Vec2{agents.posX[r], agents.posY[r]} - centroid) <= reach * reach;
    });
    if (!together) continue;
    out.events.push_back({in.tick, g.leader == kNoAgent ? g.members.front() : g.leader, EventKind::Reunited, gid, x.reunite});
    x.reunite = kNoIndex;
  }
}

}  // namespace throng::sim
