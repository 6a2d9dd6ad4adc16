// throng::common_ground situation assessment (Park et al., §3.2, Figure 2(b)): the relation A1..A6 of an
// initiator to a group mate, the approach points x_i / x_j for A3 and A6, and the attention
// micro-behaviours each relation allows (Table 2). Reads two bodies and the walls; writes nothing.
#include "throng/common_ground/relations.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace throng::common_ground {

namespace {

constexpr float kPi = 3.14159265359f;
constexpr float kTwoPi = 6.28318530718f;

Vec2 rotate(Vec2 v, float angle) { return v * std::cos(angle) + core::perp(v) * std::sin(angle); }

/// Fallback when the geometrically nearest point is occluded: the nearest unoccluded sample of the
/// sector (fixed 9 × 4 fan, deterministic order, ties keep the first).
Approach fanSearch(Vec2 a, Vec2 b, Vec2 f, float halfAngle, float rMin, float rMax, const Occlusion& occlusion,
                   Vec2 fallback) {
  constexpr int kAngles = 9;
  constexpr int kRadii = 4;
  Approach best{fallback, false};
  float bestDistSq = 0.0f;
  for (int k = 0; k < kAngles; ++k) {
    const float theta = -halfAngle + 2.0f * halfAngle * static_cast<float>(k) / static_cast<float>(kAngles - 1);
    const Vec2 u = rotate(f, theta);
    for (int j = 0; j < kRadii; ++j) {
      const float r = rMin + (rMax - rMin) * static_cast<float>(j) / static_cast<float>(kRadii - 1);
      const Vec2 x = b + u * r;
      const float dSq = core::lengthSq(x - a);
      if (best.reachable && dSq >= bestDistSq) continue;
      if (occlusion.blocked(b, x)) continue;
      best = {x, true};
      bestDistSq = dSq;
    }
  }
  return best;
}

constexpr std::array<std::string_view, 2> kA1{behaviour::kTap, behaviour::kCallOut};
constexpr std::array<std::string_view, 3> kA2{behaviour::kCallOut, behaviour::kWave, behaviour::kLookAt};
constexpr std::array<std::string_view, 2> kA3{behaviour::kMoveIntoViewWave, behaviour::kMoveIntoHearingCallOut};
constexpr std::array<std::string_view, 1> kA4{behaviour::kCallOut};
constexpr std::array<std::string_view, 1> kA5{behaviour::kWave};
constexpr std::array<std::string_view, 1> kA6{behaviour::kMoveToward};

}  // namespace

Relation assess(const Body& initiatorA, const Body& memberB, const SensoryParams& params,
                const Occlusion& occlusion) {
  const Perception pB = perceive(memberB, initiatorA, params, occlusion);
  if (pB.touch) return Relation::A1;
  if (pB.see && pB.hear) return Relation::A2;
  if (pB.hear) return Relation::A4;
  if (pB.see) return Relation::A5;
  const Perception pA = perceive(initiatorA, memberB, params, occlusion);
  return pA.see ? Relation::A3 : Relation::A6;
}

Approach pointInView(const Body& initiatorA, const Body& memberB, const SensoryParams& params,
                     const Occlusion& occlusion, float standOff) {
  const Vec2 a = initiatorA.position;
  const Vec2 b = memberB.position;
  const Perception already = perceive(memberB, initiatorA, params, occlusion);
  if (already.see && already.hear) return {a, true};

  const Vec2 f = core::normalize(memberB.facing);
  const float rMax = std::min(params.hearingRange, params.visionRange) - kApproachMargin;
  if (core::lengthSq(f) == 0.0f || rMax <= 0.0f || !(params.fieldOfView > 0.0f)) return {a, false};
  const bool fullCircle = params.fieldOfView >= kTwoPi;
  const float halfAngle = fullCircle ? kPi : std::max(0.0f, params.fieldOfView * 0.5f - kApproachMargin);
  const float rMin = std::min(std::max(standOff, initiatorA.radius + memberB.radius), rMax);

  // A in polar coordinates around B, angle measured from B's facing (positive = counter-clockwise).
  const Vec2 d = a - b;
  const float rho = core::length(d);
  const float phi = rho > 0.0f ? std::atan2(core::cross(f, d), core::dot(f, d)) : 0.0f;

  Vec2 x;
  if (std::abs(phi) <= halfAngle) {
    x = b + rotate(f, phi) * std::clamp(rho, rMin, rMax);
  } else {
    // Outside the cone's angular range the nearest point lies on one of the two straight edges
    // (the arcs' nearest points are then their end points, which are on the edges).
    const Vec2 uPos = rotate(f, halfAngle);
    const Vec2 uNeg = rotate(f, -halfAngle);
    const Vec2 xPos = core::closestPointOnSegment(a, b + uPos * rMin, b + uPos * rMax);
    const Vec2 xNeg = core::closestPointOnSegment(a, b + uNeg * rMin, b + uNeg * rMax);
    const float dPos = core::lengthSq(xPos - a);
    const float dNeg = core::lengthSq(xNeg - a);
    x = (dPos < dNeg || (dPos == dNeg && phi > 0.0f)) ? xPos : xNeg;
  }
  if (!occlusion.blocked(b, x)) return {x, true};
  return fanSearch(a, b, f, halfAngle, rMin, rMax, occlusion, x);
}

Approach pointInHearing(const Body& initiatorA, const Body& memberB, const SensoryParams& params) {
  const Vec2 a = initiatorA.position;
  const Vec2 b = memberB.position;
  const float r = std::max(0.0f, params.hearingRange - kApproachMargin);
  const Vec2 d = a - b;
  const float rho = core::length(d);
  if (rho <= r) return {a, true};
  return {b + d * (r / rho), true};
}

std::span<const std::string_view> allowedAttentionBehaviours(Relation r) {
  switch (r) {
    case Relation::A1: return kA1;
    case Relation::A2: return kA2;
    case Relation::A3: return kA3;
    case Relation::A4: return kA4;
    case Relation::A5: return kA5;
    case Relation::A6: return kA6;
  }
  return {};
}

}  // namespace throng::common_ground
