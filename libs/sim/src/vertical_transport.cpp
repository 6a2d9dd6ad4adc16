// Lifts and escalators (vertical_transport.hpp). Everything happens in whole ticks: an escalator lets one
// person on every round(headway / dt) ticks and carries each for round(length / speed / dt); a lift
// takes round(t / dt) for each door movement and each transfer, and its trips the time to travel the
// distance between two stops at `speed` with `acceleration` (a trapezoidal or, when too short to
// reach the speed, triangular velocity profile), so what a test computes from the parameters is
// what happens, to a tick. A lift serves its stops in the order of their heights: it goes on in its
// direction while someone aboard rides, or someone waits, that way, then turns (the collective
// control of passenger lifts, without direction buttons: everyone waiting boards while there is room).
#include "vertical_transport.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace throng::sim {
namespace {

/// An escalator lets on whoever queuing is within this of where people step on [m] (a body's
/// depth: they stand at the comb plate) ...
constexpr float kBoardReach = 0.5f;
/// ... or, this long after the step came with nobody there, the nearest [s].
constexpr float kBoardPatience = 5.0f;
/// At a lift, people wait this long at most for the rest of their group before riding without them [s].
constexpr float kGroupPatience = 30.0f;

std::uint64_t ticksOf(float seconds, float dt) {
  return static_cast<std::uint64_t>(std::max(0L, std::lround(seconds / dt)));
}

/// Where the k-th person stands in a car or arrives on a landing, around its stop: rows of three
/// 0.5 m apart, the first in the middle.
core::Vec2 slot(int k) {
  constexpr float kPitch = 0.5f;
  const int across = k % 3, back = k / 3;
  const float x = across == 0 ? 0.0f : (across == 1 ? kPitch : -kPitch);
  return {x, -kPitch * static_cast<float>(back)};
}

}  // namespace

void VerticalTransports::configure(const ScenarioDesc& desc) {
  states_.assign(desc.transports.size(), State{});
  for (std::size_t t = 0; t < desc.transports.size(); ++t) states_[t].queue.resize(desc.transports[t].stops.size());
}

std::uint32_t VerticalTransports::boardingAt(const ScenarioDesc& desc, std::uint32_t point) {
  for (std::size_t t = 0; t < desc.transports.size(); ++t) {
    const TransportDesc& d = desc.transports[t];
    const std::size_t boarding = d.kind == TransportKind::Elevator ? d.stops.size() : 1;  // an escalator: its foot
    if (std::find(d.stops.begin(), d.stops.begin() + static_cast<std::ptrdiff_t>(boarding), point) !=
        d.stops.begin() + static_cast<std::ptrdiff_t>(boarding)) {
      return static_cast<std::uint32_t>(t);
    }
  }
  return kNoIndex;
}

VerticalTransports::Place VerticalTransports::stopPlace(const ScenarioDesc& desc, const TransportDesc& t, std::uint32_t stop) {
  const PointDesc& p = desc.points[t.stops[stop]];
  return {p.position, p.height};
}

