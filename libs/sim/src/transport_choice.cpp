// transport_choice (transport_choice.hpp): the fields of the stops and goals, and weighing walking
// against riding.
#include "transport_choice.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "vertical_transport.hpp"

namespace throng::sim {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
/// How far from a stop's or goal's centre the navmesh is looked for [m] (as goal targets are snapped).
constexpr float kSnap = 3.0f;
/// The slowest walking speed the times are reckoned at [m/s] (someone standing still still chooses).
constexpr float kSlowest = 0.1f;
/// More stops than this: a ride's way on from the stop it reaches is walking only (no search over
/// further transports; the search costs stops² per decision).
constexpr std::size_t kMaxSearchStops = 128;

}  // namespace

void TransportRoutes::prepare(const ScenarioDesc& desc, const nav::NavMesh& mesh, const nav::NavQuery& query) {
  fields_.clear();
  fieldVersion_.clear();
  stops_.clear();
  between_.clear();
  meshVersion_ = stopsVersion_ = 0;
  fieldOfPoint_.assign(desc.points.size(), -1);
  mesh_ = &mesh;
  if (desc.transports.empty()) return;
  const auto first = std::find_if(desc.populations.begin(), desc.populations.end(), [](const PopulationDesc& p) { return p.useTransports; });
  if (first == desc.populations.end()) return;
  config_ = {};
  config_.stairCost = std::max(1.0f, 0.5f * (1.0f / first->stairUp + 1.0f / first->stairDown));  // as exit choice
  for (std::uint32_t t = 0; t < desc.transports.size(); ++t) {
    const TransportDesc& d = desc.transports[t];
    for (std::uint32_t k = 0; k < d.stops.size(); ++k) {
      Stop s;
      s.point = d.stops[k];
      s.transport = t;
      s.index = k;
      s.boards = d.kind == TransportKind::Elevator || k == 0;
      const PointDesc& p = desc.points[s.point];
      const auto snapped = query.snap(p.position, p.height, kSnap);
      s.p = snapped ? snapped->p : p.position;
      s.ref = snapped ? snapped->ref : 0;
      stops_.push_back(s);
    }
  }
  measureStops(desc);
}

void TransportRoutes::measureStops(const ScenarioDesc& desc) {
  for (const Stop& s : stops_) fieldOf(desc, s.point);
  stopsVersion_ = meshVersion_;
  const std::size_t n = stops_.size();
  if (n > kMaxSearchStops) return;
  between_.assign(n * n, kInf);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) between_[i * n + j] = fieldOf(desc, stops_[j].point)->at(stops_[i].p, stops_[i].ref);
  }
}

void TransportRoutes::meshChanged() {
  if (active()) ++meshVersion_;
}

const nav::DistanceField* TransportRoutes::fieldOf(const ScenarioDesc& desc, std::uint32_t point) {
  if (point >= desc.points.size()) return nullptr;
  if (point >= fieldOfPoint_.size()) fieldOfPoint_.resize(desc.points.size(), -1);  // a crowd's points, inserted since
  if (fieldOfPoint_[point] < 0) {
    fieldOfPoint_[point] = static_cast<std::int32_t>(fields_.size());
    fields_.push_back(nav::DistanceField::build(*mesh_, cutRegion(desc.points[point]), config_));
    fieldVersion_.push_back(meshVersion_);
  }
  const auto k = static_cast<std::size_t>(fieldOfPoint_[point]);
  if (fieldVersion_[k] != meshVersion_) {  // doors closed or opened since it was built: measured anew
    fields_[k] = nav::DistanceField::build(*mesh_, cutRegion(desc.points[point]), config_);
    fieldVersion_[k] = meshVersion_;
  }
  return &fields_[k];
}

bool TransportRoutes::claim(std::uint32_t gid, std::uint32_t cursor) {
  if (decided_.size() <= gid) decided_.resize(gid + 1, 0);
  if (cursor < decided_[gid]) return false;
  decided_[gid] = cursor + 1;
  return true;
}

std::uint32_t& TransportRoutes::ownList(std::uint32_t gid) {
  if (ownList_.size() <= gid) ownList_.resize(gid + 1, 0);
  return ownList_[gid];
}

std::uint32_t TransportRoutes::boardingFor(const ScenarioDesc& desc, const AgentStore& a, std::size_t row, std::uint32_t goal,
                                           const VerticalTransports& transports,
                                           const std::function<std::uint32_t(std::uint32_t)>& heading, bool rideIfAny) {
  if (stopsVersion_ != meshVersion_) measureStops(desc);  // a door closed or opened since
  const nav::DistanceField* toGoal = fieldOf(desc, goal);
  if (toGoal == nullptr) return kNoIndex;
  const float v = std::max(kSlowest, a.speed[row]);
  const core::Vec2 pos{a.posX[row], a.posY[row]};
  const nav::PolyRef ref = a.polyRef[row];
  const std::size_t n = stops_.size();
  // Per boarding stop: where it takes one to (rideTo, for this goal), and waiting plus riding there.
  std::vector<std::size_t>& dest = dest_;
  std::vector<float>& leg = leg_;
  std::vector<float>& onward = onward_;
  dest.assign(n, n);
  leg.assign(n, kInf);
  onward.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Stop& s = stops_[i];
    if (!s.boards) continue;
    const TransportDesc& t = desc.transports[s.transport];
    const std::size_t to = rideTo(desc, t, s.index, goal);
    if (to == s.index) continue;
    dest[i] = i - s.index + to;  // a transport's stops are consecutive in stops_
    leg[i] = transports.expectedWait(desc, s.transport, s.index, to, heading(s.point)) + VerticalTransports::rideTime(desc, t, s.index, to);
  }
  // From stepping off at each stop to the goal: walking on, or a further ride (shortest times,
  // Bellman-Ford over the stops; every leg takes time, so it settles within n rounds).
  for (std::size_t i = 0; i < n; ++i) onward[i] = toGoal->at(stops_[i].p, stops_[i].ref) / v;
  if (!between_.empty()) {
    for (std::size_t round = 0; round < n; ++round) {
      bool changed = false;
      for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t b = 0; b < n; ++b) {
          if (dest[b] == n) continue;
          const float c = between_[i * n + b] / v + leg[b] + onward[dest[b]];
          if (c < onward[i]) {
            onward[i] = c;
            changed = true;
          }
        }
      }
      if (!changed) break;
    }
  }
  float best = rideIfAny ? kInf : toGoal->at(pos, ref) / v;
  std::uint32_t board = kNoIndex;
  for (std::size_t b = 0; b < n; ++b) {
    if (dest[b] == n) continue;
    // Someone who does not take the stairs boards on the floor it stands on (walking up the stairs
    // to ride a down escalator and then the up one is a way, and the only one left were walking not
    // weighed at all).
    if (rideIfAny && a.levels && std::abs(desc.points[stops_[b].point].height - a.posZ[row]) > nav::kLevelSearch) continue;
    const float c = fieldOf(desc, stops_[b].point)->at(pos, ref) / v + leg[b] + onward[dest[b]];
    if (c < best) {
      best = c;
      board = stops_[b].point;
    }
  }
  return board;
}

}  // namespace throng::sim
