// The process-wide choice of SIMD path (simd.hpp): CPU detection, THRONG_SIMD, the override.
#include "throng/core/simd.hpp"

#include <atomic>
#include <cstdlib>
#include <mutex>

namespace throng::core {
namespace {

struct Choice {
  std::atomic<SimdPath> path{SimdPath::Portable};
  std::string problem;
};

Choice& choice() {
  static Choice c;
  static std::once_flag once;
  std::call_once(once, [] {
    const char* env = std::getenv("THRONG_SIMD");  // NOLINT(concurrency-mt-unsafe): read once, under call_once
    const std::string_view asked = env ? env : "auto";
    SimdPath path = simdSupported(SimdPath::Avx2) ? SimdPath::Avx2 : SimdPath::Portable;
    if (asked == "portable") {
      path = SimdPath::Portable;
    } else if (asked == "avx2") {
      if (!simdSupported(SimdPath::Avx2)) c.problem = "THRONG_SIMD=avx2, but this CPU has no AVX2: using the portable path";
    } else if (asked != "auto" && !asked.empty()) {
      c.problem = "THRONG_SIMD='" + std::string(asked.substr(0, 40)) + "' is not understood (expected auto, portable or avx2): using " +
                  std::string(simdPathName(path));
    }
    c.path.store(path);
  });
  return c;
}

}  // namespace

std::string_view simdPathName(SimdPath path) { return path == SimdPath::Avx2 ? "avx2" : "portable"; }

bool simdSupported(SimdPath path) {
  if (path == SimdPath::Portable) return true;
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  return __builtin_cpu_supports("avx2");
#else
  return false;
#endif
}

SimdPath simdPath() { return choice().path.load(std::memory_order_relaxed); }

std::string simdRequestProblem() { return choice().problem; }

bool setSimdPath(SimdPath path) {
  if (!simdSupported(path)) return false;
  choice().path.store(path);
  return true;
}

}  // namespace throng::core
