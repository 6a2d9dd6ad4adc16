// Tests for libs/crowd/src/subregions.cpp: §3.1.3 sub-regions, priority choice and sampling.
#include "throng/crowd/subregions.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <set>

#include "crowd_test_util.hpp"

namespace crowd = throng::crowd;
namespace core = throng::core;
using core::Vec2;

namespace {

crowd::Region randomRegion(core::Rng& rng) {
  const Vec2 c{float(rng.uniform(-50, 50)), float(rng.uniform(-50, 50))};
  switch (rng.uniformInt(0, 3)) {
    case 0: return crowd::Region::disc(c, float(rng.uniform(0.3, 12)));
    case 1: {
      const float w = float(rng.uniform(0.5, 25)), h = float(rng.uniform(0.5, 25));
      return crowd::Region::poly(crowd::testing::rect(c.x, c.y, c.x + w, c.y + h));
    }
    case 2: {
      const float w = float(rng.uniform(2, 20)), h = float(rng.uniform(2, 20));
      const float cx = float(rng.uniform(0.3, 0.7)) * w, cy = float(rng.uniform(0.3, 0.7)) * h;
      return crowd::Region::poly({{c.x, c.y}, {c.x + w, c.y}, {c.x + w, c.y + cy}, {c.x + cx, c.y + cy},
                                  {c.x + cx, c.y + h}, {c.x, c.y + h}});
    }
    default: return crowd::Region::poly(crowd::testing::randomStar(rng, c, int(rng.uniformInt(3, 12)), 0.5f, 10.0f));
  }
}

}  // namespace

TEST(Subregions, DiscCountsFollowTheRule) {
  // n = 4 k², k = ceil(sqrt(max(4, ceil(A / 4 m²)) / 4)).
  EXPECT_EQ(crowd::divideRegion(crowd::Region::disc({0, 0}, 1.0f)).size(), 4u);   // A = 3.1 m²
  EXPECT_EQ(crowd::divideRegion(crowd::Region::disc({0, 0}, 2.2f)).size(), 4u);   // A = 15.2 m²: 4
  EXPECT_EQ(crowd::divideRegion(crowd::Region::disc({0, 0}, 2.3f)).size(), 16u);  // A = 16.6 m²: 5 → k = 2
  EXPECT_EQ(crowd::divideRegion(crowd::Region::disc({0, 0}, 5.0f)).size(), 36u);  // A = 78.5 m²: 20 → k = 3
  const auto subs = crowd::divideRegion(crowd::Region::disc({0, 0}, 5.0f));
  for (const auto& s : subs) EXPECT_NEAR(s.area, 78.539816f / 36.0f, 1e-3f);
  const auto point = crowd::divideRegion(crowd::Region::disc({3, 4}, 0.0f));
  ASSERT_EQ(point.size(), 1u);
  core::Rng rng(1, 1, core::RngPurpose::Target);
  EXPECT_EQ(crowd::samplePoint(point[0], rng), Vec2(3, 4));
}

TEST(Subregions, SquareSplitsIntoAtLeastFourCells) {
  const auto small = crowd::divideRegion(crowd::Region::poly(crowd::testing::rect(0, 0, 2, 2)));
  EXPECT_EQ(small.size(), 4u);
  const auto big = crowd::divideRegion(crowd::Region::poly(crowd::testing::rect(0, 0, 10, 6)));
  EXPECT_EQ(big.size(), 15u);  // 2 m cells
  EXPECT_TRUE(crowd::divideRegion(crowd::Region::poly({{0, 0}, {1, 1}, {2, 2}})).empty());  // zero area
}

