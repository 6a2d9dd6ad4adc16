// exit_choice (exit_choice.hpp): distance fields of the chosen-among exits, the initial choice of a
// spawning group, the per-tick queue count and re-evaluation, closing and opening exits.
#include "exit_choice.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "throng/core/rng.hpp"

namespace throng::sim {
namespace {

/// Width of a distance bin of the queue counts [m]: about one person's depth in a queue.
constexpr float kBin = 0.5f;
constexpr double kNever = std::numeric_limits<double>::infinity();
/// The queues are rebuilt this many times a (shortest) period; in between, decisions update them.
constexpr std::uint32_t kQueueRebuilds = 8;
/// Buckets of the herding index (cells hashed into them; a power of two).
constexpr std::uint32_t kHerdBuckets = 4096;

}  // namespace

std::size_t ExitChoice::Queue::bin(float d) const {
  const float b = std::max(0.0f, d / kBin) + 1.0f;  // Fenwick indices start at 1
  return std::min(static_cast<std::size_t>(b), tree_.size() - 1);
}

void ExitChoice::Queue::add(float d, std::int32_t n) {
  if (!std::isfinite(d) || tree_.size() < 2) return;
  for (std::size_t i = bin(d); i < tree_.size(); i += i & (~i + 1)) tree_[i] += n;
}

std::int32_t ExitChoice::Queue::nearer(float d) const {
  if (tree_.size() < 2) return 0;
  std::int32_t sum = 0;
  for (std::size_t i = bin(d) - 1; i > 0; i -= i & (~i + 1)) sum += tree_[i];
  return sum;
}

void ExitChoice::prepare(const ScenarioDesc& desc, const nav::NavMesh& mesh, std::uint32_t firstPopulation) {
  mesh_ = &mesh;
  exitOfPoint_.resize(desc.points.size(), -1);
  for (std::size_t p = firstPopulation; p < desc.populations.size(); ++p) {
    const PopulationDesc& pop = desc.populations[p];
    if (pop.exits.empty()) continue;
    const auto ticks = static_cast<std::uint32_t>(std::max(1.0f, std::round(pop.exitChoice.period / desc.dt)));
    periodTicks_ = exits_.empty() ? ticks : std::min(periodTicks_, ticks);
    if (pop.exitChoice.herding > 0.0f) herdCell_ = std::max(herdCell_, pop.exitChoice.herdingRadius);
    nav::DistanceFieldConfig config;
    // Stairs cost as in route choice: the mean of 1/up and 1/down per metre.
    config.stairCost = std::max(1.0f, 0.5f * (1.0f / pop.stairUp + 1.0f / pop.stairDown));
    for (const std::uint32_t point : pop.exits) {
      if (exitOfPoint_[point] >= 0) continue;
      Exit e;
      e.region = cutRegion(desc.points[point]);
      e.config = config;
      e.version = meshVersion_;  // built on the mesh as it is now (doors closed so far are walls)
      e.field = nav::DistanceField::build(mesh, e.region, config);
      e.capacity = kExitSpecificFlow * desc.points[point].width;
      e.queue.reset(static_cast<std::size_t>(e.field.maxDistance() / kBin) + 2);
      exitOfPoint_[point] = static_cast<std::int32_t>(exits_.size());
      exits_.push_back(std::move(e));
    }
  }
}

void ExitChoice::meshChanged() {
  if (exits_.empty()) return;  // an exit a crowd brings later is built on the mesh as it is then
  ++meshVersion_;
  stale_ = true;
}

void ExitChoice::setMesh(const nav::NavMesh& mesh) {
  mesh_ = &mesh;
  ++meshVersion_;
  // A field answers polygon references of the mesh it was built on: none is read again before
  // it is rebuilt on this one.
  for (Exit& e : exits_) e.field = {};
  stale_ = !exits_.empty();
}

void ExitChoice::refresh(const GoalWriter& goals, const core::TaskSystem* tasks) {
  if (!stale_) return;
  stale_ = false;
  std::vector<std::size_t> due;  // exit indices, ascending
  for (std::size_t k = 0; k < exits_.size(); ++k) {
    if (!exits_[k].closed && exits_[k].version != meshVersion_) due.push_back(k);
  }
  const core::TaskSystem serial(1);
  const core::TaskSystem& run = tasks != nullptr ? *tasks : serial;
  // Each task builds whole fields of its own: the same fields for any thread count.
  run.parallelFor(due.size(), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      Exit& e = exits_[due[i]];
      e.field = nav::DistanceField::build(*mesh_, e.region, e.config);
      e.version = meshVersion_;
    }
  });
  // The bins follow the longest distance, which a detour lengthens; everyone is measured anew.
  for (const std::size_t k : due) exits_[k].queue.reset(static_cast<std::size_t>(exits_[k].field.maxDistance() / kBin) + 2);
  countQueues(0, goals, run, true);
  remeasured_ = true;
}

