// throng::crowd Bézier curves — de Casteljau evaluation, subdivision and flattening (§3.2.2,
// eq. 3.2.2.2). Stack buffers up to kInlineDegree; one heap buffer beyond.
#include "throng/crowd/bezier.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "throng/core/assert.hpp"

namespace throng::crowd {

namespace {

/// Scratch of n points: on the stack when small, on the heap otherwise.
class Scratch {
 public:
  explicit Scratch(std::size_t n) {
    if (n > inline_.size()) heap_.resize(n);
    data_ = n > inline_.size() ? heap_.data() : inline_.data();
  }
  Vec2* data() { return data_; }

 private:
  std::array<Vec2, kInlineDegree + 1> inline_{};
  std::vector<Vec2> heap_;
  Vec2* data_;
};

/// One de Casteljau step in place: b_i <- (1-t) b_i + t b_{i+1}, i < m.
inline void lerpStep(Vec2* b, std::size_t m, float t) {
  const float s = 1.0f - t;
  for (std::size_t i = 0; i < m; ++i) b[i] = b[i] * s + b[i + 1] * t;
}

}  // namespace

Vec2 evaluate(std::span<const Vec2> control, float t) {
  THRONG_ASSERT(!control.empty());
  const std::size_t n = control.size();
  Scratch s(n);
  Vec2* b = s.data();
  std::copy(control.begin(), control.end(), b);
  // r = 1..n: b_i^r = (1-t) b_i^{r-1} + t b_{i+1}^{r-1}, i = 0..n-1-r (eq. 3.2.2.2).
  for (std::size_t m = n - 1; m > 0; --m) lerpStep(b, m, t);
  return b[0];
}

void splitInto(std::span<const Vec2> control, float t, std::span<Vec2> left, std::span<Vec2> right) {
  const std::size_t n = control.size();
  THRONG_ASSERT(n >= 1 && left.size() == n && right.size() == n);
  // Work in `right`: after step r its first n-r entries are b_i^r; b_0^r is the left curve's r-th
  // point and b_{n-r}^r the right curve's (n-r)-th.
  std::copy(control.begin(), control.end(), right.begin());
  left[0] = right[0];
  for (std::size_t m = n - 1; m > 0; --m) {
    lerpStep(right.data(), m, t);
    left[n - m] = right[0];
  }
  // right[i] now holds b_0^{n-1-i}... rebuild right's order: right curve point j is b_j^{n-j}.
  // During the sweep b_j^{n-j} was right[j] at the step that left it untouched: the last entry of
  // each shrinking row stays in place, so right[j] is exactly b_j^{n-j}. Nothing to do.
}

std::pair<BezierCurve, BezierCurve> split(std::span<const Vec2> control, float t) {
  BezierCurve l{std::vector<Vec2>(control.size())};
  BezierCurve r{std::vector<Vec2>(control.size())};
  splitInto(control, t, l.points, r.points);
  return {std::move(l), std::move(r)};
}

Aabb controlBox(std::span<const Vec2> control) { return core::bounds(control); }

float flatness(std::span<const Vec2> control) {
  const std::size_t n = control.size();
  if (n <= 2) return 0.0f;
  float worst = 0.0f;
  for (std::size_t i = 1; i + 1 < n; ++i) {
    worst = std::max(worst, core::distanceToSegmentSq(control[i], control.front(), control.back()));
  }
  return std::sqrt(worst);
}

namespace {

void sampleRec(std::span<const Vec2> control, float tol, int depth, Vec2* scratch, std::vector<Vec2>& out) {
  const std::size_t n = control.size();
  if (depth <= 0 || flatness(control) <= tol) {
    out.push_back(control.back());
    return;
  }
  std::span<Vec2> left(scratch, n);
  std::span<Vec2> right(scratch + n, n);
  splitInto(control, 0.5f, left, right);
  sampleRec(left, tol, depth - 1, scratch + 2 * n, out);
  sampleRec(right, tol, depth - 1, scratch + 2 * n, out);
}

}  // namespace

void sample(std::span<const Vec2> control, float maxChordError, std::vector<Vec2>& out, int maxDepth) {
  THRONG_ASSERT(!control.empty());
  THRONG_ASSERT(maxChordError > 0.0f && maxDepth >= 0 && maxDepth <= 30);
  out.clear();
  out.push_back(control.front());
  if (control.size() == 1) return;
  // Each level keeps its two halves alive while recursing: 2 n points per level.
  std::vector<Vec2> scratch(2 * control.size() * (static_cast<std::size_t>(maxDepth) + 1));
  sampleRec(control, maxChordError, maxDepth, scratch.data(), out);
}

}  // namespace throng::crowd
