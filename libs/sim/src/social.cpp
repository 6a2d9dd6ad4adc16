// social — the Common Ground model of Park, Peng, Quek and Cao inside the World
// (docs/social-model.md):
//   goal generator (decide, parallel): stochastic needs at a rate per agent, and places of an
//     interesting category the agent sees (vision cone, range, walls), one draw per agent and place;
//   start (group pass, serial): the initiator assesses its group mates (sensing, relations), the
//     planner runs the grounding process into an action script for A, B and the companions, or a
//     lone visit when nobody else is there or Common Ground is off;
//   run (group pass, serial): every actor plays its script entry by entry — walks go through the
//     navmesh and ORCA like any walk, clips and turns hold the agent in place — and each finished
//     entry is published with its planned and actual times; divided groups reunite.
// Reads the scenario's social description and the agents; writes the Scripted agents' rows, the
// group table and the frame's script and coordination records. Serial parts visit rows and
// coordinations in a fixed order, so the result never depends on threads.
#include <algorithm>
#include <cmath>

#include "throng/sim/animation.hpp"
#include "throng/social/relations.hpp"
#include "world_impl.hpp"

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
/// Every actor is released this long after the planned end, times 3 for slow crowds [s].
constexpr double kDeadlineSlack = 120.0;

bool leavesScript(const social::ScriptEntry& e) {
  return e.step == social::GroundingStep::Execute &&
         (e.behaviour == "resume" || e.behaviour == "walk_to_destination" || e.behaviour == "walk_to_next");
}

/// Effort for A to be perceived by a member in relation r: the respondent B is the hardest one.
int effort(social::Relation r) {
  switch (r) {
    case social::Relation::A1: return 0;
    case social::Relation::A2: return 1;
    case social::Relation::A4: return 2;
    case social::Relation::A5: return 3;
    case social::Relation::A3: return 4;
    case social::Relation::A6: return 5;
  }
  return 5;
}

core::Vec2 facingOf(float x, float y) {
  const core::Vec2 f{x, y};
  return core::lengthSq(f) > 0.0f ? core::normalize(f) : core::Vec2{1.0f, 0.0f};
}

}  // namespace

void World::Impl::initSocial() {
  pointCategory.assign(desc.points.size(), -1);
  for (std::uint32_t p = 0; p < desc.points.size(); ++p) {
    const std::string& c = desc.points[p].category;
    if (c.empty()) continue;
    auto it = std::find(categories.begin(), categories.end(), c);
    if (it == categories.end()) {
      categories.push_back(c);
      categoryPoints.emplace_back();
      it = categories.end() - 1;
    }
    const auto index = static_cast<std::size_t>(it - categories.begin());
    pointCategory[p] = static_cast<std::int32_t>(index);
    categoryPoints[index].push_back(p);
  }
  for (std::uint32_t p = 0; p < desc.points.size(); ++p) {
    if (pointCategory[p] < 0) continue;
    const bool wanted = std::any_of(desc.populations.begin(), desc.populations.end(), [&](const PopulationDesc& pop) {
      return std::find(pop.interests.begin(), pop.interests.end(), desc.points[p].category) != pop.interests.end();
    });
    if (wanted) attractionPoints.push_back(p);
  }
  const std::vector<ClipInfo> clips = animationClips(desc);
  for (std::size_t i = 0; i < clips.size(); ++i) {
    clipDuration.push_back(std::max(1e-3f, clips[i].duration));
    clipIndex.emplace(clips[i].name, static_cast<std::uint16_t>(i));
  }
}

