// Golden trajectories: a bitwise hash of every agent's id, position and velocity at every tick of
// bundled scenarios, at 1 and 2 threads, against the value stored in tests/golden/<name>.hash.
// A change to the model changes these on purpose: regenerate with
//   THRONG_UPDATE_GOLDEN=1 ctest -R Golden      (then explain the change in the commit message)
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include "throng/io/scenario_loader.hpp"
#include "throng/sim/world.hpp"

namespace fs = std::filesystem;
using namespace throng;

namespace {

/// Runs `scenario`, every population walking with `model` when one is given (else the scenario's).
std::uint64_t runHash(const std::string& scenario, int threads, int ticks, std::optional<sim::ModelKind> model) {
  auto loaded = io::loadScenarioFile((fs::path(THRONG_SOURCE_DIR) / "scenarios" / (scenario + ".json")).string());
  EXPECT_TRUE(loaded.ok()) << (loaded.ok() ? "" : core::formatAll(loaded.errors()));
  if (!loaded.ok()) return 0;
  if (model) {
    for (sim::PopulationDesc& pop : loaded->desc.populations) pop.model = sim::ModelDesc(*model);
  }
  auto created = sim::World::create(loaded->desc, loaded->navmesh);
  EXPECT_TRUE(created.ok());
  if (!created.ok()) return 0;
  sim::World& world = *created.value();
  core::TaskSystem tasks(threads);
  std::uint64_t h = 14695981039346656037ull;
  for (int t = 0; t < ticks; ++t) {
    world.step(tasks);
    h = (h ^ world.stateHash()) * 1099511628211ull;
  }
  return h;
}

/// `name` is the hash file's (tests/golden/<name>.hash).
void checkGolden(const std::string& scenario, int ticks, std::optional<sim::ModelKind> model = std::nullopt,
                 const std::string& name = "") {
  const std::uint64_t h1 = runHash(scenario, 1, ticks, model);
  const std::uint64_t h2 = runHash(scenario, 2, ticks, model);
  ASSERT_EQ(h1, h2) << "trajectories differ between 1 and 2 threads";
  std::ostringstream hex;
  hex << std::hex << h1;
  const fs::path file = fs::path(THRONG_SOURCE_DIR) / "tests" / "golden" / ((name.empty() ? scenario : name) + ".hash");
  const char* update = std::getenv("THRONG_UPDATE_GOLDEN");
  if (update != nullptr && std::string(update) == "1") {
    std::ofstream(file) << hex.str() << "\n";
    GTEST_SKIP() << "updated " << file << " to " << hex.str();
  }
  std::ifstream in(file);
  std::string stored;
  in >> stored;
  EXPECT_EQ(stored, hex.str()) << "golden trajectory hash of " << scenario << " changed; if on purpose, run "
                               << "THRONG_UPDATE_GOLDEN=1 ctest -R Golden and explain why in the commit";
}

}  // namespace

TEST(Golden, Bottleneck) { checkGolden("bottleneck", 600); }
TEST(Golden, Crossing) { checkGolden("crossing", 400); }
// ORCA is no scenario's default any more; these keep its trajectories pinned (the batched
// half-planes and the SIMD paths must leave them bit for bit).
TEST(Golden, BottleneckOrca) { checkGolden("bottleneck", 600, sim::ModelKind::Orca, "bottleneck-orca"); }
TEST(Golden, CrossingOrca) { checkGolden("crossing", 400, sim::ModelKind::Orca, "crossing-orca"); }
