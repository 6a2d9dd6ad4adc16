// Interest management: area of interest, detail tiers, the near cap, the far rate.
#include <gtest/gtest.h>

#include "throng/hub/interest.hpp"

namespace throng::hub {
namespace {

sim::Frame lineOfAgents(std::size_t n, float spacing) {
  sim::Frame f;
  for (std::size_t i = 0; i < n; ++i) {
    f.ids.push_back(static_cast<std::uint32_t>(i));
    f.posX.push_back(static_cast<float>(i) * spacing);
    f.posY.push_back(0.0f);
  }
  return f;
}

TEST(Interest, TiersFollowDistanceAndAreaOfInterestCutsOff) {
  const sim::Frame f = lineOfAgents(100, 1.0f);  // agents at x = 0, 1, ..., 99
  InterestOptions o;
  o.nearRadius = 3.0f;
  o.middleRadius = 10.0f;
  o.areaOfInterest = 20.0f;
  o.nearMax = 100;
  const core::Vec2 at{0.0f, 0.0f};
  std::vector<Interested> out;
  std::vector<std::pair<float, std::uint32_t>> scratch;
  selectInterest(f, &at, o, out, scratch);
  ASSERT_EQ(out.size(), 21u);  // x = 0..20
  for (const Interested& it : out) {
    const float x = f.posX[it.row];
    const Tier expected = x <= 3.0f ? Tier::Near : x <= 10.0f ? Tier::Middle : Tier::Far;
    EXPECT_EQ(it.tier, expected) << "agent at x=" << x;
  }
  for (std::size_t i = 1; i < out.size(); ++i) EXPECT_LT(out[i - 1].row, out[i].row);
}

TEST(Interest, NearCapKeepsTheClosest) {
  const sim::Frame f = lineOfAgents(50, 0.5f);  // x = 0 .. 24.5
  InterestOptions o;
  o.nearRadius = 5.0f;
  o.nearMax = 3;
  o.middleRadius = 10.0f;
  o.areaOfInterest = 30.0f;
  const core::Vec2 at{2.0f, 0.0f};  // closest: x = 2 (row 4), then 1.5 and 2.5 (rows 3, 5)
  std::vector<Interested> out;
  std::vector<std::pair<float, std::uint32_t>> scratch;
  selectInterest(f, &at, o, out, scratch);
  std::vector<std::uint32_t> nearRows;
  std::size_t far = 0;
  for (const Interested& it : out) {
    if (it.tier == Tier::Near) nearRows.push_back(it.row);
    if (it.tier == Tier::Far) ++far;
  }
  EXPECT_EQ(nearRows, (std::vector<std::uint32_t>{3, 4, 5}));
  EXPECT_EQ(far, 25u);  // x = 12.5 .. 24.5 (rows 25..49): beyond the middle radius, inside the area
}

TEST(Interest, NoViewpointIsAnOverviewOfEveryAgentAtMiddleDetail) {
  const sim::Frame f = lineOfAgents(10, 100.0f);
  std::vector<Interested> out;
  std::vector<std::pair<float, std::uint32_t>> scratch;
  selectInterest(f, nullptr, InterestOptions{}, out, scratch);
  ASSERT_EQ(out.size(), 10u);
  for (const Interested& it : out) EXPECT_EQ(it.tier, Tier::Middle);
}

}  // namespace
}  // namespace throng::hub
