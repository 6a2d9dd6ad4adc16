// throng bench scenarios — see bench_scenarios.hpp.
#include "bench_scenarios.hpp"

#include <atomic>
#include <cmath>

#include <fmt/format.h>
#include <unistd.h>

#include "throng/core/rng.hpp"

namespace throng::cli {
namespace {

core::Polygon rect(float x0, float y0, float x1, float y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

sim::PopulationDesc wanderers(std::string id, core::Polygon area, std::uint32_t count) {
  sim::PopulationDesc p;
  p.id = std::move(id);
  p.groups = count;  // groups of one: every agent walks on its own
  p.sizeMin = p.sizeMax = 1;
  p.spawn.kind = sim::SpawnKind::Polygon;
  p.spawn.polygon = std::move(area);
  p.start = 0.0f;
  p.wander = true;
  p.speedMean = kBenchSpeed;
  p.speedSd = 0.0f;
  p.speedMin = kBenchSpeed;
  p.speedMax = kBenchSpeed;
  p.radius = kBenchRadius;
  return p;
}

/// Pillar rows sit at y in [c - h, c + h] with c = spacing/2 + k*spacing; the spawn strips are the
/// bands between them (kept a radius away), each given agents in proportion to its area.
std::vector<sim::PopulationDesc> stripPopulations(float side, std::size_t agents) {
  const float h = kBenchPillarSize / 2 + kBenchRadius;
  std::vector<std::pair<float, float>> bands;
  float y = kBenchRadius;
  for (float c = kBenchPillarSpacing / 2; c + kBenchPillarSize / 2 <= side; c += kBenchPillarSpacing) {
    if (c - h > y) bands.emplace_back(y, c - h);
    y = c + h;
  }
  if (side - kBenchRadius > y) bands.emplace_back(y, side - kBenchRadius);
  double total = 0;
  for (const auto& [a, b] : bands) total += b - a;
  std::vector<sim::PopulationDesc> populations;
  std::size_t given = 0;
  double cumulative = 0;
  for (std::size_t i = 0; i < bands.size(); ++i) {
    cumulative += bands[i].second - bands[i].first;
    // Cumulative rounding: the counts add up to exactly `agents`.
    const auto upTo = i + 1 == bands.size() ? agents : static_cast<std::size_t>(std::llround(agents * cumulative / total));
    const auto count = static_cast<std::uint32_t>(upTo - given);
    given = upTo;
    if (count == 0) continue;
    populations.push_back(wanderers(fmt::format("band{}", i), rect(kBenchRadius, bands[i].first, side - kBenchRadius,
                                                                    bands[i].second),
                                    count));
  }
  return populations;
}

}  // namespace

float benchSide(std::size_t agents) {
  return std::max(2.0f, std::sqrt(static_cast<float>(agents) / kBenchDensity));
}

sim::ScenarioDesc makeBenchScenario(BenchLayout layout, std::size_t agents, std::uint64_t seed) {
  const float side = benchSide(agents);
  sim::ScenarioDesc desc;
  desc.name = fmt::format("bench-{}-{}", layout == BenchLayout::Random ? "random" : layout == BenchLayout::Musse ? "musse" : "navmesh", agents);
  desc.seed = seed;
  desc.duration = 1.0e6f;  // wanderers never finish; bench stops after its ticks
  desc.dt = kBenchDt;
  desc.navCellSize = kBenchCellSize;
  desc.walkable.push_back(rect(0, 0, side, side));
  if (layout == BenchLayout::Musse) {
    // The crowd model on: flocking groups of three (shared speed, walking abreast, waiting for each
    // other) wandering together between random points; the remainder walks alone.
    const auto area = rect(kBenchRadius, kBenchRadius, side - kBenchRadius, side - kBenchRadius);
    sim::PopulationDesc groups = wanderers("groups", area, static_cast<std::uint32_t>(agents / 3));
    groups.sizeMin = groups.sizeMax = 3;
    if (groups.groups > 0) desc.populations.push_back(groups);
    if (agents % 3 != 0) desc.populations.push_back(wanderers("singles", area, static_cast<std::uint32_t>(agents % 3)));
    return desc;
  }
  if (layout == BenchLayout::Random) {
    desc.populations.push_back(wanderers("crowd", rect(kBenchRadius, kBenchRadius, side - kBenchRadius,
                                                       side - kBenchRadius),
                                         static_cast<std::uint32_t>(agents)));
    return desc;
  }
  const float h = kBenchPillarSize / 2;
  for (float cx = kBenchPillarSpacing / 2; cx + h <= side; cx += kBenchPillarSpacing) {
    for (float cy = kBenchPillarSpacing / 2; cy + h <= side; cy += kBenchPillarSpacing) {
      desc.obstacles.push_back(rect(cx - h, cy - h, cx + h, cy + h));
    }
  }
  desc.populations = stripPopulations(side, agents);
  return desc;
}

core::Result<std::shared_ptr<const nav::NavMesh>> buildBenchNavMesh(const sim::ScenarioDesc& desc) {
  nav::NavMeshConfig config;
  config.agentRadius = desc.maxRadius();
  config.cellSize = desc.navCellSize;
  return nav::NavMesh::build(desc.walkable, desc.obstacles, config);
}

std::vector<core::Vec2> drawBenchStarts(const std::shared_ptr<const nav::NavMesh>& navmesh, std::size_t count,
                                        std::uint64_t seed) {
  nav::NavQuery query(navmesh);
  std::vector<core::Vec2> starts;
  starts.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    core::Rng rng(seed, i, core::RngPurpose::Bench);
    for (int attempt = 0; attempt < 8; ++attempt) {
      const auto p = query.randomPoint(static_cast<float>(rng.uniform()), static_cast<float>(rng.uniform()),
                                       static_cast<float>(rng.uniform()));
      if (p) {
        starts.push_back(*p);
        break;
      }
    }
  }
  return starts;
}

bool benchLayoutFromName(const std::string& name, BenchLayout& layout) {
  if (name == "random") layout = BenchLayout::Random;
  else if (name == "navmesh") layout = BenchLayout::Navmesh;
  else if (name == "musse") layout = BenchLayout::Musse;
  else return false;
  return true;
}

std::string checkBenchScenarioValue(const std::string& value) {
  BenchLayout layout{};
  if (benchLayoutFromName(value, layout)) return {};
  for (const char* name : kBundledBenchScenarios) {
    if (value == name) return {};
  }
  const bool looksLikeFile = value.size() > 5 && value.compare(value.size() - 5, 5, ".json") == 0;
  std::error_code ec;
  if (looksLikeFile || value.find('/') != std::string::npos || std::filesystem::is_regular_file(value, ec)) return {};
  return fmt::format("'{}' is not a bench scenario: expected {}", value, kBenchScenarioValues);
}

std::vector<std::filesystem::path> bundledScenarioCandidates(const std::string& name,
                                                             const std::filesystem::path& exe) {
  const std::string file = name + ".json";
  std::vector<std::filesystem::path> candidates{std::filesystem::path("scenarios") / file};
  if (!exe.empty()) {
    const auto dir = exe.parent_path();
    candidates.push_back((dir / "../../../scenarios" / file).lexically_normal());
    candidates.push_back((dir / "../share/throng/scenarios" / file).lexically_normal());
  }
  return candidates;
}

std::filesystem::path currentExecutable() {
  std::error_code ec;
  auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::path{} : exe;
}

std::uint64_t benchFrameStride(double fps, double dt, double& actualFps) {
  const double ratio = 1.0 / (fps * dt);
  const auto stride = static_cast<std::uint64_t>(std::max(1.0, std::round(ratio)));
  const bool exact = std::fabs(ratio - static_cast<double>(stride)) <= 1e-6 * ratio;
  actualFps = exact ? fps : 1.0 / (static_cast<double>(stride) * dt);
  return stride;
}

TempRecording::TempRecording() {
  static std::atomic<unsigned> counter{0};
  std::error_code ec;
  std::filesystem::path dir = std::filesystem::temp_directory_path(ec);
  if (ec) dir = "/tmp";
  path_ = (dir / fmt::format("throng-bench-{}-{}.sqlite", ::getpid(), counter++)).string();
}

TempRecording::~TempRecording() {
  for (const char* suffix : {"", "-wal", "-shm", "-journal"}) {
    std::error_code ec;
    std::filesystem::remove(path_ + suffix, ec);
  }
}

}  // namespace throng::cli