void VerticalTransports::step(const ScenarioDesc& desc, std::uint64_t tick, const nav::NavQuery& query, GoalWriter goals) {
  if (states_.empty()) return;
  AgentStore& a = goals.agents;
  agents_ = &a;
  dt_ = desc.dt;
  // This tick's riders, by id.
  riders_.clear();
  for (std::size_t row = 0; row < a.size(); ++row) {
    if (a.goalState[row] != GoalState::Riding) continue;
    const std::uint32_t id = a.id[row];
    if (rowOfId_.size() <= id) {
      rowOfId_.resize(static_cast<std::size_t>(id) + 1, kNoRow);
      known_.resize(static_cast<std::size_t>(id) + 1, 0);
    }
    rowOfId_[id] = static_cast<std::uint32_t>(row);
    riders_.push_back(id);
  }
  std::sort(riders_.begin(), riders_.end());
  const auto gone = [&](const Rider& r) {
    if (std::binary_search(riders_.begin(), riders_.end(), r.id)) return false;
    known_[r.id] = 0;
    return true;
  };
  // Those gone (removed by the host) leave the queues and the cars.
  for (State& s : states_) {
    for (auto& q : s.queue) q.erase(std::remove_if(q.begin(), q.end(), gone), q.end());
    s.aboard.erase(std::remove_if(s.aboard.begin(), s.aboard.end(), gone), s.aboard.end());
  }
  // Newcomers queue at the stop they reached (their current goal), in id order, for the stop their
  // next goal says (rideTo).
  for (const std::uint32_t id : riders_) {
    if (known_[id] != 0) continue;
    const std::uint32_t row = rowOfId_[id];
    const GoalView view = goals.view();
    const std::uint32_t point = view.currentGoalPoint(row);
    const std::uint32_t t = point == kNoPoint ? kNoIndex : boardingAt(desc, point);
    if (t == kNoIndex) {  // its goal changed under it: walk on
      a.goalState[row] = GoalState::Seeking;
      a.mode[row] = AgentMode::Walking;
      a.needPath[row] = 1;
      continue;
    }
    const TransportDesc& d = desc.transports[t];
    const auto from = static_cast<std::size_t>(std::find(d.stops.begin(), d.stops.end(), point) - d.stops.begin());
    const std::vector<std::uint32_t>& list = view.activeGoals(goals.groups[a.group[row]]);
    const std::size_t cursor = a.goalCursor[row];
    const std::uint32_t next = cursor + 1 < list.size() ? list[cursor + 1] : kNoPoint;
    states_[t].queue[from].push_back({id, static_cast<std::uint32_t>(rideTo(desc, d, from, next)), tick});
    known_[id] = 1;
  }
  off_.clear();
  for (std::size_t t = 0; t < states_.size(); ++t) {
    const TransportDesc& d = desc.transports[t];
    if (d.kind == TransportKind::Escalator) {
      runEscalator(desc, d, states_[t], tick);
    } else {
      runElevator(desc, d, states_[t], tick);
    }
  }
  // Those let off: on the mesh at their stop, then on to their next goal (in id order).
  std::sort(off_.begin(), off_.end(), [&](const Off& x, const Off& y) { return a.id[x.row] < a.id[y.row]; });
  for (const Off& o : off_) {
    const std::uint32_t row = o.row;
    const auto snapped = query.snap(o.place.p, o.place.z, 2.0f);
    const core::Vec2 p = snapped ? snapped->p : o.place.p;
    a.velX[row] = (p.x - a.posX[row]) / dt_;
    a.velY[row] = (p.y - a.posY[row]) / dt_;
    a.posX[row] = p.x;
    a.posY[row] = p.y;
    if (snapped) a.polyRef[row] = static_cast<std::uint32_t>(snapped->ref);
    if (a.levels) a.posZ[row] = snapped ? snapped->height : o.place.z;
    a.goalState[row] = GoalState::Seeking;
    a.mode[row] = AgentMode::Walking;
    a.corners[row].clear();
    a.stuckTime[row] = 0.0f;
    known_[a.id[row]] = 0;
    goals.events.push_back({tick, a.id[row], EventKind::GoalReached, o.point, 0});
    goals.advanceGoal(row);
  }
  for (const std::uint32_t id : riders_) rowOfId_[id] = kNoRow;
}

std::size_t VerticalTransports::nearest(const std::deque<Rider>& queue, core::Vec2 p,
                                        const std::function<bool(const Rider&)>& eligible) const {
  std::size_t best = 0;
  float bestD2 = std::numeric_limits<float>::max();
  for (std::size_t i = 0; i < queue.size(); ++i) {  // ties: the first to come
    if (eligible && !eligible(queue[i])) continue;
    const std::uint32_t row = rowOfId_[queue[i].id];
    const float d2 = core::lengthSq(core::Vec2{agents_->posX[row], agents_->posY[row]} - p);
    if (d2 < bestD2) {
      bestD2 = d2;
      best = i;
    }
  }
  return best;
}

void VerticalTransports::alight(const ScenarioDesc& desc, const TransportDesc& t, std::uint32_t stop, std::uint32_t id,
                                int k) {
  Place place = stopPlace(desc, t, stop);
  place.p += slot(k);
  off_.push_back({rowOfId_[id], t.stops[stop], place});
}