void ExitChoice::setClosed(std::uint32_t point, bool closed) {
  if (point >= exitOfPoint_.size() || exitOfPoint_[point] < 0) return;
  Exit& e = exits_[static_cast<std::size_t>(exitOfPoint_[point])];
  e.closed = closed;
  availabilityChanged_ = true;
  // Doors changed while it was closed (its field was left as it was): measured anew on opening.
  if (!closed && e.version != meshVersion_) stale_ = true;
}

bool ExitChoice::closed(std::uint32_t point) const {
  return point < exitOfPoint_.size() && exitOfPoint_[point] >= 0 && exits_[static_cast<std::size_t>(exitOfPoint_[point])].closed;
}

double ExitChoice::cost(const Exit& e, ExitRule rule, float d, float speed) const {
  if (e.closed || !std::isfinite(d)) return kNever;
  if (rule == ExitRule::Nearest) return d;
  const double walk = static_cast<double>(d) / std::max(0.1f, speed);
  return walk + static_cast<double>(e.queue.nearer(d)) / static_cast<double>(e.capacity);
}

std::uint32_t ExitChoice::better(const PopulationDesc& pop, ExitRule rule, std::uint32_t current, core::Vec2 p,
                                 nav::PolyRef ref, float speed, std::uint32_t group) const {
  double best = kNever, now = kNever;
  std::uint32_t choice = current;
  const std::vector<std::uint32_t>& known = pop.exitChoice.familiar;
  thread_local std::vector<double> share;  // serial code; thread_local only spares an allocation
  const bool herds = pop.exitChoice.herding > 0.0f && herdCell_ > 0.0f;
  if (herds) sharesNear(pop, p, group, share);
  for (std::size_t k = 0; k < pop.exits.size(); ++k) {
    const std::uint32_t point = pop.exits[k];
    const Exit& e = exits_[static_cast<std::size_t>(exitOfPoint_[point])];
    double c = cost(e, rule, e.field.at(p, ref), speed);
    // Affiliation: an exit the group does not know looks this much dearer (kNever stays kNever).
    if (!known.empty() && c < kNever && std::find(known.begin(), known.end(), point) == known.end()) {
      c *= static_cast<double>(pop.exitChoice.familiarity);
    }
    // Herding: the more of the people around head there, the cheaper it looks.
    if (herds && c < kNever) c *= 1.0 - static_cast<double>(pop.exitChoice.herding) * share[k];
    if (point == current) now = c;
    if (c < best) {
      best = c;
      choice = point;
    }
  }
  if (best == kNever) return current;  // every exit closed or out of reach: keep going
  if (now == kNever || current == kNoPoint) return choice;
  return best < now * (1.0 - static_cast<double>(pop.exitChoice.hysteresis)) ? choice : current;
}

std::uint32_t ExitChoice::initial(const ScenarioDesc& desc, const PopulationDesc& pop, std::uint32_t gid,
                                  std::uint32_t members, core::Vec2 p, nav::PolyRef ref, float speed) {
  const auto population = static_cast<std::uint16_t>(&pop - desc.populations.data());
  if (!ranges_.empty() && ranges_.back().population == population && ranges_.back().first + ranges_.back().count == gid) {
    ++ranges_.back().count;  // a population's groups have consecutive ids
  } else {
    ranges_.push_back({gid, 1, population});
  }
  const std::uint32_t chosen = firstChoice(desc, pop, gid, p, ref, speed);
  exitAt(chosen).queue.add(exitAt(chosen).field.at(p, ref), static_cast<std::int32_t>(members));
  return chosen;
}

std::uint32_t ExitChoice::firstChoice(const ScenarioDesc& desc, const PopulationDesc& pop, std::uint32_t gid, core::Vec2 p,
                                      nav::PolyRef ref, float speed) const {
  if (pop.exitChoice.rule != ExitRule::Allocation) {
    const std::uint32_t chosen = better(pop, pop.exitChoice.rule, kNoPoint, p, ref, speed, gid);
    return chosen != kNoPoint ? chosen : pop.exits.front();
  }
  // A probabilistic split by fixed shares, drawn per group from (seed, group id).
  core::Rng rng(desc.seed, gid, core::RngPurpose::ExitChoice);
  const std::vector<float>& shares = pop.exitChoice.shares;
  double total = 0.0;
  for (std::size_t k = 0; k < pop.exits.size(); ++k) total += k < shares.size() ? shares[k] : 1.0;
  double u = rng.uniform() * total;
  for (std::size_t k = 0; k < pop.exits.size(); ++k) {
    u -= k < shares.size() ? shares[k] : 1.0;
    if (u < 0.0) return pop.exits[k];
  }
  return pop.exits.back();
}

