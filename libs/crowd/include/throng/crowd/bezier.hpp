// throng::crowd Bézier curves — evaluation, subdivision and flattening by de Casteljau's algorithm
// (Musse & Thalmann, §3.2.2, eq. 3.2.2.2: b_i^r(t) = (1-t) b_i^{r-1}(t) + t b_{i+1}^{r-1}(t)).
// A curve of degree n is its n+1 control points (metres). Pure functions: they read control points
// and write only their results; up to degree kInlineDegree nothing is allocated but the output.
#pragma once
#include <span>
#include <vector>

#include "throng/core/geometry.hpp"

namespace throng::crowd {

using core::Aabb;
using core::Vec2;

/// Curves up to this degree are evaluated and split in stack buffers (no allocation).
inline constexpr std::size_t kInlineDegree = 15;

/// A Bézier curve: `points.size() - 1` is its degree (1 = straight line, eq. 3.2.2.1; 3 = cubic).
struct BezierCurve {
  std::vector<Vec2> points;  ///< control points b_0..b_n [m]; b_0 is the start, b_n the end [Limit: size >= 1]

  [[nodiscard]] std::size_t degree() const { return points.empty() ? 0 : points.size() - 1; }
  [[nodiscard]] Vec2 start() const { return points.front(); }
  [[nodiscard]] Vec2 end() const { return points.back(); }
};

/// Point b_0^n(t) of the curve, by de Casteljau (eq. 3.2.2.2). t in [0, 1] (extrapolates outside).
[[nodiscard]] Vec2 evaluate(std::span<const Vec2> control, float t);

/// Splits the curve at t into two curves of the same degree covering [0, t] and [t, 1]: `left` and
/// `right` must each hold control.size() points (the outer diagonals of de Casteljau's triangle).
void splitInto(std::span<const Vec2> control, float t, std::span<Vec2> left, std::span<Vec2> right);

/// splitInto, returning the two halves.
[[nodiscard]] std::pair<BezierCurve, BezierCurve> split(std::span<const Vec2> control, float t);

/// Min-max box of the control polygon. By the convex-hull property the whole curve lies inside it.
[[nodiscard]] Aabb controlBox(std::span<const Vec2> control);

/// Largest distance of an inner control point from the chord b_0 b_n [m]. The curve lies in the
/// convex hull of its control points, so it deviates from the chord by at most this much.
[[nodiscard]] float flatness(std::span<const Vec2> control);

/// Flattens the curve into a polyline whose chords stay within `maxChordError` metres of the curve
/// (adaptive subdivision at t = 1/2 until flatness() <= maxChordError, at most 2^maxDepth chords).
/// Appends to `out` (cleared first) the start point, then each chord's end; b_n is always last.
void sample(std::span<const Vec2> control, float maxChordError, std::vector<Vec2>& out, int maxDepth = 16);

}  // namespace throng::crowd
