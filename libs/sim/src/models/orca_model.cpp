// ORCA as an operational model: each nearby wall segment and each neighbour found by `sense`
// contributes a half-plane of permitted velocities; the new velocity is the one closest to the
// preferred velocity inside all of them and the speed disc (throng/sim/orca.hpp, van den Berg,
// Guy, Lin, Manocha 2011). Walls are hard constraints, neighbours soft. Two throng additions:
// head-on priority (Musse et al. §3.2.1, relationship (i): the agent of the smaller group, then of
// the higher group id, gives way, taking `yieldResponsibility` of the avoidance), and a cheaper
// solve far from every viewer (§3.2.4: `lodNeighbours` neighbours, no wall half-planes; the
// navmesh still keeps agents inside). Reads the steer phase's preferred velocities; writes newVel.
#include <algorithm>
#include <cmath>
#include <vector>

#include "operational_model.hpp"
#include "throng/core/rng.hpp"
#include "throng/sim/orca.hpp"

namespace throng::sim {
namespace {

constexpr ModelParameter kParameters[] = {
    {"yieldResponsibility", "1", 0.5, false, 1.0, false, 0.8f,
     "share of the avoidance taken, head on, by the agent that gives way (0.5: both equally)",
     "Musse et al. 2000 §3.2.1 relationship (i) (the rule; the share is throng's, tuned on scenarios/crossing.json)"},
    {"lodNeighbours", "", 1, false, 1000, true, 4.0f,
     "neighbours considered far from every viewer (steering.lodDistance)",
     "Musse et al. 2000 §3.2.4 (multiresolution; the count is throng's)"},
    {"wallMargin", "m", 0.0, false, 0.5, false, 0.01f,
     "gap kept between agent centres and the walls (the navmesh is already eroded by the body radius)",
     "throng: 1 cm keeps ORCA's wall lines off the mesh edge where moveAlongSurface clamps"},
};
enum Parameter : std::size_t { kYieldResponsibility, kLodNeighbours, kWallMargin };

/// ORCA's parameters for one population, with units.
struct OrcaParams {
  float timeHorizon = 2.0f;          ///< agents [s] (steering.timeHorizon)
  float timeHorizonObstacle = 0.5f;  ///< walls [s] (steering.timeHorizonObstacle)
  float yieldResponsibility = 0.8f;  ///< [1]
  std::size_t lodNeighbours = 4;
  float wallMargin = 0.01f;          ///< [m]
};

class OrcaScratch final : public ModelScratch {
 public:
  std::vector<OrcaLine> lines, projected;
  std::vector<std::uint32_t> wallIds;
  /// The neighbours of the agent being solved, as agentOrcaLines reads them.
  std::vector<float> relPosX, relPosY, relVelX, relVelY, combinedRadius, responsibility;
  void resizeColumns(std::size_t n) {
    if (relPosX.size() >= n) return;
    for (auto* column : {&relPosX, &relPosY, &relVelX, &relVelY, &combinedRadius, &responsibility}) column->resize(n);
  }
};

/// Two centres in the same spot give ORCA no direction to push apart; pick one from the pair's ids
/// (opposite for the two agents, so they separate).
core::Vec2 separationAxis(std::uint32_t self, std::uint32_t other) {
  const std::uint32_t lo = std::min(self, other), hi = std::max(self, other);
  const std::uint64_t h = core::mix64((static_cast<std::uint64_t>(lo) << 32) | hi);
  const float angle = static_cast<float>(h % 6283u) * 0.001f;
  const float sign = self < other ? 1.0f : -1.0f;
  return core::Vec2{std::cos(angle), std::sin(angle)} * (1e-4f * sign);
}

class OrcaModel final : public OperationalModel {
 public:
  [[nodiscard]] ModelKind kind() const override { return ModelKind::Orca; }

  void configure(const ScenarioDesc& desc) override {
    params_.clear();
    for (const PopulationDesc& pop : desc.populations) {
      OrcaParams p;
      p.timeHorizon = desc.steering.timeHorizon;
      p.timeHorizonObstacle = desc.steering.timeHorizonObstacle;
      if (pop.model.kind == ModelKind::Orca) {
        p.yieldResponsibility = pop.model.values[kYieldResponsibility];
        p.lodNeighbours = static_cast<std::size_t>(pop.model.values[kLodNeighbours]);
        p.wallMargin = pop.model.values[kWallMargin];
      }
      params_.push_back(p);
    }
  }

  [[nodiscard]] std::unique_ptr<ModelScratch> makeScratch() const override { return std::make_unique<OrcaScratch>(); }

  void computeVelocities(const ModelInput& in, RowRange rows, ModelScratch& scratch, VelocityOutput out) const override {
    auto& ws = static_cast<OrcaScratch&>(scratch);
    for (std::size_t i = rows.begin; i < rows.end; ++i) {
      const std::size_t row = rows.row(i);
      const core::Vec2 v = solveRow(in, row, params_[in.agents.population[row]], ws);
      out.x[row] = v.x;
      out.y[row] = v.y;
    }
  }