void ExitChoice::countQueues(std::uint64_t tick, const GoalWriter& goals, const core::TaskSystem& tasks, bool all) {
  // Every few ticks each exit counts who is heading there by distance (the queue ahead of any
  // distance); each agent re-measures its distance once a period, spread by its id (`all`: every
  // agent, now). The measurements are pure lookups, made in parallel; the counting is serial, in
  // row order.
  const std::uint32_t every = std::max(1u, periodTicks_ / kQueueRebuilds);
  if (tick % every != 0 && !all) return;
  const std::uint64_t round = tick / every;
  const std::uint32_t rounds = std::max(1u, periodTicks_ / every);
  const AgentStore& agents = goals.agents;
  const GoalView view = goals.view();
  heading_.clear();
  measure_.clear();
  for (std::size_t row = 0; row < agents.size(); ++row) {
    const GoalState state = agents.goalState[row];
    if (state == GoalState::Exited || state == GoalState::Done || state == GoalState::Incapacitated) continue;
    const std::uint32_t point = view.currentGoalPoint(row);
    if (point == kNoPoint || point >= exitOfPoint_.size() || exitOfPoint_[point] < 0) continue;
    const std::uint32_t id = agents.id[row];
    if (id >= distanceOfId_.size()) distanceOfId_.resize(std::max<std::size_t>(id + 1, distanceOfId_.size() * 2), -1.0f);
    heading_.push_back({static_cast<std::uint32_t>(row), static_cast<std::uint32_t>(exitOfPoint_[point])});
    if (all || distanceOfId_[id] < 0.0f || (round + id) % rounds == 0) measure_.push_back(heading_.back());
  }
  tasks.parallelFor(measure_.size(), 512, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      const std::uint32_t row = measure_[k].row;
      distanceOfId_[agents.id[row]] = exits_[measure_[k].exit].field.at({agents.posX[row], agents.posY[row]}, agents.polyRef[row]);
    }
  });
  for (Exit& e : exits_) e.queue.clear();
  for (const Heading& h : heading_) exits_[h.exit].queue.add(distanceOfId_[agents.id[h.row]], 1);
  if (herdCell_ > 0.0f) indexHerders(agents);
}

std::uint32_t ExitChoice::herdBucket(int cx, int cy) const {
  const auto h = static_cast<std::uint32_t>(cx) * 73856093u ^ static_cast<std::uint32_t>(cy) * 19349663u;
  return h & (kHerdBuckets - 1);
}

void ExitChoice::indexHerders(const AgentStore& agents) {
  // A counting sort of heading_ (row order) into hashed cells of herdCell_ metres.
  herdStart_.assign(kHerdBuckets + 1, 0);
  herders_.resize(heading_.size());
  std::vector<std::uint32_t> bucketOf(heading_.size());
  for (std::size_t k = 0; k < heading_.size(); ++k) {
    const std::uint32_t row = heading_[k].row;
    bucketOf[k] = herdBucket(static_cast<int>(std::floor(agents.posX[row] / herdCell_)),
                             static_cast<int>(std::floor(agents.posY[row] / herdCell_)));
    ++herdStart_[bucketOf[k] + 1];
  }
  for (std::uint32_t b = 0; b < kHerdBuckets; ++b) herdStart_[b + 1] += herdStart_[b];
  std::vector<std::uint32_t> next(herdStart_.begin(), herdStart_.end() - 1);
  for (std::size_t k = 0; k < heading_.size(); ++k) {
    const std::uint32_t row = heading_[k].row;
    herders_[next[bucketOf[k]]++] = Herder{agents.posX[row], agents.posY[row], heading_[k].exit, agents.group[row]};
  }
}

