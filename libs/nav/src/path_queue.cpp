// throng::nav::PathQueue — time-sliced path planning (after DetourPathQueue). Requests wait in a
// FIFO; update() runs Detour's sliced A* (init/update/finalizeSlicedFindPath) on the oldest one,
// spending at most the iteration budget across as many requests as it covers, then string-pulls the
// corridor exactly as NavQuery::findPath does, so a queued result equals a direct query (also with
// heights: a request's ends are searched as NavQuery::findPath's height-taking overload does).
// Route costs: one Detour query filter per cost class (setStairCosts), each pricing the stair area;
// a layered request names its class.
//
// Result lifetime: a finished result stays until take() or until kResultLifetimeUpdates (64)
// further update() calls have passed without it being taken; then its ticket becomes Unknown.
// Writes only its own queue, Detour node pool and results; deterministic (FIFO order, no clocks).
//
// Parallel update (a TaskSystem of several threads): the next waiting requests are searched whole
// on per-worker Detour queries (Speculated: result + node expansions), then the budget is replayed
// over them in FIFO order. A sliced search expands the same nodes however it is sliced, and
// updateSlicedFindPath(b) spends min(b, remaining) expansions (at least 1), so the replay completes
// each request in the very update the serial queue would, with the same corridor and corners.
#include "throng/nav/path_queue.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

#include "navmesh_data.hpp"
#include "throng/core/assert.hpp"

namespace throng::nav {
namespace {

/// Updates an unread result survives before it expires.
constexpr std::uint64_t kResultLifetimeUpdates = 64;

/// 16 bytes: a path request for every agent of a million-agent world can wait in the queue at once,
/// so the heights of layered meshes wait in a queue of their own (Impl::waitingHeights), and the
/// tickets are not stored: they are issued in order and served in order, so the waiting ones are
/// the last waiting.size() issued (Impl::frontTicket).
struct Request {
  Vec2 from;
  Vec2 to;
};

struct Finished {
  PathResult result;
  std::uint64_t doneAtUpdate = 0;
};

/// Layered meshes: a request's from and to height, and its cost class.
struct Layered {
  float fromHeight = 0.0f, toHeight = 0.0f;
  std::uint32_t costClass = 0;
};

/// One search's query state: the ends snapped, Detour's sliced A*, the corridor string-pulled.
/// The queue's own (serial) searches use one; speculative searches (parallel update) one per worker.
struct Searcher {
  dtNavMeshQuery* query = nullptr;
  float start[3] = {};
  float end[3] = {};
  dtPolyRef endRef = 0;
  std::vector<dtPolyRef> polys = std::vector<dtPolyRef>(detail::kMaxPathPolys);

  Searcher(const NavMesh& mesh, int maxNodes) : query(dtAllocNavMeshQuery()) {
    query->init(mesh.detour(), maxNodes);
  }
  ~Searcher() { dtFreeNavMeshQuery(query); }
  Searcher(const Searcher&) = delete;
  Searcher& operator=(const Searcher&) = delete;

  /// Snaps the ends and starts the sliced search with `filter` (which must outlive it). Returns
  /// the result when the request finished at once (an end off the mesh), nothing when it started.
  std::optional<PathResult> begin(const NavMesh& mesh, const Request& r, const Layered* heights,
                                  const dtQueryFilter& filter) {
    detail::EndSearch fromSearch, toSearch;
    if (heights != nullptr) {
      fromSearch = detail::endSearch(mesh, heights->fromHeight);
      toSearch = detail::endSearch(mesh, heights->toHeight);
    }
    const dtPolyRef startRef = detail::snapEnd(*query, filter, r.from, fromSearch, start);
    if (startRef == 0) return PathResult{PathStatus::Failed, {}};
    endRef = detail::snapEnd(*query, filter, r.to, toSearch, end);
    if (endRef == 0) return PathResult{PathStatus::Partial, {detail::fromRecast(start)}};
    if (dtStatusFailed(query->initSlicedFindPath(startRef, endRef, start, end, &filter, 0))) {
      return PathResult{PathStatus::Failed, {}};
    }
    return std::nullopt;
  }