 private:
  /// Walls first (hard), then neighbours; the LP gives the velocity closest to the preferred one.
  static core::Vec2 solveRow(const ModelInput& in, std::size_t row, const OrcaParams& p, OrcaScratch& ws) {
    const AgentStore& agents = in.agents;
    const core::Vec2 pos{agents.posX[row], agents.posY[row]};
    const core::Vec2 vel{agents.velX[row], agents.velY[row]};
    const float maxSpeed = agents.speed[row];
    const bool cheap = in.reducedDetail(pos);
    auto& lines = ws.lines;
    lines.clear();
    const float wallReach = p.timeHorizonObstacle * maxSpeed + p.wallMargin;
    ws.wallIds.clear();
    if (!cheap) in.walls.query(pos.x, pos.y, wallReach, ws.wallIds);
    for (std::uint32_t w : ws.wallIds) {
      if (agents.levels && !in.walls.onLevel(w, pos, agents.posZ[row])) continue;  // another floor's edge
      const core::Segment& seg = in.walls.segments()[w];
      OrcaLine line;
      if (segmentOrcaLine(seg.a - pos, seg.b - pos, vel, p.wallMargin, p.timeHorizonObstacle, maxSpeed, line)) {
        lines.push_back(line);
      }
    }
    const std::size_t numWallLines = lines.size();
    const std::size_t k = in.desc.steering.maxNeighbours;
    const std::uint32_t* nb = &agents.neighbours[row * k];
    const std::size_t count = cheap ? std::min<std::size_t>(agents.neighbourCount[row], p.lodNeighbours) : agents.neighbourCount[row];
    ws.resizeColumns(count);
    for (std::size_t i = 0; i < count; ++i) {
      const std::uint32_t o = nb[i];
      core::Vec2 relPos{agents.posX[o] - pos.x, agents.posY[o] - pos.y};
      if (core::lengthSq(relPos) < 1e-10f) relPos = separationAxis(agents.id[row], agents.id[o]);
      const core::Vec2 otherVel{agents.velX[o], agents.velY[o]};
      ws.relPosX[i] = relPos.x;
      ws.relPosY[i] = relPos.y;
      ws.relVelX[i] = vel.x - otherVel.x;
      ws.relVelY[i] = vel.y - otherVel.y;
      ws.combinedRadius[i] = agents.radius[row] + agents.radius[o];
      ws.responsibility[i] = responsibility(agents, row, o, vel, otherVel, p);
    }
    lines.resize(numWallLines + count);
    agentOrcaLines({ws.relPosX.data(), ws.relPosY.data(), ws.relVelX.data(), ws.relVelY.data(), ws.combinedRadius.data(),
                    ws.responsibility.data(), count},
                   vel, p.timeHorizon, in.desc.dt, lines.data() + numWallLines);
    // ORCA's preferred velocity: the desired one reached over steering.accelerationTime.
    const SteeringDesc& s = in.desc.steering;
    const float relax = std::min(1.0f, in.desc.dt / std::max(in.desc.dt, s.accelerationTime));
    const core::Vec2 desired{agents.prefVelX[row], agents.prefVelY[row]};
    const core::Vec2 pref = vel + (desired - vel) * relax;
    return solveOrca(lines, numWallLines, maxSpeed, pref, ws.projected);
  }

  /// This agent's share of avoiding `o`: half, except head on (velocities more than 120° apart,
  /// cos < -0.5, tested without square roots) between two groups, where the one of lower priority
  /// (smaller group, then higher group id) changes its path.
  static float responsibility(const AgentStore& agents, std::size_t row, std::uint32_t o, core::Vec2 vel,
                              core::Vec2 otherVel, const OrcaParams& p) {
    const float d = core::dot(vel, otherVel);
    if (d < 0.0f && d * d > 0.25f * core::lengthSq(vel) * core::lengthSq(otherVel) && agents.group[row] != agents.group[o]) {
      const bool yields = agents.groupSize[row] != agents.groupSize[o] ? agents.groupSize[row] < agents.groupSize[o]
                                                                        : agents.group[row] > agents.group[o];
      return yields ? p.yieldResponsibility : 1.0f - p.yieldResponsibility;
    }
    return 0.5f;
  }

  std::vector<OrcaParams> params_;  ///< per population
};

}  // namespace

const ModelInfo& orcaModelInfo() {
  static const ModelInfo info{ModelKind::Orca, "orca", "optimal reciprocal collision avoidance (ORCA)",
                              "van den Berg, Guy, Lin, Manocha, Reciprocal n-Body Collision Avoidance, ISRR 2011",
                              kParameters};
  return info;
}

std::unique_ptr<OperationalModel> makeOrcaModel() { return std::make_unique<OrcaModel>(); }

}  // namespace throng::sim
