// Tests for libs/sim/src/common_ground_state.cpp: point categories indexed once for creation and
// run-time insertion, and what populations and needs want of them.
#include "common_ground_state.hpp"

#include <gtest/gtest.h>

using namespace throng;

namespace {

sim::PointDesc point(const char* id, const char* category) {
  sim::PointDesc p;
  p.id = id;
  p.category = category;
  return p;
}

}  // namespace

TEST(CommonGroundState, CategoriesAreIndexedInPointOrderAndExtendedByLaterPoints) {
  std::vector<sim::PointDesc> points{point("a", "shoes"), point("b", ""), point("c", "restroom"), point("d", "shoes")};
  sim::CommonGroundState cg;
  cg.addPoints(points, 0);
  EXPECT_EQ(cg.categories, (std::vector<std::string>{"shoes", "restroom"}));
  EXPECT_EQ(cg.pointCategory, (std::vector<std::int32_t>{0, -1, 1, 0}));
  EXPECT_EQ(cg.categoryPoints[0], (std::vector<std::uint32_t>{0, 3}));
  EXPECT_EQ(cg.categoryIndex("restroom"), 1);
  EXPECT_EQ(cg.categoryIndex("cafe"), -1);
  // A crowd inserted later brings a known category and a new one; earlier indices stay.
  points.push_back(point("e", "cafe"));
  points.push_back(point("f", "restroom"));
  cg.addPoints(points, 4);
  EXPECT_EQ(cg.categories, (std::vector<std::string>{"shoes", "restroom", "cafe"}));
  EXPECT_EQ(cg.pointCategory, (std::vector<std::int32_t>{0, -1, 1, 0, 2, 1}));
  EXPECT_EQ(cg.categoryPoints[1], (std::vector<std::uint32_t>{2, 5}));
}

TEST(CommonGroundState, AttractionsAreThePlacesSomePopulationWantsAndNeedsFindTheirCategory) {
  sim::ScenarioDesc desc;
  desc.points = {point("a", "shoes"), point("b", "restroom"), point("c", "cafe"), point("d", "")};
  sim::PopulationDesc shoppers;
  shoppers.interests = {"shoes"};
  sim::PopulationDesc tourists;
  tourists.interests = {"cafe", "museum"};
  desc.populations = {shoppers, tourists};
  sim::NeedDesc restroom;
  restroom.category = "restroom";
  sim::NeedDesc missing;
  missing.category = "bank";
  desc.social.needs = {restroom, missing};
  sim::CommonGroundState cg;
  cg.addPoints(desc.points, 0);
  cg.refreshInterests(desc);
  EXPECT_EQ(cg.attractionPoints, (std::vector<std::uint32_t>{0, 2}));
  EXPECT_EQ(cg.needCategory, (std::vector<std::int32_t>{1, -1}));
  // Again after a population interested in restrooms arrives: recomputed, not appended.
  sim::PopulationDesc visitors;
  visitors.interests = {"restroom"};
  desc.populations.push_back(visitors);
  cg.refreshInterests(desc);
  EXPECT_EQ(cg.attractionPoints, (std::vector<std::uint32_t>{0, 1, 2}));
  EXPECT_EQ(cg.needCategory.size(), 2u);
}