void ExitChoice::sharesNear(const PopulationDesc& pop, core::Vec2 p, std::uint32_t group, std::vector<double>& share) const {
  share.assign(pop.exits.size(), 0.0);
  if (herdStart_.empty()) return;
  const float r = pop.exitChoice.herdingRadius;
  const int reach = static_cast<int>(std::ceil(r / herdCell_));
  const int cx = static_cast<int>(std::floor(p.x / herdCell_)), cy = static_cast<int>(std::floor(p.y / herdCell_));
  double total = 0.0;
  for (int y = cy - reach; y <= cy + reach; ++y) {
    for (int x = cx - reach; x <= cx + reach; ++x) {
      const std::uint32_t b = herdBucket(x, y);
      for (std::uint32_t k = herdStart_[b]; k < herdStart_[b + 1]; ++k) {
        const Herder& h = herders_[k];
        // Hashed cells can share a bucket, and a bucket can be visited twice: the distance and
        // the cell itself decide.
        if (h.group == group || static_cast<int>(std::floor(h.x / herdCell_)) != x ||
            static_cast<int>(std::floor(h.y / herdCell_)) != y) continue;
        const float dx = h.x - p.x, dy = h.y - p.y;
        if (dx * dx + dy * dy > r * r) continue;
        total += 1.0;
        for (std::size_t e = 0; e < pop.exits.size(); ++e) {
          if (exitOfPoint_[pop.exits[e]] == static_cast<std::int32_t>(h.exit)) share[e] += 1.0;
        }
      }
    }
  }
  if (total > 0.0) {
    for (double& s : share) s /= total;
  }
}

void ExitChoice::reconsider(std::uint64_t tick, std::span<const std::uint32_t> rowOfId, GoalWriter& goals) {
  // The groups due this tick — those whose id + tick is a multiple of their population's period:
  // every period-th id of each range — and, on the tick after an exit closed or opened, all:
  // those heading for a closed exit choose again, and after the fields were rebuilt round closed
  // or opened doors every group does (an allocated one only when its exit is out of reach).
  const bool all = availabilityChanged_ || remeasured_;
  const bool lookAgain = remeasured_;
  availabilityChanged_ = false;
  remeasured_ = false;
  for (const Range& r : ranges_) {
    const PopulationDesc& pop = goals.desc.populations[r.population];
    if (pop.exitChoice.rule == ExitRule::Allocation && !all) continue;
    const auto period = static_cast<std::uint32_t>(std::max(1.0f, std::round(pop.exitChoice.period / goals.desc.dt)));
    const std::uint32_t step = all ? 1 : period;
    const std::uint32_t offset = all ? 0 : static_cast<std::uint32_t>((period - (tick + r.first) % period) % period);
    for (std::uint32_t gid = r.first + offset; gid < r.first + r.count; gid += step) {
      const std::uint32_t current = goals.goalLists[goals.groups[gid].goalList].back();
      const bool due = (tick + gid) % period == 0 && pop.exitChoice.rule != ExitRule::Allocation;
      if (due || closed(current) || lookAgain) reconsiderGroup(gid, pop, rowOfId, goals);
    }
  }
}

void ExitChoice::reconsiderGroup(std::uint32_t gid, const PopulationDesc& pop, std::span<const std::uint32_t> rowOfId,
                                 GoalWriter& goals) {
  const AgentStore& agents = goals.agents;
  const GroupState& g = goals.groups[gid];
  const std::uint32_t current = goals.goalLists[g.goalList].back();
  // The group decides where its leader (or first member present) stands.
  std::uint32_t row = kNoRow;
  if (g.leader != kNoAgent && g.leader < rowOfId.size()) row = rowOfId[g.leader];
  for (std::size_t m = 0; row == kNoRow && m < g.members.size(); ++m) {
    if (g.members[m] < rowOfId.size()) row = rowOfId[g.members[m]];
  }
  if (row == kNoRow || agents.goalState[row] == GoalState::Exited) return;
  const core::Vec2 p{agents.posX[row], agents.posY[row]};
  // An allocated group whose exit closed, or can no longer be reached, takes the nearest open one.
  const bool allocated = pop.exitChoice.rule == ExitRule::Allocation;
  if (allocated && !closed(current) && std::isfinite(exitAt(current).field.at(p, agents.polyRef[row]))) return;
  const ExitRule rule = allocated ? ExitRule::Nearest : pop.exitChoice.rule;
  const std::uint32_t next = better(pop, rule, current, p, agents.polyRef[row], agents.speed[row], gid);
  if (next == current) return;
  // The others deciding this tick see the move at once.
  const auto members = static_cast<std::int32_t>(g.members.size());
  exitAt(current).queue.add(exitAt(current).field.at(p, agents.polyRef[row]), -members);
  exitAt(next).queue.add(exitAt(next).field.at(p, agents.polyRef[row]), members);
  goals.changeExit(gid, next, rowOfId, agents.id[row]);
}

void ExitChoice::step(std::uint64_t tick, std::span<const std::uint32_t> rowOfId, GoalWriter& goals,
                      const core::TaskSystem& tasks) {
  if (exits_.empty()) return;
  countQueues(tick, goals, tasks);
  reconsider(tick, rowOfId, goals);
}

}  // namespace throng::sim
