// Tests for libs/core/include/throng/core/rng.hpp: determinism, independent streams, sampling.
#include "throng/core/rng.hpp"

#include <gtest/gtest.h>

#include <cmath>

using throng::core::Rng;
using throng::core::RngPurpose;

TEST(Rng, SameArgumentsSameSequence) {
  Rng a(42, 7, RngPurpose::Spawn);
  Rng b(42, 7, RngPurpose::Spawn);
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(a.next(), b.next());
}

TEST(Rng, DifferentStreamsDiffer) {
  auto firstDraws = [](std::uint64_t seed, std::uint64_t entity, RngPurpose p) {
    Rng r(seed, entity, p);
    std::vector<std::uint32_t> v;
    for (int i = 0; i < 8; ++i) v.push_back(r.next());
    return v;
  };
  const auto base = firstDraws(1, 1, RngPurpose::Spawn);
  EXPECT_NE(base, firstDraws(2, 1, RngPurpose::Spawn));
  EXPECT_NE(base, firstDraws(1, 2, RngPurpose::Spawn));
  EXPECT_NE(base, firstDraws(1, 1, RngPurpose::Speed));
}

TEST(Rng, UniformInRange) {
  Rng r(3, 0, RngPurpose::Bench);
  for (int i = 0; i < 10000; ++i) {
    const double u = r.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    const double v = r.uniform(-2.0, 5.0);
    ASSERT_GE(v, -2.0);
    ASSERT_LT(v, 5.0);
  }
}

TEST(Rng, UniformIntBoundsInclusiveAndCovered) {
  Rng r(9, 1, RngPurpose::GroupSize);
  int counts[4] = {0, 0, 0, 0};
  for (int i = 0; i < 10000; ++i) {
    const std::uint32_t v = r.uniformInt(3, 6);
    ASSERT_GE(v, 3u);
    ASSERT_LE(v, 6u);
    ++counts[v - 3];
  }
  for (int c : counts) EXPECT_GT(c, 2000);  // each ~2500
  EXPECT_EQ(r.uniformInt(5, 5), 5u);
  (void)r.uniformInt(0, 0xffffffffu);  // full range must not loop forever
}

TEST(Rng, NormalMeanAndSd) {
  Rng r(11, 5, RngPurpose::Speed);
  const int n = 100000;
  double sum = 0, sumSq = 0;
  for (int i = 0; i < n; ++i) {
    const double x = r.normal(1.34, 0.26);
    ASSERT_TRUE(std::isfinite(x));
    sum += x;
    sumSq += x * x;
  }
  const double mean = sum / n;
  const double sd = std::sqrt(sumSq / n - mean * mean);
  EXPECT_NEAR(mean, 1.34, 0.01);
  EXPECT_NEAR(sd, 0.26, 0.01);
}
