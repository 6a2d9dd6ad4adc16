// throng::crowd paths automatic reconstruction (§3.1.2): Bézier interpolation from the initial
// position to the final AP, curve points near an IP snapped onto it.
#include "throng/crowd/path_reconstruction.hpp"

#include <limits>

#include "throng/core/assert.hpp"

namespace throng::crowd {

std::optional<ReconstructedPath> reconstructPath(Vec2 initial, Vec2 final, std::span<const Region> interestPoints,
                                                 float nearDistance, const ReconstructParams& params, core::Rng& rng,
                                                 const WalkableTest* test) {
  THRONG_ASSERT(nearDistance >= 0.0f && params.maxChordError > 0.0f);
  ReconstructedPath out;
  if (test != nullptr) {
    auto curve = buildPath(initial, final, *test, params.bezier, rng);
    if (!curve) return std::nullopt;
    out.curve = std::move(*curve);
  } else {
    // Same two draws as buildPath, so a test-less run follows the same stream.
    const float b1 = static_cast<float>(rng.uniform(-1.0, 1.0)) * params.bezier.maxBend;
    const float b2 = static_cast<float>(rng.uniform(-1.0, 1.0)) * params.bezier.maxBend;
    out.curve = makeBentCubic(initial, final, b1, b2);
  }

  std::vector<Vec2> samples;
  sample(out.curve.points, params.maxChordError, samples);
  out.points.reserve(samples.size());
  out.pointRegion.reserve(samples.size());
  for (const Vec2 p : samples) {
    // for each interest point pj: if Near_distance(pi, pj) then pi = pj, pi_region = pj_region.
    std::int32_t best = kNoRegion;
    float bestDist = std::numeric_limits<float>::infinity();
    for (std::size_t j = 0; j < interestPoints.size(); ++j) {
      const float d = distanceToRegion(interestPoints[j], p);
      if (d <= nearDistance && d < bestDist) {
        bestDist = d;
        best = static_cast<std::int32_t>(j);
      }
    }
    if (best == kNoRegion) {
      out.points.push_back(p);
      out.pointRegion.push_back(kNoRegion);
      continue;
    }
    if (!out.pointRegion.empty() && out.pointRegion.back() == best) continue;  // same IP: keep once
    out.points.push_back(interestPoints[static_cast<std::size_t>(best)].centre);
    out.pointRegion.push_back(best);
    out.visited.push_back(static_cast<std::uint32_t>(best));
  }
  return out;
}

}  // namespace throng::crowd
