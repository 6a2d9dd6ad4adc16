// Tests for libs/sim/src/group_table.cpp: groups, cold parts, routes and the busy set.
#include "group_table.hpp"

#include <gtest/gtest.h>

using namespace throng;

TEST(GroupTable, ColdPartsAndRoutesExistOnlyForGroupsThatNeedThem) {
  sim::GroupTable t;
  for (int i = 0; i < 4; ++i) EXPECT_EQ(t.add(sim::GroupState{}), static_cast<std::uint32_t>(i));
  EXPECT_EQ(t.size(), 4u);
  // Lone groups read the defaults and own nothing.
  EXPECT_EQ(t[1].extra, sim::kNoIndex);
  EXPECT_FALSE(t.hasRoute(t[1]));
  EXPECT_EQ(t.routeOf(t[1]).followGroup, sim::kNoGroup);
  // A route makes the group busy and gives it a cold part; asking again returns the same route.
  t.routeFor(2).followGroup = 0;
  EXPECT_TRUE(t[2].busy);
  EXPECT_TRUE(t.hasRoute(t[2]));
  EXPECT_EQ(t.routeFor(2).followGroup, 0u);
  EXPECT_EQ(t.routeOf(t[2]).followGroup, 0u);
  // Common Ground gives any group a cold part without making it busy.
  t.giveExtra(3);
  EXPECT_NE(t[3].extra, sim::kNoIndex);
  EXPECT_FALSE(t[3].busy);
  EXPECT_FALSE(t.hasRoute(t[3]));
  t.extraOf(t[3]).waiting = true;
  EXPECT_TRUE(t.extraOf(static_cast<const sim::GroupTable&>(t)[3]).waiting);
}

TEST(GroupTable, TheBusySetChangesOnlyWhenRefreshed) {
  sim::GroupTable t;
  for (int i = 0; i < 5; ++i) t.add(sim::GroupState{});
  t.markBusy(3);
  t.markBusy(1);
  EXPECT_TRUE(t.busy().empty()) << "groups join the busy set at the next refresh";
  t.refreshBusy();
  EXPECT_EQ(t.busy(), (std::vector<std::uint32_t>{1, 3})) << "ascending group ids";
  // Marked during a pass (the list is being iterated): the list stays as it is until the refresh.
  const std::vector<std::uint32_t>& during = t.busy();
  t.markBusy(0);
  EXPECT_EQ(during, (std::vector<std::uint32_t>{1, 3}));
  t.refreshBusy();
  EXPECT_EQ(t.busy(), (std::vector<std::uint32_t>{0, 1, 3}));
  t.markBusy(3);  // already busy: nothing to rebuild
  t.refreshBusy();
  EXPECT_EQ(t.busy(), (std::vector<std::uint32_t>{0, 1, 3}));
}

TEST(GroupTable, ManySmallInsertionsGrowTheTableGeometrically) {
  sim::GroupTable t;
  std::size_t reallocations = 0;
  const sim::GroupState* before = nullptr;
  for (std::uint32_t i = 0; i < 20000; ++i) {
    t.reserve(t.size() + 1, 0);  // one group per run-time insertion
    t.add(sim::GroupState{});
    if (&t[0] != before) ++reallocations;
    before = &t[0];
  }
  EXPECT_LT(reallocations, 40u) << "exact reserves per insertion would copy the table every time";
}
