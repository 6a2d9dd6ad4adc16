// Tests of libs/common_ground/src/relations.cpp: every relation A1..A6 from a constructed configuration,
// approach points x_i (pointInView) and x_j (pointInHearing), and the relation → attention
// micro-behaviour table's consistency with what B perceives.
#include "throng/common_ground/relations.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace throng::common_ground {
namespace {

Body at(float x, float y, Vec2 facing = {0.0f, 1.0f}, float radius = 0.2f) { return {{x, y}, facing, radius}; }

const SensoryParams kParams{};
const NoOcclusion kOpen{};
// B stands at the origin facing +y in every configuration below.
const Body kB = at(0, 0);

struct Config {
  const char* name;
  Body a;
  Relation expected;
};

std::vector<Config> configs() {
  return {
      {"touching beside B", at(0.4f, 0, {-1, 0}), Relation::A1},
      {"touching behind B", at(0, -0.45f), Relation::A1},
      {"face to face at 5 m", at(0, 5, {0, -1}), Relation::A2},
      {"behind B at 10 m, facing B", at(0, -10, {0, 1}), Relation::A3},
      {"behind B at 5 m", at(0, -5, {0, 1}), Relation::A4},
      {"in front of B at 15 m", at(0, 15, {0, -1}), Relation::A5},
      {"behind B at 10 m, facing away", at(0, -10, {0, -1}), Relation::A6},
      {"40 m behind B", at(0, -40, {0, 1}), Relation::A6},
  };
}

TEST(Relations, EveryRelationFromAConstructedConfiguration) {
  std::vector<bool> produced(7, false);
  for (const Config& c : configs()) {
    const Relation r = assess(c.a, kB, kParams, kOpen);
    EXPECT_EQ(relationName(r), relationName(c.expected)) << c.name;
    produced[static_cast<int>(r)] = true;
  }
  for (int i = 1; i <= 6; ++i) EXPECT_TRUE(produced[i]) << "A" << i;
}

TEST(Relations, WallsTurnSeeingIntoHearingOnly) {
  const SegmentOcclusion wall({{{-5.0f, 3.0f}, {5.0f, 3.0f}}});
  EXPECT_EQ(assess(at(0, 5, {0, -1}), kB, kParams, wall), Relation::A4);   // A2 without the wall
  EXPECT_EQ(assess(at(0, 15, {0, -1}), kB, kParams, wall), Relation::A6);  // A5 without the wall
}

TEST(Relations, AllowedBehavioursMatchWhatBPerceives) {
  for (const Config& c : configs()) {
    const Relation r = assess(c.a, kB, kParams, kOpen);
    const Perception pB = perceive(kB, c.a, kParams, kOpen);
    const auto allowed = allowedAttentionBehaviours(r);
    ASSERT_FALSE(allowed.empty()) << c.name;
    for (std::string_view bhv : allowed) {
      if (bhv == behaviour::kTap) EXPECT_TRUE(pB.touch) << c.name;
      if (bhv == behaviour::kCallOut) EXPECT_TRUE(pB.hear) << c.name;
      if (bhv == behaviour::kWave || bhv == behaviour::kLookAt) EXPECT_TRUE(pB.see) << c.name;
      if (bhv.find("move_") == 0) EXPECT_FALSE(pB.see || pB.hear) << c.name;  // moves only when unperceived
    }
  }
  const auto a3 = allowedAttentionBehaviours(Relation::A3);
  EXPECT_NE(std::find(a3.begin(), a3.end(), behaviour::kMoveIntoViewWave), a3.end());
  EXPECT_NE(std::find(a3.begin(), a3.end(), behaviour::kMoveIntoHearingCallOut), a3.end());
  EXPECT_EQ(allowedAttentionBehaviours(Relation::A6).front(), behaviour::kMoveToward);
}

TEST(Relations, PointInViewForA3IsTheNearestConeEdgePoint) {
  const Body a = at(0, -10, {0, 1});
  const Approach x = pointInView(a, kB, kParams, kOpen, 2.0f);
  ASSERT_TRUE(x.reachable);
  // A is straight behind: the nearest point of the sector is at the stand-off on a cone edge.
  EXPECT_NEAR(length(x.point), 2.0f, 1e-3f);
  EXPECT_NEAR(std::abs(x.point.x), 2.0f * std::sin(2.0944f / 2 - kApproachMargin), 1e-3f);
  const Perception p = perceive(kB, {x.point, {}, 0.2f}, kParams, kOpen);
  EXPECT_TRUE(p.see && p.hear);
  // Already seen and heard: stay.
  const Body near = at(1, 4);
  EXPECT_EQ(pointInView(near, kB, kParams, kOpen).point, near.position);
  // A in front beyond hearing: walk straight toward B to just inside hearing range.
  const Approach front = pointInView(at(0, 15), kB, kParams, kOpen);
  EXPECT_NEAR(front.point.x, 0.0f, 1e-4f);
  EXPECT_NEAR(front.point.y, kParams.hearingRange - kApproachMargin, 1e-4f);
}

TEST(Relations, PointInViewAvoidsOccludedPoints) {
  // A is straight behind B: both cone edges are equally near. A wall hides the chosen one.
  const Approach open = pointInView(at(0, -10), kB, kParams, kOpen);
  ASSERT_TRUE(open.reachable);
  const float side = open.point.x < 0.0f ? -1.0f : 1.0f;
  const SegmentOcclusion wall({{{side * 2.5f, 0.3f}, {side * 0.3f, 0.3f}}});
  ASSERT_TRUE(wall.blocked(kB.position, open.point));
  const Approach x = pointInView(at(0, -10), kB, kParams, wall);
  ASSERT_TRUE(x.reachable);
  EXPECT_FALSE(wall.blocked(kB.position, x.point));
  EXPECT_LT(x.point.x * side, 0.0f);  // the other side
  const Perception p = perceive(kB, {x.point, {}, 0.2f}, kParams, wall);
  EXPECT_TRUE(p.see && p.hear);
  // B boxed in at 1 m: nothing beyond the 2 m stand-off is visible.
  const SegmentOcclusion box({{{-1, -1}, {1, -1}}, {{1, -1}, {1, 1}}, {{1, 1}, {-1, 1}}, {{-1, 1}, {-1, -1}}});
  EXPECT_FALSE(pointInView(at(0, -10), kB, kParams, box).reachable);
}

TEST(Relations, PointInHearing) {
  const Approach x = pointInHearing(at(0, -10), kB, kParams);
  ASSERT_TRUE(x.reachable);
  EXPECT_NEAR(x.point.x, 0.0f, 1e-5f);
  EXPECT_NEAR(x.point.y, -(kParams.hearingRange - kApproachMargin), 1e-4f);
  EXPECT_TRUE(perceive(kB, {x.point, {}, 0.2f}, kParams, kOpen).hear);
  EXPECT_EQ(pointInHearing(at(3, 3), kB, kParams).point, Vec2(3, 3));
}

// x_i is seen and heard by B, and no point of the (margin-shrunk) sector is nearer to A.
RC_GTEST_PROP(RelationsProperty, PointInViewIsSeenHeardAndNearest, ()) {
  const auto uniform = [](float lo, float hi) {
    return lo + (hi - lo) * static_cast<float>(*rc::gen::inRange(0, 10001)) / 10000.0f;
  };
  SensoryParams params;
  params.hearingRange = uniform(1.0f, 30.0f);
  params.visionRange = uniform(1.0f, 40.0f);
  params.fieldOfView = uniform(0.3f, 6.2831853f);
  const float standOff = uniform(0.0f, 5.0f);
  const float ta = uniform(0.0f, 6.2831853f);
  const float tb = uniform(0.0f, 6.2831853f);
  const Body a{{uniform(-50, 50), uniform(-50, 50)}, {std::cos(ta), std::sin(ta)}, uniform(0.1f, 0.4f)};
  const Body b{{uniform(-50, 50), uniform(-50, 50)}, {std::cos(tb), std::sin(tb)}, uniform(0.1f, 0.4f)};

  const Approach x = pointInView(a, b, params, kOpen, standOff);
  RC_ASSERT(x.reachable);
  const Perception p = perceive(b, {x.point, a.facing, a.radius}, params, kOpen);
  RC_ASSERT(p.see);
  RC_ASSERT(p.hear);

  // Nearest: sample the sector the function searches and check none is clearly nearer to A.
  const float rMax = std::min(params.hearingRange, params.visionRange) - kApproachMargin;
  const float rMin = std::min(std::max(standOff, a.radius + b.radius), rMax);
  const float half = std::min(3.14159265f, params.fieldOfView * 0.5f - kApproachMargin);
  const float dx = distance(x.point, a.position);
  for (int i = 0; i < 64; ++i) {
    const float r = uniform(rMin, rMax);
    const float th = uniform(-half, half);
    const Vec2 u = b.facing * std::cos(th) + perp(b.facing) * std::sin(th);
    RC_ASSERT(dx <= distance(b.position + u * r, a.position) + 1e-3f);
  }
}

RC_GTEST_PROP(RelationsProperty, PointInHearingIsHeardAndNearest, ()) {
  const auto coord = [] { return static_cast<float>(*rc::gen::inRange(-500, 501)) / 10.0f; };
  const Body a = at(coord(), coord());
  const Body b = at(coord(), coord());
  const Approach x = pointInHearing(a, b, kParams);
  RC_ASSERT(x.reachable);
  RC_ASSERT(perceive(b, {x.point, {}, 0.2f}, kParams, kOpen).hear);
  const float expected = std::max(0.0f, distance(a.position, b.position) - (kParams.hearingRange - kApproachMargin));
  RC_ASSERT(std::abs(distance(x.point, a.position) - expected) < 1e-3f);
}

}  // namespace
}  // namespace throng::common_ground
