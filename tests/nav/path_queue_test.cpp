// Tests for throng::nav::PathQueue (libs/nav/src/path_queue.cpp): budgeted progress across
// updates, FIFO completion, equality with NavQuery::findPath, ticket expiry, and the parallel
// update (searches ahead on a TaskSystem) completing every request as one thread does.
#include "throng/nav/path_queue.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>

#include "nav_test_worlds.hpp"
#include "throng/core/rng.hpp"

namespace throng::nav {
namespace {
using testing::buildOrFail;
using testing::rect;

std::shared_ptr<const NavMesh> pillarWorld() {
  return buildOrFail({rect(0, 0, 100, 100)}, testing::pillars(100, 6));
}

TEST(PathQueue, SmallBudgetCompletesAcrossUpdatesAndMatchesFindPath) {
  auto mesh = pillarWorld();
  ASSERT_TRUE(mesh);
  PathQueue queue(mesh);
  NavQuery query(mesh);
  core::Rng rng(3, 0, core::RngPurpose::Bench);
  struct Req { PathTicket ticket; Vec2 from, to; };
  std::vector<Req> reqs;
  for (int i = 0; i < 20; ++i) {
    const Vec2 from{static_cast<float>(rng.uniform(1, 99)), static_cast<float>(rng.uniform(1, 99))};
    const Vec2 to{static_cast<float>(rng.uniform(1, 99)), static_cast<float>(rng.uniform(1, 99))};
    reqs.push_back({queue.request(from, to), from, to});
  }
  reqs.push_back({queue.request({500, 500}, {5, 5}), {500, 500}, {5, 5}});  // off the mesh
  EXPECT_EQ(queue.pending(), reqs.size());
  for (const Req& r : reqs) EXPECT_EQ(queue.state(r.ticket), TicketState::Pending);

  int updates = 0;
  int completed = 0;
  std::size_t nextDone = 0;
  std::vector<PathResult> results;
  while (queue.pending() > 0) {
    completed += queue.update(25);
    ++updates;
    ASSERT_LT(updates, 10000);
    // Served in submission order: completed tickets form a prefix. Take them as they finish
    // (unread results expire after 64 updates).
    while (nextDone < reqs.size() && queue.state(reqs[nextDone].ticket) == TicketState::Done) {
      results.push_back(queue.take(reqs[nextDone].ticket));
      EXPECT_EQ(queue.state(reqs[nextDone].ticket), TicketState::Unknown);  // taken: forgotten
      ++nextDone;
    }
    for (std::size_t k = nextDone; k < reqs.size(); ++k) EXPECT_EQ(queue.state(reqs[k].ticket), TicketState::Pending);
  }
  EXPECT_EQ(completed, static_cast<int>(reqs.size()));
  ASSERT_EQ(results.size(), reqs.size());
  EXPECT_GT(updates, static_cast<int>(reqs.size()));  // the budget really slices the work

  for (std::size_t k = 0; k < reqs.size(); ++k) {
    std::vector<Vec2> direct;
    const PathStatus status = query.findPath(reqs[k].from, reqs[k].to, direct);
    EXPECT_EQ(results[k].status, status) << k;
    EXPECT_EQ(results[k].corners, direct) << k;
  }
  EXPECT_EQ(results.back().status, PathStatus::Failed);
  EXPECT_EQ(queue.take(reqs.back().ticket).status, PathStatus::Failed);  // unknown ticket
}

TEST(PathQueue, UnreadResultsExpire) {
  auto mesh = buildOrFail({rect(0, 0, 10, 10)}, {});
  ASSERT_TRUE(mesh);
  PathQueue queue(mesh);
  const PathTicket ticket = queue.request({1, 1}, {9, 9});
  queue.update(100);
  ASSERT_EQ(queue.state(ticket), TicketState::Done);
  int updates = 0;
  while (queue.state(ticket) == TicketState::Done && updates < 1000) {
    queue.update(100);
    ++updates;
  }
  EXPECT_EQ(queue.state(ticket), TicketState::Unknown);
  EXPECT_GE(updates, 10);
  EXPECT_LE(updates, 200);
  EXPECT_EQ(queue.state(12345), TicketState::Unknown);
}

TEST(PathQueue, ZeroBudgetStillProgresses) {
  auto mesh = buildOrFail({rect(0, 0, 10, 10)}, {});
  ASSERT_TRUE(mesh);
  PathQueue queue(mesh);
  const PathTicket ticket = queue.request({1, 1}, {9, 9});
  for (int i = 0; i < 100 && queue.state(ticket) == TicketState::Pending; ++i) queue.update(0);
  ASSERT_EQ(queue.state(ticket), TicketState::Done);
  EXPECT_EQ(queue.take(ticket).status, PathStatus::Complete);
}

}  // namespace
}  // namespace throng::nav

