// Tests of libs/common_ground/src/sensing.cpp: touch, hearing and vision (field of view, range, walls),
// the grid query perceivedBy, navmesh occlusion and parameter validation.
#include "throng/common_ground/sensing.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <vector>

#include "throng/nav/navmesh.hpp"

namespace throng::common_ground {
namespace {

constexpr float kHalfFov = 2.0944f * 0.5f;

Body at(float x, float y, Vec2 facing = {0.0f, 1.0f}, float radius = 0.2f) { return {{x, y}, facing, radius}; }
Vec2 dir(float angleFromPlusY) { return {-std::sin(angleFromPlusY), std::cos(angleFromPlusY)}; }

const SensoryParams kParams{};
const NoOcclusion kOpen{};

TEST(Sensing, DefaultsValidate) {
  EXPECT_TRUE(validate(kParams).empty());
  SensoryParams bad;
  bad.hearingRange = -1.0f;
  bad.fieldOfView = 7.0f;
  bad.touchMargin = NAN;
  const auto diags = validate(bad, "/senses");
  ASSERT_EQ(diags.size(), 3u);
  EXPECT_EQ(diags[0].pointer, "/senses/touchMargin");
  EXPECT_EQ(diags[1].pointer, "/senses/hearingRange");
  EXPECT_EQ(diags[2].pointer, "/senses/fieldOfView");
  EXPECT_NE(diags[2].expected.find("field of view"), std::string::npos);
}

TEST(Sensing, VisionInFrontSeenBehindNot) {
  const Body b = at(0, 0);
  EXPECT_TRUE(perceive(b, at(0, 10), kParams, kOpen).see);
  EXPECT_FALSE(perceive(b, at(0, -10), kParams, kOpen).see);
  EXPECT_FALSE(perceive(b, at(10, 0), kParams, kOpen).see);  // 90° off gaze > 60°
  EXPECT_FALSE(perceive(b, at(-10, 0), kParams, kOpen).see);
}

TEST(Sensing, VisionEdgesOfFieldOfView) {
  const Body b = at(0, 0);
  for (float sign : {1.0f, -1.0f}) {
    EXPECT_TRUE(perceive(b, {dir(sign * (kHalfFov - 1e-3f)) * 10.0f, {}, 0.2f}, kParams, kOpen).see) << sign;
    EXPECT_FALSE(perceive(b, {dir(sign * (kHalfFov + 1e-3f)) * 10.0f, {}, 0.2f}, kParams, kOpen).see) << sign;
  }
  // A rotated observer: facing +x, the cone follows.
  const Body east = at(0, 0, {1.0f, 0.0f});
  EXPECT_TRUE(perceive(east, at(10, 0), kParams, kOpen).see);
  EXPECT_FALSE(perceive(east, at(0, 10), kParams, kOpen).see);
  // Full circle sees behind; a zero facing sees nothing.
  SensoryParams full = kParams;
  full.fieldOfView = 6.2831853f;
  EXPECT_TRUE(perceive(b, at(0, -10), full, kOpen).see);
  EXPECT_FALSE(perceive(at(0, 0, {0, 0}), at(0, 10), kParams, kOpen).see);
  // Facing need not be unit for the cone test.
  EXPECT_TRUE(perceive(at(0, 0, {0, 5}), at(1, 10), kParams, kOpen).see);
}

TEST(Sensing, RangeLimits) {
  const Body b = at(0, 0);
  EXPECT_TRUE(perceive(b, at(0, 25.0f), kParams, kOpen).see);
  EXPECT_FALSE(perceive(b, at(0, 25.01f), kParams, kOpen).see);
  EXPECT_TRUE(perceive(b, at(0, -7.0f), kParams, kOpen).hear);  // hearing is omnidirectional
  EXPECT_TRUE(perceive(b, at(7.0f, 0), kParams, kOpen).hear);
  EXPECT_FALSE(perceive(b, at(0, -7.01f), kParams, kOpen).hear);
}

TEST(Sensing, TouchAtSumOfRadiiPlusMargin) {
  const Body b = at(0, 0, {0, 1}, 0.25f);
  // 0.25 + 0.2 + 0.1 = 0.55 m
  EXPECT_TRUE(perceive(b, at(0.55f, 0), kParams, kOpen).touch);
  EXPECT_TRUE(perceive(b, at(0, -0.5f), kParams, kOpen).touch);  // touch is felt from behind
  EXPECT_FALSE(perceive(b, at(0.56f, 0), kParams, kOpen).touch);
  SensoryParams noMargin = kParams;
  noMargin.touchMargin = 0.0f;
  EXPECT_TRUE(perceive(b, at(0.45f, 0), noMargin, kOpen).touch);
  EXPECT_FALSE(perceive(b, at(0.46f, 0), noMargin, kOpen).touch);
  // Symmetric.
  EXPECT_TRUE(perceive(at(0.55f, 0), b, kParams, kOpen).touch);
}

TEST(Sensing, WallsOccludeVisionNotHearing) {
  const SegmentOcclusion wall({{{-5.0f, 3.0f}, {5.0f, 3.0f}}});
  const Body b = at(0, 0);
  const Perception p = perceive(b, at(0, 5), kParams, wall);
  EXPECT_FALSE(p.see);
  EXPECT_TRUE(p.hear);
  // Around the wall's end the line of sight is clear.
  // (10.2, 6) is 59.5° off the gaze and passes the wall's end at x = 5.1.
  EXPECT_TRUE(perceive(b, at(10.2f, 6), kParams, wall).see);
  // Same side of the wall: seen.
  EXPECT_TRUE(perceive(b, at(0, 2), kParams, wall).see);
}

TEST(Sensing, NavMeshOcclusionBlocksAcrossWallsAndOffMesh) {
  // 20 x 10 room split at x = 10 by a wall with a 1.2 m door at y in [4.4, 5.6].
  const std::vector<nav::Polygon> walkable{{{0, 0}, {20, 0}, {20, 10}, {0, 10}}};
  const std::vector<nav::Polygon> walls{{{9.9f, 0}, {10.1f, 0}, {10.1f, 4.4f}, {9.9f, 4.4f}},
                                        {{9.9f, 5.6f}, {10.1f, 5.6f}, {10.1f, 10}, {9.9f, 10}}};
  auto mesh = nav::NavMesh::build(walkable, walls, {});
  ASSERT_TRUE(mesh.ok()) << core::formatAll(mesh.errors());
  const nav::NavQuery query(mesh.value());
  const NavMeshOcclusion occ(query);
  const Body b = at(8, 2, {1, 0});
  EXPECT_FALSE(perceive(b, at(12, 2), kParams, occ).see);  // through the wall
  EXPECT_TRUE(perceive(b, at(12, 2), kParams, occ).hear);
  EXPECT_TRUE(perceive(at(8, 5, {1, 0}), at(12, 5), kParams, occ).see);  // through the door
  EXPECT_TRUE(perceive(b, at(9, 3), kParams, occ).see);                    // same room
  EXPECT_TRUE(occ.blocked({8, 2}, {25, 2}));                                 // leaves the mesh
}

TEST(Sensing, PerceivedByListsOnlyPerceivedCandidatesInOrder) {
  const SegmentOcclusion wall({{{-5.0f, 3.0f}, {5.0f, 3.0f}}});
  const std::vector<Body> cands{at(0, 10), at(0, 30), at(0, -1), at(0, -20), at(1, 1)};
  std::vector<std::pair<std::uint32_t, Perception>> out{{99, {}}};
  perceivedBy(at(0, 0), cands, kParams, wall, out);
  // (0,10) is beyond hearing and behind the wall; (0,30) and (0,-20) are out of every range;
  // (0,-1) is heard but behind; (1,1) is heard and seen.
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].first, 2u);
  EXPECT_TRUE(out[0].second.hear);
  EXPECT_FALSE(out[0].second.see);
  EXPECT_EQ(out[1].first, 4u);
  EXPECT_TRUE(out[1].second.hear);
  EXPECT_TRUE(out[1].second.see);
  EXPECT_FALSE(out[1].second.touch);
}

