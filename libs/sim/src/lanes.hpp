// Vectors of W floats / int32s for the SIMD kernels (GCC/Clang vector extensions), W = 4 (the
// portable path) or 8 (the AVX2 path); docs/architecture.md, "SIMD paths". Spelled out per width
// because GCC ignores a vector_size that depends on a template parameter.
#pragma once
#include <cmath>
#include <cstdint>
#include <cstring>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

/// Kernels are inlined into each path's entry point, so they compile for that path's target.
#define THRONG_KERNEL [[gnu::always_inline]] inline

namespace throng::sim::simd {

template <int W>
struct LaneTypes;
template <>
struct LaneTypes<4> {
  using F = float __attribute__((vector_size(16)));
  using I = std::int32_t __attribute__((vector_size(16)));
};
template <>
struct LaneTypes<8> {
  using F = float __attribute__((vector_size(32)));
  using I = std::int32_t __attribute__((vector_size(32)));
};

/// Vectors go in and out by reference only: a 32-byte vector by value would change the calling
/// convention between the AVX2 entry point and baseline code.
template <int W>
struct Lanes {
  using F = typename LaneTypes<W>::F;
  using I = typename LaneTypes<W>::I;
  THRONG_KERNEL static void fill(F& out, float v) {
    for (int l = 0; l < W; ++l) out[l] = v;
  }
  THRONG_KERNEL static void fill(I& out, std::int32_t v) {
    for (int l = 0; l < W; ++l) out[l] = v;
  }
  THRONG_KERNEL static std::int32_t sum(const I& v) {
    std::int32_t s = 0;
    for (int l = 0; l < W; ++l) s += v[l];
    return s;
  }
};

/// out = √v lane by lane (exactly rounded, as std::sqrt): SSE2's sqrtps four lanes at a time.
template <int W, class F>
THRONG_KERNEL void sqrtLanes(F& out, const F& v) {
#if defined(__SSE2__)
  for (int h = 0; h < W; h += 4) {
    __m128 q;
    std::memcpy(&q, reinterpret_cast<const float*>(&v) + h, sizeof q);
    q = _mm_sqrt_ps(q);
    std::memcpy(reinterpret_cast<float*>(&out) + h, &q, sizeof q);
  }
#else
  for (int l = 0; l < W; ++l) out[l] = std::sqrt(v[l]);
#endif
}

}  // namespace throng::sim::simd
