// throng::common_ground sensing — the sensory model (Park et al., §3.2, Figure 2(a)): touch, hearing and
// vision of one observer toward candidates the spatial grid supplies; wall occlusion over a segment
// list or the navigation mesh. Reads bodies, writes Perceptions; no state.
#include "throng/common_ground/sensing.hpp"

#include <cmath>
#include <string>

#include "throng/core/assert.hpp"
#include "throng/nav/navmesh.hpp"

namespace throng::common_ground {

namespace {

constexpr float kTwoPi = 6.28318530718f;

// Range and field-of-view tests without occlusion; `see` is a candidate that still needs the
// line-of-sight check. Shared by perceive() and perceivedBy() so the two agree bit for bit.
struct Geometric {
  Perception p;
  bool needsSightCheck = false;
};

Geometric geometric(const Body& observer, const Body& other, const SensoryParams& params) {
  Geometric g;
  const Vec2 d = other.position - observer.position;
  const float distSq = core::lengthSq(d);
  const float touch = observer.radius + other.radius + params.touchMargin;
  g.p.touch = distSq <= touch * touch;
  g.p.hear = distSq <= params.hearingRange * params.hearingRange;
  if (distSq > params.visionRange * params.visionRange) return g;
  if (distSq == 0.0f) {
    g.needsSightCheck = true;  // coincident: in view by convention
    return g;
  }
  const float facingLenSq = core::lengthSq(observer.facing);
  if (facingLenSq == 0.0f) return g;
  // angle(facing, d) <= α/2  <=>  dot(facing, d) >= |facing| |d| cos(α/2). Exact for any α in (0, 2π]
  // (cos is monotone on [0, π]); α >= 2π covers every direction.
  const float halfAngle = params.fieldOfView * 0.5f;
  if (params.fieldOfView >= kTwoPi) {
    g.needsSightCheck = true;
    return g;
  }
  const float lhs = core::dot(observer.facing, d);
  const float rhs = std::sqrt(facingLenSq * distSq) * std::cos(halfAngle);
  g.needsSightCheck = lhs >= rhs;
  return g;
}

}  // namespace

core::Diagnostics validate(const SensoryParams& params, const std::string& pointer) {
  core::Diagnostics out;
  auto check = [&](bool ok, const char* field, float value, const char* expected) {
    if (ok) return;
    core::Diagnostic d;
    d.pointer = pointer + "/" + field;
    d.what = std::to_string(value) + " is out of range";
    d.expected = expected;
    out.push_back(std::move(d));
  };
  check(std::isfinite(params.touchMargin) && params.touchMargin >= 0.0f, "touchMargin", params.touchMargin,
        "a touch margin >= 0 m");
  check(std::isfinite(params.hearingRange) && params.hearingRange >= 0.0f, "hearingRange", params.hearingRange,
        "a hearing range >= 0 m");
  check(std::isfinite(params.visionRange) && params.visionRange >= 0.0f, "visionRange", params.visionRange,
        "a vision range >= 0 m");
  check(std::isfinite(params.fieldOfView) && params.fieldOfView > 0.0f && params.fieldOfView <= kTwoPi + 1e-6f,
        "fieldOfView", params.fieldOfView, "a field of view 0 < alpha <= 2*pi rad");
  return out;
}

bool SegmentOcclusion::blocked(Vec2 a, Vec2 b) const {
  for (const core::Segment& w : walls_) {
    if (core::segmentsIntersect(a, b, w.a, w.b)) return true;
  }
  return false;
}

bool NavMeshOcclusion::blocked(Vec2 a, Vec2 b) const { return !query_->visible(a, b); }

Perception perceive(const Body& observer, const Body& other, const SensoryParams& params,
                    const Occlusion& occlusion) {
  Geometric g = geometric(observer, other, params);
  g.p.see = g.needsSightCheck && !occlusion.blocked(observer.position, other.position);
  return g.p;
}

void perceivedBy(const Body& observer, std::span<const Body> candidates, std::span<const std::uint32_t> ids,
                 const SensoryParams& params, const Occlusion& occlusion,
                 std::vector<std::pair<std::uint32_t, Perception>>& out) {
  THRONG_ASSERT(ids.empty() || ids.size() == candidates.size());
  out.clear();
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    Geometric g = geometric(observer, candidates[i], params);
    g.p.see = g.needsSightCheck && !occlusion.blocked(observer.position, candidates[i].position);
    if (!(g.p.touch || g.p.hear || g.p.see)) continue;
    const auto id = ids.empty() ? static_cast<std::uint32_t>(i) : ids[i];
    out.emplace_back(id, g.p);
  }
}

void perceivedBy(const Body& observer, std::span<const Body> candidates, const SensoryParams& params,
                 const Occlusion& occlusion, std::vector<std::pair<std::uint32_t, Perception>>& out) {
  perceivedBy(observer, candidates, {}, params, occlusion, out);
}

}  // namespace throng::common_ground