namespace throng::nav {
namespace {

/// What one update did: how many completed, and every ticket's state and (when taken) result.
struct UpdateTrace {
  int completed = 0;
  std::vector<TicketState> states;
  std::vector<std::pair<PathTicket, PathResult>> taken;
};

/// Feeds `queue` the same stream of requests and budgets for every queue (seeded), taking each
/// finished result; the trace says what happened in each update.
/// `toggle`, when given, runs before every 23rd update (a door closing or opening under way).
std::vector<UpdateTrace> drive(PathQueue& queue, const core::TaskSystem* tasks,
                               const std::function<void(int)>& toggle = nullptr) {
  core::Rng rng(11, 0, core::RngPurpose::Bench);
  std::vector<PathTicket> open;
  std::vector<UpdateTrace> trace;
  for (int u = 0; u < 1000; ++u) {
    if (toggle && u % 23 == 0) toggle(u / 23);
    const int arrivals = u < 300 ? static_cast<int>(rng.uniform(0, 9)) : 0;
    for (int k = 0; k < arrivals; ++k) {
      Vec2 from{static_cast<float>(rng.uniform(1, 99)), static_cast<float>(rng.uniform(1, 99))};
      Vec2 to{static_cast<float>(rng.uniform(1, 99)), static_cast<float>(rng.uniform(1, 99))};
      const double kind = rng.uniform(0, 1);
      if (kind < 0.05) from = {400, 400};                    // start off the mesh: Failed at once
      else if (kind < 0.10) to = {-300, 50};                 // end off the mesh: Partial at once
      else if (kind < 0.15) to = {from.x + 0.01f, from.y};   // one polygon: no expansion at all
      open.push_back(queue.request(from, to));
    }
    UpdateTrace t;
    t.completed = queue.update(static_cast<int>(rng.uniform(1, 600)), tasks);
    for (PathTicket ticket : open) t.states.push_back(queue.state(ticket));
    for (std::size_t k = 0; k < open.size();) {
      if (queue.state(open[k]) == TicketState::Done && rng.uniform(0, 1) < 0.9) {  // some read late
        t.taken.emplace_back(open[k], queue.take(open[k]));
        open.erase(open.begin() + static_cast<std::ptrdiff_t>(k));
      } else {
        ++k;
      }
    }
    trace.push_back(std::move(t));
  }
  return trace;
}

/// Expects both traces to be the same, update by update; returns (results taken, pending ticket-updates).
std::pair<std::size_t, std::size_t> expectSameTraces(const std::vector<UpdateTrace>& a, const std::vector<UpdateTrace>& b) {
  EXPECT_EQ(a.size(), b.size());
  std::size_t results = 0, sliced = 0;
  for (std::size_t u = 0; u < std::min(a.size(), b.size()); ++u) {
    EXPECT_EQ(a[u].completed, b[u].completed) << "update " << u;
    EXPECT_EQ(a[u].states, b[u].states) << "update " << u;
    if (a[u].taken.size() != b[u].taken.size()) {
      ADD_FAILURE() << "update " << u << ": " << a[u].taken.size() << " vs " << b[u].taken.size() << " results";
      return {results, sliced};
    }
    for (std::size_t k = 0; k < a[u].taken.size(); ++k) {
      EXPECT_EQ(a[u].taken[k].first, b[u].taken[k].first);
      EXPECT_EQ(a[u].taken[k].second.status, b[u].taken[k].second.status);
      if (a[u].taken[k].second.corners.size() != b[u].taken[k].second.corners.size()) {
        ADD_FAILURE() << "update " << u << ", ticket " << a[u].taken[k].first << ": different paths";
        return {results, sliced};
      }
      for (std::size_t c = 0; c < a[u].taken[k].second.corners.size(); ++c) {
        EXPECT_EQ(a[u].taken[k].second.corners[c].x, b[u].taken[k].second.corners[c].x);
        EXPECT_EQ(a[u].taken[k].second.corners[c].y, b[u].taken[k].second.corners[c].y);
      }
      ++results;
    }
    for (TicketState st : a[u].states) sliced += st == TicketState::Pending ? 1 : 0;
  }
  return {results, sliced};
}

TEST(PathQueue, ParallelSearchCompletesTheSameRequestsInTheSameUpdatesAsOneThread) {
  auto mesh = pillarWorld();
  ASSERT_TRUE(mesh);
  PathQueue serial(mesh), parallel(mesh);
  const core::TaskSystem one(1), four(4);
  const std::vector<UpdateTrace> a = drive(serial, &one);
  const std::vector<UpdateTrace> b = drive(parallel, &four);
  const auto [results, sliced] = expectSameTraces(a, b);
  EXPECT_GT(results, 1000u);  // the stream really ran through both queues
  EXPECT_GT(sliced, 1000u);   // and the budgets really left requests waiting across updates
  EXPECT_EQ(serial.pending(), 0u);
  EXPECT_EQ(parallel.pending(), 0u);
}

TEST(PathQueue, DoorsClosingUnderWayGiveTheSameResultsOnAnyThreadCount) {
  // The pillar world with a 2 m band across it at x 49..51 and two discs cut in (NavMeshConfig::cuts);
  // every 23rd update closes or opens some of them and restarts the searches under way
  // (PathQueue::restart). One thread and four must still complete the same requests in the same
  // updates with the same paths: without the restart, a search sliced over the change sees both
  // meshes on one thread and one of them on four.
  NavMeshConfig cfg;
  CutRegion band, a, b;
  band.polygon = rect(49, 0, 51, 100);
  a.centre = {25, 30};
  a.radius = 4;
  b.centre = {75, 70};
  b.radius = 4;
  cfg.cuts = {band, a, b};
  auto built = buildOrFail({rect(0, 0, 100, 100)}, testing::pillars(100, 6), cfg);
  ASSERT_TRUE(built);
  auto meshA = built->clone(), meshB = built->clone();
  std::vector<std::vector<PolyRef>> polys;
  for (const CutRegion& r : cfg.cuts) polys.push_back(built->cutPolygons(r));
  ASSERT_FALSE(polys[0].empty());
  PathQueue serial(meshA), parallel(meshB);
  const auto toggler = [&](NavMesh& mesh, PathQueue& queue) {
    return [&mesh, &queue, &polys](int k) {
      mesh.setClosed(polys[static_cast<std::size_t>(k) % 3], (k / 3) % 2 == 0);
      queue.restart();
    };
  };
  const core::TaskSystem one(1), four(4);
  const std::vector<UpdateTrace> ta = drive(serial, &one, toggler(*meshA, serial));
  const std::vector<UpdateTrace> tb = drive(parallel, &four, toggler(*meshB, parallel));
  const auto [results, sliced] = expectSameTraces(ta, tb);
  EXPECT_GT(results, 1000u);
  EXPECT_GT(sliced, 1000u);
}

}  // namespace
}  // namespace throng::nav
