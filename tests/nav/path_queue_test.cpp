// Tests for throng::nav::PathQueue (libs/nav/src/path_queue.cpp): budgeted progress across
// updates, FIFO completion, equality with NavQuery::findPath, ticket expiry.
#include "throng/nav/path_queue.hpp"

#include <gtest/gtest.h>

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
