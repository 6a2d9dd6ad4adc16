// throng bench scenarios — what `throng bench` times. The in-memory scenarios, shared by throng and
// the DetourCrowd baseline: "random": a square of side sqrt(N / density) (1 agent/m²) where every
// agent wanders (walks to random points, picks a new one on arrival). "navmesh": the same square
// with a regular grid of square pillars so paths bend. Agents: radius 0.25 m, speed 1.34 m/s, dt
// 0.1 s. Scenario files: "mall" (the bundled scenarios/mall.json, looked up next to the working
// directory and the executable) or any PATH.json. Also the temporary recording file of --record.
#pragma once
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "throng/core/result.hpp"
#include "throng/nav/navmesh.hpp"
#include "throng/sim/scenario.hpp"

namespace throng::cli {

enum class BenchLayout { Random, Navmesh, Musse };

/// The in-memory scenario names; any other --scenario value is a scenario file.
inline constexpr const char* kBenchLayoutNames[] = {"random", "navmesh", "musse"};
/// Bundled scenario files known by name (scenarios/<name>.json).
inline constexpr const char* kBundledBenchScenarios[] = {"mall"};
/// The accepted --scenario values, for messages.
inline constexpr const char* kBenchScenarioValues = "random, navmesh, musse, mall or a scenario file PATH.json";

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

/// True for "random", "navmesh", "musse" (`layout` set) — the in-memory scenarios.
[[nodiscard]] bool benchLayoutFromName(const std::string& name, BenchLayout& layout);

/// An empty string when `value` is a usable --scenario value: an in-memory layout name, a bundled
/// name, a name ending in ".json", containing a '/', or naming an existing file; else the message.
[[nodiscard]] std::string checkBenchScenarioValue(const std::string& value);

/// Where a bundled scenario (`name`.json) is looked for, in order: ./scenarios/, the source tree
/// seen from a build tree's executable (<exe dir>/../../../scenarios/), an installed share dir
/// (<exe dir>/../share/throng/scenarios/). `exe` is this executable's path (empty: skipped).
[[nodiscard]] std::vector<std::filesystem::path> bundledScenarioCandidates(const std::string& name,
                                                                           const std::filesystem::path& exe);

/// This executable's path (/proc/self/exe), empty when unknown.
[[nodiscard]] std::filesystem::path currentExecutable();

/// Ticks between recorded frames for `fps` at time step `dt` — the rule of `throng run`:
/// round(1 / (fps * dt)), at least 1; `actualFps` is the rate that gives.
[[nodiscard]] std::uint64_t benchFrameStride(double fps, double dt, double& actualFps);

/// A recording path in the temporary directory ($TMPDIR, else /tmp), unique in this process; the
/// file and its SQLite companions (-wal, -shm, -journal) are deleted on destruction.
class TempRecording {
 public:
  TempRecording();
  ~TempRecording();
  TempRecording(const TempRecording&) = delete;
  TempRecording& operator=(const TempRecording&) = delete;

  [[nodiscard]] const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace throng::cli