  /// Finalizes the search that ended with `searchStatus` and string-pulls its corridor.
  PathResult complete(dtStatus searchStatus) {
    PathResult result;
    int count = 0;
    const dtStatus status = query->finalizeSlicedFindPath(polys.data(), &count, detail::kMaxPathPolys);
    if (dtStatusFailed(searchStatus) || dtStatusFailed(status) || count == 0) return result;
    const bool partial = dtStatusDetail(status, DT_PARTIAL_RESULT) || polys[count - 1] != endRef;
    result.status = detail::straighten(*query, start, end, polys.data(), count, partial, result.corners, &result.heights);
    return result;
  }
};

/// A request searched to its end ahead of its turn (parallel update): its result and what the
/// sliced search would have cost. A sliced search expands the same nodes however it is sliced
/// (Detour's open list and node pool carry over between updateSlicedFindPath calls), so knowing
/// the whole search's expansions is enough to replay the budget exactly.
struct Speculated {
  PathResult result;
  int iterations = 0;      ///< node expansions of the whole search (0: start and end on one polygon)
  bool immediate = false;  ///< finished in begin (an end off the mesh): costs no budget
};

}  // namespace

struct PathQueue::Impl {
  std::shared_ptr<const NavMesh> mesh;
  int maxNodes = 4096;
  std::deque<dtQueryFilter> filters = std::deque<dtQueryFilter>(1);  ///< per cost class
  std::size_t costClasses = 0;  ///< classes set by setStairCosts
  std::deque<Request> waiting;
  /// Layered meshes only, as `waiting`: from and to height, and the cost class.
  std::deque<Layered> waitingHeights;
  std::map<PathTicket, Finished> finished;
  PathTicket nextTicket = 1;
  std::uint64_t updates = 0;

  // The serial search in progress (sliced), if any. Its filter is a copy taken when it began, so
  // it keeps its class's costs as they were then (as a speculative search does).
  std::unique_ptr<Searcher> serial;
  bool active = false;
  PathTicket current = 0;
  Request currentRequest;  ///< the request in progress (serial or replayed), for restart()
  Layered currentHeights;
  dtQueryFilter currentFilter;

  // Parallel update: results of waiting[0 .. ahead.size()) searched ahead of their turn by the
  // workers, and the replay of the one whose turn came and whose budget is not yet spent.
  std::deque<Speculated> ahead;
  std::vector<std::unique_ptr<Searcher>> workers;
  bool replaying = false;
  PathTicket replayTicket = 0;
  Speculated replay;
  int replayRemaining = 0;

  void finish(PathTicket ticket, PathResult result) {
    finished[ticket] = Finished{std::move(result), updates};
  }

  const dtQueryFilter& filterOf(const Layered* heights) const {
    return filters[heights != nullptr && heights->costClass < filters.size() ? heights->costClass : 0];
  }

  /// The ticket of waiting.front(): the waiting requests hold the last tickets issued, in order (the
  /// one restart() puts back at the front is the one taken from there last).
  [[nodiscard]] PathTicket frontTicket() const { return nextTicket - waiting.size(); }

  /// Starts the oldest waiting request on the serial searcher. Returns false when it finished at
  /// once (not on the mesh).
  bool begin() {
    const PathTicket ticket = frontTicket();
    const Request r = waiting.front();
    waiting.pop_front();
    std::optional<Layered> heights;
    if (!waitingHeights.empty()) {
      heights = waitingHeights.front();
      waitingHeights.pop_front();
    }
    currentRequest = r;
    currentHeights = heights ? *heights : Layered{};
    currentFilter = filterOf(heights ? &*heights : nullptr);
    if (!serial) serial = std::make_unique<Searcher>(*mesh, maxNodes);
    std::optional<PathResult> now = serial->begin(*mesh, r, heights ? &*heights : nullptr, currentFilter);
    if (now) {
      finish(ticket, std::move(*now));
      return false;
    }
    current = ticket;
    active = true;
    return true;
  }

  /// One step of the serial sliced search; returns whether it completed.
  bool stepSerial(int& budget) {
    int done = 0;
    const dtStatus status = serial->query->updateSlicedFindPath(budget, &done);
    budget -= std::max(done, 1);
    if (dtStatusInProgress(status)) return false;
    active = false;
    finish(current, serial->complete(status));
    return true;
  }

