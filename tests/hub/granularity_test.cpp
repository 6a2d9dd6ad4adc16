// Animation granularity: X grows when a client is congested and comes back down when it is clear.
#include <gtest/gtest.h>

#include "throng/hub/granularity.hpp"

namespace throng::hub {
namespace {

TEST(Granularity, DoublesOnDroppedFramesAndStepsBackWhenClear) {
  GranularityOptions o;
  o.budgetKbitPerSecond = 500.0;
  o.maxFactor = 8;
  GranularityController c(o);
  LinkSample s;
  EXPECT_EQ(c.update(s), 1u);
  // A client that does not keep up: frames are replaced before they are sent.
  for (int second = 1; second <= 4; ++second) {
    s.seconds = second;
    s.bytesSent += 10'000;  // 80 kbit/s: under budget
    s.framesDropped += 5;
    c.update(s);
  }
  EXPECT_EQ(c.factor(), 8u);  // 1 → 2 → 4 → 8, capped
  EXPECT_STREQ(c.reason(), "congested: frames dropped");
  // It catches up: nothing dropped, little traffic.
  for (int second = 5; second <= 20; ++second) {
    s.seconds = second;
    s.bytesSent += 10'000;
    c.update(s);
  }
  EXPECT_EQ(c.factor(), 1u);
  EXPECT_NEAR(c.kbitPerSecond(), 80.0, 1e-9);
}

TEST(Granularity, OverBudgetRaisesXAndRoundTripCountsAsCongestion) {
  GranularityOptions o;
  o.budgetKbitPerSecond = 100.0;
  GranularityController c(o);
  LinkSample s;
  c.update(s);
  s.seconds = 1.0;
  s.bytesSent = 50'000;  // 400 kbit/s
  EXPECT_EQ(c.update(s), 2u);
  EXPECT_STREQ(c.reason(), "over budget");
  s.seconds = 2.0;
  s.bytesSent += 1'000;  // 8 kbit/s but a slow round trip
  s.roundTripMs = 900.0;
  EXPECT_EQ(c.update(s), 4u);
  EXPECT_STREQ(c.reason(), "congested: round trip");
  // Updates within the evaluation period change nothing.
  s.seconds = 2.5;
  s.framesDropped = 100;
  EXPECT_EQ(c.update(s), 4u);
  EXPECT_TRUE(c.animationFrame(8));
  EXPECT_FALSE(c.animationFrame(9));
}

}  // namespace
}  // namespace throng::hub