RC_GTEST_PROP(SensingProperty, PerceivedByEqualsPerPairPerceive, ()) {
  const auto coord = [] { return static_cast<float>(*rc::gen::inRange(-300, 301)) / 10.0f; };
  const auto angle = [] { return static_cast<float>(*rc::gen::inRange(0, 628)) / 100.0f; };
  const Body observer{{coord(), coord()}, {std::cos(angle()), std::sin(angle())}, 0.2f};
  const int n = *rc::gen::inRange(0, 40);
  std::vector<Body> cands;
  std::vector<std::uint32_t> ids;
  for (int i = 0; i < n; ++i) {
    const float a = angle();
    cands.push_back({{coord(), coord()}, {std::cos(a), std::sin(a)}, 0.15f + 0.01f * *rc::gen::inRange(0, 15)});
    ids.push_back(static_cast<std::uint32_t>(1000 + 7 * i));
  }
  const SegmentOcclusion walls({{{-10, 0}, {10, 0}}, {{5, -20}, {5, 20}}});
  std::vector<std::pair<std::uint32_t, Perception>> out;
  perceivedBy(observer, cands, ids, kParams, walls, out);
  std::size_t k = 0;
  for (int i = 0; i < n; ++i) {
    const Perception p = perceive(observer, cands[i], kParams, walls);
    if (!(p.touch || p.hear || p.see)) continue;
    RC_ASSERT(k < out.size());
    RC_ASSERT(out[k].first == ids[i]);
    RC_ASSERT(out[k].second.touch == p.touch);
    RC_ASSERT(out[k].second.hear == p.hear);
    RC_ASSERT(out[k].second.see == p.see);
    ++k;
  }
  RC_ASSERT(k == out.size());
}

}  // namespace
}  // namespace throng::common_ground
