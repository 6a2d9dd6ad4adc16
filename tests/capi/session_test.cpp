// A C API world steps as the C++ World and `throng run` do (libs/capi/src/session.cpp): the same
// seed gives the same positions, bit for bit, as World::step at 1 and 2 threads with enough agents
// that the work is split, the same state hash as `throng run --json`, and a recording holding the
// same rows as the CLI's, even when the caller looks at agents and events between recorded ticks.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <fstream>
#include <string>

#include "capi_fixtures.hpp"
#include "cli_runner.hpp"
#include "sqlite_query.hpp"
#include "temp_dir.hpp"
#include "throng/core/parallel.hpp"
#include "throng/io/scenario_loader.hpp"
#include "throng/sim/world.hpp"
#include "throng/throng.h"

namespace throng::capi_test {
namespace {

/// The frame after `ticks` ticks of the C++ World, built from the same JSON.
sim::FramePtr cppFrame(const std::string& json, int threads, std::uint64_t ticks, std::uint64_t& hash) {
  auto loaded = io::parseScenario(json, "capi-test.json");
  EXPECT_TRUE(loaded);
  auto world = sim::World::create(loaded->desc, loaded->navmesh);
  EXPECT_TRUE(world);
  const core::TaskSystem tasks(threads);
  for (std::uint64_t t = 0; t < ticks; ++t) (*world)->step(tasks);
  hash = (*world)->stateHash();
  return (*world)->takeFrame();
}

TEST(CApiSession, SameSeedSamePositionsAsTheCppWorldAtOneAndTwoThreads) {
  const std::string json = corridor(400, 10.0, 3, 20.0);
  std::uint64_t cppHash = 0;
  const sim::FramePtr expected = cppFrame(json, 1, 60, cppHash);
  ASSERT_GT(expected->size(), 300u) << "enough agents that the work is split";
  auto s = loadJson(json);
  for (int threads : {1, 2}) {
    auto w = makeWorld(s.get(), threads);
    ASSERT_EQ(throng_world_step(w.get(), 60, nullptr), THRONG_OK);
    const Agents a = readAgents(w.get());
    ASSERT_EQ(a.size(), expected->size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      ASSERT_EQ(a.ids[i], expected->ids[i]);
      // Bit patterns, not tolerances.
      ASSERT_EQ(std::memcmp(&a.positions[2 * i], &expected->posX[i], sizeof(float)), 0) << threads << " threads, agent " << i;
      ASSERT_EQ(std::memcmp(&a.positions[2 * i + 1], &expected->posY[i], sizeof(float)), 0);
      ASSERT_EQ(std::memcmp(&a.velocities[2 * i], &expected->velX[i], sizeof(float)), 0);
    }
    std::uint64_t hash = 0;
    ASSERT_EQ(throng_world_state_hash(w.get(), &hash), THRONG_OK);
    EXPECT_EQ(hash, cppHash) << threads << " threads";
  }
  // Another seed, other trajectories (the comparison above can tell them apart).
  const std::uint64_t seed = 99;
  auto other = makeWorld(s.get(), 1, &seed);
  ASSERT_EQ(throng_world_step(other.get(), 60, nullptr), THRONG_OK);
  std::uint64_t hash = 0;
  ASSERT_EQ(throng_world_state_hash(other.get(), &hash), THRONG_OK);
  EXPECT_NE(hash, cppHash);
  EXPECT_EQ(throng_world_state_hash(other.get(), nullptr), THRONG_ERROR_NULL_ARGUMENT);
}

TEST(CApiSession, RecordingIsWhatThrongRunWrites) {
  test::TempDir dir("capi-session");
  const std::string scenario = dir.file("study.json");
  std::ofstream(scenario) << corridor(60, 20.0);
  const std::string cliOut = dir.file("cli.sqlite");
  const e2e::CliResult run = e2e::runThrong({"run", scenario, "--out", cliOut, "--json", "-q", "--threads", "2"}, dir.path());
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const auto summary = nlohmann::json::parse(run.out);

  throng_scenario* sc = nullptr;
  ASSERT_EQ(throng_scenario_load_file(scenario.c_str(), &sc, nullptr), THRONG_OK);
  ScenarioPtr owned(sc);
  auto w = makeWorld(sc, 3);
  const std::string capiOut = dir.file("capi.sqlite");
  ASSERT_EQ(throng_world_record(w.get(), capiOut.c_str(), 10.0, 0), THRONG_OK) << throng_last_error();
  // Looks between recorded ticks (every 3rd tick; frames every 2nd) must not take events from the recording.
  std::size_t exitsSeen = 0;
  while (stats(w.get()).time < 15.0) {
    ASSERT_EQ(throng_world_step(w.get(), 1, nullptr), THRONG_OK);
    if (stats(w.get()).tick % 3 != 0) continue;
    readAgents(w.get());
    for (const throng_event& e : drainEvents(w.get())) exitsSeen += e.kind == THRONG_EVENT_EXIT;
  }
  EXPECT_GT(exitsSeen, 0u) << "exits happened between recorded frames";
  ASSERT_EQ(throng_world_run(w.get(), stats(w.get()).duration), THRONG_OK);
  std::uint64_t hash = 0;
  ASSERT_EQ(throng_world_state_hash(w.get(), &hash), THRONG_OK);
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash));
  EXPECT_EQ(summary["state_hash"], hex);
  std::uint64_t frames = 0;
  ASSERT_EQ(throng_world_record_close(w.get(), &frames), THRONG_OK);
  EXPECT_EQ(frames, summary["recording"]["frames"].get<std::uint64_t>());
  for (const char* q : {"SELECT frame, id, pos_x, pos_y, ori_x, ori_y FROM trajectory_data ORDER BY frame, id",
                        "SELECT frame, tick, agent, kind, a, b FROM throng_events ORDER BY rowid",
                        "SELECT * FROM throng_agents ORDER BY id", "SELECT * FROM throng_frames ORDER BY frame"}) {
    EXPECT_EQ(e2e::queryText(cliOut, q), e2e::queryText(capiOut, q)) << q;
  }
}

}  // namespace
}  // namespace throng::capi_test
