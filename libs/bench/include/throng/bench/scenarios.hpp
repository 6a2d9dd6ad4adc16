// throng::bench — the in-memory scenarios `throng bench` and the benchmarks in benches/ time, and
// the DetourCrowd baseline runs on: "random": a square of side sqrt(N / density) (1 agent/m²) where
// every agent wanders (walks to random points, picks a new one on arrival). "navmesh": the same
// square with a regular grid of square pillars so paths bend. "musse": the random square with
// flocking groups of three. Agents: radius 0.25 m, speed 1.34 m/s, dt 0.1 s. Pure construction:
// no files, no clock.
#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "throng/core/result.hpp"
#include "throng/nav/navmesh.hpp"
#include "throng/sim/scenario.hpp"

namespace throng::bench {

enum class Layout { Random, Navmesh, Musse };

/// The layouts' names, in enum order ("random", "navmesh", "musse").
inline constexpr const char* kLayoutNames[] = {"random", "navmesh", "musse"};

inline constexpr float kDensity = 1.0f;       ///< agents per m² of the square
inline constexpr float kRadius = 0.25f;       ///< body radius [m]
inline constexpr float kSpeed = 1.34f;        ///< desired speed [m/s]
inline constexpr float kDt = 0.1f;            ///< time step [s]
inline constexpr float kCellSize = 0.125f;    ///< navmesh voxel size [m]
inline constexpr float kPillarSize = 1.0f;    ///< pillar edge [m] (navmesh layout)
inline constexpr float kPillarSpacing = 8.0f; ///< pillar centre spacing [m] (navmesh layout)

/// Side of the square holding `agents` at kDensity [m].
[[nodiscard]] float squareSide(std::size_t agents);

/// The scenario: walkable square, pillars for the navmesh layout, `agents` wandering agents spawned
/// at tick 0 by polygon spawns that avoid the pillars.
[[nodiscard]] sim::ScenarioDesc makeScenario(Layout layout, std::size_t agents, std::uint64_t seed);

/// The navmesh for `desc`, built once and handed to every World and to the baseline.
[[nodiscard]] core::Result<std::shared_ptr<const nav::NavMesh>> buildNavMesh(const sim::ScenarioDesc& desc);

/// `count` start positions drawn uniformly (area-weighted) on the navmesh with core::Rng streams
/// (seed, agent index, Bench): the same distribution as throng's spawns, not the same points.
[[nodiscard]] std::vector<core::Vec2> drawStarts(const std::shared_ptr<const nav::NavMesh>& navmesh,
                                                 std::size_t count, std::uint64_t seed);

/// The layout named "random", "navmesh" or "musse"; nullopt for any other name.
[[nodiscard]] std::optional<Layout> layoutFromName(const std::string& name);

}  // namespace throng::bench
