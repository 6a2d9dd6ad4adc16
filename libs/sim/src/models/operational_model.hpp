// OperationalModel — the seam between the steer phase and the avoidance model (after JuPedSim's
// OperationalModel: compute from a const view, then commit). Steer computes every agent's
// preferred velocity (steer.cpp); then, for runs of consecutive rows whose populations walk with
// the same model, it calls that model's computeVelocities, which reads the agents' columns, the
// neighbours found by `sense` and the walls, and writes only the new velocity of the rows it is
// given. `integrate` commits those velocities. One object per model in use, shared by all threads:
// computeVelocities is const and keeps per-thread state in the ModelScratch it is handed.
//
// Adding a model (docs/architecture.md): one file in this folder defining the model class, its
// parameter table and its `…ModelInfo()`/`make…Model()` pair, declared at the end of this header;
// one ModelKind value (throng/sim/models.hpp); one line in models.cpp's catalogue.
#pragma once
#include <cmath>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "../agent_store.hpp"
#include "../walls.hpp"
#include "throng/core/exp.hpp"
#include "throng/core/vec2.hpp"
#include "throng/sim/models.hpp"
#include "throng/sim/scenario.hpp"

namespace throng::sim {

/// What a model may read while it computes (all of it read-only during the steer phase).
struct ModelInput {
  const AgentStore& agents;   ///< every column; neighbours[row * maxNeighbours …] from sense
  const Walls& walls;         ///< the walkable area's boundary
  const ScenarioDesc& desc;   ///< dt, steering, populations (each with its ModelDesc)
  std::span<const core::Vec2> viewers;  ///< for the level of detail (World::setViewers)
  std::uint64_t tick = 0;               ///< the tick being steered (time-sliced work: avm's look ahead)
  /// During steer, when a model in use asks for them (OperationalModel::readsPriorDesired): every
  /// row's preferred velocity of the previous tick [m/s]. Steer rewrites prefVelX/Y row by row in
  /// parallel, so a model that reads what its neighbours wanted reads it here: the same for any
  /// thread or rank count. Else empty.
  std::span<const float> priorDesiredX, priorDesiredY;