// Sub-regions partition the region: there are at least four, their areas add up to the region's,
// every point of the region lies in one, and points sampled in a sub-region lie in it and in the region.
RC_GTEST_PROP(Subregions, PartitionTheRegion, (std::uint64_t seed)) {
  core::Rng rng(seed, 0, core::RngPurpose::Bench);
  const auto region = randomRegion(rng);
  const auto subs = crowd::divideRegion(region);
  RC_ASSERT(subs.size() >= 4u);
  double total = 0.0;
  for (const auto& s : subs) {
    RC_ASSERT(s.area > 0.0f);
    total += s.area;
    for (int k = 0; k < 10; ++k) {
      const Vec2 p = crowd::samplePoint(s, rng);
      RC_ASSERT(crowd::subregionContains(s, p));
      RC_ASSERT(crowd::distanceToRegion(region, p) < 1e-3f);
    }
  }
  const double area = crowd::regionArea(region);
  RC_ASSERT(std::abs(total - area) <= 1e-3 * area + 1e-4);
  const auto b = crowd::regionBounds(region);
  for (int k = 0; k < 100; ++k) {
    const Vec2 p{float(rng.uniform(b.min.x, b.max.x)), float(rng.uniform(b.min.y, b.max.y))};
    if (!crowd::regionContains(region, p)) continue;
    RC_ASSERT(std::any_of(subs.begin(), subs.end(), [&](const auto& s) { return crowd::subregionContains(s, p); }));
  }
}

/// The sub-regions pickSubregion may choose from `from`: those whose centre is at most
/// max(detourMin, detourFraction · nearest) farther than the nearest centre.
std::vector<std::size_t> candidates(const std::vector<crowd::Subregion>& subs, Vec2 from,
                                    const crowd::PickParams& params) {
  float nearest = 1e30f;
  for (const auto& s : subs) nearest = std::min(nearest, core::distance(s.centre, from));
  const float reach = nearest + std::max(params.detourMin, params.detourFraction * nearest);
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < subs.size(); ++i) {
    if (core::distance(subs[i].centre, from) <= reach) out.push_back(i);
  }
  return out;
}

// Members of a group assigned in turn, occupancy updated after each, take only candidates (the
// near side of the region) and never share one while a free candidate exists; once all are taken,
// everyone still gets one.
RC_GTEST_PROP(Subregions, GroupMembersNeverShareWhileFreeCandidatesExist, (std::uint64_t seed)) {
  core::Rng rng(seed, 0, core::RngPurpose::Bench);
  const auto region = randomRegion(rng);
  const auto subs = crowd::divideRegion(region);
  RC_PRE(!subs.empty());
  const Vec2 from{float(rng.uniform(-80, 80)), float(rng.uniform(-80, 80))};
  const crowd::PickParams params;
  const std::vector<std::size_t> near = candidates(subs, from, params);
  RC_ASSERT(!near.empty());
  std::vector<std::uint32_t> occupancy(subs.size(), 0);
  const std::size_t members = near.size() + rng.uniformInt(0, 5);
  std::set<std::size_t> taken;
  for (std::size_t m = 0; m < members; ++m) {
    const std::size_t i = crowd::pickSubregion(subs, from, occupancy, rng, params);
    RC_ASSERT(std::find(near.begin(), near.end(), i) != near.end());
    if (m < near.size()) RC_ASSERT(occupancy[i] == 0u);
    ++occupancy[i];
    taken.insert(i);
  }
  RC_ASSERT(taken.size() == near.size());
}

TEST(Subregions, FreeSubregionsAreTakenNearestFirstWithoutJitter) {
  const auto subs = crowd::divideRegion(crowd::Region::disc({0, 0}, 5.0f));
  std::vector<std::uint32_t> occupancy(subs.size(), 0);
  crowd::PickParams params;
  params.jitter = 0.0f;
  core::Rng rng(3, 3, core::RngPurpose::Target);
  const Vec2 from{20, 0};
  std::size_t nearest = 0;
  for (std::size_t i = 1; i < subs.size(); ++i) {
    if (core::distance(subs[i].centre, from) < core::distance(subs[nearest].centre, from)) nearest = i;
  }
  EXPECT_EQ(crowd::pickSubregion(subs, from, occupancy, rng, params), nearest);
  occupancy[nearest] = 1;
  const std::size_t second = crowd::pickSubregion(subs, from, occupancy, rng, params);
  EXPECT_NE(second, nearest);
  EXPECT_GT(subs[second].centre.x, 0.0f) << "the next pick is still on the near side";
}