void World::Impl::generateGoal(std::size_t row, ChunkOutput& out, const nav::NavQuery& query) {
  const SocialDesc& social = desc.social;
  if (!social.enabled || agents.desirePoint[row] != kNoAgent || tick < agents.socialReady[row]) return;
  const GroupState& g = groups[agents.group[row]];
  if (extraOf(g).coordination != kNoAgent || g.guided || g.following || agents.followedAgent(row) != kNoAgent) return;
  const std::uint32_t id = agents.id[row];
  const core::Vec2 pos{agents.posX[row], agents.posY[row]};
  auto want = [&](std::uint32_t point, GoalTrigger trigger) {
    agents.desirePoint[row] = point;
    agents.desireTrigger[row] = static_cast<std::uint8_t>(trigger);
    out.desireRows.push_back(static_cast<std::uint32_t>(row));
  };
  // Stochastic needs (a restroom visit): rate × dt per tick; the nearest place of the category.
  for (std::size_t i = 0; i < social.needs.size(); ++i) {
    const NeedDesc& need = social.needs[i];
    const auto c = std::find(categories.begin(), categories.end(), need.category);
    if (c == categories.end() || need.rate <= 0.0f) continue;
    core::Rng rng(desc.seed, core::mix64((static_cast<std::uint64_t>(id) << 32) ^ tick) ^ i, core::RngPurpose::Social);
    if (rng.uniform() >= static_cast<double>(need.rate) * desc.dt) continue;
    std::uint32_t best = kNoAgent;
    float bestD = 1e30f;
    for (const std::uint32_t p : categoryPoints[static_cast<std::size_t>(c - categories.begin())]) {
      const float d = core::lengthSq(desc.points[p].position - pos);
      if (d < bestD) { bestD = d; best = p; }
    }
    if (best != kNoAgent) {
      want(best, GoalTrigger::Need);
      return;
    }
  }
  // Environmentally driven goals: a place of an interesting category in view (cone, range, walls).
  const std::uint64_t mask = agents.interests[row];
  if (mask == 0 || attractionPoints.empty()) return;
  const auto period = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::lround(social.attraction.checkPeriod / desc.dt)));
  if ((tick + id) % period != 0) return;
  const social::Body me{pos, facingOf(agents.oriX[row], agents.oriY[row]), agents.radius[row]};
  const social::NavMeshOcclusion walls(query);
  const std::vector<std::uint32_t>& seen = agents.visited[row];
  for (const std::uint32_t p : attractionPoints) {
    if (!((mask >> static_cast<unsigned>(pointCategory[p])) & 1u)) continue;
    if (std::find(seen.begin(), seen.end(), p) != seen.end()) continue;
    const social::Body place{desc.points[p].position, {0.0f, 0.0f}, 0.0f};
    if (!social::perceive(me, place, social.senses, walls).see) continue;
    // One draw per agent and place: the same place never tempts the same agent twice.
    core::Rng rng(desc.seed, (static_cast<std::uint64_t>(id) << 32) ^ p, core::RngPurpose::Social);
    if (rng.uniform() < social.attraction.probability) {
      want(p, GoalTrigger::Attraction);
      return;
    }
  }
}