void VerticalTransports::runEscalator(const ScenarioDesc& desc, const TransportDesc& t, State& s, std::uint64_t tick) {
  AgentStore& a = *agents_;
  const Place from = stopPlace(desc, t, 0), to = stopPlace(desc, t, 1);
  const std::uint64_t ride = std::max<std::uint64_t>(1, ticksOf(rideTime(desc, t, 0, 1), dt_));
  const std::uint64_t headway = std::max<std::uint64_t>(1, ticksOf(t.headway, dt_));
  // Off at the top: those who have ridden the whole length (in boarding order).
  std::size_t done = 0;
  while (done < s.aboard.size() && tick - s.aboard[done].boarded >= ride) {
    alight(desc, t, 1, s.aboard[done].id, 0);
    ++done;
  }
  s.aboard.erase(s.aboard.begin(), s.aboard.begin() + static_cast<std::ptrdiff_t>(done));
  // On at the bottom, once the one before is a headway ahead: whoever of those queuing has come
  // nearest where people step on, when within kBoardReach of it (or, kBoardPatience after the step
  // came, whoever is nearest: nobody waits for ever behind a knot).
  std::deque<Rider>& queue = s.queue[0];
  if (!queue.empty() && tick >= s.nextBoard) {
    const std::size_t k = nearest(queue, from.p);
    const std::uint32_t row = rowOfId_[queue[k].id];
    const float d2 = core::lengthSq(core::Vec2{a.posX[row], a.posY[row]} - from.p);
    if (d2 <= kBoardReach * kBoardReach || tick >= s.nextBoard + ticksOf(kBoardPatience, dt_)) {
      s.aboard.push_back({queue[k].id, 1, tick});
      queue.erase(queue.begin() + static_cast<std::ptrdiff_t>(k));
      s.nextBoard = tick + headway;
    }
  }
  // The belt carries them: the straight line between the stops.
  for (const Rider& r : s.aboard) {
    const std::uint32_t row = rowOfId_[r.id];
    const float f = static_cast<float>(tick - r.boarded) / static_cast<float>(ride);
    const core::Vec2 p = from.p + (to.p - from.p) * f;
    a.velX[row] = (p.x - a.posX[row]) / dt_;
    a.velY[row] = (p.y - a.posY[row]) / dt_;
    a.posX[row] = p.x;
    a.posY[row] = p.y;
    if (a.levels) a.posZ[row] = from.z + (to.z - from.z) * f;
    a.mode[row] = AgentMode::Acting;  // carried: standing on a step (sense, integrate: not on the floor)
  }
}

float VerticalTransports::tripTime(const ScenarioDesc& desc, const TransportDesc& t, std::size_t from, std::size_t to) {
  const Place here = stopPlace(desc, t, static_cast<std::uint32_t>(from)), there = stopPlace(desc, t, static_cast<std::uint32_t>(to));
  const float dz = there.z - here.z;
  const float distance = std::sqrt(core::lengthSq(there.p - here.p) + dz * dz);
  // Trapezoidal profile: accelerate to `speed`, cruise, brake; too short a trip never reaches it.
  const float v = t.speed, acc = t.acceleration;
  return distance >= v * v / acc ? distance / v + v / acc : 2.0f * std::sqrt(distance / acc);
}

float VerticalTransports::rideTime(const ScenarioDesc& desc, const TransportDesc& t, std::size_t from, std::size_t to) {
  if (t.kind == TransportKind::Escalator) {
    const Place a = stopPlace(desc, t, static_cast<std::uint32_t>(from)), b = stopPlace(desc, t, static_cast<std::uint32_t>(to));
    const float dz = b.z - a.z;
    return std::sqrt(core::lengthSq(b.p - a.p) + dz * dz) / t.speed;
  }
  return t.doorCloseTime + tripTime(desc, t, from, to) + t.doorOpenTime + t.transferTime;
}

