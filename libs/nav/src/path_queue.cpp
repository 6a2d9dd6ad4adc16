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
#include "throng/nav/path_queue.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "navmesh_data.hpp"
#include "throng/core/assert.hpp"

namespace throng::nav {
namespace {

/// Updates an unread result survives before it expires.
constexpr std::uint64_t kResultLifetimeUpdates = 64;

/// 24 bytes: a path request for every agent of a million-agent world can wait in the queue at once,
/// so the heights of layered meshes wait in a queue of their own (Impl::waitingHeights).
struct Request {
  PathTicket ticket = 0;
  Vec2 from;
  Vec2 to;
};

struct Finished {
  PathResult result;
  std::uint64_t doneAtUpdate = 0;
};

}  // namespace

struct PathQueue::Impl {
  std::shared_ptr<const NavMesh> mesh;
  dtNavMeshQuery* query = nullptr;
  std::deque<dtQueryFilter> filters = std::deque<dtQueryFilter>(1);  ///< per cost class (a deque: growing keeps `filter` valid)
  std::size_t costClasses = 0;  ///< classes set by setStairCosts
  const dtQueryFilter* filter = &filters[0];  ///< the current request's
  std::deque<Request> waiting;
  /// Layered meshes only, as `waiting`: from and to height, and the cost class.
  struct Layered {
    float fromHeight = 0.0f, toHeight = 0.0f;
    std::uint32_t costClass = 0;
  };
  std::deque<Layered> waitingHeights;
  // The search in progress (sliced), if any.
  bool active = false;
  Request current;
  detail::EndSearch fromSearch, toSearch;  ///< how the current request's ends are snapped
  float start[3] = {};
  float end[3] = {};
  dtPolyRef endRef = 0;
  std::map<PathTicket, Finished> finished;
  PathTicket nextTicket = 1;
  std::uint64_t updates = 0;
  std::vector<dtPolyRef> polys = std::vector<dtPolyRef>(detail::kMaxPathPolys);

  ~Impl() { dtFreeNavMeshQuery(query); }

  void finish(PathTicket ticket, PathResult result) {
    finished[ticket] = Finished{std::move(result), updates};
  }

  // Starts the oldest waiting request. Returns false when it finished at once (not on the mesh).
  bool begin() {
    current = waiting.front();
    waiting.pop_front();
    fromSearch = toSearch = detail::EndSearch{};
    filter = &filters[0];
    if (!waitingHeights.empty()) {
      const Layered& l = waitingHeights.front();
      fromSearch = detail::endSearch(*mesh, l.fromHeight);
      toSearch = detail::endSearch(*mesh, l.toHeight);
      filter = &filters[l.costClass < filters.size() ? l.costClass : 0];
      waitingHeights.pop_front();
    }
    const dtPolyRef startRef =
        detail::snapEnd(*query, *filter, current.from, fromSearch, start);
    if (startRef == 0) {
      finish(current.ticket, PathResult{PathStatus::Failed, {}});
      return false;
    }
    endRef = detail::snapEnd(*query, *filter, current.to, toSearch, end);
    if (endRef == 0) {
      finish(current.ticket, PathResult{PathStatus::Partial, {detail::fromRecast(start)}});
      return false;
    }
    if (dtStatusFailed(query->initSlicedFindPath(startRef, endRef, start, end, filter, 0))) {
      finish(current.ticket, PathResult{PathStatus::Failed, {}});
      return false;
    }
    active = true;
    return true;
  }

  void complete(dtStatus searchStatus) {
    active = false;
    PathResult result;
    int count = 0;
    const dtStatus status = query->finalizeSlicedFindPath(polys.data(), &count, detail::kMaxPathPolys);
    if (dtStatusFailed(searchStatus) || dtStatusFailed(status) || count == 0) {
      finish(current.ticket, std::move(result));
      return;
    }
    const bool partial = dtStatusDetail(status, DT_PARTIAL_RESULT) || polys[count - 1] != endRef;
    result.status = detail::straighten(*query, start, end, polys.data(), count, partial, result.corners);
    finish(current.ticket, std::move(result));
  }
};

PathQueue::PathQueue(std::shared_ptr<const NavMesh> mesh, int maxNodes) : impl_(std::make_unique<Impl>()) {
  impl_->mesh = std::move(mesh);
  impl_->query = dtAllocNavMeshQuery();
  impl_->query->init(impl_->mesh->detour(), std::clamp(maxNodes, 16, 65535));
}

PathQueue::~PathQueue() = default;

PathTicket PathQueue::request(Vec2 from, Vec2 to) {
  const PathTicket ticket = impl_->nextTicket++;
  impl_->waiting.push_back(Request{ticket, from, to});
  if (impl_->mesh->layered()) impl_->waitingHeights.push_back({});
  return ticket;
}

PathTicket PathQueue::request(Vec2 from, float fromHeight, Vec2 to, float toHeight, std::uint32_t costClass) {
  const PathTicket ticket = impl_->nextTicket++;
  impl_->waiting.push_back(Request{ticket, from, to});
  if (impl_->mesh->layered()) impl_->waitingHeights.push_back({fromHeight, toHeight, costClass});
  return ticket;
}

void PathQueue::setStairCosts(std::span<const float> stairCost) {
  Impl& q = *impl_;
  if (q.filters.size() < stairCost.size()) q.filters.resize(stairCost.size());
  for (std::size_t i = 0; i < stairCost.size(); ++i) {
    THRONG_ASSERT(std::isfinite(stairCost[i]) && stairCost[i] >= 1.0f);
    q.filters[i].setAreaCost(kStairArea, stairCost[i]);
  }
  q.costClasses = std::max(q.costClasses, stairCost.size());
}

std::size_t PathQueue::costClasses() const { return impl_->costClasses; }

int PathQueue::update(int iterationBudget) {
  Impl& q = *impl_;
  ++q.updates;
  // Expire results nobody took.
  for (auto it = q.finished.begin(); it != q.finished.end();) {
    if (q.updates - it->second.doneAtUpdate > kResultLifetimeUpdates)
      it = q.finished.erase(it);
    else
      ++it;
  }
  int completed = 0;
  int budget = std::max(iterationBudget, 1);  // always progress
  while (budget > 0 && (q.active || !q.waiting.empty())) {
    if (!q.active && !q.begin()) {  // finished at once: an end is off the mesh
      ++completed;
      continue;
    }
    int done = 0;
    const dtStatus status = q.query->updateSlicedFindPath(budget, &done);
    budget -= std::max(done, 1);
    if (dtStatusInProgress(status)) continue;
    q.complete(status);
    ++completed;
  }
  return completed;
}

TicketState PathQueue::state(PathTicket ticket) const {
  const Impl& q = *impl_;
  if (q.finished.count(ticket)) return TicketState::Done;
  if (q.active && q.current.ticket == ticket) return TicketState::Pending;
  // Waiting tickets are increasing from front to back.
  if (!q.waiting.empty() && ticket >= q.waiting.front().ticket && ticket <= q.waiting.back().ticket)
    return TicketState::Pending;
  return TicketState::Unknown;
}

PathResult PathQueue::take(PathTicket ticket) {
  auto it = impl_->finished.find(ticket);
  if (it == impl_->finished.end()) return PathResult{};  // precondition violated: Failed, no corners
  PathResult result = std::move(it->second.result);
  impl_->finished.erase(it);
  return result;
}

std::size_t PathQueue::pending() const { return impl_->waiting.size() + (impl_->active ? 1u : 0u); }

}  // namespace throng::nav
