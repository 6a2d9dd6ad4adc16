// throng::sim::World — owns the agents and runs the tick as explicit phases:
//   applyCommands → sense → decide → plan → steer → integrate → emit
// Each phase is a function over the structure-of-arrays AgentStore, parallel over agents with a
// compute/commit split, so one seed gives identical trajectories for any thread count. The World
// does no I/O: no files, sockets, logging or clocks; time is an integer tick times a fixed dt.
#pragma once
#include <cstdint>
#include <memory>
#include <string_view>

#include "throng/core/parallel.hpp"
#include "throng/core/result.hpp"
#include "throng/nav/navmesh.hpp"
#include "throng/sim/frame.hpp"
#include "throng/sim/scenario.hpp"

namespace throng::sim {

/// Running totals; reductions are per fixed chunk, combined in chunk order (deterministic).
struct WorldStats {
  std::uint64_t tick = 0;
  double time = 0.0;                 ///< [s]
  std::uint32_t spawned = 0;
  std::uint32_t exited = 0;
  std::uint32_t active = 0;          ///< in the world now
  std::uint32_t scheduled = 0;       ///< still to spawn
  double lastExitTime = -1.0;        ///< [s]; < 0 when nobody exited
  double walkedDistance = 0.0;       ///< summed over agents [m]
  double walkingTime = 0.0;          ///< agent-seconds spent walking (mode Walking) [s]
  std::uint64_t agentSteps = 0;      ///< sum over ticks of active agents

  /// Mean walking speed over all agents and time spent walking [m/s].
  [[nodiscard]] double meanWalkingSpeed() const { return walkingTime > 0 ? walkedDistance / walkingTime : 0.0; }
};

/// Receives each phase's duration; the app passes one in (the core reads no clock itself).
class PhaseObserver {
 public:
  virtual ~PhaseObserver() = default;
  virtual void phaseBegin(std::string_view phase) = 0;
  virtual void phaseEnd(std::string_view phase) = 0;
};

class World {
 public:
  /// Builds a world from a validated description. `navmesh` may be passed when the loader already
  /// built it (for validation); otherwise it is built here.
  static core::Result<std::unique_ptr<World>> create(const ScenarioDesc& desc,
                                                     std::shared_ptr<const nav::NavMesh> navmesh = nullptr);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  /// Advances one tick of dt seconds. Threads come from `tasks`; the result does not depend on them.
  void step(const core::TaskSystem& tasks, PhaseObserver* observer = nullptr);

  /// Snapshot of the current state plus the events since the previous snapshot.
  [[nodiscard]] FramePtr snapshot();

  /// True when nothing is left to simulate: every agent spawned has exited and none is scheduled
  /// (only when the scenario has exits or finite goals; wandering crowds never finish).
  [[nodiscard]] bool finished() const;

  [[nodiscard]] const WorldStats& stats() const;
  [[nodiscard]] const ScenarioDesc& desc() const;
  [[nodiscard]] const nav::NavMesh& navMesh() const;
  /// FNV-1a hash of the bit patterns of every agent's id, position and velocity, in id order
  /// (determinism tests compare it across thread counts).
  [[nodiscard]] std::uint64_t stateHash() const;

 private:
  World();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace throng::sim