float VerticalTransports::expectedWait(const ScenarioDesc& desc, std::size_t t, std::size_t stop, std::size_t to,
                                       std::uint32_t heading) const {
  const TransportDesc& d = desc.transports[t];
  const State& s = states_[t];
  // Those carried still target the stop they boarded at until they step off: not ahead of anyone.
  const std::size_t ahead = std::max(s.queue[stop].size(), heading > s.aboard.size() ? heading - s.aboard.size() : 0);
  const auto queuing = static_cast<float>(ahead);
  if (d.kind == TransportKind::Escalator) return queuing * d.headway;
  // The car comes (from the stop it travels to, or stands at) and opens; each full car ahead of
  // one's own goes to `to` and back first.
  const float come = s.at == stop ? 0.0f : tripTime(desc, d, s.at, stop) + d.doorOpenTime;
  const float load = static_cast<float>(d.capacity) * d.transferTime;
  const float roundTrip = 2.0f * (d.doorCloseTime + tripTime(desc, d, stop, to) + d.doorOpenTime + load);
  return come + std::floor(queuing / static_cast<float>(d.capacity)) * roundTrip;
}

void VerticalTransports::startMove(const ScenarioDesc& desc, const TransportDesc& t, State& s, std::uint64_t tick,
                                   std::uint32_t to) {
  const float seconds = tripTime(desc, t, s.at, to);
  s.moveTicks = std::max<std::uint64_t>(1, ticksOf(seconds, dt_));
  s.moveStart = tick;
  s.until = tick + s.moveTicks;
  s.from = s.at;
  s.at = to;
  s.phase = Phase::Moving;
}

std::uint32_t VerticalTransports::nextStop(const ScenarioDesc& desc, const TransportDesc& t, State& s) {
  // Stops ordered by height, then list order: `above(i, j)` when j lies in the up direction from i.
  const auto key = [&](std::uint32_t i) { return std::make_pair(desc.points[t.stops[i]].height, i); };
  const auto wanted = [&](std::uint32_t i) {
    if (i == s.at) return false;
    if (!s.queue[i].empty()) return true;
    return std::any_of(s.aboard.begin(), s.aboard.end(), [&](const Rider& r) { return r.dest == i; });
  };
  for (const int dir : {s.dir == 0 ? 1 : s.dir, s.dir == 0 ? -1 : -s.dir}) {
    std::uint32_t best = kNoIndex;
    for (std::uint32_t i = 0; i < t.stops.size(); ++i) {
      if (!wanted(i) || (dir > 0 ? !(key(s.at) < key(i)) : !(key(i) < key(s.at)))) continue;
      if (best == kNoIndex || (dir > 0 ? key(i) < key(best) : key(best) < key(i))) best = i;
    }
    if (best != kNoIndex) {
      s.dir = dir;
      return best;
    }
  }
  s.dir = 0;
  return kNoIndex;
}

int VerticalTransports::servingDirection(const ScenarioDesc& desc, const TransportDesc& t, const State& s) {
  if (s.dir == 0) return 0;
  const auto key = [&](std::uint32_t i) { return std::make_pair(desc.points[t.stops[i]].height, i); };
  const auto beyond = [&](std::uint32_t i) { return s.dir > 0 ? key(s.at) < key(i) : key(i) < key(s.at); };
  for (const Rider& r : s.aboard) {
    if (beyond(r.dest)) return s.dir;
  }
  for (std::uint32_t i = 0; i < t.stops.size(); ++i) {
    if (!s.queue[i].empty() && beyond(i)) return s.dir;
  }
  return 0;
}

