// ORCA half-planes and the incremental 2D linear program that combines them.
// Paper: van den Berg et al. 2011, §4 (ORCA for agents), §5 (linear programming), §6 (obstacles).
#include "throng/sim/orca.hpp"

#include "throng/core/geometry.hpp"
#include "throng/core/simd.hpp"
#include "lanes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace throng::sim {
namespace {

using core::cross;
using core::dot;
using core::lengthSq;
using core::normalize;

constexpr float kEpsilon = 1e-5f;

/// Is v outside (violating) the half-plane of `line`?
inline bool violates(const OrcaLine& line, Vec2 v) { return cross(line.direction, line.point - v) > 0.0f; }

// §5.2: optimise along line `lineNo` subject to lines [0, lineNo) and the speed disc.
bool solveOnLine(std::span<const OrcaLine> lines, std::size_t lineNo, float radius, Vec2 optVelocity,
                 bool directionOpt, Vec2& result) {
  const OrcaLine& line = lines[lineNo];
  const float dotProduct = dot(line.point, line.direction);
  const float discriminant = dotProduct * dotProduct + radius * radius - lengthSq(line.point);
  if (discriminant < 0.0f) return false;  // the speed disc misses this line entirely

  const float sqrtDiscriminant = std::sqrt(discriminant);
  float tLeft = -dotProduct - sqrtDiscriminant;
  float tRight = -dotProduct + sqrtDiscriminant;

  for (std::size_t i = 0; i < lineNo; ++i) {
    const float denominator = cross(line.direction, lines[i].direction);
    const float numerator = cross(lines[i].direction, line.point - lines[i].point);
    if (std::fabs(denominator) <= kEpsilon) {
      if (numerator < 0.0f) return false;  // parallel and on the wrong side
      continue;
    }
    const float t = numerator / denominator;
    if (denominator >= 0.0f) {
      tRight = std::min(tRight, t);
    } else {
      tLeft = std::max(tLeft, t);
    }
    if (tLeft > tRight) return false;
  }

  if (directionOpt) {
    result = line.point + (dot(optVelocity, line.direction) > 0.0f ? tRight : tLeft) * line.direction;
  } else {
    const float t = std::clamp(dot(line.direction, optVelocity - line.point), tLeft, tRight);
    result = line.point + t * line.direction;
  }
  return true;
}

// §5.2: incremental randomised-order-free LP; returns the index of the first line that could not
// be satisfied, or lines.size() on success.
std::size_t solvePlane(std::span<const OrcaLine> lines, float radius, Vec2 optVelocity, bool directionOpt,
                       Vec2& result) {
  if (directionOpt) {
    result = optVelocity * radius;  // optVelocity is a unit direction here
  } else if (lengthSq(optVelocity) > radius * radius) {
    result = normalize(optVelocity) * radius;
  } else {
    result = optVelocity;
  }
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (violates(lines[i], result)) {
      const Vec2 previous = result;
      if (!solveOnLine(lines, i, radius, optVelocity, directionOpt, result)) {
        result = previous;
        return i;
      }
    }
  }
  return lines.size();
}

// §5.3: infeasible — minimise the largest violation of the soft (agent) lines, walls stay hard.
void solveInfeasible(std::span<const OrcaLine> lines, std::size_t numHard, std::size_t beginLine, float radius,
                     Vec2& result, std::vector<OrcaLine>& projected) {
  float distance = 0.0f;
  for (std::size_t i = beginLine; i < lines.size(); ++i) {
    if (cross(lines[i].direction, lines[i].point - result) <= distance) continue;
    projected.assign(lines.begin(), lines.begin() + static_cast<std::ptrdiff_t>(numHard));
    for (std::size_t j = numHard; j < i; ++j) {
      OrcaLine line;
      const float determinant = cross(lines[i].direction, lines[j].direction);
      if (std::fabs(determinant) <= kEpsilon) {
        if (dot(lines[i].direction, lines[j].direction) > 0.0f) continue;  // same direction
        line.point = 0.5f * (lines[i].point + lines[j].point);             // opposite: midway
      } else {
        line.point = lines[i].point +
                     (cross(lines[j].direction, lines[i].point - lines[j].point) / determinant) * lines[i].direction;
      }
      line.direction = normalize(lines[j].direction - lines[i].direction);
      projected.push_back(line);
    }
    const Vec2 previous = result;
    if (solvePlane(projected, radius, core::perp(lines[i].direction), true, result) < projected.size()) {
      result = previous;  // numerical trouble: keep the best so far
    }
    distance = cross(lines[i].direction, lines[i].point - result);
  }
}

}  // namespace