  /// Searches waiting[ahead.size() .. + count) to their ends on the workers, each with the filter
  /// of its class as it is now; appends them to `ahead` in queue order.
  void speculate(const core::TaskSystem& tasks, std::size_t count) {
    const std::size_t first = ahead.size();
    count = std::min(count, waiting.size() - first);
    if (count == 0) return;
    while (workers.size() < static_cast<std::size_t>(tasks.threads())) {
      workers.push_back(std::make_unique<Searcher>(*mesh, maxNodes));
    }
    std::vector<Speculated> out(count);
    tasks.parallelFor(count, 1, [&](std::size_t b, std::size_t e) {
      Searcher& s = *workers[static_cast<std::size_t>(tasks.workerIndex())];
      for (std::size_t i = b; i < e; ++i) {
        const Request& r = waiting[first + i];
        const Layered* heights = waitingHeights.empty() ? nullptr : &waitingHeights[first + i];
        const dtQueryFilter& filter = filterOf(heights);
        std::optional<PathResult> now = s.begin(*mesh, r, heights, filter);
        if (now) {
          out[i] = Speculated{std::move(*now), 0, true};
          continue;
        }
        int done = 0;  // stays 0 when start and end share a polygon (the search is over at init)
        const dtStatus status = s.query->updateSlicedFindPath(std::numeric_limits<int>::max(), &done);
        out[i] = Speculated{s.complete(status), done, false};
      }
    });
    for (Speculated& r : out) ahead.push_back(std::move(r));
  }

  /// Takes the oldest waiting request, already searched; returns false when it costs no budget
  /// (finished at once), true when its replay began.
  bool beginReplay() {
    const PathTicket ticket = frontTicket();
    currentRequest = waiting.front();
    waiting.pop_front();
    if (!waitingHeights.empty()) {
      currentHeights = waitingHeights.front();
      waitingHeights.pop_front();
    }
    Speculated s = std::move(ahead.front());
    ahead.pop_front();
    if (s.immediate) {
      finish(ticket, std::move(s.result));
      return false;
    }
    replayTicket = ticket;
    replayRemaining = s.iterations;
    replay = std::move(s);
    replaying = true;
    return true;
  }