void VerticalTransports::runElevator(const ScenarioDesc& desc, const TransportDesc& t, State& s, std::uint64_t tick) {
  AgentStore& a = *agents_;
  const std::uint64_t open = ticksOf(t.doorOpenTime, dt_), close = ticksOf(t.doorCloseTime, dt_);
  const std::uint64_t transfer = ticksOf(t.transferTime, dt_);
  int offHere = 0;
  const auto room = [&] { return s.aboard.size() < t.capacity; };
  // Who may step on here: anyone, unless the car goes on its way (someone aboard or waiting
  // further), when only those riding that way (the up and down buttons of a landing).
  const auto key = [&](std::uint32_t i) { return std::make_pair(desc.points[t.stops[i]].height, i); };
  // Groups ride together: someone waits until the rest of its group has come too (those aboard
  // count; at most kGroupPatience), then until the car has room for all of them waiting here (unless
  // they could never fit); once one of a group is aboard, the others waiting here step on first.
  const auto groupOf = [&](const Rider& r) { return agents_->group[rowOfId_[r.id]]; };
  const auto fits = [&](const Rider& r) {
    const std::deque<Rider>& q = s.queue[s.at];
    const std::uint32_t g = groupOf(r);
    const auto same = [&](const Rider& o) { return groupOf(o) == g; };
    const auto waiting = static_cast<std::size_t>(std::count_if(q.begin(), q.end(), same));
    const auto aboard = static_cast<std::size_t>(std::count_if(s.aboard.begin(), s.aboard.end(), same));
    const std::uint32_t size = agents_->groupSize[rowOfId_[r.id]];
    if (waiting + aboard < size && tick < r.boarded + ticksOf(kGroupPatience, dt_)) return false;
    return waiting > t.capacity || waiting <= t.capacity - s.aboard.size();
  };
  const auto boards = [&](const Rider& r) {
    const int way = servingDirection(desc, t, s);
    return (way == 0 || (way > 0 ? key(s.at) < key(r.dest) : key(r.dest) < key(s.at))) && fits(r);
  };
  const auto joins = [&](const Rider& r) { return !s.aboard.empty() && groupOf(r) == groupOf(s.aboard.back()) && boards(r); };
  const auto anyBoards = [&](const std::deque<Rider>& q) { return room() && std::any_of(q.begin(), q.end(), boards); };
  // Steps whose time has come, as many as end by this tick (zero-length steps follow at once).
  for (int guard = 0; guard < 4096 && tick >= s.until; ++guard) {
    std::deque<Rider>& here = s.queue[s.at];
    if (s.phase == Phase::Idle) {
      if (!here.empty()) {
        s.phase = Phase::Opening;
        s.until = tick + open;
      } else if (const std::uint32_t to = nextStop(desc, t, s); to != kNoIndex) {
        startMove(desc, t, s, tick, to);
      } else {
        break;
      }
    } else if (s.phase == Phase::Moving) {  // arrived
      s.phase = Phase::Opening;
      s.until = tick + open;
    } else if (s.phase == Phase::Opening) {
      s.phase = Phase::Transfer;
    } else if (s.phase == Phase::Transfer) {
      const auto off = std::find_if(s.aboard.begin(), s.aboard.end(), [&](const Rider& r) { return r.dest == s.at; });
      if (off != s.aboard.end()) {  // off first
        alight(desc, t, s.at, off->id, offHere++);
        s.aboard.erase(off);
        s.until = tick + transfer;
      } else if (anyBoards(here)) {  // then on: the rest of the group of the one before, else the nearest the car
        const bool together = std::any_of(here.begin(), here.end(), joins);
        const std::size_t k = together ? nearest(here, stopPlace(desc, t, s.at).p, joins) : nearest(here, stopPlace(desc, t, s.at).p, boards);
        s.aboard.push_back(here[k]);
        here.erase(here.begin() + static_cast<std::ptrdiff_t>(k));
        s.until = tick + transfer;
      } else {
        s.phase = Phase::Closing;
        s.until = tick + close;
      }
    } else {  // Closing
      if (anyBoards(here)) {  // someone came while the doors closed
        s.phase = Phase::Opening;
        s.until = tick + open;
      } else if (const std::uint32_t to = nextStop(desc, t, s); to != kNoIndex) {
        startMove(desc, t, s, tick, to);
      } else {
        s.phase = Phase::Idle;
      }
    }
  }
  // The people aboard stand in the car: at its stop, or on the way between two.
  Place where = stopPlace(desc, t, s.at);
  if (s.phase == Phase::Moving) {
    const Place from = stopPlace(desc, t, s.from);
    const float f = static_cast<float>(tick - s.moveStart) / static_cast<float>(s.moveTicks);
    where = {from.p + (where.p - from.p) * f, from.z + (where.z - from.z) * f};
  }
  for (std::size_t i = 0; i < s.aboard.size(); ++i) {
    const std::uint32_t row = rowOfId_[s.aboard[i].id];
    const core::Vec2 p = where.p + slot(static_cast<int>(i));
    a.velX[row] = (p.x - a.posX[row]) / dt_;
    a.velY[row] = (p.y - a.posY[row]) / dt_;
    a.posX[row] = p.x;
    a.posY[row] = p.y;
    if (a.levels) a.posZ[row] = where.z;
    a.mode[row] = AgentMode::Acting;  // carried: in the car (sense, integrate: not on the floor)
  }
}

}  // namespace throng::sim