OrcaLine agentOrcaLine(Vec2 relPos, Vec2 relVel, Vec2 selfVel, float combinedRadius, float timeHorizon, float dt,
                       float responsibility) {
  const float distSq = lengthSq(relPos);
  const float combinedRadiusSq = combinedRadius * combinedRadius;
  OrcaLine line;
  Vec2 u;
  if (distSq > combinedRadiusSq) {
    const float invTimeHorizon = 1.0f / timeHorizon;
    const Vec2 w = relVel - invTimeHorizon * relPos;  // from the cut-off centre to relVel
    const float wLengthSq = lengthSq(w);
    const float dotProduct = dot(w, relPos);
    if (dotProduct < 0.0f && dotProduct * dotProduct > combinedRadiusSq * wLengthSq) {
      // Closest boundary point is on the cut-off circle.
      const float wLength = std::sqrt(wLengthSq);
      const Vec2 unitW = w / wLength;
      line.direction = Vec2{unitW.y, -unitW.x};
      u = (combinedRadius * invTimeHorizon - wLength) * unitW;
    } else {
      // Closest boundary point is on a leg of the cone.
      const float leg = std::sqrt(distSq - combinedRadiusSq);
      if (cross(relPos, w) > 0.0f) {
        line.direction = Vec2{relPos.x * leg - relPos.y * combinedRadius, relPos.x * combinedRadius + relPos.y * leg} / distSq;
      } else {
        line.direction = -Vec2{relPos.x * leg + relPos.y * combinedRadius, -relPos.x * combinedRadius + relPos.y * leg} / distSq;
      }
      u = dot(relVel, line.direction) * line.direction - relVel;
    }
  } else {
    // Already overlapping: resolve within one step.
    const float invTimeStep = 1.0f / dt;
    const Vec2 w = relVel - invTimeStep * relPos;
    const float wLength = core::length(w);
    const Vec2 unitW = wLength > 0.0f ? w / wLength : Vec2{1.0f, 0.0f};
    line.direction = Vec2{unitW.y, -unitW.x};
    u = (combinedRadius * invTimeStep - wLength) * unitW;
  }
  line.point = selfVel + responsibility * u;
  return line;
}

