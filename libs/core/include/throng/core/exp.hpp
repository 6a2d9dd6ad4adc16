// core::exp — e^x for floats, computed by throng itself rather than by the C library.
//
// Why not std::exp: the pedestrian models evaluate an exponential for every neighbour pushing an
// agent (Tordeux et al.'s a·exp((ℓ − s)/D)), a few million times a second. The C library's expf
// is a function call whose last bit is the library's choice (glibc even picks an FMA variant at
// run time by CPU), so the same scenario could walk differently on another system. This one is
// inline and uses only IEEE double additions and multiplications in a fixed order (the build
// forbids contracting them into FMAs), so it gives the same bits on every x86-64 and ARM64 machine
// and compiler, and costs about as much as the call alone.
//
// Method (the textbook reduction, e.g. Muller, "Elementary Functions", ch. 11): x·log2(e) = k + f
// with k = round(x·log2 e) an integer, r = x − k·ln 2 in [−ln2/2, ln2/2]; e^x = 2^k · e^r, with
// e^r from its Taylor polynomial of degree 8 (truncation below 2.1e-10 relative) evaluated by
// Estrin's scheme (four levels, not eight, of dependent operations), all in double, and one
// rounding to float at the end. Error below 0.51 ulp of the float result: tests/core/exp_test.cpp
// compares it with the correctly rounded value (long double) over a sweep of the range.
#pragma once
#include <bit>
#include <cstdint>
#include <limits>

namespace throng::core {

namespace exp_detail {
inline constexpr float kLow = -104.0f;       // e^−104 is below half the smallest subnormal: 0
inline constexpr float kHigh = 88.72284f;    // e^88.72284 is above the largest float: +inf
inline constexpr double kLog2e = 1.4426950408889634;
inline constexpr double kLn2 = 0.6931471805599453;
inline constexpr double kRound = 6755399441055744.0;  // 1.5 · 2^52: adding it rounds to an integer (to nearest)

/// e^x for x in (kLow, kHigh], as double (before the one rounding to float); D is double or a
/// vector of doubles, Q the same shape of int64: the same operations lane by lane. (In and out by
/// reference: a 32-byte vector by value would change the calling convention outside AVX code.)
template <class D, class Q>
[[gnu::always_inline]] inline void inRange(const D& xd, D& out) {
  const D shifted = xd * kLog2e + kRound;
  const D kd = shifted - kRound;
  // k = round(x·log2 e) sits in shifted's low mantissa bits (|k| <= 151 keeps it in 2^52's binade).
  const Q k = __builtin_bit_cast(Q, shifted) - __builtin_bit_cast(std::int64_t, kRound);  // (builtins: no 32-byte vector returned by a function)
  const D r = xd - kd * kLn2;  // |r| <= 0.347: k·ln2 rounds by at most 1e-14 for |k| <= 151
  const D r2 = r * r;
  const D r4 = r2 * r2;
  // e^r ≈ Σ r^n / n!, n = 0 … 8, grouped (Estrin) as (1 + r) + r²(1/2 + r/6) + r⁴((1/24 + r/120) +
  // r²(1/720 + r/5040)) + r⁸/40320.
  const D p01 = 1.0 + r;
  const D p23 = 0.5 + r * (1.0 / 6.0);
  const D p45 = 1.0 / 24.0 + r * (1.0 / 120.0);
  const D p67 = 1.0 / 720.0 + r * (1.0 / 5040.0);
  const D p = (p01 + r2 * p23) + r4 * ((p45 + r2 * p67) + r4 * (1.0 / 40320.0));
  out = p * __builtin_bit_cast(D, (k + 1023) << 52);  // · 2^k
}
}  // namespace exp_detail

/// e^x [Limit: any float; NaN gives NaN, below −104 gives 0, above 88.72 gives +inf].
inline float exp(float x) {
  if (!(x > exp_detail::kLow)) return x != x ? x : 0.0f;
  if (x > exp_detail::kHigh) return std::numeric_limits<float>::infinity();
  double e;
  exp_detail::inRange<double, std::int64_t>(static_cast<double>(x), e);
  return static_cast<float>(e);
}

/// Four floats (GCC/Clang vector extensions; SSE2 on x86-64, NEON on ARM64).
using Float4 = float __attribute__((vector_size(16)));

/// core::exp of each lane, to the bit (the same double operations, two lanes at a time).
[[gnu::always_inline]] inline Float4 exp(const Float4& x) {
  using D2 = double __attribute__((vector_size(16)));
  using Q2 = std::int64_t __attribute__((vector_size(16)));
  using F2 = float __attribute__((vector_size(8)));
  using I4 = std::int32_t __attribute__((vector_size(16)));
  const I4 low = !(x > exp_detail::kLow), high = x > exp_detail::kHigh;
  const Float4 safe = (low | high) != 0 ? Float4{} : x;  // out of range: worked out on 0, replaced below
  D2 lo, hi;
  exp_detail::inRange<D2, Q2>(__builtin_convertvector(__builtin_shufflevector(safe, safe, 0, 1), D2), lo);
  exp_detail::inRange<D2, Q2>(__builtin_convertvector(__builtin_shufflevector(safe, safe, 2, 3), D2), hi);
  const Float4 e = __builtin_shufflevector(__builtin_convertvector(lo, F2), __builtin_convertvector(hi, F2), 0, 1, 2, 3);
  const Float4 below = x != x ? x : Float4{};  // NaN stays NaN, the rest 0
  return low != 0 ? below : high != 0 ? Float4{} + std::numeric_limits<float>::infinity() : e;
}

/// core::exp of each lane, to the bit, the four lanes' doubles in one 32-byte vector: for code
/// compiled for AVX2 (one instruction for each double operation where exp(Float4) takes two).
/// Called from baseline code it is still exact, only slower.
[[gnu::always_inline]] inline Float4 expWide(const Float4& x) {
  using D4 = double __attribute__((vector_size(32)));
  using Q4 = std::int64_t __attribute__((vector_size(32)));
  using I4 = std::int32_t __attribute__((vector_size(16)));
  const I4 low = !(x > exp_detail::kLow), high = x > exp_detail::kHigh;
  const Float4 safe = (low | high) != 0 ? Float4{} : x;  // out of range: worked out on 0, replaced below
  D4 wide;
  exp_detail::inRange<D4, Q4>(__builtin_convertvector(safe, D4), wide);
  const Float4 e = __builtin_convertvector(wide, Float4);
  const Float4 below = x != x ? x : Float4{};  // NaN stays NaN, the rest 0
  return low != 0 ? below : high != 0 ? Float4{} + std::numeric_limits<float>::infinity() : e;
}

}  // namespace throng::core
