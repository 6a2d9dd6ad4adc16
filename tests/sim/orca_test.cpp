// Tests for libs/sim/src/orca.cpp: the half-planes and the linear program.
#include "throng/sim/orca.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "throng/core/rng.hpp"
#include "throng/core/simd.hpp"

using throng::core::Vec2;
using namespace throng::sim;

namespace {

bool satisfies(const OrcaLine& line, Vec2 v, float tol = 1e-3f) {
  return throng::core::cross(line.direction, v - line.point) >= -tol;
}

}  // namespace

TEST(Orca, FreeFlowKeepsPreferredVelocity) {
  std::vector<OrcaLine> scratch;
  const Vec2 v = solveOrca({}, 0, 1.5f, Vec2{1.2f, 0.3f}, scratch);
  EXPECT_FLOAT_EQ(v.x, 1.2f);
  EXPECT_FLOAT_EQ(v.y, 0.3f);
}

TEST(Orca, ClampsToMaxSpeed) {
  std::vector<OrcaLine> scratch;
  const Vec2 v = solveOrca({}, 0, 1.0f, Vec2{3.0f, 4.0f}, scratch);
  EXPECT_NEAR(throng::core::length(v), 1.0f, 1e-5f);
  EXPECT_NEAR(v.x, 0.6f, 1e-5f);
}

TEST(Orca, HeadOnAgentsBothTurnAside) {
  // A at origin walking +x, B 4 m ahead walking -x: ORCA must bend both velocities sideways.
  std::vector<OrcaLine> scratch;
  const Vec2 va{1.3f, 0.0f}, vb{-1.3f, 0.0f};
  const OrcaLine la = agentOrcaLine(Vec2{4, 0}, va - vb, va, 0.4f, 2.0f, 0.05f);
  const OrcaLine lb = agentOrcaLine(Vec2{-4, 0}, vb - va, vb, 0.4f, 2.0f, 0.05f);
  const Vec2 na = solveOrca(std::span(&la, 1), 0, 1.3f, va, scratch);
  const Vec2 nb = solveOrca(std::span(&lb, 1), 0, 1.3f, vb, scratch);
  EXPECT_GT(std::fabs(na.y), 0.05f);
  EXPECT_GT(std::fabs(nb.y), 0.05f);
  // Reciprocity: they dodge to opposite sides in world frame (mirror symmetry).
  EXPECT_LT(na.y * nb.y, 0.0f);
}

TEST(Orca, WallAheadStopsApproach) {
  // A wall 0.3 m ahead across the path; walking into it at 1.3 m/s must be cut down.
  std::vector<OrcaLine> scratch;
  OrcaLine line;
  ASSERT_TRUE(segmentOrcaLine(Vec2{0.3f, -5}, Vec2{0.3f, 5}, Vec2{1.3f, 0}, 0.05f, 0.5f, 1.3f, line));
  const Vec2 v = solveOrca(std::span(&line, 1), 1, 1.3f, Vec2{1.3f, 0}, scratch);
  // Within the horizon 0.5 s the agent may travel at most (0.3 - 0.05) m toward the wall.
  EXPECT_LE(v.x * 0.5f, 0.25f + 1e-3f);
}

TEST(Orca, FarWallIgnored) {
  OrcaLine line;
  EXPECT_FALSE(segmentOrcaLine(Vec2{10, -1}, Vec2{10, 1}, Vec2{1, 0}, 0.05f, 0.5f, 1.3f, line));
}

TEST(Orca, TouchingWallForbidsMovingIntoIt) {
  std::vector<OrcaLine> scratch;
  OrcaLine line;
  ASSERT_TRUE(segmentOrcaLine(Vec2{0.01f, -1}, Vec2{0.01f, 1}, Vec2{}, 0.05f, 0.5f, 1.3f, line));
  const Vec2 v = solveOrca(std::span(&line, 1), 1, 1.3f, Vec2{1.0f, 0.5f}, scratch);
  EXPECT_LE(v.x, 1e-4f);
  EXPECT_NEAR(v.y, 0.5f, 1e-3f);  // sliding along the wall is still allowed
}