  /// Spends budget on the replayed search exactly as updateSlicedFindPath would have: all of it
  /// while expansions remain beyond it, else the remaining expansions (at least 1) and done.
  bool stepReplay(int& budget) {
    if (replayRemaining > budget) {
      replayRemaining -= budget;
      budget = 0;
      return false;
    }
    budget -= std::max(replayRemaining, 1);
    replaying = false;
    finish(replayTicket, std::move(replay.result));
    return true;
  }
};

PathQueue::PathQueue(std::shared_ptr<const NavMesh> mesh, int maxNodes) : impl_(std::make_unique<Impl>()) {
  impl_->mesh = std::move(mesh);
  impl_->maxNodes = std::clamp(maxNodes, 16, 65535);
  impl_->serial = std::make_unique<Searcher>(*impl_->mesh, impl_->maxNodes);
  impl_->filters[0].setIncludeFlags(kWalkFlag);  // not a closed cut polygon (NavMesh::setClosed)
}

PathQueue::~PathQueue() = default;

PathTicket PathQueue::request(Vec2 from, Vec2 to) {
  const PathTicket ticket = impl_->nextTicket++;
  impl_->waiting.push_back(Request{from, to});
  if (impl_->mesh->layered()) impl_->waitingHeights.push_back({});
  return ticket;
}

PathTicket PathQueue::request(Vec2 from, float fromHeight, Vec2 to, float toHeight, std::uint32_t costClass) {
  const PathTicket ticket = impl_->nextTicket++;
  impl_->waiting.push_back(Request{from, to});
  if (impl_->mesh->layered()) impl_->waitingHeights.push_back({fromHeight, toHeight, costClass});
  return ticket;
}

void PathQueue::setStairCosts(std::span<const float> stairCost) {
  Impl& q = *impl_;
  bool changed = q.filters.size() < stairCost.size();
  if (q.filters.size() < stairCost.size()) q.filters.resize(stairCost.size());
  for (dtQueryFilter& f : q.filters) f.setIncludeFlags(kWalkFlag);
  for (std::size_t i = 0; i < stairCost.size(); ++i) {
    THRONG_ASSERT(std::isfinite(stairCost[i]) && stairCost[i] >= 1.0f);
    changed = changed || q.filters[i].getAreaCost(kStairArea) != stairCost[i];
    q.filters[i].setAreaCost(kStairArea, stairCost[i]);
  }
  // Searched ahead with the old classes: search them again when their turn comes.
  if (changed) q.ahead.clear();
  q.costClasses = std::max(q.costClasses, stairCost.size());
}

void PathQueue::restart() {
  Impl& q = *impl_;
  q.ahead.clear();  // searched on the mesh as it was
  if (q.active || q.replaying) {
    // The search under way starts again from scratch at its turn, on one thread as on several.
    q.waiting.push_front(q.currentRequest);
    if (q.mesh->layered()) q.waitingHeights.push_front(q.currentHeights);
    q.active = false;
    q.replaying = false;
  }
}

void PathQueue::setMesh(std::shared_ptr<const NavMesh> mesh) {
  Impl& q = *impl_;
  restart();
  // Layered and flat meshes queue heights differently: a rebuilt mesh is the same kind.
  THRONG_ASSERT(mesh->layered() == q.mesh->layered());
  q.mesh = std::move(mesh);
  q.serial = std::make_unique<Searcher>(*q.mesh, q.maxNodes);
  q.workers.clear();  // made again on the new mesh by the next parallel update
}

std::size_t PathQueue::costClasses() const { return impl_->costClasses; }

int PathQueue::update(int iterationBudget, const core::TaskSystem* tasks) {
  Impl& q = *impl_;
  ++q.updates;
  // Expire results nobody took.
  for (auto it = q.finished.begin(); it != q.finished.end();) {
    if (q.updates - it->second.doneAtUpdate > kResultLifetimeUpdates)
      it = q.finished.erase(it);
    else
      ++it;
  }
  const bool parallel = tasks != nullptr && tasks->threads() > 1;
  // Speculative batches grow while the budget lasts: few wasted searches on a quiet tick, few
  // rounds on a busy one. What is searched beyond the budget waits in `ahead` for later updates.
  std::size_t batch = parallel ? 8u * static_cast<std::size_t>(tasks->threads()) : 0;
  int completed = 0;
  int budget = std::max(iterationBudget, 1);  // always progress
  while (budget > 0 && (q.active || q.replaying || !q.waiting.empty())) {
    if (q.active) {
      completed += q.stepSerial(budget) ? 1 : 0;
      continue;
    }
    if (q.replaying) {
      completed += q.stepReplay(budget) ? 1 : 0;
      continue;
    }
    if (q.ahead.empty() && parallel) {
      q.speculate(*tasks, batch);
      batch = std::min<std::size_t>(batch * 2, 4096);
    }
    const bool started = q.ahead.empty() ? q.begin() : q.beginReplay();
    if (!started) ++completed;  // finished at once: an end is off the mesh
  }
  return completed;
}

TicketState PathQueue::state(PathTicket ticket) const {
  const Impl& q = *impl_;
  // The cheap tests first: most tickets asked about wait in the queue (at 100,000 wandering agents
  // tens of thousands do). A waiting or searched ticket is never among the finished ones.
  if (ticket >= q.frontTicket() && ticket < q.nextTicket) return TicketState::Pending;  // waiting
  if ((q.active && q.current == ticket) || (q.replaying && q.replayTicket == ticket)) return TicketState::Pending;
  return q.finished.count(ticket) != 0 ? TicketState::Done : TicketState::Unknown;
}

PathResult PathQueue::take(PathTicket ticket) {
  auto it = impl_->finished.find(ticket);
  if (it == impl_->finished.end()) return PathResult{};  // precondition violated: Failed, no corners
  PathResult result = std::move(it->second.result);
  impl_->finished.erase(it);
  return result;
}

std::size_t PathQueue::pending() const {
  return impl_->waiting.size() + (impl_->active ? 1u : 0u) + (impl_->replaying ? 1u : 0u);
}

}  // namespace throng::nav
