// goals — one home for where an agent is going (Musse et al. §3.1: goals are interest and action
// points visited in order): the active goal list of a group (its own, or the followed group's),
// the current goal point of an agent, setting and advancing goals, drawing a target inside a goal's
// region (sub-regions, §3.1.3; an exit's near side, pickParams) and releasing it, waypoint choices
// (a goal picked among several by shares or least targeted, when a group reaches it), Bézier paths to it (§3.2.2), automatic goals
// (§3.1.2) and the pending goal changes decide hands to the group pass. Serial code (the group pass
// and spawning) writes goals through GoalWriter (goals.hpp), the points' sub-regions being
// PointRegions; the parallel phases only read them (currentGoalPoint, stopsAtGoal) through GoalView
// (phases.hpp), which World::Impl's helpers of the same names use too.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "throng/crowd/bezier_path.hpp"
#include "throng/crowd/path_reconstruction.hpp"
#include "throng/crowd/walkable.hpp"
#include "goals.hpp"
#include "transport_choice.hpp"
#include "vertical_transport.hpp"
#include "world_impl.hpp"

namespace throng::sim {

std::uint32_t GoalView::activeList(const GroupState& g) const {
  return g.following && groups.routeOf(g).followGroup != kNoGroup ? groups[groups.routeOf(g).followGroup].goalList : g.goalList;
}

const std::vector<std::uint32_t>& GoalView::activeGoals(const GroupState& g) const { return goalLists[activeList(g)]; }

std::uint32_t GoalView::groupGoalPoint(const GroupState& g) const {
  const std::vector<std::uint32_t>& goals = activeGoals(g);
  return g.cursor < goals.size() ? goals[g.cursor] : kNoPoint;
}

std::uint32_t GoalView::currentGoalPoint(std::size_t row) const {
  const std::vector<std::uint32_t>& goals = activeGoals(groups[group[row]]);
  const std::uint32_t cursor = goalCursor[row];
  return cursor < goals.size() ? goals[cursor] : kNoPoint;
}

std::uint32_t World::Impl::groupGoalPoint(const GroupState& g) const { return goalView().groupGoalPoint(g); }
std::uint32_t World::Impl::currentGoalPoint(std::size_t row) const { return goalView().currentGoalPoint(row); }

bool stopsAtGoal(const GoalView& goals, std::span<const PointDesc> points, const PopulationDesc& pop, std::size_t row) {
  const std::uint32_t point = goals.currentGoalPoint(row);
  if (point == kNoPoint) return !pop.wander;  // done: stands there
  const PointDesc& p = points[point];
  return p.kind == PointKind::Action && p.stop;
}

void PointRegions::add(const PointDesc& p) {
  // Its bounds and its region's sub-regions (Musse et al. §3.1.3), with no one targeting them yet.
  bounds.push_back(p.polygon.empty() ? core::Aabb{{p.position.x - p.radius, p.position.y - p.radius},
                                                       {p.position.x + p.radius, p.position.y + p.radius}}
                                          : core::bounds(p.polygon));
  const crowd::Region region = p.polygon.empty() ? crowd::Region::disc(p.position, p.radius) : crowd::Region::poly(p.polygon);
  std::vector<crowd::Subregion> subs = crowd::divideRegion(region);
  subregions.insert(subregions.end(), std::make_move_iterator(subs.begin()), std::make_move_iterator(subs.end()));
  subOffset.push_back(static_cast<std::uint32_t>(subregions.size()));
  occupancy.resize(subregions.size(), 0);
}

crowd::PickParams pickParams(PointKind kind) {
  // An exit is left wherever it is reached, so only its near side is worth aiming at: a wide one is
  // never crossed sideways to an empty spot (crowd::PickParams' detour limit). Interest and action
  // points are places a group spreads over (Musse et al. §3.1.3): the whole region stays open.
  if (kind == PointKind::Exit) return {};
  crowd::PickParams whole;
  whole.detourMin = std::numeric_limits<float>::infinity();
  return whole;
}

namespace {

/// How far inside the walkable surface a target drawn in the navmesh's eroded margin is put [m].
/// Snapped onto the nearest point of the mesh it lay exactly on the mesh's edge, where a sight
/// line along the edge holds from one spot and not from the next: a walker 6 cm short of an exit
/// alternated for ever between its target and the corner before it (steer.cpp's turn back to a
/// corner it can see; NIST 2.9, session 41).
constexpr float kTargetInset = 0.03f;

/// The mesh point nearest `target` within `radius` at about `height` (NavQuery::snap: the floor on a
/// multi-level mesh, the nearest point on a flat one), kTargetInset inside the edge on the same
/// floor when `target` lies off the mesh (and the point that far in is on it).
std::optional<nav::MeshPoint> snapInside(const nav::NavQuery& query, core::Vec2 target, float height, float radius) {
  const auto hit = query.snap(target, height, radius);
  if (!hit) return std::nullopt;
  const core::Vec2 off = hit->p - target;
  const float d = core::length(off);
  if (d < 1e-4f) return hit;
  const core::Vec2 in = hit->p + off * (kTargetInset / d);
  const auto again = query.snap(in, hit->height, 2.0f * kTargetInset);
  if (!again || core::lengthSq(again->p - in) >= 1e-8f) return hit;
  return nav::MeshPoint{in, again->height, again->ref};
}

}  // namespace

void GoalWriter::releaseTarget(std::size_t row) {
  if (agents.targetSub[row] >= 0) {
    --regions.occupancy[static_cast<std::size_t>(agents.targetSub[row])];
    agents.targetSub[row] = -1;
  }
}

namespace {

/// Where the line through p along the unit vector u crosses `point`'s region: the middle of the
/// first stretch of it inside the region that does not lie wholly behind p (even-odd along the
/// line; the last one when all do), or, when the line misses the region, the region's point nearest
/// the line (a polygon's vertex nearest it; for a disc the point of its rim towards the line).
core::Vec2 laneCrossing(const PointDesc& point, core::Vec2 p, core::Vec2 u) {
  if (point.polygon.empty()) {
    const core::Vec2 foot = p + u * core::dot(point.position - p, u);
    const core::Vec2 off = foot - point.position;
    const float len = core::length(off);
    return len <= point.radius ? foot : point.position + off * (point.radius / len);
  }
  std::vector<float> ts;
  const std::size_t n = point.polygon.size();
  for (std::size_t k = 0; k < n; ++k) {
    const core::Vec2 a = point.polygon[k], b = point.polygon[(k + 1) % n];
    const float sa = core::cross(u, a - p), sb = core::cross(u, b - p);  // sides of the line
    if ((sa < 0.0f) == (sb < 0.0f)) continue;
    const float f = sa / (sa - sb);
    ts.push_back(core::dot(a + (b - a) * f - p, u));
  }
  if (ts.size() >= 2) {
    std::sort(ts.begin(), ts.end());
    std::size_t pick = ts.size() / 2 * 2 - 2;  // the last stretch, unless one ends ahead of p
    for (std::size_t k = 0; k + 1 < ts.size(); k += 2) {
      if (ts[k + 1] >= 0.0f) {
        pick = k;
        break;
      }
    }
    return p + u * (0.5f * (ts[pick] + ts[pick + 1]));
  }
  core::Vec2 best = point.polygon[0];
  for (const core::Vec2 v : point.polygon) {
    if (std::abs(core::cross(u, v - p)) < std::abs(core::cross(u, best - p))) best = v;
  }
  return best;
}

/// The point of `point`'s region nearest p (p itself inside it).
core::Vec2 nearestInRegion(const PointDesc& point, core::Vec2 p) {
  if (point.polygon.empty()) {
    const core::Vec2 off = p - point.position;
    const float len = core::length(off);
    return len <= point.radius ? p : point.position + off * (point.radius / len);
  }
  if (core::pointInPolygon(point.polygon, p)) return p;
  core::Vec2 best = point.polygon[0];
  const std::size_t n = point.polygon.size();
  for (std::size_t k = 0; k < n; ++k) {
    const core::Vec2 c = core::closestPointOnSegment(p, point.polygon[k], point.polygon[(k + 1) % n]);
    if (core::lengthSq(c - p) < core::lengthSq(best - p)) best = c;
  }
  return best;
}

}  // namespace

core::Vec2 GoalWriter::drawTarget(std::size_t row, const PointDesc& point, const PointDesc* from) {
  // Sub-regions (Musse et al. §3.1.3): the target lies in a sub-region of the goal's region picked
  // by proximity and by how many agents already target it, so group members take similar but never
  // identical paths and spread over the region (an exit: over its near side, pickParams).
  // Serial (group pass / spawning): occupancy is shared.
  core::Rng rng(desc.seed, (static_cast<std::uint64_t>(agents.id[row]) << 20) ^ agents.targetDraws[row]++,
                core::RngPurpose::Target);
  releaseTarget(row);
  const auto p = static_cast<std::size_t>(&point - desc.points.data());
  const std::uint32_t first = regions.subOffset[p], last = regions.subOffset[p + 1];
  core::Vec2 target = point.position;
  if (point.aim == PointAim::Lane) {
    // Its lane: the way from the goal it reached last, moved across to where the walker stands (the
    // region's nearest point for a first goal). Between checkpoints set across a corridor or a
    // ring, people keep their place across the way; a spot spread over each one made every walker
    // cross the way anew at each (docs/validation.md, "Fundamental diagram in a ring").
    const core::Vec2 here{agents.posX[row], agents.posY[row]};
    const core::Vec2 way = from != nullptr ? point.position - from->position : core::Vec2{};
    target = core::lengthSq(way) > 1e-12f ? laneCrossing(point, here, core::normalize(way)) : nearestInRegion(point, here);
  } else if (last > first) {
    const std::span<const crowd::Subregion> subs(regions.subregions.data() + first, last - first);
    const std::span<const std::uint32_t> occupancy(regions.occupancy.data() + first, last - first);
    const std::size_t k = crowd::pickSubregion(subs, core::Vec2{agents.posX[row], agents.posY[row]}, occupancy, rng,
                                               pickParams(point.kind));
    target = crowd::samplePoint(subs[k], rng);
    agents.targetSub[row] = static_cast<std::int32_t>(first + k);
    ++regions.occupancy[first + k];
  }
  // On a multi-level world the point's height picks the floor the target is snapped onto.
  auto hit = snapInside(query, target, point.height, 3.0f);
  if (!hit) hit = snapInside(query, point.position, point.height, 10.0f);
  if (agents.levels) agents.setTargetHeight(row, hit ? hit->height : point.height);
  return hit ? hit->p : target;
}

void GoalWriter::setGoal(std::size_t row, std::uint32_t cursor) {
  if (agents.goalState[row] == GoalState::Incapacitated) return;  // stays where it fell (decide.cpp)
  const GroupState& g = groups[agents.group[row]];
  const PopulationDesc& pop = desc.populations[g.population];
  if (cursor < view().activeGoals(g).size()) {
    chooseWaypoint(row, cursor);  // the goal first, then the way there
    if (routes != nullptr) routeByTransport(row, cursor);
  }
  const std::vector<std::uint32_t>& goals = view().activeGoals(g);
  agents.goalCursor[row] = cursor;
  agents.ticket[row] = 0;  // a path still queued for the old goal expires unread
  agents.dynamicTarget[row] = 0;
  agents.corners[row].clear();
  agents.progressDistance[row] = 1e30f;
  if (cursor < goals.size()) {
    const core::Vec2 t = drawTarget(row, desc.points[goals[cursor]], cursor > 0 ? &desc.points[goals[cursor - 1]] : nullptr);
    agents.targetX[row] = t.x;
    agents.targetY[row] = t.y;
    agents.needPath[row] = 1;
    agents.goalState[row] = GoalState::Seeking;
    agents.mode[row] = AgentMode::Walking;
    if (pop.bezierPaths) bezierPath(row);
  } else if (pop.wander) {
    // Random points of the walkable area; a flocking group shares one per release (its cursor).
    const bool together = g.flocks(pop) && g.expected >= 2;
    const std::uint32_t gid = agents.group[row];
    core::Rng rng = together ? core::Rng(desc.seed, (static_cast<std::uint64_t>(gid) << 32) ^ cursor ^ 0x5a5a0000u, core::RngPurpose::Goal)
                             : core::Rng(desc.seed, (static_cast<std::uint64_t>(agents.id[row]) << 20) ^ agents.targetDraws[row]++,
                                         core::RngPurpose::Goal);
    releaseTarget(row);
    const float r0 = static_cast<float>(rng.uniform()), r1 = static_cast<float>(rng.uniform()),
                r2 = static_cast<float>(rng.uniform());
    if (agents.levels) {
      const auto p = query.randomMeshPoint(r0, r1, r2);
      if (p) {
        agents.targetX[row] = p->p.x;
        agents.targetY[row] = p->p.y;
        agents.targetZ[row] = p->height;
      } else {
        agents.targetSelf(row);
      }
    } else {
      const auto p = query.randomPoint(r0, r1, r2);
      agents.targetX[row] = p ? p->x : agents.posX[row];
      agents.targetY[row] = p ? p->y : agents.posY[row];
    }
    agents.needPath[row] = 1;
    agents.goalState[row] = GoalState::Seeking;
    agents.mode[row] = AgentMode::Walking;
  } else {
    releaseTarget(row);
    agents.goalState[row] = GoalState::Done;
    agents.mode[row] = AgentMode::Waiting;
    agents.targetSelf(row);
  }
}

void GoalWriter::routeByTransport(std::size_t row, std::uint32_t cursor) {
  const std::uint32_t gid = agents.group[row];
  GroupState& g = groups[gid];
  const PopulationDesc& pop = desc.populations[g.population];
  if (!pop.useTransports || !routes->active()) return;
  const std::uint32_t listIndex = view().activeList(g);
  if (listIndex != g.goalList) return;  // following another group: its list is not this group's to change
  if (!routes->claim(gid, cursor)) return;
  const std::uint32_t goal = goalLists[listIndex][cursor];
  for (const TransportDesc& t : desc.transports) {
    if (std::find(t.stops.begin(), t.stops.end(), goal) != t.stops.end()) return;  // a stop: the scenario's own way
  }
  const auto heading = [&](std::uint32_t point) {
    std::uint32_t n = 0;
    for (std::uint32_t k = regions.subOffset[point]; k < regions.subOffset[point + 1]; ++k) n += regions.occupancy[k];
    return n;
  };
  // Changing floors, most people ride whenever a lift or escalator goes there; a share of them
  // (drawn per group and goal) weigh the stairs by time and climb when that is quicker.
  bool rideIfAny = false;
  if (agents.levels) {
    const float dz = desc.points[goal].height - agents.posZ[row];
    if (std::abs(dz) > nav::kLevelSearch) {
      const float climbs = dz > 0.0f ? pop.stairClimbUp : pop.stairClimbDown;
      core::Rng rng(desc.seed, (static_cast<std::uint64_t>(gid) << 20) ^ cursor, core::RngPurpose::StairClimb);
      rideIfAny = !(rng.uniform() < static_cast<double>(climbs));
    }
  }
  const std::uint32_t board = routes->boardingFor(desc, agents, row, goal, *transports, heading, rideIfAny);
  if (board == kNoIndex) return;
  std::uint32_t& own = routes->ownList(gid);
  if (own != listIndex + 1) {  // a list of its own (the population's may be shared, exit choice's is kept)
    own = static_cast<std::uint32_t>(goalLists.size()) + 1;
    std::vector<std::uint32_t> copy = goalLists[listIndex];  // copied first: pushing may move the lists
    goalLists.push_back(std::move(copy));
    if (listIndex < choices.lists.size() && choices.lists[listIndex].group == gid && !choices.lists[listIndex].choiceAt.empty()) {
      choices.lists.resize(std::max<std::size_t>(choices.lists.size(), own));
      choices.lists[own - 1] = choices.lists[listIndex];
      choices.lists[listIndex].choiceAt.clear();
    }
    g.goalList = own - 1;
  }
  std::vector<std::uint32_t>& list = goalLists[g.goalList];
  list.insert(list.begin() + cursor, board);
  if (g.goalList < choices.lists.size() && !choices.lists[g.goalList].choiceAt.empty()) {
    auto& at = choices.lists[g.goalList].choiceAt;
    at.insert(at.begin() + std::min<std::size_t>(cursor, at.size()), 0);
  }
  events.push_back({tick, agents.id[row], EventKind::WaypointChosen, board, cursor});
}

void GoalWriter::applyPendingGoals(std::span<ChunkOutput> chunks) {
  // Rows flagged by decide, in ascending id order, whatever the threads and the order of the rows
  // (row_order.cpp): targets drawn one after another share the free spots of a region.
  std::vector<std::uint64_t> rows;  // (id << 32) | row: sorted without reading ids again
  for (ChunkOutput& c : chunks) {
    for (const std::uint32_t r : c.pendingRows) rows.push_back(static_cast<std::uint64_t>(agents.id[r]) << 32 | r);
    c.pendingRows.clear();
  }
  if (!std::is_sorted(rows.begin(), rows.end())) std::sort(rows.begin(), rows.end());
  for (const std::uint64_t entry : rows) {
    const auto r = static_cast<std::uint32_t>(entry);
    const GoalPending pending = agents.goalPending[r];
    agents.goalPending[r] = GoalPending::None;
    if (pending == GoalPending::NextGoal) {
      advanceGoal(r);
    } else if (pending == GoalPending::NextWanderTarget) {
      setGoal(r, static_cast<std::uint32_t>(view().activeGoals(groups[agents.group[r]]).size()));
    }
  }
}

void GoalWriter::giveExitGoals(std::uint32_t gid, std::uint32_t exit) {
  GroupState& g = groups[gid];
  std::vector<std::uint32_t> goals = desc.populations[g.population].goals;
  goals.push_back(exit);
  g.goalList = static_cast<std::uint32_t>(goalLists.size());
  goalLists.push_back(std::move(goals));
}

void GoalWriter::openGoalChoices(std::uint32_t gid) {
  GroupState& g = groups[gid];
  const PopulationDesc& pop = desc.populations[g.population];
  if (pop.goalChoices.empty()) return;
  if (pop.exits.empty()) {  // still the population's shared list: a copy of its own
    g.goalList = static_cast<std::uint32_t>(goalLists.size());
    goalLists.push_back(pop.goals);
  }
  if (choices.lists.size() <= g.goalList) choices.lists.resize(g.goalList + 1);
  OpenChoices::List& list = choices.lists[g.goalList];
  list.group = gid;
  list.choiceAt.assign(goalLists[g.goalList].size(), 0);
  for (std::size_t k = 0; k < pop.goalChoices.size(); ++k) list.choiceAt[pop.goalChoices[k].slot] = static_cast<std::uint32_t>(k + 1);
}

void GoalWriter::chooseWaypoint(std::size_t row, std::uint32_t cursor) {
  const GroupState& g = groups[agents.group[row]];
  const std::uint32_t listIndex = view().activeList(g);
  if (listIndex >= choices.lists.size()) return;
  OpenChoices::List& list = choices.lists[listIndex];
  if (cursor >= list.choiceAt.size() || list.choiceAt[cursor] == 0) return;
  const GoalChoiceDesc& choice = desc.populations[groups[list.group].population].goalChoices[list.choiceAt[cursor] - 1u];
  list.choiceAt[cursor] = 0;  // chosen once, for the whole group
  std::uint32_t chosen = choice.options.front();
  if (choice.split == GoalSplit::LeastTargeted) {
    // The option the fewest agents head for now (their targets lie in its sub-regions); ties: first listed.
    std::uint64_t fewest = UINT64_MAX;
    for (const std::uint32_t point : choice.options) {
      std::uint64_t heading = 0;
      for (std::uint32_t s = regions.subOffset[point]; s < regions.subOffset[point + 1]; ++s) heading += regions.occupancy[s];
      if (heading < fewest) fewest = heading, chosen = point;
    }
  } else {
    // By shares (equal when none are given): one draw from the group's stream for this slot.
    core::Rng rng(desc.seed, (static_cast<std::uint64_t>(list.group) << 20) ^ cursor, core::RngPurpose::GoalChoice);
    double total = 0.0;
    for (std::size_t k = 0; k < choice.options.size(); ++k) total += choice.shares.empty() ? 1.0 : choice.shares[k];
    double u = rng.uniform() * total;
    for (std::size_t k = 0; k < choice.options.size(); ++k) {
      u -= choice.shares.empty() ? 1.0 : choice.shares[k];
      if (u < 0.0 || k + 1 == choice.options.size()) {
        chosen = choice.options[k];
        break;
      }
    }
  }
  goalLists[listIndex][cursor] = chosen;
  events.push_back({tick, groups[list.group].leader, EventKind::WaypointChosen, chosen, cursor});
}

void GoalWriter::changeExit(std::uint32_t gid, std::uint32_t exit, std::span<const std::uint32_t> rowOfId,
                            std::uint32_t agentId) {
  const GroupState& g = groups[gid];
  std::vector<std::uint32_t>& goals = goalLists[g.goalList];
  const std::uint32_t previous = goals.back();
  goals.back() = exit;
  events.push_back({tick, agentId, EventKind::ExitChosen, exit, previous});
  const auto slot = static_cast<std::uint32_t>(goals.size() - 1);
  for (const std::uint32_t id : g.members) {
    const std::uint32_t row = id < rowOfId.size() ? rowOfId[id] : kNoRow;
    if (row == kNoRow || agents.goalCursor[row] != slot) continue;
    const GoalState state = agents.goalState[row];
    if (state != GoalState::Seeking && state != GoalState::PreMovement) continue;
    setGoal(row, slot);
    if (state == GoalState::PreMovement) {
      agents.goalState[row] = GoalState::PreMovement;
      agents.mode[row] = AgentMode::Waiting;
    }
  }
}

void GoalWriter::bezierPath(std::size_t row) {
  // Seek goal with a Bézier curve (Musse et al. §3.2.2), verified inside the walkable surface by
  // the control boxes' convex-hull property; where no curve fits, the navmesh path is used and the
  // fallback is recorded.
  const core::Vec2 from{agents.posX[row], agents.posY[row]};
  const core::Vec2 to{agents.targetX[row], agents.targetY[row]};
  const crowd::NavMeshWalkable walkable(query);
  core::Rng rng(desc.seed, (static_cast<std::uint64_t>(agents.id[row]) << 20) ^ agents.targetDraws[row],
                core::RngPurpose::Behaviour);
  const auto curve = crowd::buildPath(from, to, walkable, crowd::BezierPathParams{}, rng);
  const std::vector<std::uint32_t>& goals = view().activeGoals(groups[agents.group[row]]);
  const std::uint32_t cursor = agents.goalCursor[row];
  if (!curve) {
    events.push_back({tick, agents.id[row], EventKind::PathFallback, cursor < goals.size() ? goals[cursor] : kNoPoint, 0});
    return;  // needPath stays set: plan asks the navmesh
  }
  std::vector<core::Vec2> points;
  crowd::sample(curve->points, 0.1f, points);
  if (!points.empty() && core::lengthSq(points.front() - from) < 1e-6f) points.erase(points.begin());
  agents.corners[row].assign(points);
  if (agents.levels) agents.cornerZ[row].clear();  // not plan's: no heights
  agents.needPath[row] = 0;
}

void GoalWriter::reconstructGoals(std::uint32_t gid, core::Vec2 anchor) {
  // Paths automatic reconstruction (Musse et al. §3.1.2): a random final action point, a Bézier
  // curve from the group's initial position to it, and every interest point near the curve
  // becomes a goal on the way, in the order the curve passes them.
  GroupState& g = groups[gid];
  const PopulationDesc& pop = desc.populations[g.population];
  std::vector<std::uint32_t> actions, interests;
  std::vector<crowd::Region> regions;
  for (std::uint32_t p = 0; p < desc.points.size(); ++p) {
    const PointDesc& point = desc.points[p];
    if (point.kind == PointKind::Action) actions.push_back(p);
    if (point.kind == PointKind::Interest) {
      interests.push_back(p);
      regions.push_back(point.polygon.empty() ? crowd::Region::disc(point.position, point.radius) : crowd::Region::poly(point.polygon));
    }
  }
  if (actions.empty()) return;  // validation requires one; keep the explicit list otherwise
  core::Rng rng(desc.seed, gid, core::RngPurpose::Goal);
  const std::uint32_t final = actions[rng.uniformInt(0, static_cast<std::uint32_t>(actions.size() - 1))];
  const crowd::NavMeshWalkable walkable(query);
  const auto path = crowd::reconstructPath(anchor, desc.points[final].position, regions, pop.autoNearDistance,
                                           crowd::ReconstructParams{}, rng, &walkable);
  std::vector<std::uint32_t> goals;
  if (path) {
    for (std::uint32_t ip : path->visited) {
      const std::uint32_t point = interests[ip];
      if (goals.empty() || goals.back() != point) goals.push_back(point);
    }
  } else {
    events.push_back({tick, kNoAgent, EventKind::PathFallback, final, gid});
  }
  goals.push_back(final);
  g.goalList = static_cast<std::uint32_t>(goalLists.size());
  goalLists.push_back(std::move(goals));
}

}  // namespace throng::sim
