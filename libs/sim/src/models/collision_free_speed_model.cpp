// The collision-free speed model (Tordeux, Chraibi, Seyfried, "Collision-free speed model for
// pedestrian dynamics", Traffic and Granular Flow '15, 2016) as an operational model. A first-order
// model: the velocity is a speed times a direction.
//   direction e_i = normalise(e0 + Σ_j a·exp((ℓ_ij − s_ij)/D)·n_ij + Σ_w b·exp(−s_iw/D_w)·n_iw)
//   speed     v_i = min(v0, max(0, (s_i − ℓ)/T))
// e0 and v0 are the direction and length of the preferred velocity (steer phase), n_ij the unit
// vector from neighbour j to i, s_ij their distance, ℓ_ij = r_i + r_j, n_iw and s_iw the same for
// the nearest point of wall w (walls bound centres: the navmesh is eroded by the body), and s_i the
// distance to the nearest neighbour ahead within the corridor of width ℓ along e_i. A headway
// model: speed falls with the gap ahead, so it slows in dense crowds where ORCA does not.
// Reads the steer phase's preferred velocities; writes newVel. Not calibrated yet (issue 17).
#include <algorithm>
#include <cmath>
#include <vector>

#include "operational_model.hpp"

namespace throng::sim {
namespace {

constexpr std::string_view kDefaults = "Tordeux et al. 2016 (the model); values: JuPedSim's CollisionFreeSpeedModel defaults";
constexpr ModelParameter kParameters[] = {
    {"timeGap", "s", 0.0, true, 10.0, false, 1.0f, "time gap T kept to the person ahead", kDefaults},
    {"neighbourStrength", "1", 0.0, false, 100.0, false, 8.0f, "strength a of the repulsion between neighbours", kDefaults},
    {"neighbourRange", "m", 0.0, true, 5.0, false, 0.1f, "range D of the repulsion between neighbours", kDefaults},
    {"wallStrength", "1", 0.0, false, 100.0, false, 5.0f, "strength b of the repulsion from walls", kDefaults},
    {"wallRange", "m", 0.0, true, 5.0, false, 0.02f, "range D_w of the repulsion from walls", kDefaults},
};
enum Parameter : std::size_t { kTimeGap, kNeighbourStrength, kNeighbourRange, kWallStrength, kWallRange };

struct CfsmParams {
  float timeGap = 1.0f;            ///< T [s]
  float neighbourStrength = 8.0f;  ///< a [1]
  float neighbourRange = 0.1f;     ///< D [m]
  float wallStrength = 5.0f;       ///< b [1]
  float wallRange = 0.02f;         ///< D_w [m]
};

class CfsmScratch final : public ModelScratch {
 public:
  std::vector<std::uint32_t> wallIds;
};

class CollisionFreeSpeedModel final : public OperationalModel {
 public:
  [[nodiscard]] ModelKind kind() const override { return ModelKind::CollisionFreeSpeed; }

  void configure(const ScenarioDesc& desc) override {
    params_.clear();
    for (const PopulationDesc& pop : desc.populations) {
      CfsmParams p;
      if (pop.model.kind == ModelKind::CollisionFreeSpeed) {
        const auto& v = pop.model.values;
        p = {v[kTimeGap], v[kNeighbourStrength], v[kNeighbourRange], v[kWallStrength], v[kWallRange]};
      }
      params_.push_back(p);
    }
  }

  [[nodiscard]] std::unique_ptr<ModelScratch> makeScratch() const override { return std::make_unique<CfsmScratch>(); }

  void computeVelocities(const ModelInput& in, RowRange rows, ModelScratch& scratch, VelocityOutput out) const override {
    auto& ws = static_cast<CfsmScratch&>(scratch);
    for (std::size_t i = rows.begin; i < rows.end; ++i) {
      const std::size_t row = rows.row(i);
      const core::Vec2 v = velocity(in, row, params_[in.agents.population[row]], ws);
      out.x[row] = v.x;
      out.y[row] = v.y;
    }
  }

 private:
  static core::Vec2 velocity(const ModelInput& in, std::size_t row, const CfsmParams& p, CfsmScratch& ws) {
    const AgentStore& a = in.agents;
    const core::Vec2 pos{a.posX[row], a.posY[row]};
    const core::Vec2 pref{a.prefVelX[row], a.prefVelY[row]};
    const float v0 = core::length(pref);
    if (v0 < 1e-6f) return {};  // nowhere to go: stand
    const std::size_t k = in.desc.steering.maxNeighbours;
    const std::uint32_t* nb = &a.neighbours[row * k];
    const std::size_t count = a.neighbourCount[row];
    // Direction: the desired one pushed away from close neighbours and walls.
    core::Vec2 dir = pref / v0;
    for (std::size_t i = 0; i < count; ++i) {
      const std::uint32_t o = nb[i];
      const core::Vec2 away = pos - core::Vec2{a.posX[o], a.posY[o]};
      const float s = core::length(away);
      if (s < 1e-6f) continue;
      dir += away * (p.neighbourStrength * core::exp((a.radius[row] + a.radius[o] - s) / p.neighbourRange) / s);
    }
    dir += exponentialWallPush(in, row, a.radius[row] + 30.0f * p.wallRange, p.wallStrength, p.wallRange, ws.wallIds);
    const float len = core::length(dir);
    if (len < 1e-6f) return {};
    dir = dir / len;
    // Speed: the headway to the nearest neighbour ahead within the body's corridor.
    float speed = v0;
    for (std::size_t i = 0; i < count; ++i) {
      const std::uint32_t o = nb[i];
      const core::Vec2 d = core::Vec2{a.posX[o], a.posY[o]} - pos;
      const float ahead = core::dot(d, dir);
      const float l = a.radius[row] + a.radius[o];
      if (ahead <= 0.0f || std::abs(core::cross(dir, d)) > l) continue;
      speed = std::min(speed, std::max(0.0f, (core::length(d) - l) / p.timeGap));
    }
    return dir * speed;
  }

  std::vector<CfsmParams> params_;  ///< per population
};

}  // namespace

const ModelInfo& collisionFreeSpeedModelInfo() {
  static const ModelInfo info{ModelKind::CollisionFreeSpeed, "cfsm", "collision-free speed model",
                              "Tordeux, Chraibi, Seyfried, Collision-free speed model for pedestrian dynamics, "
                              "Traffic and Granular Flow '15, Springer 2016",
                              kParameters};
  return info;
}

std::unique_ptr<OperationalModel> makeCollisionFreeSpeedModel() { return std::make_unique<CollisionFreeSpeedModel>(); }

}  // namespace throng::sim
