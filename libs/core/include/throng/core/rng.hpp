// throng::core::Rng — PCG32 (O'Neill, pcg-random.org; XSH-RR output), seeded per
// (seed, stable entity id, purpose) so one entity's draws never shift another's. Sampling is our
// own: std:: distributions are implementation-defined and would break cross-platform determinism.
#pragma once
#include <cmath>
#include <cstdint>

namespace throng::core {

/// Purposes keep streams of one entity apart (spawn position vs. speed vs. goal choice).
enum class RngPurpose : std::uint32_t {
  Spawn = 1,
  Speed = 2,
  Goal = 3,
  GroupSize = 4,
  Target = 5,
  Behaviour = 6,
  Bench = 7,
  Social = 8,  ///< Common Ground: goal generator (needs, attraction, interests)
  PreMovement = 9,  ///< an agent's pre-movement time (PopulationDesc::preMovement)
  ExitChoice = 10,  ///< a group's exit drawn by shares (ExitRule::Allocation)
  GoalChoice = 11,  ///< a group's waypoint drawn by shares (GoalSplit::Shares)
  StairClimb = 12,  ///< whether a group takes the stairs over a ride (PopulationDesc::stairClimbUp/Down)
};

/// SplitMix64 finaliser: a well-mixed 64-bit hash of x.
constexpr std::uint64_t mix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

class Rng {
 public:
  /// A stream for one entity and purpose. Same arguments, same sequence, on every platform.
  Rng(std::uint64_t seed, std::uint64_t entity, RngPurpose purpose) {
    const std::uint64_t s = mix64(seed ^ mix64(entity * 0x100000001b3ull + static_cast<std::uint64_t>(purpose)));
    const std::uint64_t stream = mix64(s ^ static_cast<std::uint64_t>(purpose));
    inc_ = (stream << 1u) | 1u;
    state_ = 0;
    next();
    state_ += s;
    next();
  }

  /// Uniform 32-bit value.
  std::uint32_t next() {
    const std::uint64_t old = state_;
    state_ = old * 6364136223846793005ull + inc_;
    const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rot = static_cast<std::uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }

  /// Uniform in [0, 1).
  double uniform() { return (next() >> 8) * (1.0 / 16777216.0); }
  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// Uniform integer in [lo, hi] (inclusive), unbiased by rejection.
  std::uint32_t uniformInt(std::uint32_t lo, std::uint32_t hi) {
    const std::uint32_t range = hi - lo + 1u;
    if (range == 0) return next();  // full 32-bit range
    const std::uint32_t limit = (0xffffffffu / range) * range;
    std::uint32_t r;
    do { r = next(); } while (r >= limit);
    return lo + r % range;
  }
  /// Standard normal (Box–Muller; our own, so identical everywhere).
  double normal() {
    double u1 = uniform();
    if (u1 < 1e-300) u1 = 1e-300;
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }
  double normal(double mean, double sd) { return mean + sd * normal(); }

 private:
  std::uint64_t state_ = 0;
  std::uint64_t inc_ = 1;
};

}  // namespace throng::core
