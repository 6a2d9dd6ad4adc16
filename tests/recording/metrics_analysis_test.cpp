// Tests for libs/recording/src/metrics_analysis.cpp on hand-made data (no recording): density
// statistics of a histogram, arrival bins, congestion around key points (near and far apart),
// group cohesion and coordination statistics, each against values worked out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "metrics_analysis.hpp"

namespace throng::recording::metrics {
namespace {

constexpr double kPi = std::numbers::pi;

KeyPoint key(std::uint32_t index, const std::string& id, const std::string& category, double x, double y) {
  KeyPoint k;
  k.index = index;
  k.id = id;
  k.category = category;
  k.x = x;
  k.y = y;
  return k;
}

TEST(MetricsAnalysis, DensityOfAHistogram) {
  // Two samples with nobody, one with 2 agents, one with 3; area 2 m².
  const DensityStats d = densityOf({2, 0, 1, 1}, 2.0);
  EXPECT_EQ(d.samples, 4u);
  EXPECT_DOUBLE_EQ(d.mean, (2.0 + 3.0) / 4.0 / 2.0);
  EXPECT_DOUBLE_EQ(d.p95, 1.5);  // nearest rank ceil(0.95 × 4) = 4: the sample with 3 agents
  EXPECT_DOUBLE_EQ(d.max, 1.5);
  const DensityStats none = densityOf({}, 2.0);
  EXPECT_EQ(none.samples, 0u);
  EXPECT_EQ(none.mean, 0.0);
  EXPECT_EQ(none.max, 0.0);
}

TEST(MetricsAnalysis, ArrivalsPerBinAndCategory) {
  // Bins of 10 s over 25 s: [0, 10), [10, 20), [20, 30); point 0 is a "shop", point 1 has no category.
  ArrivalTally tally(10.0, 25.0, {"shop", ""});
  tally.add(EventKind::VisitStart, 3.0, 0);
  tally.add(EventKind::VisitStart, 12.0, 7);   // an unknown point: no category
  tally.add(EventKind::Exit, 21.0, -1);
  tally.add(EventKind::Exit, -1.0, -1);         // before the start: not counted
  tally.add(EventKind::VisitStart, std::numeric_limits<double>::quiet_NaN(), 0);  // not counted
  tally.add(EventKind::VisitStart, 35.0, 0);   // after the last bin: one more bin
  tally.add(EventKind::Reunited, -5.0, 0);     // counted whatever its time
  tally.add(EventKind::GoalGenerated, 1.0, 0);
  tally.add(EventKind::GoalGenerated, 2.0, 0);
  SocialMetrics m;
  tally.writeTo(m);
  ASSERT_EQ(m.arrivals.size(), 4u);
  EXPECT_DOUBLE_EQ(m.arrivals[3].start, 30.0);
  EXPECT_EQ(m.arrivals[0].visits, 1u);
  EXPECT_EQ(m.arrivals[0].byCategory.at("shop"), 1u);
  EXPECT_EQ(m.arrivals[1].byCategory.at(""), 1u);
  EXPECT_EQ(m.arrivals[2].exits, 1u);
  EXPECT_EQ(m.arrivals[3].visits, 1u);
  EXPECT_EQ(m.visits, 3u);
  EXPECT_EQ(m.exits, 1u);
  EXPECT_EQ(m.visitsByCategory.at("shop"), 2u);
  EXPECT_DOUBLE_EQ(m.visitsPerMinute, 3.0 / (25.0 / 60.0));
  EXPECT_DOUBLE_EQ(m.exitsPerMinute, 1.0 / (25.0 / 60.0));
  EXPECT_EQ(m.coordinations.reunited, 1u);
  EXPECT_EQ(m.coordinations.goalsGenerated, 2u);
}

TEST(MetricsAnalysis, CongestionAroundKeyPoints) {
  // A and B are shops, C a cafe; radius 1 m (area π m²).
  CongestionTally tally({key(0, "A", "shop", 0, 0), key(3, "B", "shop", 10, 0), key(5, "C", "cafe", 0, 10)}, 1.0);
  tally.addAgent(0.0, 0.5);   // near A
  tally.addAgent(0.2, 0.0);   // near A
  tally.addAgent(10.0, 0.9);  // near B
  tally.addAgent(5.0, 5.0);   // near nothing
  tally.endFrame();
  tally.addAgent(0.0, 9.5);   // near C
  tally.addAgent(std::nan(""), 0.0);  // ignored
  tally.endFrame();
  SocialMetrics m;
  m.categories = {"cafe", "shop"};
  tally.writeTo(m, 4, 2);  // 4 frames: the 2 not seen had nobody near any point
  ASSERT_EQ(m.congestion.size(), 2u);
  EXPECT_EQ(m.congestion[0].category, "cafe");
  EXPECT_EQ(m.congestion[0].points, 1u);
  EXPECT_EQ(m.congestion[0].samples, 4u);
  EXPECT_NEAR(m.congestion[0].mean, 1.0 / 4.0 / kPi, 1e-12);
  EXPECT_EQ(m.congestion[1].category, "shop");
  EXPECT_EQ(m.congestion[1].points, 2u);
  EXPECT_EQ(m.congestion[1].samples, 8u);
  EXPECT_NEAR(m.congestion[1].mean, 3.0 / 8.0 / kPi, 1e-12);
  EXPECT_NEAR(m.congestion[1].max, 2.0 / kPi, 1e-12);
  // Worst first: A (mean 2/4 per π); B and C tie on mean and max, so key order keeps B.
  ASSERT_EQ(m.worstPoints.size(), 2u);
  EXPECT_EQ(m.worstPoints[0].point, "A");
  EXPECT_EQ(m.worstPoints[0].pointIndex, 0u);
  EXPECT_NEAR(m.worstPoints[0].mean, 0.5 / kPi, 1e-12);
  EXPECT_EQ(m.worstPoints[1].point, "B");
  EXPECT_EQ(m.worstPoints[1].points, 1u);
}

TEST(MetricsAnalysis, FarApartPointsAreStillFound) {
  // 50 km apart with a 1 m radius: the grid's cells grow (span / 2048), the answers do not change.
  CongestionTally tally({key(0, "west", "gate", 0, 0), key(1, "east", "gate", 50000, 0)}, 1.0);
  tally.addAgent(50000.5, 0.0);
  tally.addAgent(49998.0, 0.0);  // 2 m away: not near
  tally.addAgent(0.0, -0.9);
  tally.endFrame();
  SocialMetrics m;
  m.categories = {"gate"};
  tally.writeTo(m, 1, 5);
  ASSERT_EQ(m.worstPoints.size(), 2u);
  EXPECT_NEAR(m.worstPoints[0].max, 1.0 / kPi, 1e-12);
  EXPECT_NEAR(m.worstPoints[1].max, 1.0 / kPi, 1e-12);
  EXPECT_NEAR(m.congestion[0].mean, 1.0 / kPi, 1e-12);
}

TEST(MetricsAnalysis, CohesionOfGroups) {
  // Agents 1, 2 form group 0; agents 3, 4 group 1; "together" within 3 m of the centroid.
  CohesionTally tally({{1, 0}, {2, 0}, {3, 1}, {4, 1}}, 2, 3.0);
  ASSERT_TRUE(tally.tracksGroups());
  tally.addAgent(1, 0.0, 0.0);
  tally.addAgent(2, 2.0, 0.0);  // centroid (1, 0): both 1 m away
  tally.addAgent(3, 0.0, 0.0);  // alone in its group this frame: not counted
  tally.addAgent(4, std::nan(""), 0.0);
  tally.addAgent(9, 5.0, 5.0);  // in no group
  tally.endFrame();
  tally.addAgent(1, 0.0, 0.0);
  tally.addAgent(2, 8.0, 0.0);  // 4 m from the centroid: apart
  tally.addAgent(3, 0.0, 0.0);
  tally.addAgent(4, 0.0, 2.0);  // 1 m each
  tally.endFrame();
  const CohesionStats c = tally.result();
  EXPECT_EQ(c.groupFrames, 3u);
  EXPECT_EQ(c.groups, 2u);
  EXPECT_DOUBLE_EQ(c.meanDistance, (1.0 + 4.0 + 1.0) / 3.0);
  EXPECT_DOUBLE_EQ(c.shareTogether, 2.0 / 3.0);
  EXPECT_FALSE(CohesionTally({}, 0, 3.0).tracksGroups());
  EXPECT_EQ(CohesionTally({}, 0, 3.0).result().groupFrames, 0u);
}

TEST(MetricsAnalysis, CoordinationStatistics) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CoordinationInfo alone;
  alone.plan = "resume";
  alone.outcome = "alone";
  alone.trigger = "need";
  alone.start = 0.0;
  alone.execute = 50.0;  // alone: no grounding time counted
  CoordinationInfo divide;
  divide.plan = "divide_and_wait";
  divide.outcome = "grounded";
  divide.trigger = "attraction";
  divide.relation = "A1";
  divide.start = 1.0;
  divide.execute = 3.0;
  divide.end = 10.0;
  CoordinationInfo unfinished;
  unfinished.plan = "detour_together";
  unfinished.outcome = "failed";
  unfinished.trigger = "need";
  unfinished.relation = "A3";
  unfinished.start = 2.0;
  unfinished.execute = nan;
  const CoordinationStats cs = coordinationStats({alone, divide, unfinished});
  EXPECT_EQ(cs.total, 3u);
  EXPECT_EQ(cs.byRelation.at("none"), 1u);
  EXPECT_EQ(cs.byRelation.at("A1"), 1u);
  EXPECT_EQ(cs.byTrigger.at("need"), 2u);
  EXPECT_EQ(cs.byOutcome.at("grounded"), 1u);
  EXPECT_EQ(cs.byPlan.at("detour_together"), 1u);
  EXPECT_EQ(cs.groundingSamples, 1u);  // the unfinished one has no t_8
  EXPECT_DOUBLE_EQ(cs.meanGrounding, 2.0);
  EXPECT_DOUBLE_EQ(cs.maxGrounding, 2.0);
  EXPECT_EQ(cs.divideSamples, 1u);
  EXPECT_DOUBLE_EQ(cs.meanDivide, 7.0);
  EXPECT_TRUE(cs.microBehaviours.empty());
}

}  // namespace
}  // namespace throng::recording::metrics