namespace {

/// One block of W neighbours (every array holds W entries): agentOrcaLine's three cases are all
/// computed, in its order of operations, and the right one chosen per lane.
template <int W>
THRONG_KERNEL void orcaLineBlock(const float* px, const float* py, const float* pvx, const float* pvy, const float* pcr,
                                 const float* presp, Vec2 selfVel, float invTimeHorizon, float invTimeStep, OrcaLine* out) {
  using L = simd::Lanes<W>;
  using F = typename L::F;
  using I = typename L::I;
  F x, y, vx, vy, cr, resp, zero, one, invTH, invTS;
  std::memcpy(&x, px, sizeof x);
  std::memcpy(&y, py, sizeof y);
  std::memcpy(&vx, pvx, sizeof vx);
  std::memcpy(&vy, pvy, sizeof vy);
  std::memcpy(&cr, pcr, sizeof cr);
  std::memcpy(&resp, presp, sizeof resp);
  L::fill(zero, 0.0f), L::fill(one, 1.0f), L::fill(invTH, invTimeHorizon), L::fill(invTS, invTimeStep);
  const F distSq = x * x + y * y;
  const F crSq = cr * cr;
  // Apart: the cut-off circle or a leg of the cone.
  const F wx = vx - x * invTH, wy = vy - y * invTH;
  const F wLengthSq = wx * wx + wy * wy;
  const F dp = wx * x + wy * y;
  const I onCircle = (dp < zero) & (dp * dp > crSq * wLengthSq);
  F wLength, leg, oLength;
  simd::sqrtLanes<W>(wLength, wLengthSq);
  const F circleX = wx / wLength, circleY = wy / wLength;
  const F circleS = cr * invTH - wLength;
  simd::sqrtLanes<W>(leg, distSq - crSq);
  const I leftLeg = (x * wy - y * wx) > zero;
  const F lx = (x * leg - y * cr) / distSq, ly = (x * cr + y * leg) / distSq;
  const F rx = (-(x * leg + y * cr)) / distSq, ry = (-(-x * cr + y * leg)) / distSq;
  const F legX = leftLeg ? lx : rx, legY = leftLeg ? ly : ry;
  const F legDot = vx * legX + vy * legY;
  // Overlapping: push apart within one step.
  const F ox = vx - x * invTS, oy = vy - y * invTS;
  simd::sqrtLanes<W>(oLength, ox * ox + oy * oy);
  const I moving = oLength > zero;
  const F oux = moving ? ox / oLength : one, ouy = moving ? oy / oLength : zero;
  const F overlapS = cr * invTS - oLength;

  const I apart = distSq > crSq;
  const I circle = apart & onCircle, cone = apart & ~onCircle;
  const F dirX = circle ? circleY : cone ? legX : ouy;
  const F dirY = circle ? -circleX : cone ? legY : -oux;
  const F ux = circle ? circleX * circleS : cone ? legX * legDot - vx : oux * overlapS;
  const F uy = circle ? circleY * circleS : cone ? legY * legDot - vy : ouy * overlapS;
  const F pointX = ux * resp, pointY = uy * resp;
  for (int l = 0; l < W; ++l) {
    out[l].point = Vec2{selfVel.x + pointX[l], selfVel.y + pointY[l]};
    out[l].direction = Vec2{dirX[l], dirY[l]};
  }
}

template <int W>
THRONG_KERNEL void agentOrcaLinesIn(const OrcaNeighbours& nb, Vec2 selfVel, float timeHorizon, float dt, OrcaLine* out) {
  const float invTimeHorizon = 1.0f / timeHorizon, invTimeStep = 1.0f / dt;
  std::size_t i = 0;
  for (; i + W <= nb.count; i += W) {
    orcaLineBlock<W>(nb.relPosX + i, nb.relPosY + i, nb.relVelX + i, nb.relVelY + i, nb.combinedRadius + i,
                     nb.responsibility + i, selfVel, invTimeHorizon, invTimeStep, out + i);
  }
  if (i == nb.count) return;
  // The last few: copied into full blocks, the empty lanes a harmless neighbour 1 m away.
  float x[W], y[W], vx[W], vy[W], cr[W], resp[W];
  OrcaLine lines[W];
  const std::size_t left = nb.count - i;
  for (std::size_t l = 0; l < static_cast<std::size_t>(W); ++l) {
    const bool real = l < left;
    x[l] = real ? nb.relPosX[i + l] : 1.0f;
    y[l] = real ? nb.relPosY[i + l] : 0.0f;
    vx[l] = real ? nb.relVelX[i + l] : 0.0f;
    vy[l] = real ? nb.relVelY[i + l] : 0.0f;
    cr[l] = real ? nb.combinedRadius[i + l] : 0.5f;
    resp[l] = real ? nb.responsibility[i + l] : 0.5f;
  }
  orcaLineBlock<W>(x, y, vx, vy, cr, resp, selfVel, invTimeHorizon, invTimeStep, lines);
  std::copy(lines, lines + left, out + i);
}

#if defined(__x86_64__)
[[gnu::target("avx2")]] void agentOrcaLinesAvx2(const OrcaNeighbours& nb, Vec2 selfVel, float timeHorizon, float dt,
                                                OrcaLine* out) {
  agentOrcaLinesIn<8>(nb, selfVel, timeHorizon, dt, out);
}
#endif

}  // namespace

void agentOrcaLines(const OrcaNeighbours& nb, Vec2 selfVel, float timeHorizon, float dt, OrcaLine* out) {
#if defined(__x86_64__)
  if (core::simdPath() == core::SimdPath::Avx2) return agentOrcaLinesAvx2(nb, selfVel, timeHorizon, dt, out);
#endif
  agentOrcaLinesIn<4>(nb, selfVel, timeHorizon, dt, out);
}

