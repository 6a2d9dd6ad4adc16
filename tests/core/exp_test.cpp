// core::exp (throng/core/exp.hpp) against the correctly rounded exponential.
#include "throng/core/exp.hpp"
#include "throng/core/simd.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>

namespace {

/// |core::exp(x) − e^x| in units of the float spacing at e^x (e^x in long double: 64-bit mantissa,
/// so its own error is far below what is measured).
double ulpError(float x) {
  const long double exact = std::exp(static_cast<long double>(x));
  const float got = throng::core::exp(x);
  const auto rounded = static_cast<float>(exact);
  const float ulp = std::nextafter(rounded, std::numeric_limits<float>::infinity()) - rounded;
  return static_cast<double>(std::fabs(static_cast<long double>(got) - exact) / static_cast<long double>(ulp));
}

TEST(Exp, WithinHalfAnUlpAndABitOverTheWholeRange) {
  // Every 2^-10 of the range where the result is a normal float, and 200,000 random floats.
  double worst = 0.0;
  float worstAt = 0.0f;
  std::size_t notNearest = 0, count = 0;
  const auto check = [&](float x) {
    const double e = ulpError(x);
    if (e > worst) worst = e, worstAt = x;
    notNearest += static_cast<std::size_t>(throng::core::exp(x) != static_cast<float>(std::exp(static_cast<long double>(x))));
    ++count;
  };
  for (float x = -87.0f; x < 88.7f; x += 1.0f / 1024.0f) check(x);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> any(-87.0f, 88.7f), small(-3.0f, 3.0f);
  for (int i = 0; i < 100000; ++i) check(any(rng)), check(small(rng));
  EXPECT_LT(worst, 0.505) << "at x = " << worstAt;
  std::printf("worst %.4f ulp at %g; %zu of %zu not the nearest float\n", worst, static_cast<double>(worstAt), notNearest, count);  // 0.5 from the rounding, the rest the polynomial's
  EXPECT_LT(static_cast<double>(notNearest), 1e-3 * static_cast<double>(count)) << notNearest << " of " << count;
}

TEST(Exp, ExactWhereTheAnswerIsExactAndLimitsAtTheEnds) {
  EXPECT_EQ(throng::core::exp(0.0f), 1.0f);
  EXPECT_EQ(throng::core::exp(-0.0f), 1.0f);
  EXPECT_EQ(throng::core::exp(1.0f), 2.71828182845904523536f);
  EXPECT_EQ(throng::core::exp(-200.0f), 0.0f);
  EXPECT_EQ(throng::core::exp(-std::numeric_limits<float>::infinity()), 0.0f);
  EXPECT_EQ(throng::core::exp(89.0f), std::numeric_limits<float>::infinity());
  EXPECT_EQ(throng::core::exp(std::numeric_limits<float>::infinity()), std::numeric_limits<float>::infinity());
  EXPECT_TRUE(std::isnan(throng::core::exp(std::numeric_limits<float>::quiet_NaN())));
  // Subnormal results are rounded, not flushed: e^-100 is about 3.7e-44.
  EXPECT_GT(throng::core::exp(-100.0f), 0.0f);
  EXPECT_LT(ulpError(-100.0f), 0.51);
  EXPECT_EQ(throng::core::exp(88.72f), static_cast<float>(std::exp(static_cast<long double>(88.72f))));
}

#if defined(__x86_64__)
/// expWide as the AVX2 path calls it (compiled for AVX2; 32-byte vectors need it).
[[gnu::target("avx2"), gnu::noinline]] void wideOnAvx2(const throng::core::Float4& x, throng::core::Float4& out) {
  out = throng::core::expWide(x);
}
throng::core::Float4 wideOnAvx2(const throng::core::Float4& x) {
  throng::core::Float4 out;
  wideOnAvx2(x, out);
  return out;
}
const bool avx2 = throng::core::simdSupported(throng::core::SimdPath::Avx2);
#else
throng::core::Float4 wideOnAvx2(const throng::core::Float4& x) { return x; }
const bool avx2 = false;  // expWide is called only on the AVX2 path
#endif

TEST(Exp, FourLanesGiveTheScalarBitsInEveryLane) {
  // The vector forms (pushes of the pedestrian model, four neighbours at a time; expWide on the
  // AVX2 path) must equal the scalar one bit for bit, in range and out of it, whatever the other
  // lanes hold.
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> any(-120.0f, 100.0f);
  const float specials[] = {0.0f, -0.0f, 1.0f, -104.0f, -103.99f, 88.72284f, 88.72285f, -200.0f, 200.0f,
                            std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                            std::numeric_limits<float>::quiet_NaN()};
  std::size_t checked = 0;
  const auto same = [](float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; };
  for (int i = 0; i < 50000; ++i) {
    throng::core::Float4 x{any(rng), any(rng), any(rng), any(rng)};
    if (i < 12 * 4) x[i % 4] = specials[i / 4];
    const throng::core::Float4 e = throng::core::exp(x), wide = avx2 ? wideOnAvx2(x) : e;
    for (int l = 0; l < 4; ++l) {
      ASSERT_TRUE(same(e[l], throng::core::exp(x[l])) || (std::isnan(e[l]) && std::isnan(x[l]))) << "x = " << x[l];
      ASSERT_TRUE(same(wide[l], throng::core::exp(x[l])) || (std::isnan(wide[l]) && std::isnan(x[l]))) << "wide, x = " << x[l];
      ++checked;
    }
  }
  EXPECT_EQ(checked, 200000u);
}

}  // namespace
