// throng::crowd Bézier seek-goal paths (Musse & Thalmann, §3.2.2, eq. 3.2.2.1-2, Figures 6-8): a
// smooth curve from an agent's position to its target inside the next goal region, "recalculated
// to have all the points inside" the walkable surface. The min-max box check uses the convex-hull
// property of de Casteljau's algorithm: a curve whose control box is walkable is walkable; otherwise
// it is split at t = 1/2 and each half checked, down to a depth limit.
// Reads the walkable oracle and one Rng stream; writes only the returned curve. Called when an
// agent's target changes (decide phase), never per tick.
#pragma once
#include <optional>
#include <span>

#include "throng/core/rng.hpp"
#include "throng/crowd/bezier.hpp"
#include "throng/crowd/region.hpp"
#include "throng/crowd/walkable.hpp"

namespace throng::crowd {

/// Min-max box check (§3.2.2): true when the curve provably lies on the walkable surface. A curve
/// of degree <= 1 is checked as the segment itself (exact); higher degrees by control boxes,
/// subdividing at t = 1/2 a box that is not inside, up to `maxDepth` levels (at most 2^maxDepth
/// boxes); a box still not inside at the depth limit rejects the curve. maxDepth [Limit: 0..20].
/// `boxTests`, when given, is increased by the number of oracle calls made (cost accounting).
[[nodiscard]] bool verifyCurve(std::span<const Vec2> control, const WalkableTest& test, int maxDepth,
                               int* boxTests = nullptr);

struct BezierPathParams {
  float maxBend = 0.3f;      ///< largest lateral offset of the two inner control points, as a fraction of the
                             ///< straight distance from start to target [-] [Limit: >= 0]
  int attempts = 4;          ///< bent cubics tried (each with the bend scaled by `shrink`) before the straight
                             ///< line [Limit: >= 0]
  float shrink = 0.5f;       ///< bend scale applied after each rejected attempt [-] [Limit: (0, 1)]
  int maxDepth = 6;          ///< subdivision depth of the min-max box check [Limit: 0..20]
  float minLength = 0.05f;   ///< start and target closer than this get a straight line [m] [Limit: >= 0]
};

/// Cubic from `from` to `to` with inner control points at 1/3 and 2/3 of the chord, pushed sideways
/// (to the left of from→to) by bend1 and bend2 times the chord length. bend1 = bend2 = 0 is the
/// straight line; equal signs make a C, opposite signs an S.
[[nodiscard]] BezierCurve makeBentCubic(Vec2 from, Vec2 to, float bend1, float bend2);

/// Builds a walkable seek-goal curve from `from` to `to` (§3.2.2):
///   1. draw two bends b1, b2 uniform in [-maxBend, maxBend] from `rng` (always exactly two draws,
///      so the stream advances the same whatever the outcome);
///   2. for k = 0 .. attempts-1, side = +1, -1: the cubic makeBentCubic(from, to, side·b1·shrink^k,
///      side·b2·shrink^k) (the drawn bend, then its mirror image); return the first that
///      verifyCurve accepts ("recompute it until it lies inside");
///   3. then the symmetric arcs (C shapes) with bends ±maxBend and ±maxBend·shrink, which pass an
///      obstacle lying across the chord when the drawn bend was small or an S;
///   4. else the straight line (degree 1, eq. 3.2.2.1) when its segment is walkable;
///   5. else std::nullopt: no Bézier path (the caller falls back to the navigation-mesh path and
///      records an event). Start or target off the surface always gives nullopt.
/// Steps 2-3 are skipped when attempts = 0, maxBend = 0 or the chord is shorter than minLength. At most
/// 2·attempts + 4 curve checks of at most 2^(maxDepth+1) - 1 box tests each.
[[nodiscard]] std::optional<BezierCurve> buildPath(Vec2 from, Vec2 to, const WalkableTest& test,
                                                   const BezierPathParams& params, core::Rng& rng);

/// buildPath restricted to a corridor of regions (IP/AP regions, Figures 6-7): every point of the
/// curve lies on the walkable surface AND inside at least one of `corridor` (empty = no restriction).
[[nodiscard]] std::optional<BezierCurve> buildPath(Vec2 from, Vec2 to, std::span<const Region> corridor,
                                                   const WalkableTest& test, const BezierPathParams& params,
                                                   core::Rng& rng);

}  // namespace throng::crowd