  /// Multiresolution (Musse et al. §3.2.4): an agent farther than steering.lodDistance from every
  /// viewer may be steered more cheaply (what "cheaper" means is the model's choice).
  [[nodiscard]] bool reducedDetail(core::Vec2 pos) const {
    const float lod = desc.steering.lodDistance;
    if (lod <= 0.0f || viewers.empty()) return false;
    float nearest = 1e30f;
    for (const core::Vec2& v : viewers) nearest = std::min(nearest, core::lengthSq(v - pos));
    return nearest > lod * lod;
  }
};

/// The rows a call handles: rows[begin, end) of a list, or the rows begin … end-1 themselves when
/// `list` is null (the whole world, not partitioned).
struct RowRange {
  const std::uint32_t* list = nullptr;
  std::size_t begin = 0, end = 0;
  [[nodiscard]] std::size_t row(std::size_t i) const { return list != nullptr ? list[i] : i; }
};

/// Where a model writes: the new velocity column [m/s]; only the rows it was given.
/// How bodies turn (integrate applies it; a model that holds headings predicts it): the time constant
/// of heading changes [s] — bodies do not snap to their velocity direction —
inline constexpr float kTurnTime = 0.25f;
/// and the speed below which a body turns toward where it wants to go (its preferred velocity), not
/// toward its motion [m/s]: pressed sideways or back in a queue, people keep facing the door.
/// Measured on the dense room of scripts/validate.py (200 people, a 1 m door, seed 1): of the
/// samples of people standing (< 0.2 m/s) in the room, 37 % faced more than 45° away from the door
/// when the body turned toward any motion over 0.1 m/s, 0.8 % with this rule (docs/crowd-model.md).
inline constexpr float kFaceDesiredBelow = 0.5f;

struct VelocityOutput {
  std::span<float> x, y;
  /// 1: the body keeps its heading this tick (integrate does not turn it); a model that never
  /// holds headings leaves the column alone (0).
  std::span<std::uint8_t> holdHeading;
  /// What the model keeps of a row between ticks (AgentStore::lookTurn); a model without such
  /// state leaves it alone.
  std::span<std::int8_t> lookTurn;
};

/// A model's per-thread working memory (half-planes, wall ids, …), made by the model.
class ModelScratch {
 public:
  virtual ~ModelScratch() = default;
};

class OperationalModel {
 public:
  virtual ~OperationalModel() = default;
  [[nodiscard]] virtual ModelKind kind() const = 0;
  /// Reads the model's typed parameters of every population (at creation and whenever crowds add
  /// populations at run time).
  virtual void configure(const ScenarioDesc& desc) = 0;
  [[nodiscard]] virtual std::unique_ptr<ModelScratch> makeScratch() const = 0;
  /// Whether the model reads the previous tick's preferred velocities (ModelInput::priorDesiredX/Y);
  /// they are there during steer only when some model in use does.
  [[nodiscard]] virtual bool readsPriorDesired() const { return false; }
  /// Called once per tick, on one thread beside sense's neighbour search (World::Impl::sense), with
  /// in.priorDesiredX/Y set: per-tick structures built from every row (the avm's crowd grid). It
  /// may read the positions, bodies and priorDesired, which nothing changes before steer, but not
  /// the neighbour lists, which sense is writing.
  virtual void beginStep(const ModelInput& in) {}
  /// New velocities of the given rows from their preferred velocities (prefVelX/Y), positions,
  /// velocities, bodies, neighbours and the walls. Writes out.x/out.y of those rows only.
  virtual void computeVelocities(const ModelInput& in, RowRange rows, ModelScratch& scratch,
                                 VelocityOutput out) const = 0;
  /// How many position corrections (separation) the population's rows get after each move; 0 (the
  /// default): none.
  [[nodiscard]] virtual int separationPasses(std::uint16_t population) const { return 0; }
  /// After the move (integrate: positions and headings as moved this tick): the displacement [m]
  /// that takes the row's body out of the bodies it still overlaps — its share of each pair's
  /// depth — or zero. Every row of a pass reads the same positions (Jacobi).
  [[nodiscard]] virtual core::Vec2 separation(const ModelInput& in, std::size_t row) const { return {}; }
};

/// The walls' push of the collision-free speed model (Tordeux et al. 2016), shared by the first-order
/// models: Σ strength · exp(−s / range) · n over the boundary edges within `reach` of the row's
/// centre on its own floor (s its distance to the edge, n the unit vector away from it). Leaves the
/// edges found in `wallIds`: those of the row's own floor (on a multi-level world another floor's
/// edges, above or below, are no walls to it).
inline core::Vec2 exponentialWallPush(const ModelInput& in, std::size_t row, float reach, float strength, float range,
                                      std::vector<std::uint32_t>& wallIds) {
  const AgentStore& a = in.agents;
  const core::Vec2 pos{a.posX[row], a.posY[row]};
  wallIds.clear();
  in.walls.query(pos.x, pos.y, reach, wallIds);
  if (a.levels) {
    std::erase_if(wallIds, [&](std::uint32_t w) { return !in.walls.onLevel(w, pos, a.posZ[row]); });
  }
  core::Vec2 push;
  for (std::uint32_t w : wallIds) {
    const core::Segment& seg = in.walls.segments()[w];
    const core::Vec2 away = pos - core::closestPointOnSegment(pos, seg.a, seg.b);
    const float s = core::length(away);
    if (s < 1e-6f) continue;
    push += away * (strength * core::exp(-s / range) / s);
  }
  return push;
}

// The models (one file each in this folder).
const ModelInfo& orcaModelInfo();
std::unique_ptr<OperationalModel> makeOrcaModel();
const ModelInfo& collisionFreeSpeedModelInfo();
std::unique_ptr<OperationalModel> makeCollisionFreeSpeedModel();
const ModelInfo& anticipationVelocityModelInfo();
std::unique_ptr<OperationalModel> makeAnticipationVelocityModel();

/// A new instance of the model `kind` (models.cpp).
std::unique_ptr<OperationalModel> makeModel(ModelKind kind);

}  // namespace throng::sim
