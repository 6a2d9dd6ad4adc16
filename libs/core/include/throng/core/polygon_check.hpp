// throng::core polygon check — findSelfIntersection (geometry.hpp) with a work budget, for input
// that may be hostile: near-linear for ordinary outlines, but shapes whose long edges cross much
// of the polygon (a star of 250,000 spikes) would need every pair of edges tested; past the
// budget the check gives up and says so instead of running for an hour.
#pragma once
#include <cstdint>
#include <optional>
#include <span>
#include <utility>

#include "throng/core/vec2.hpp"

namespace throng::core {

struct SimplicityCheck {
  /// The first crossing pair of edges found (as findSelfIntersection), if any.
  std::optional<std::pair<std::size_t, std::size_t>> crossing;
  /// The budget ran out before the answer was known (no crossing found so far).
  bool tooComplex = false;
};

/// findSelfIntersection testing at most `maxTests` pairs of edges.
[[nodiscard]] SimplicityCheck checkSimple(std::span<const Vec2> poly, std::uint64_t maxTests);

}  // namespace throng::core