TEST(Subregions, AFarFreeSubregionNeverBeatsANearOccupiedOne) {
  // A 200 m × 0.5 m exit strip seen from 50 m in front of its left end (RiMEA 7's wide exit): 50
  // agents picking in turn stay where the walk is at most 5 % longer than straight ahead, about
  // 16 m along the strip (the old density-first rule took every free 2 m cell first, up to ~100 m).
  const auto subs = crowd::divideRegion(crowd::Region::poly(crowd::testing::rect(0, 50, 200, 50.5f)));
  std::vector<std::uint32_t> occupancy(subs.size(), 0);
  core::Rng rng(5, 5, core::RngPurpose::Target);
  const Vec2 from{2, 0};
  float farthest = 0.0f;
  for (int m = 0; m < 50; ++m) {
    const std::size_t i = crowd::pickSubregion(subs, from, occupancy, rng);
    ++occupancy[i];
    farthest = std::max(farthest, std::abs(subs[i].centre.x - from.x));
  }
  EXPECT_LE(farthest, 17.0f) << "along the strip";
  EXPECT_GE(farthest, 10.0f) << "the near side still spreads the 50";
}

TEST(Subregions, AGoalSmallAgainstItsDistanceIsOpenWhole) {
  // 10 m exit strip 24 m away (RiMEA 16's corridor-wide exit): every sub-region is a candidate, so
  // twice as many agents as sub-regions fill each one twice, the far corners too.
  const auto subs = crowd::divideRegion(crowd::Region::poly(crowd::testing::rect(24, 0, 24.5f, 10)));
  std::vector<std::uint32_t> occupancy(subs.size(), 0);
  core::Rng rng(6, 6, core::RngPurpose::Target);
  for (std::size_t m = 0; m < 2 * subs.size(); ++m) ++occupancy[crowd::pickSubregion(subs, {0, 5}, occupancy, rng)];
  for (const std::uint32_t o : occupancy) EXPECT_EQ(o, 2u);
}

TEST(Subregions, DeterministicForAGivenSeed) {
  const auto region = crowd::Region::poly({{0, 0}, {12, 0}, {12, 5}, {5, 5}, {5, 9}, {0, 9}});
  auto run = [&](std::uint64_t entity) {
    const auto subs = crowd::divideRegion(region);
    std::vector<std::uint32_t> occupancy(subs.size(), 0);
    core::Rng rng(42, entity, core::RngPurpose::Target);
    std::vector<Vec2> out;
    for (int m = 0; m < 8; ++m) {
      const std::size_t i = crowd::pickSubregion(subs, {-3, 4}, occupancy, rng);
      ++occupancy[i];
      out.push_back(crowd::samplePoint(subs[i], rng));
    }
    return out;
  };
  EXPECT_EQ(run(1), run(1));
  EXPECT_NE(run(1), run(2));
}

TEST(Subregions, SectorSamplesAreUniform) {
  // The mean of uniform samples approaches the sector's centroid.
  const auto subs = crowd::divideRegion(crowd::Region::disc({0, 0}, 5.0f));
  core::Rng rng(7, 7, core::RngPurpose::Target);
  for (std::size_t i : {std::size_t{0}, std::size_t{10}, subs.size() - 1}) {
    double sx = 0, sy = 0;
    const int n = 4000;
    for (int k = 0; k < n; ++k) {
      const Vec2 p = crowd::samplePoint(subs[i], rng);
      sx += p.x;
      sy += p.y;
    }
    EXPECT_NEAR(sx / n, subs[i].centre.x, 0.05);
    EXPECT_NEAR(sy / n, subs[i].centre.y, 0.05);
  }
}
