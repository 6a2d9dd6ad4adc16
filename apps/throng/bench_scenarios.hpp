// throng bench scenarios — the in-memory scenarios `throng bench` times, shared by throng and the
// DetourCrowd baseline. "random": a square of side sqrt(N / density) (1 agent/m²) where every agent
// wanders (walks to random points, picks a new one on arrival). "navmesh": the same square with a
// regular grid of square pillars so paths bend. Agents: radius 0.25 m, speed 1.34 m/s, dt 0.1 s.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "throng/core/result.hpp"
#include "throng/nav/navmesh.hpp"
#include "throng/sim/scenario.hpp"

namespace throng::cli {

enum class BenchLayout { Random, Navmesh, Musse };

inline constexpr float kBenchDensity = 1.0f;         ///< agents per m² of the square
inline constexpr float kBenchRadius = 0.25f;         ///< body radius [m]
inline constexpr float kBenchSpeed = 1.34f;          ///< desired speed [m/s]
inline constexpr float kBenchDt = 0.1f;              ///< time step [s]
inline constexpr float kBenchCellSize = 0.125f;      ///< navmesh voxel size [m]
inline constexpr float kBenchPillarSize = 1.0f;      ///< pillar edge [m] (navmesh layout)
inline constexpr float kBenchPillarSpacing = 8.0f;   ///< pillar centre spacing [m] (navmesh layout)

/// Side of the square holding `agents` at kBenchDensity [m].
[[nodiscard]] float benchSide(std::size_t agents);

/// The scenario: walkable square, pillars for the navmesh layout, `agents` wandering agents spawned
/// at tick 0 by polygon spawns that avoid the pillars.
[[nodiscard]] sim::ScenarioDesc makeBenchScenario(BenchLayout layout, std::size_t agents, std::uint64_t seed);

/// The navmesh for `desc`, built once and handed to every World and to the baseline.
[[nodiscard]] core::Result<std::shared_ptr<const nav::NavMesh>> buildBenchNavMesh(const sim::ScenarioDesc& desc);

/// `count` start positions drawn uniformly (area-weighted) on the navmesh with core::Rng streams
/// (seed, agent index, Bench): the same distribution as throng's spawns, not the same points.
[[nodiscard]] std::vector<core::Vec2> drawBenchStarts(const std::shared_ptr<const nav::NavMesh>& navmesh,
                                                      std::size_t count, std::uint64_t seed);

}  // namespace throng::cli
