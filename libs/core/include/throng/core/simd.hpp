#pragma once
// Which instruction set the hot loops use (the neighbour search first): the widest this CPU runs,
// chosen once per process. Every path gives bit-identical results (the kernels use only exactly
// rounded IEEE operations in the same order, with -ffp-contract=off: no fused multiply-add), so
// the choice changes speed, never a trajectory. It is recorded in recordings (`throng_simd`) and
// printed by `throng info` and `throng bench`.
#include <cstdint>
#include <string>
#include <string_view>

namespace throng::core {

enum class SimdPath : std::uint8_t {
  Portable,  ///< four-lane vectors every x86-64 (SSE2) and ARM (NEON) CPU has
  Avx2,      ///< eight-lane vectors and lane permutes (x86-64 with AVX2: Intel since 2013, AMD since 2015)
};

/// "portable" or "avx2".
[[nodiscard]] std::string_view simdPathName(SimdPath path);

/// Can this CPU run `path`?
[[nodiscard]] bool simdSupported(SimdPath path);

/// The path in use. Chosen at first use: the environment variable THRONG_SIMD ("auto", the
/// default; "portable"; "avx2") asks for one, and a path this CPU cannot run falls back to the
/// portable one.
[[nodiscard]] SimdPath simdPath();

/// Why THRONG_SIMD was not followed ("" when it was, or is unset): for front ends to print.
[[nodiscard]] std::string simdRequestProblem();

/// Uses `path` from now on in this process (tests and benchmarks compare paths); false, and no
/// change, when this CPU cannot run it. Not to be called while a world steps.
bool setSimdPath(SimdPath path);

}  // namespace throng::core
