// Tests for libs/crowd/src/path_reconstruction.cpp: §3.1.2 paths automatic reconstruction.
#include "throng/crowd/path_reconstruction.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "crowd_test_util.hpp"

namespace crowd = throng::crowd;
namespace core = throng::core;
using core::Vec2;

TEST(ReconstructPath, SnapsNearInterestPointsInOrder) {
  const std::vector<crowd::Region> ips{crowd::Region::disc({12, -0.5f}, 1.0f), crowd::Region::disc({5, 0.5f}, 1.0f),
                                       crowd::Region::disc({10, 15}, 1.0f)};
  crowd::ReconstructParams p;
  p.bezier.maxBend = 0.0f;  // straight: the curve passes 0.5 m from both near IPs
  p.maxChordError = 0.05f;
  core::Rng rng(1, 1, core::RngPurpose::Goal);
  // Straight curves flatten to their two ends: use a bent-but-flat cubic by sampling finely instead.
  const auto path = crowd::reconstructPath({0, 0}, {20, 0}, ips, 0.5f, p, rng);
  ASSERT_TRUE(path.has_value());
  // A straight line samples to its two endpoints, neither near an IP.
  EXPECT_TRUE(path->visited.empty());

  p.bezier.maxBend = 0.02f;  // a slight bend: many samples along the line
  p.maxChordError = 0.001f;
  core::Rng rng2(1, 1, core::RngPurpose::Goal);
  const auto bent = crowd::reconstructPath({0, 0}, {20, 0}, ips, 0.5f, p, rng2);
  ASSERT_TRUE(bent.has_value());
  ASSERT_EQ(bent->visited.size(), 2u);
  EXPECT_EQ(bent->visited[0], 1u);  // (5, 0.5) comes first along the way
  EXPECT_EQ(bent->visited[1], 0u);
  EXPECT_EQ(bent->points.front(), Vec2(0, 0));
  EXPECT_EQ(bent->points.back(), Vec2(20, 0));
  int snapped = 0;
  for (std::size_t i = 0; i < bent->points.size(); ++i) {
    if (bent->pointRegion[i] == crowd::kNoRegion) continue;
    ++snapped;
    EXPECT_EQ(bent->points[i], ips[static_cast<std::size_t>(bent->pointRegion[i])].centre);
  }
  EXPECT_EQ(snapped, 2);
}

TEST(ReconstructPath, WithAWalkableTestFailsLikeBuildPath) {
  const crowd::PolygonWalkable rooms({crowd::testing::rect(0, 0, 20, 10)},
                                     {crowd::testing::rect(9.9f, 0, 10.1f, 10)});
  core::Rng rng(2, 1, core::RngPurpose::Goal);
  EXPECT_FALSE(crowd::reconstructPath({5, 5}, {15, 5}, {}, 1.0f, {}, rng, &rooms).has_value());
  const auto ok = crowd::reconstructPath({2, 5}, {8, 5}, {}, 1.0f, {}, rng, &rooms);
  ASSERT_TRUE(ok.has_value());
  EXPECT_TRUE(ok->visited.empty());
}

// Invariants of the reconstruction over random interest points: unsnapped points are farther than
// nearDistance from every IP, snapped points are their IP's centre, `visited` lists the snapped
// entries in order, no IP appears twice in a row, and the same stream gives the same path.
RC_GTEST_PROP(ReconstructPath, SnappingInvariants, (std::uint64_t seed)) {
  core::Rng gen(seed, 0, core::RngPurpose::Bench);
  std::vector<crowd::Region> ips;
  const int n = static_cast<int>(gen.uniformInt(0, 8));
  for (int i = 0; i < n; ++i) {
    const Vec2 c{float(gen.uniform(0, 30)), float(gen.uniform(-8, 8))};
    if (gen.uniform() < 0.5) {
      ips.push_back(crowd::Region::disc(c, float(gen.uniform(0, 2))));
    } else {
      ips.push_back(crowd::Region::poly(crowd::testing::randomStar(gen, c, 6, 0.5f, 2.0f)));
    }
  }
  const float near = float(gen.uniform(0, 2));
  crowd::ReconstructParams p;
  p.maxChordError = 0.05f;
  core::Rng r1(seed, 1, core::RngPurpose::Goal);
  core::Rng r2(seed, 1, core::RngPurpose::Goal);
  const auto a = crowd::reconstructPath({0, 0}, {30, 0}, ips, near, p, r1);
  const auto b = crowd::reconstructPath({0, 0}, {30, 0}, ips, near, p, r2);
  RC_ASSERT(a.has_value() && b.has_value());
  RC_ASSERT(a->points == b->points);
  RC_ASSERT(a->points.size() == a->pointRegion.size());
  std::vector<std::uint32_t> snapped;
  for (std::size_t i = 0; i < a->points.size(); ++i) {
    const auto reg = a->pointRegion[i];
    if (reg == crowd::kNoRegion) {
      for (const auto& ip : ips) RC_ASSERT(crowd::distanceToRegion(ip, a->points[i]) > near);
    } else {
      RC_ASSERT(a->points[i] == ips[static_cast<std::size_t>(reg)].centre);
      if (i > 0) RC_ASSERT(a->pointRegion[i - 1] != reg);
      snapped.push_back(static_cast<std::uint32_t>(reg));
    }
  }
  RC_ASSERT(snapped == a->visited);
}
