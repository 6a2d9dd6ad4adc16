// throng::sim ORCA — optimal reciprocal collision avoidance (van den Berg, Guy, Lin, Manocha,
// "Reciprocal n-Body Collision Avoidance", ISRR 2011). Each neighbour and each nearby wall segment
// contributes a half-plane of permitted velocities; the new velocity is the one closest to the
// preferred velocity inside all half-planes and the max-speed disc (2D linear program, §5.2), or,
// when they are infeasible, the velocity that least violates the agents' half-planes (§5.3) while
// walls stay hard constraints. Pure functions: no state, no allocation (scratch is passed in).
#pragma once
#include <span>
#include <vector>

#include "throng/core/vec2.hpp"

namespace throng::sim {

using core::Vec2;

/// A half-plane of velocities: valid on the left of `direction` through `point`,
/// i.e. det(direction, v - point) >= 0. `direction` is a unit vector.
struct OrcaLine {
  Vec2 point;
  Vec2 direction;
};

/// Half-plane for a neighbour agent. relPos = other.pos - self.pos, relVel = self.vel - other.vel,
/// selfVel = self.vel. `dt` is the step used when the two already overlap (push apart within one
/// step). `responsibility` is this agent's share of the avoidance (0.5 = reciprocal; the two shares
/// of a pair must add up to 1 for the collision-free guarantee).
OrcaLine agentOrcaLine(Vec2 relPos, Vec2 relVel, Vec2 selfVel, float combinedRadius, float timeHorizon, float dt,
                       float responsibility = 0.5f);

/// Neighbours as columns for agentOrcaLines: relative position and velocity, combined radius and
/// responsibility, as agentOrcaLine takes them.
struct OrcaNeighbours {
  const float* relPosX;
  const float* relPosY;
  const float* relVelX;
  const float* relVelY;
  const float* combinedRadius;
  const float* responsibility;
  std::size_t count;
};

/// agentOrcaLine for `nb.count` neighbours at once, written to out[0, count): the same lines bit
/// for bit, computed four or eight neighbours at a time (core::simdPath()) with every branch
/// evaluated and blended.
void agentOrcaLines(const OrcaNeighbours& nb, Vec2 selfVel, float timeHorizon, float dt, OrcaLine* out);

/// Half-plane for a static wall segment [a, b] given relative to the agent (a - pos, b - pos),
/// inflated by `radius`. The agent takes full responsibility. Returns false when the segment is
/// too far to matter within `timeHorizon` at `maxSpeed` (no line written).
bool segmentOrcaLine(Vec2 a, Vec2 b, Vec2 selfVel, float radius, float timeHorizon, float maxSpeed, OrcaLine& out);

/// Solves for the velocity closest to `prefVel` satisfying every line and |v| <= maxSpeed.
/// lines[0, numHardLines) (walls) are never relaxed. `scratch` is reused workspace.
Vec2 solveOrca(std::span<const OrcaLine> lines, std::size_t numHardLines, float maxSpeed, Vec2 prefVel,
               std::vector<OrcaLine>& scratch);

}  // namespace throng::sim
