// throng::crowd paths automatic reconstruction (Musse & Thalmann, §3.1.2, "Paths Automatic
// Reconstruction" pseudocode): a group's path is a Bézier interpolation from its initial position
// to its final action point; every curve point near an interest point is snapped onto it (and takes
// its region), so the path passes through the IPs it comes close to. Reads the IPs and one Rng
// stream; writes only the returned path. Called once per group when a world is built.
#pragma once
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "throng/core/rng.hpp"
#include "throng/crowd/bezier.hpp"
#include "throng/crowd/bezier_path.hpp"
#include "throng/crowd/region.hpp"
#include "throng/crowd/walkable.hpp"

namespace throng::crowd {

inline constexpr std::int32_t kNoRegion = -1;

struct ReconstructParams {
  float maxChordError = 0.1f;  ///< flattening tolerance of the curve before snapping [m] [Limit: > 0]
  BezierPathParams bezier;     ///< curve construction (bends, retries, box-check depth)
};

struct ReconstructedPath {
  BezierCurve curve;                     ///< the interpolating curve (before snapping)
  std::vector<Vec2> points;              ///< the path: sampled curve points, snapped ones replaced by their IP's
                                         ///< centre; a run of points snapped to one IP is kept once [m]
  std::vector<std::int32_t> pointRegion; ///< per point: index of the IP it was snapped to, or kNoRegion
  std::vector<std::uint32_t> visited;    ///< IP indices in the order the path passes them (equals the
                                         ///< snapped entries of pointRegion; an IP left and re-entered repeats)
};

/// §3.1.2: curve = Bézier interpolation from `initial` to `final` (buildPath when `test` is given,
/// else makeBentCubic with bends drawn as buildPath draws them); flattened with maxChordError;
/// each sampled point p whose distance to an IP region (distanceToRegion) is <= nearDistance is
/// replaced by that IP's centre — the nearest such region, lowest index on ties (the paper's loop
/// lets the last IP win; nearest is the stable choice). nearDistance [m] [Limit: >= 0].
/// std::nullopt only when `test` is given and buildPath finds no walkable curve.
[[nodiscard]] std::optional<ReconstructedPath> reconstructPath(Vec2 initial, Vec2 final,
                                                               std::span<const Region> interestPoints,
                                                               float nearDistance, const ReconstructParams& params,
                                                               core::Rng& rng, const WalkableTest* test = nullptr);

}  // namespace throng::crowd