// Property: when the LP is feasible, the result meets every half-plane and never exceeds max speed.
RC_GTEST_PROP(OrcaProperty, ResultMeetsAllLinesAndSpeed, ()) {
  const int neighbours = *rc::gen::inRange(0, 8);
  const float maxSpeed = static_cast<float>(*rc::gen::inRange(5, 25)) / 10.0f;
  const Vec2 pref{static_cast<float>(*rc::gen::inRange(-30, 30)) / 10.0f, static_cast<float>(*rc::gen::inRange(-30, 30)) / 10.0f};
  std::vector<OrcaLine> lines;
  for (int i = 0; i < neighbours; ++i) {
    const float angle = static_cast<float>(*rc::gen::inRange(0, 628)) / 100.0f;
    const float dist = static_cast<float>(*rc::gen::inRange(6, 60)) / 10.0f;  // no overlap: > 0.4 m
    const Vec2 relPos{dist * std::cos(angle), dist * std::sin(angle)};
    const Vec2 otherVel{static_cast<float>(*rc::gen::inRange(-15, 15)) / 10.0f, static_cast<float>(*rc::gen::inRange(-15, 15)) / 10.0f};
    lines.push_back(agentOrcaLine(relPos, Vec2{} - otherVel, Vec2{}, 0.4f, 2.0f, 0.05f));
  }
  std::vector<OrcaLine> scratch;
  const Vec2 v = solveOrca(lines, 0, maxSpeed, pref, scratch);
  RC_ASSERT(throng::core::length(v) <= maxSpeed * 1.001f + 1e-4f);
  // When some velocity inside the speed disc meets every line (here: standing still), the LP is
  // feasible and its result must meet every line too.
  bool zeroFeasible = true;
  for (const OrcaLine& l : lines) zeroFeasible = zeroFeasible && satisfies(l, Vec2{}, 0.0f);
  RC_CLASSIFY(zeroFeasible, "feasible");
  if (zeroFeasible) {
    for (const OrcaLine& l : lines) RC_ASSERT(satisfies(l, v));
  }
}

namespace {

/// Every SIMD path this CPU runs (the portable one always).
std::vector<throng::core::SimdPath> runnablePaths() {
  std::vector<throng::core::SimdPath> paths{throng::core::SimdPath::Portable};
  if (throng::core::simdSupported(throng::core::SimdPath::Avx2)) paths.push_back(throng::core::SimdPath::Avx2);
  return paths;
}

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST(Orca, BatchedLinesEqualOneAtATimeBitForBitOnEverySimdPath) {
  // Neighbours in all three of agentOrcaLine's cases — apart with the cut-off circle closest,
  // apart with a leg (left and right), overlapping (moving and at rest relative to each other) —
  // in counts that leave every tail length of a four- and an eight-lane block.
  throng::core::Rng rng(7, 0, throng::core::RngPurpose::Bench);
  const throng::core::SimdPath before = throng::core::simdPath();
  int cases[3] = {0, 0, 0};
  for (throng::core::SimdPath path : runnablePaths()) {
    ASSERT_TRUE(throng::core::setSimdPath(path));
    for (int trial = 0; trial < 400; ++trial) {
      const std::size_t n = static_cast<std::size_t>(trial % 23);
      std::vector<float> px(n), py(n), vx(n), vy(n), cr(n), resp(n);
      for (std::size_t i = 0; i < n; ++i) {
        const float scale = (i % 3 == 0) ? 0.3f : 4.0f;  // a third of them overlapping, most apart
        px[i] = static_cast<float>(rng.uniform(-scale, scale));
        py[i] = static_cast<float>(rng.uniform(-scale, scale));
        vx[i] = (i % 7 == 0) ? px[i] / 0.05f : static_cast<float>(rng.uniform(-2.5, 2.5));  // at rest relative to the push
        vy[i] = (i % 7 == 0) ? py[i] / 0.05f : static_cast<float>(rng.uniform(-2.5, 2.5));
        cr[i] = static_cast<float>(rng.uniform(0.3, 0.6));
        resp[i] = (i % 2 == 0) ? 0.5f : static_cast<float>(rng.uniform(0.2, 0.8));
      }
      const Vec2 self{static_cast<float>(rng.uniform(-1.3, 1.3)), static_cast<float>(rng.uniform(-1.3, 1.3))};
      std::vector<OrcaLine> batch(n);
      agentOrcaLines({px.data(), py.data(), vx.data(), vy.data(), cr.data(), resp.data(), n}, self, 2.0f, 0.05f, batch.data());
      for (std::size_t i = 0; i < n; ++i) {
        const Vec2 rel{px[i], py[i]};
        const float distSq = throng::core::lengthSq(rel);
        const Vec2 w = Vec2{vx[i], vy[i]} - 0.5f * rel;
        const float d = throng::core::dot(w, rel);
        ++cases[distSq <= cr[i] * cr[i] ? 2 : (d < 0.0f && d * d > cr[i] * cr[i] * throng::core::lengthSq(w)) ? 0 : 1];
        const OrcaLine one = agentOrcaLine(rel, Vec2{vx[i], vy[i]}, self, cr[i], 2.0f, 0.05f, resp[i]);
        ASSERT_TRUE(sameBits(batch[i].point.x, one.point.x) && sameBits(batch[i].point.y, one.point.y) &&
                    sameBits(batch[i].direction.x, one.direction.x) && sameBits(batch[i].direction.y, one.direction.y))
            << throng::core::simdPathName(path) << " neighbour " << i << " of " << n << ": (" << batch[i].point.x << ", "
            << batch[i].point.y << ") / (" << batch[i].direction.x << ", " << batch[i].direction.y << ") against ("
            << one.point.x << ", " << one.point.y << ") / (" << one.direction.x << ", " << one.direction.y << ")";
      }
    }
  }
  throng::core::setSimdPath(before);
  for (int c : cases) EXPECT_GT(c, 100) << "every case of agentOrcaLine is exercised";
}
