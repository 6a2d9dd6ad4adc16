// Lifts and escalators (vertical_transport.hpp). Everything happens in whole ticks: an escalator lets one
// person on every round(headway / dt) ticks and carries each for round(length / speed / dt); a lift
// takes round(t / dt) for each door movement and each transfer, and its trips the time to travel the
// distance between its stops at `speed` with `acceleration` (a trapezoidal or, when too short to
// reach the speed, triangular velocity profile), so what a test computes from the parameters is
// what happens, to a tick.
#include "vertical_transport.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace throng::sim {
namespace {

/// An escalator lets on whoever queuing is within this of where people step on [m] (a body's
/// depth: they stand at the comb plate) ...
constexpr float kBoardReach = 0.5f;
/// ... or, this long after the step came with nobody there, the nearest [s].
constexpr float kBoardPatience = 5.0f;

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

void VerticalTransports::configure(const ScenarioDesc& desc) { states_.assign(desc.transports.size(), State{}); }

std::uint32_t VerticalTransports::boardingAt(const ScenarioDesc& desc, std::uint32_t point) {
  for (std::size_t t = 0; t < desc.transports.size(); ++t) {
    const TransportDesc& d = desc.transports[t];
    if (d.stops[0] == point || (d.kind == TransportKind::Elevator && d.stops[1] == point)) {
      return static_cast<std::uint32_t>(t);
    }
  }
  return kNoIndex;
}

VerticalTransports::Place VerticalTransports::stopPlace(const ScenarioDesc& desc, const TransportDesc& t, int stop) {
  const PointDesc& p = desc.points[t.stops[stop]];
  return {p.position, p.height};
}

void VerticalTransports::step(const ScenarioDesc& desc, std::uint64_t tick, const nav::NavQuery& query, GoalWriter goals) {
  if (states_.empty()) return;
  AgentStore& a = goals.agents;
  agents_ = &a;
  write_ = &a;
  dt_ = desc.dt;
  // This tick's riders, by id.
  riders_.clear();
  for (std::size_t row = 0; row < a.size(); ++row) {
    if (a.goalState[row] != GoalState::Riding) continue;
    const std::uint32_t id = a.id[row];
    if (rowOfId_.size() <= id) rowOfId_.resize(static_cast<std::size_t>(id) + 1, kNoRow);
    rowOfId_[id] = static_cast<std::uint32_t>(row);
    riders_.push_back(id);
  }
  std::sort(riders_.begin(), riders_.end());
  const auto riding = [&](std::uint32_t id) { return std::binary_search(riders_.begin(), riders_.end(), id); };
  // Those gone (removed by the host) leave the queues and the cars.
  for (State& s : states_) {
    for (auto& q : s.queue) q.erase(std::remove_if(q.begin(), q.end(), [&](std::uint32_t id) { return !riding(id); }), q.end());
    for (std::size_t i = s.aboard.size(); i-- > 0;) {
      if (riding(s.aboard[i])) continue;
      s.aboard.erase(s.aboard.begin() + static_cast<std::ptrdiff_t>(i));
      if (i < s.toLetOff) --s.toLetOff;
      if (!s.boarded.empty()) s.boarded.erase(s.boarded.begin() + static_cast<std::ptrdiff_t>(i));
    }
  }
  // Newcomers queue at the stop they reached (their current goal), in id order.
  for (const std::uint32_t id : riders_) {
    bool known = false;
    for (const State& s : states_) {
      known = known || std::find(s.aboard.begin(), s.aboard.end(), id) != s.aboard.end() ||
              std::find(s.queue[0].begin(), s.queue[0].end(), id) != s.queue[0].end() ||
              std::find(s.queue[1].begin(), s.queue[1].end(), id) != s.queue[1].end();
      if (known) break;
    }
    if (known) continue;
    const std::uint32_t row = rowOfId_[id];
    const std::uint32_t point = goals.view().currentGoalPoint(row);
    const std::uint32_t t = point == kNoPoint ? kNoIndex : boardingAt(desc, point);
    if (t == kNoIndex) {  // its goal changed under it: walk on
      a.goalState[row] = GoalState::Seeking;
      a.mode[row] = AgentMode::Walking;
      a.needPath[row] = 1;
      continue;
    }
    states_[t].queue[desc.transports[t].stops[0] == point ? 0 : 1].push_back(id);
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
    goals.events.push_back({tick, a.id[row], EventKind::GoalReached, o.point, 0});
    goals.advanceGoal(row);
  }
  for (const std::uint32_t id : riders_) rowOfId_[id] = kNoRow;
}

std::size_t VerticalTransports::nearest(const std::deque<std::uint32_t>& queue, core::Vec2 p) const {
  std::size_t best = 0;
  float bestD2 = std::numeric_limits<float>::max();
  for (std::size_t i = 0; i < queue.size(); ++i) {  // ties: the first to come
    const std::uint32_t row = rowOfId_[queue[i]];
    const float d2 = core::lengthSq(core::Vec2{agents_->posX[row], agents_->posY[row]} - p);
    if (d2 < bestD2) {
      bestD2 = d2;
      best = i;
    }
  }
  return best;
}

void VerticalTransports::alight(const ScenarioDesc& desc, const TransportDesc& t, int stop, std::uint32_t id, int k) {
  Place place = stopPlace(desc, t, stop);
  place.p += slot(k);
  off_.push_back({rowOfId_[id], t.stops[stop], place});
}

void VerticalTransports::runEscalator(const ScenarioDesc& desc, const TransportDesc& t, State& s, std::uint64_t tick) {
  AgentStore& a = *write_;
  const Place from = stopPlace(desc, t, 0), to = stopPlace(desc, t, 1);
  const float dz = to.z - from.z;
  const float length = std::sqrt(core::lengthSq(to.p - from.p) + dz * dz);
  const std::uint64_t ride = std::max<std::uint64_t>(1, ticksOf(length / t.speed, dt_));
  const std::uint64_t headway = std::max<std::uint64_t>(1, ticksOf(t.headway, dt_));
  // Off at the top: those who have ridden the whole length (in boarding order).
  std::size_t done = 0;
  while (done < s.aboard.size() && tick - s.boarded[done] >= ride) {
    alight(desc, t, 1, s.aboard[done], 0);
    ++done;
  }
  s.aboard.erase(s.aboard.begin(), s.aboard.begin() + static_cast<std::ptrdiff_t>(done));
  s.boarded.erase(s.boarded.begin(), s.boarded.begin() + static_cast<std::ptrdiff_t>(done));
  // On at the bottom, once the one before is a headway ahead: whoever of those queuing has come
  // nearest where people step on, when within kBoardReach of it (or, kBoardPatience after the step
  // came, whoever is nearest: nobody waits for ever behind a knot).
  if (!s.queue[0].empty() && tick >= s.nextBoard) {
    const std::size_t k = nearest(s.queue[0], from.p);
    const std::uint32_t row = rowOfId_[s.queue[0][k]];
    const float d2 = core::lengthSq(core::Vec2{a.posX[row], a.posY[row]} - from.p);
    if (d2 <= kBoardReach * kBoardReach || tick >= s.nextBoard + ticksOf(kBoardPatience, dt_)) {
      s.aboard.push_back(s.queue[0][k]);
      s.boarded.push_back(tick);
      s.queue[0].erase(s.queue[0].begin() + static_cast<std::ptrdiff_t>(k));
      s.nextBoard = tick + headway;
    }
  }
  // The belt carries them: the straight line between the stops.
  for (std::size_t i = 0; i < s.aboard.size(); ++i) {
    const std::uint32_t row = rowOfId_[s.aboard[i]];
    const float f = static_cast<float>(tick - s.boarded[i]) / static_cast<float>(ride);
    const core::Vec2 p = from.p + (to.p - from.p) * f;
    a.velX[row] = (p.x - a.posX[row]) / dt_;
    a.velY[row] = (p.y - a.posY[row]) / dt_;
    a.posX[row] = p.x;
    a.posY[row] = p.y;
    if (a.levels) a.posZ[row] = from.z + dz * f;
    a.mode[row] = AgentMode::Acting;  // carried: standing on a step (sense, integrate: not on the floor)
  }
}

void VerticalTransports::startMove(const ScenarioDesc& desc, const TransportDesc& t, State& s, std::uint64_t tick) {
  const Place here = stopPlace(desc, t, s.at), there = stopPlace(desc, t, 1 - s.at);
  const float dz = there.z - here.z;
  const float distance = std::sqrt(core::lengthSq(there.p - here.p) + dz * dz);
  // Trapezoidal profile: accelerate to `speed`, cruise, brake; too short a trip never reaches it.
  const float v = t.speed, acc = t.acceleration;
  const float seconds = distance >= v * v / acc ? distance / v + v / acc : 2.0f * std::sqrt(distance / acc);
  s.moveTicks = std::max<std::uint64_t>(1, ticksOf(seconds, dt_));
  s.moveStart = tick;
  s.until = tick + s.moveTicks;
  s.at = 1 - s.at;
  s.phase = Phase::Moving;
}

void VerticalTransports::runElevator(const ScenarioDesc& desc, const TransportDesc& t, State& s, std::uint64_t tick) {
  AgentStore& a = *write_;
  const std::uint64_t open = ticksOf(t.doorOpenTime, dt_), close = ticksOf(t.doorCloseTime, dt_);
  const std::uint64_t transfer = ticksOf(t.transferTime, dt_);
  int offHere = 0;
  // Steps whose time has come, as many as end by this tick (zero-length steps follow at once).
  for (int guard = 0; guard < 4096 && tick >= s.until; ++guard) {
    const int other = 1 - s.at;
    if (s.phase == Phase::Idle) {
      if (!s.queue[s.at].empty()) {
        s.phase = Phase::Opening;
        s.until = tick + open;
      } else if (!s.queue[other].empty()) {
        startMove(desc, t, s, tick);
      } else {
        break;
      }
    } else if (s.phase == Phase::Moving || s.phase == Phase::Opening) {
      if (s.phase == Phase::Moving) {  // arrived: everyone aboard gets off here
        s.phase = Phase::Opening;
        s.until = tick + open;
        s.toLetOff = static_cast<std::uint32_t>(s.aboard.size());
        continue;
      }
      s.phase = Phase::Transfer;
    } else if (s.phase == Phase::Transfer) {
      if (s.toLetOff > 0) {  // off first
        alight(desc, t, s.at, s.aboard.front(), offHere++);
        s.aboard.erase(s.aboard.begin());
        --s.toLetOff;
        s.until = tick + transfer;
      } else if (!s.queue[s.at].empty() && s.aboard.size() < t.capacity) {  // the nearest the car first
        const std::size_t k = nearest(s.queue[s.at], stopPlace(desc, t, s.at).p);
        s.aboard.push_back(s.queue[s.at][k]);
        s.queue[s.at].erase(s.queue[s.at].begin() + static_cast<std::ptrdiff_t>(k));
        s.until = tick + transfer;
      } else {
        s.phase = Phase::Closing;
        s.until = tick + close;
      }
    } else {  // Closing
      if (!s.aboard.empty()) {
        startMove(desc, t, s, tick);
      } else if (!s.queue[s.at].empty()) {  // someone came while the doors closed
        s.phase = Phase::Opening;
        s.until = tick + open;
      } else {
        s.phase = Phase::Idle;
      }
    }
  }
  // The people aboard stand in the car: at its stop, or on the way between the two.
  const Place here = stopPlace(desc, t, s.at);
  Place where = here;
  if (s.phase == Phase::Moving) {
    const Place from = stopPlace(desc, t, 1 - s.at);
    const float f = static_cast<float>(tick - s.moveStart) / static_cast<float>(s.moveTicks);
    where = {from.p + (here.p - from.p) * f, from.z + (here.z - from.z) * f};
  }
  for (std::size_t i = 0; i < s.aboard.size(); ++i) {
    const std::uint32_t row = rowOfId_[s.aboard[i]];
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