void World::Impl::startCoordinations() {
  const SocialDesc& social = desc.social;
  const nav::NavQuery& query = *mainQuery;
  const double now = static_cast<double>(tick) * desc.dt;
  for (ChunkOutput& chunk : chunks) {
    for (const std::uint32_t row : chunk.desireRows) {
      const std::uint32_t point = agents.desirePoint[row];
      const auto trigger = static_cast<GoalTrigger>(agents.desireTrigger[row]);
      agents.desirePoint[row] = kNoAgent;
      if (point == kNoAgent || agents.goalState[row] != GoalState::Seeking || agents.coordination[row] != kNoAgent) continue;
      const std::uint32_t gid = agents.group[row];
      GroupState& g = groups[gid];
      if (extraOf(g).coordination != kNoAgent) continue;  // a mate got there first this tick
      const std::uint32_t aId = agents.id[row];
      const PointDesc& place = desc.points[point];

      // The goal: what the macro-plan rules read.
      social::Goal goal;
      goal.kind = social::GoalKind::Personal;
      goal.expectedVisit = social.attraction.expectedVisit;
      if (trigger == GoalTrigger::Need) {
        for (const NeedDesc& need : social.needs) {
          if (need.category == place.category) { goal.kind = need.kind; goal.expectedVisit = need.expectedVisit; break; }
        }
      }
      // Group mates that can take part: present, not busy at an action point or in another script.
      std::vector<std::uint32_t> mates;
      for (const std::uint32_t m : g.members) {
        if (m == aId) continue;
        const std::uint32_t r = rowOfId[m];
        const GoalState s = agents.goalState[r];
        if (agents.coordination[r] != kNoAgent) continue;
        if (s == GoalState::Seeking || s == GoalState::WaitingForGroup || s == GoalState::Done) mates.push_back(m);
      }
      if (trigger == GoalTrigger::Attraction && !mates.empty()) {
        // A place every mate is interested in too is a shared goal (detour together).
        const int cat = pointCategory[point];
        const bool all = std::all_of(mates.begin(), mates.end(), [&](std::uint32_t m) {
          return ((agents.interests[rowOfId[m]] >> static_cast<unsigned>(cat)) & 1u) != 0;
        });
        if (all) goal.kind = social::GoalKind::Shared;
      }
      // x_s: a spot in the place's region (sub-regions spread visitors), on the navmesh.
      goal.position = drawTarget(row, place, query);
      const core::Vec2 aPos{agents.posX[row], agents.posY[row]};
      const core::Vec2 destination{agents.targetX[row], agents.targetY[row]};
      auto body = [&](std::uint32_t r) {
        social::ActorBody b;
        b.position = {agents.posX[r], agents.posY[r]};
        b.heading = std::atan2(agents.oriY[r], agents.oriX[r]);
        b.walkSpeed = std::clamp(agents.speed[r], 0.1f, 10.0f);
        b.id = agents.id[r];
        return b;
      };
      auto sensed = [&](std::uint32_t r) {
        return social::Body{{agents.posX[r], agents.posY[r]}, facingOf(agents.oriX[r], agents.oriY[r]), agents.radius[r]};
      };

      ActiveCoordination c;
      c.record.id = nextCoordinationId++;
      c.record.group = gid;
      c.record.initiator = aId;
      c.record.goalPoint = point;
      c.record.goalKind = static_cast<std::uint8_t>(goal.kind);
      c.record.trigger = trigger;
      c.record.start = now;
      c.actors.push_back(aId);
      bool alone = !social.commonGround || mates.empty();
      if (!alone) {
        const social::NavMeshOcclusion walls(query);
        const social::Body aBody = sensed(row);
        std::vector<std::pair<social::Relation, std::uint32_t>> rel;
        for (const std::uint32_t m : mates) rel.emplace_back(social::assess(aBody, sensed(rowOfId[m]), social.senses, walls), m);
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
        social::CoordinationInput in;
        in.initiator = body(row);
        in.respondent = body(bRow);
        in.relation = rel[bi].first;
        for (std::size_t i = 0; i < rel.size(); ++i) {
          if (i == bi) continue;
          in.companions.push_back({body(rowOfId[rel[i].second]), rel[i].first});
        }
        const social::Body bBody = sensed(bRow);
        const auto snap = [&](social::Approach a) -> std::optional<core::Vec2> {
          if (!a.reachable) return std::nullopt;
          if (auto hit = query.nearest(a.point, 2.0f)) return hit->first;
          return std::nullopt;
        };
        in.viewPoint = snap(social::pointInView(aBody, bBody, social.senses, walls));
        in.hearingPoint = snap(social::pointInHearing(aBody, bBody, social.senses));
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
        auto planned = social::planCoordination(in, {&social.micro, &social.macro}, social.clipLengths, social.coordination);
        if (planned.ok()) {
          c.script = std::move(planned).value();
          c.actors.push_back(rel[bi].second);
          for (std::size_t i = 0; i < rel.size(); ++i) {
            if (i != bi) c.actors.push_back(rel[i].second);
          }
          c.record.relation = static_cast<std::uint8_t>(rel[bi].first);
          c.record.plan = static_cast<std::uint8_t>(c.script.plan);
          c.record.outcome = c.script.outcome == social::Outcome::Grounded ? CoordinationOutcome::Grounded
                                                                            : CoordinationOutcome::Failed;
        } else {
          alone = true;  // a database without a clip length: the agent goes on its own
        }
      }
      if (alone) {
        // A lone visit: walk to the goal, stay the plan's visit duration, walk on (no grounding).
        const auto chosen = social::selectPlan(social.macro, goal, core::distance(goal.position, aPos));
        const social::PlanKind kind = chosen ? social.macro.plans[*chosen].kind : social::PlanKind::DivideAndProceed;
        const double visit = chosen ? social.macro.plans[*chosen].visitDuration : 30.0;
        const double speed = std::max(0.1f, agents.speed[row]);
        social::ActionScript s;
        s.actors.resize(1);
        s.plan = kind;
        s.startTime = s.executeTime = now;
        auto add = [&](const char* motion, const char* behaviour, double start, double duration, core::Vec2 target) {
          social::ScriptEntry e;
          e.start = start;
          e.duration = duration;
          e.motion = motion;
          e.behaviour = behaviour;
          e.targetType = social::ScriptEntry::Target::Point;
          e.targetPoint = target;
          e.step = social::GroundingStep::Execute;
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
      for (std::size_t i = 1; i < c.actors.size(); ++i) c.record.respondents.push_back(c.actors[i]);
      for (const auto& list : c.script.actors) {
        for (const auto& e : list) c.record.retries += e.attempt > 0 && e.step != social::GroundingStep::Execute ? 1u : 0u;
      }
      const std::size_t n = c.actors.size();
      c.cursor.assign(n, 0);
      c.started.assign(n, -1.0);
      c.left.assign(n, 0);
      c.deadline = now + 3.0 * std::max(0.0, c.script.endTime - now) + kDeadlineSlack;
      c.divides = g.members.size() >= 2 && (c.script.plan == social::PlanKind::DivideAndProceed ||
                                            c.script.plan == social::PlanKind::DivideAndWait);
      for (const std::uint32_t actor : c.actors) {
        const std::uint32_t r = rowOfId[actor];
        agents.coordination[r] = c.record.id;
        agents.goalState[r] = GoalState::Scripted;
        agents.mode[r] = AgentMode::Waiting;
        agents.scriptWalk[r] = 0;
        agents.scriptClip[r] = kNoClip;
        agents.targetX[r] = agents.posX[r];
        agents.targetY[r] = agents.posY[r];
        agents.corners[r].clear();
        agents.needPath[r] = 0;
        agents.ticket[r] = 0;
      }
      if (!alone) extraOf(g).coordination = c.record.id;
      markBusy(gid);
      pendingEvents.push_back({tick, aId, EventKind::GoalGenerated, point, static_cast<std::uint32_t>(trigger)});
      pendingEvents.push_back({tick, aId, EventKind::CoordinationStart, c.record.id, gid});
      coordinations.emplace(c.record.id, std::move(c));
    }
    chunk.desireRows.clear();
  }
}

void World::Impl::beginEntry(ActiveCoordination& c, std::size_t actor, std::size_t row, double now) {
  const social::ScriptEntry& e = c.script.actor(actor)[c.cursor[actor]];
  if (e.step == social::GroundingStep::Execute && c.record.executeTime <= 0.0 && actor == 0) c.record.executeTime = now;
  const core::Vec2 pos{agents.posX[row], agents.posY[row]};
  agents.scriptWalk[row] = 0;
  agents.scriptClip[row] = kNoClip;
  agents.targetX[row] = pos.x;
  agents.targetY[row] = pos.y;
  agents.corners[row].clear();
  agents.needPath[row] = 0;
  agents.ticket[row] = 0;
  agents.mode[row] = AgentMode::Waiting;
  if (e.motion == social::kWalkMotion) {
    core::Vec2 target = e.targetPoint;
    if (e.behaviour == "walk_to_partner" && e.targetType == social::ScriptEntry::Target::Agent &&
        e.targetActor < c.actors.size()) {
      // Back to where the partner stands now (it may have been nudged), touch distance short of it.
      const std::uint32_t pr = rowOfId[c.actors[e.targetActor]];
      if (pr != kNoAgent) {
        const core::Vec2 partner{agents.posX[pr], agents.posY[pr]};
        const core::Vec2 away = core::normalize(pos - partner);
        target = partner + away * static_cast<float>(desc.social.coordination.touchDistance);
      }
    }
    if (auto hit = mainQuery->nearest(target, 3.0f)) target = hit->first;
    agents.targetX[row] = target.x;
    agents.targetY[row] = target.y;
    agents.needPath[row] = 1;
    agents.scriptWalk[row] = 1;
    agents.dynamicTarget[row] = 1;
    agents.progressDistance[row] = 1e30f;
    agents.stuckTime[row] = 0.0f;
    agents.mode[row] = AgentMode::Walking;
  } else if (e.motion == social::kIdleMotion) {
    if (e.behaviour == "stay") {
      agents.mode[row] = AgentMode::Acting;
      if (actor == 0) pendingEvents.push_back({tick, c.actors[0], EventKind::VisitStart, c.record.goalPoint, c.record.id});
    }
  } else if (e.motion != social::kTurnMotion) {
    const auto clip = clipIndex.find(e.motion);
    if (clip != clipIndex.end()) agents.scriptClip[row] = clip->second;
    agents.mode[row] = AgentMode::Acting;
  }
}

void World::Impl::runCoordinations() {
  if (coordinations.empty()) return;
  const nav::NavQuery& query = *mainQuery;
  const double now = static_cast<double>(tick) * desc.dt;
  const double eps = 1e-9;
  const float turnStep = static_cast<float>(desc.social.coordination.turnRate * desc.dt);
  for (auto it = coordinations.begin(); it != coordinations.end();) {
    ActiveCoordination& c = it->second;
    auto publish = [&](std::size_t actor, const social::ScriptEntry& e, double start, double duration) {
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
      if (e.targetType == social::ScriptEntry::Target::Agent && e.targetActor < c.actors.size()) r.targetAgent = c.actors[e.targetActor];
      r.targetX = e.targetPoint.x;
      r.targetY = e.targetPoint.y;
      r.plannedStart = e.start;
      r.plannedDuration = e.duration;
      r.start = start;
      r.duration = duration;
      r.motion = e.motion;
      r.behaviour = e.behaviour;
      pendingScript.push_back(std::move(r));
    };
    auto leave = [&](std::size_t actor) {
      c.left[actor] = 1;
      const std::uint32_t row = c.actors[actor] < rowOfId.size() ? rowOfId[c.actors[actor]] : kNoAgent;
      if (row == kNoAgent) return;
      agents.coordination[row] = kNoAgent;
      agents.scriptWalk[row] = 0;
      agents.scriptClip[row] = kNoClip;
      if (actor == 0) {
        agents.socialReady[row] = static_cast<std::uint32_t>(tick + static_cast<std::uint64_t>(std::lround(desc.social.cooldown / desc.dt)));
        agents.visited[row].push_back(c.record.goalPoint);
      }
      // Back to the group's navigation, where the group is now.
      setGoal(row, groups[agents.group[row]].cursor, query);
    };
    const bool overdue = now >= c.deadline;
    for (std::size_t i = 0; i < c.actors.size(); ++i) {
      if (c.left[i]) continue;
      const std::uint32_t row = c.actors[i] < rowOfId.size() ? rowOfId[c.actors[i]] : kNoAgent;
      if (row == kNoAgent) {  // gone from the world
        c.left[i] = 1;
        continue;
      }
      if (overdue) {
        leave(i);
        continue;
      }
      const auto& entries = c.script.actor(i);
      while (!c.left[i]) {
        if (c.cursor[i] >= entries.size()) {
          leave(i);
          break;
        }
        const social::ScriptEntry& e = entries[c.cursor[i]];
        // A walk of another actor that should be over by then must really be over: the response to
        // a motion never starts before it (walking times are only estimates in a crowd).
        auto waitsForWalk = [&](double until) {
          for (std::size_t j = 0; j < c.actors.size(); ++j) {
            if (j == i || c.left[j]) continue;
            const auto& other = c.script.actor(j);
            if (c.cursor[j] >= other.size()) continue;
            const social::ScriptEntry& w = other[c.cursor[j]];
            if (w.motion == social::kWalkMotion && w.duration > 0.0 && w.end() <= until + eps) return true;
          }
          return false;
        };
        if (c.started[i] < 0.0) {
          if (now + eps < e.start + c.slip) break;  // waits for its activation time
          if (waitsForWalk(e.start)) break;
          if (leavesScript(e)) {
            publish(i, e, now, e.duration);
            leave(i);
            break;
          }
          beginEntry(c, i, row, now);
          c.started[i] = now;
        }
        bool complete;
        if (e.motion == social::kWalkMotion) {
          const float dx = agents.targetX[row] - agents.posX[row], dy = agents.targetY[row] - agents.posY[row];
          const float d2 = dx * dx + dy * dy;
          const float reach = e.behaviour == "follow" ? kFollowArrive : kScriptArrive;
          complete = d2 < reach * reach ||
                     (agents.stuckTime[row] > kStuckArrive && d2 < kStuckArriveDistance * kStuckArriveDistance) ||
                     now - c.started[i] > std::max(kWalkGiveUpMin, kWalkGiveUpFactor * e.duration);
          if (complete) c.slip += std::max(0.0, now - (e.end() + c.slip));  // a late walk delays what follows
        } else {
          complete = now + eps >= e.end() + c.slip && !waitsForWalk(e.end());
          if (!complete && e.targetType != social::ScriptEntry::Target::None) {
            // Turn toward the target at the turning rate (turns, and clips aimed at something).
            core::Vec2 aim = e.targetPoint;
            if (e.targetType == social::ScriptEntry::Target::Agent && e.targetActor < c.actors.size()) {
              const std::uint32_t tr = rowOfId[c.actors[e.targetActor]];
              if (tr != kNoAgent) aim = {agents.posX[tr], agents.posY[tr]};
            }
            const core::Vec2 want = aim - core::Vec2{agents.posX[row], agents.posY[row]};
            if (core::lengthSq(want) > 1e-6f) {
              const float have = std::atan2(agents.oriY[row], agents.oriX[row]);
              float delta = std::atan2(want.y, want.x) - have;
              while (delta > 3.14159265f) delta -= 6.28318531f;
              while (delta < -3.14159265f) delta += 6.28318531f;
              const float step = std::clamp(delta, -turnStep, turnStep);
              agents.oriX[row] = std::cos(have + step);
              agents.oriY[row] = std::sin(have + step);
            }
          }
        }
        if (!complete) break;
        publish(i, e, c.started[i], now - c.started[i]);
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
        agents.targetX[row] = agents.posX[row];
        agents.targetY[row] = agents.posY[row];
        agents.corners[row].clear();
        agents.mode[row] = AgentMode::Waiting;
      }
    }
    if (std::all_of(c.left.begin(), c.left.end(), [](std::uint8_t l) { return l != 0; })) {
      finishCoordination(c, now);
      it = coordinations.erase(it);
    } else {
      ++it;
    }
  }
}

void World::Impl::finishCoordination(ActiveCoordination& c, double now) {
  c.record.end = now;
  if (c.record.executeTime <= 0.0) c.record.executeTime = now;
  GroupExtra& x = extraOf(groups[c.record.group]);
  if (x.coordination == c.record.id) x.coordination = kNoAgent;
  if (c.divides && !c.reunitedOnReturn) {
    x.reunite = c.record.id;
    markBusy(c.record.group);
  }
  pendingEvents.push_back({tick, c.record.initiator, EventKind::CoordinationEnd, c.record.id,
                           static_cast<std::uint32_t>(c.record.outcome)});
  pendingCoordinations.push_back(std::move(c.record));
}

void World::Impl::checkReunions() {
  for (const std::uint32_t gid : busyGroups) {
    GroupState& g = groups[gid];
    GroupExtra& x = extraOf(g);
    if (x.reunite == kNoAgent || x.coordination != kNoAgent) continue;
    if (g.members.size() < 2) {
      x.reunite = kNoAgent;
      continue;
    }
    // Whole again: nobody in a script, everybody within the group's width of the centroid.
    core::Vec2 sum;
    bool busy = false;
    for (const std::uint32_t id : g.members) {
      const std::uint32_t r = rowOfId[id];
      busy = busy || agents.coordination[r] != kNoAgent;
      sum += core::Vec2{agents.posX[r], agents.posY[r]};
    }
    if (busy) continue;
    const core::Vec2 centroid = sum / static_cast<float>(g.members.size());
    const float reach = 1.5f + desc.populations[g.population].groupSpacing * static_cast<float>(g.members.size()) * 0.5f;
    const bool together = std::all_of(g.members.begin(), g.members.end(), [&](std::uint32_t id) {
      const std::uint32_t r = rowOfId[id];
      return core::lengthSq(core::Vec2{agents.posX[r], agents.posY[r]} - centroid) <= reach * reach;
    });
    if (!together) continue;
    pendingEvents.push_back({tick, g.leader == kNoAgent ? g.members.front() : g.leader, EventKind::Reunited, gid, x.reunite});
    x.reunite = kNoAgent;
  }
}

}  // namespace throng::sim