bool segmentOrcaLine(Vec2 a, Vec2 b, Vec2 selfVel, float radius, float timeHorizon, float maxSpeed, OrcaLine& out) {
  const Vec2 closest = core::closestPointOnSegment(Vec2{}, a, b);
  const float closestDistSq = lengthSq(closest);
  const float reach = timeHorizon * maxSpeed + radius;
  if (closestDistSq > reach * reach) return false;

  const float radiusSq = radius * radius;
  if (closestDistSq <= radiusSq) {
    // Touching the wall: forbid any velocity component towards it.
    const Vec2 n = closestDistSq > 0.0f ? normalize(closest) : normalize(core::perp(b - a));
    out.point = Vec2{};
    out.direction = core::perp(n);
    return true;
  }

  // Legs: tangents from the origin to the discs around each end; keep the outermost pair.
  auto leftTangent = [&](Vec2 q) {
    const float d2 = lengthSq(q);
    const float leg = std::sqrt(std::max(0.0f, d2 - radiusSq));
    return Vec2{q.x * leg - q.y * radius, q.x * radius + q.y * leg} / d2;
  };
  auto rightTangent = [&](Vec2 q) {
    const float d2 = lengthSq(q);
    const float leg = std::sqrt(std::max(0.0f, d2 - radiusSq));
    return Vec2{q.x * leg + q.y * radius, -q.x * radius + q.y * leg} / d2;
  };
  const Vec2 leftA = leftTangent(a), leftB = leftTangent(b);
  const Vec2 rightA = rightTangent(a), rightB = rightTangent(b);
  const bool leftIsB = cross(leftA, leftB) > 0.0f;    // b's tangent is further counter-clockwise
  const bool rightIsB = cross(rightA, rightB) < 0.0f; // b's tangent is further clockwise
  const Vec2 leftLeg = leftIsB ? leftB : leftA;
  const Vec2 rightLeg = rightIsB ? rightB : rightA;

  const float invTimeHorizon = 1.0f / timeHorizon;
  const Vec2 leftCutoff = invTimeHorizon * (leftIsB ? b : a);
  const Vec2 rightCutoff = invTimeHorizon * (rightIsB ? b : a);
  const float cutoffRadius = radius * invTimeHorizon;
  const Vec2 cutoffVec = rightCutoff - leftCutoff;
  const bool pointCutoff = lengthSq(cutoffVec) <= kEpsilon * kEpsilon;

  const float t = pointCutoff ? 0.5f : dot(selfVel - leftCutoff, cutoffVec) / lengthSq(cutoffVec);
  const float tLeft = dot(selfVel - leftCutoff, leftLeg);
  const float tRight = dot(selfVel - rightCutoff, rightLeg);

  auto onCutoffCircle = [&](Vec2 centre) {
    Vec2 w = normalize(selfVel - centre);
    if (lengthSq(w) == 0.0f) w = normalize(-centre);
    out.direction = Vec2{w.y, -w.x};
    out.point = centre + cutoffRadius * w;
  };

  if ((t < 0.0f && tLeft < 0.0f) || (pointCutoff && tLeft < 0.0f && tRight < 0.0f)) {
    onCutoffCircle(leftCutoff);
    return true;
  }
  if (t > 1.0f && tRight < 0.0f) {
    onCutoffCircle(rightCutoff);
    return true;
  }

  constexpr float kInf = std::numeric_limits<float>::infinity();
  const float distCutoff = (t < 0.0f || t > 1.0f || pointCutoff) ? kInf : lengthSq(selfVel - (leftCutoff + t * cutoffVec));
  const float distLeft = tLeft < 0.0f ? kInf : lengthSq(selfVel - (leftCutoff + tLeft * leftLeg));
  const float distRight = tRight < 0.0f ? kInf : lengthSq(selfVel - (rightCutoff + tRight * rightLeg));

  if (distCutoff <= distLeft && distCutoff <= distRight) {
    // The flat front of the truncated cone; valid side faces the agent (the origin).
    Vec2 n = normalize(core::perp(cutoffVec));
    if (dot(n, -leftCutoff) < 0.0f) n = -n;
    out.direction = Vec2{n.y, -n.x};
    out.point = leftCutoff + cutoffRadius * n;
    return true;
  }
  if (distLeft <= distRight) {
    out.direction = leftLeg;
    out.point = leftCutoff + cutoffRadius * Vec2{-leftLeg.y, leftLeg.x};
    return true;
  }
  out.direction = -rightLeg;
  out.point = rightCutoff + cutoffRadius * Vec2{rightLeg.y, -rightLeg.x};
  return true;
}

Vec2 solveOrca(std::span<const OrcaLine> lines, std::size_t numHardLines, float maxSpeed, Vec2 prefVel,
               std::vector<OrcaLine>& scratch) {
  Vec2 result;
  const std::size_t failed = solvePlane(lines, maxSpeed, prefVel, false, result);
  if (failed < lines.size()) solveInfeasible(lines, numHardLines, failed, maxSpeed, result, scratch);
  return result;
}

}  // namespace throng::sim
