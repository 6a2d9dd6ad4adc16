// End-to-end tests of `throng bench` on scenario files and with --record: a tiny scenario file is
// run from start to end (JSON line with x real time), --record adds a "throng+rec" line and deletes
// its temporary recording, and missing or unknown --scenario values fail with a message. Runs the
// built binary; every scenario is a few agents for a few simulated seconds.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace throng::e2e {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// A 10 m × 4 m room; four agents walk to an exit at the right wall and leave (about 6 s).
constexpr const char* kExitRoom = R"({
  "format": "throng/1",
  "name": "bench-exit-room",
  "seed": 5,
  "duration": 60,
  "dt": 0.05,
  "walkable": [[[0, 0], [10, 0], [10, 4], [0, 4]]],
  "points": [{"id": "exit", "kind": "exit", "polygon": [[9, 1], [10, 1], [10, 3], [9, 3]]}],
  "populations": [{"id": "walkers", "groups": 4, "size": 1,
                   "spawn": {"polygon": [[1, 1], [3, 1], [3, 3], [1, 3]]}, "goals": ["exit"]}]
})";

/// Wanderers that never finish: the run ends at the duration (5 s).
constexpr const char* kWanderRoom = R"({
  "format": "throng/1",
  "name": "bench-wander",
  "seed": 3,
  "duration": 5,
  "dt": 0.1,
  "walkable": [[[0, 0], [12, 0], [12, 12], [0, 12]]],
  "populations": [{"id": "crowd", "groups": 30, "size": 1,
                   "spawn": {"polygon": [[1, 1], [11, 1], [11, 11], [1, 11]]}, "wander": true}]
})";

std::vector<json> jsonLines(const std::string& text) {
  std::vector<json> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty()) out.push_back(json::parse(line));
  }
  return out;
}

/// Files in `dir` other than `keep`.
std::vector<std::string> othersIn(const fs::path& dir, const std::string& keep) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().filename() != keep) names.push_back(entry.path().filename().string());
  }
  return names;
}

void expectSaneFileRow(const json& m, const std::string& engine, const std::string& scenario) {
  EXPECT_EQ(m.at("engine"), engine);
  EXPECT_EQ(m.at("scenario"), scenario);
  EXPECT_EQ(m.at("threads").get<int>(), 1);
  EXPECT_GT(m.at("ticks").get<int>(), 0);
  EXPECT_GT(m.at("agent_steps_per_s").get<double>(), 0.0);
  EXPECT_GT(m.at("realtime_factor").get<double>(), 0.0);
  EXPECT_GT(m.at("wall_s").get<double>(), 0.0);
  EXPECT_LE(m.at("ms_per_tick_median").get<double>(), m.at("ms_per_tick_p99").get<double>());
  for (const char* key : {"agents", "bytes_per_agent", "peak_rss_bytes", "simulated_s", "dt_s", "scenario_file"}) {
    EXPECT_TRUE(m.contains(key)) << key;
  }
  // simulated = ticks × dt (from the start).
  EXPECT_NEAR(m.at("simulated_s").get<double>(), m.at("ticks").get<int>() * m.at("dt_s").get<double>(), 1e-3);
}

TEST(BenchScenarioFile, RunsToTheEndAndReportsRealTime) {
  ScratchDir dir("bench-file");
  const fs::path file = dir.write("exit-room.json", kExitRoom);
  const CliResult r = runThrong({"bench", "--scenario", file.string(), "--threads", "1", "--json"}, dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto rows = jsonLines(r.out);
  ASSERT_EQ(rows.size(), 1u) << r.out;
  expectSaneFileRow(rows[0], "throng", "exit-room");
  EXPECT_EQ(rows[0].at("agents").get<int>(), 4);  // the most present at once
  // Everyone left long before the 60 s duration: the run stopped when the world finished.
  EXPECT_LT(rows[0].at("simulated_s").get<double>(), 30.0);
  EXPECT_TRUE(contains(r.err, "no DetourCrowd baseline")) << r.err;
}

TEST(BenchScenarioFile, DurationCapsAndAgentsIsNoted) {
  ScratchDir dir("bench-cap");
  const fs::path file = dir.write("wander.json", kWanderRoom);
  const CliResult r = runThrong({"bench", "--scenario", file.string(), "--threads", "1", "--duration", "2",
                                 "--agents", "500", "--no-baseline", "--json"},
                                dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto rows = jsonLines(r.out);
  ASSERT_EQ(rows.size(), 1u) << r.out;
  expectSaneFileRow(rows[0], "throng", "wander");
  EXPECT_NEAR(rows[0].at("simulated_s").get<double>(), 2.0, 1e-3);
  EXPECT_EQ(rows[0].at("agents").get<int>(), 30);
  EXPECT_TRUE(contains(r.err, "--agents is not used")) << r.err;
}

TEST(BenchScenarioFile, RecordAddsARowAndDeletesItsFile) {
  ScratchDir dir("bench-rec");
  const fs::path file = dir.write("wander.json", kWanderRoom);
  // The temporary recording goes to $TMPDIR: point it at the scratch directory to see it is gone.
  const char* oldTmp = std::getenv("TMPDIR");
  const std::string saved = oldTmp ? oldTmp : "";
  ::setenv("TMPDIR", dir.path().c_str(), 1);
  const CliResult r = runThrong({"bench", "--scenario", file.string(), "--threads", "1", "--record", "--fps", "5",
                                 "--no-baseline", "--json"},
                                dir.path());
  if (oldTmp) ::setenv("TMPDIR", saved.c_str(), 1);
  else ::unsetenv("TMPDIR");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto rows = jsonLines(r.out);
  ASSERT_EQ(rows.size(), 2u) << r.out;
  expectSaneFileRow(rows[0], "throng", "wander");
  expectSaneFileRow(rows[1], "throng+rec", "wander");
  EXPECT_EQ(rows[0].at("ticks"), rows[1].at("ticks"));  // the same run, timed again
  EXPECT_DOUBLE_EQ(rows[1].at("recording").at("fps").get<double>(), 5.0);
  EXPECT_EQ(rows[1].at("recording").at("frames").get<int>(), 26);  // frame 0 + one per 0.2 s of 5 s
  EXPECT_TRUE(othersIn(dir.path(), "wander.json").empty());
}

TEST(BenchScenarioFile, RecordWorksForInMemoryScenarios) {
  ScratchDir dir("bench-rec-mem");
  const CliResult r = runThrong({"bench", "--agents", "50", "--threads", "1", "--ticks", "3", "--warmup", "1",
                                 "--record", "--no-baseline", "--json"},
                                dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto rows = jsonLines(r.out);
  ASSERT_EQ(rows.size(), 2u) << r.out;
  EXPECT_EQ(rows[0].at("engine"), "throng");
  EXPECT_EQ(rows[1].at("engine"), "throng+rec");
  EXPECT_EQ(rows[1].at("ticks").get<int>(), 3);
  EXPECT_EQ(rows[1].at("recording").at("frames").get<int>(), 4);  // frame 0 + every 0.1 s tick at 10 fps
  EXPECT_GT(rows[1].at("realtime_factor").get<double>(), 0.0);
}

// --model: every population walks with the named model; its rows say which, and the crowd moves
// differently than with ORCA (same layout, seed and ticks).
TEST(BenchScenarioFile, ModelChoosesTheAvoidanceModelOfEveryPopulation) {
  ScratchDir dir("bench-model");
  std::map<std::string, double> speed;
  for (const char* model : {"orca", "cfsm"}) {
    const CliResult r = runThrong({"bench", "--agents", "300", "--threads", "1", "--ticks", "20", "--warmup", "5",
                                   "--no-baseline", "--json", "--model", model},
                                  dir.path());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto rows = jsonLines(r.out);
    ASSERT_EQ(rows.size(), 1u) << r.out;
    EXPECT_EQ(rows[0].at("model"), model);
    speed[model] = rows[0].at("mean_speed_mps").get<double>();
  }
  EXPECT_NE(speed["orca"], speed["cfsm"]);
  const CliResult bad = runThrong({"bench", "--model", "ocra"}, dir.path());
  EXPECT_EQ(bad.exitCode, 2) << bad.err;
  for (const char* value : {"ocra", "orca", "cfsm"}) EXPECT_TRUE(contains(bad.err, value)) << value << "\n" << bad.err;
  // A scenario file keeps its own models unless --model is given.
  const fs::path file = dir.path() / "room.json";
  std::ofstream(file) << kExitRoom;
  const CliResult own = runThrong({"bench", "--scenario", file.string(), "--threads", "1", "--no-baseline", "--json"}, dir.path());
  ASSERT_EQ(own.exitCode, 0) << own.err;
  EXPECT_EQ(jsonLines(own.out).at(0).at("model"), "scenario");
}

// --row-order: rows sorted spatially give the same crowd as rows in id order (the same mean speed
// to the last digit), the rows say which order ran, and the sort shows as its own phase.
TEST(BenchScenarioFile, RowOrderSortsRowsAndChangesNoTrajectory) {
  ScratchDir dir("bench-row-order");
  std::map<std::string, double> speed;
  for (const char* order : {"id", "spatial"}) {
    const CliResult r = runThrong({"bench", "--agents", "400", "--threads", "2", "--ticks", "45", "--warmup", "0",
                                   "--no-baseline", "--json", "--phase-times", "--row-order", order},
                                  dir.path());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto rows = jsonLines(r.out);
    ASSERT_EQ(rows.size(), 1u) << r.out;
    EXPECT_EQ(rows[0].at("row_order"), order);
    EXPECT_TRUE(rows[0].at("phase_ms_per_tick").contains("order")) << r.out;
    speed[order] = rows[0].at("mean_speed_mps").get<double>();
  }
  EXPECT_GT(speed["id"], 0.1);
  EXPECT_EQ(speed["id"], speed["spatial"]);
  const CliResult bad = runThrong({"bench", "--row-order", "hilbert"}, dir.path());
  EXPECT_EQ(bad.exitCode, 2) << bad.err;
  for (const char* value : {"hilbert", "auto", "id", "spatial"}) EXPECT_TRUE(contains(bad.err, value)) << value << "\n" << bad.err;
}

TEST(BenchScenarioFile, PhaseTimesSplitTheTick) {
  ScratchDir dir("bench-phases");
  const CliResult r = runThrong({"bench", "--agents", "200", "--threads", "1", "--ticks", "5", "--warmup", "1",
                                 "--no-baseline", "--phase-times", "--json"},
                                dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto rows = jsonLines(r.out);
  ASSERT_EQ(rows.size(), 1u) << r.out;
  const json& phases = rows[0].at("phase_ms_per_tick");
  double sum = 0.0;
  for (const char* phase : {"decide", "plan", "sense", "steer", "integrate", "emit"}) {
    ASSERT_TRUE(phases.contains(phase)) << phases.dump();
    EXPECT_GE(phases.at(phase).get<double>(), 0.0);
    sum += phases.at(phase).get<double>();
  }
  EXPECT_GT(phases.at("steer").get<double>(), 0.0);
  // The phases are the tick: their sum cannot exceed the mean tick by more than clock noise.
  const double meanTick = 1000.0 * rows[0].at("wall_s").get<double>() / rows[0].at("ticks").get<double>();
  EXPECT_LE(sum, meanTick * 1.05 + 0.01) << phases.dump();
  // Text: a line under the row.
  const CliResult text = runThrong({"bench", "--agents", "200", "--threads", "1", "--ticks", "2", "--warmup", "1",
                                    "--no-baseline", "--phase-times"},
                                   dir.path());
  ASSERT_EQ(text.exitCode, 0) << text.err;
  EXPECT_TRUE(contains(text.out, "ms/tick by phase:")) << text.out;
  EXPECT_TRUE(contains(text.out, " steer ")) << text.out;
}

TEST(BenchScenarioFile, TextTableShowsRealTime) {
  ScratchDir dir("bench-text");
  const fs::path file = dir.write("exit-room.json", kExitRoom);
  const CliResult r = runThrong({"bench", "--scenario", file.string(), "--threads", "1"}, dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "x real")) << r.out;
  EXPECT_TRUE(contains(r.out, "exit-room")) << r.out;
  EXPECT_TRUE(contains(r.out, "no DetourCrowd baseline")) << r.out;
}

TEST(BenchScenarioFile, MissingFileFailsWithMessage) {
  ScratchDir dir("bench-missing");
  const CliResult r = runThrong({"bench", "--scenario", "nosuch.json", "--threads", "1"}, dir.path());
  EXPECT_EQ(r.exitCode, 1) << r.err;
  EXPECT_TRUE(contains(r.err, "nosuch.json")) << r.err;
  EXPECT_TRUE(contains(r.err, "not found")) << r.err;
  EXPECT_TRUE(r.out.empty() || !contains(r.out, "agent_steps")) << r.out;
}

TEST(BenchScenarioFile, UnknownNameNamesTheAcceptedValues) {
  ScratchDir dir("bench-bogus");
  const CliResult r = runThrong({"bench", "--scenario", "bogus"}, dir.path());
  EXPECT_EQ(r.exitCode, 2) << r.err;
  for (const char* value : {"bogus", "random", "navmesh", "musse", "mall", "PATH.json"}) {
    EXPECT_TRUE(contains(r.err, value)) << value << "\n" << r.err;
  }
}

TEST(BenchScenarioFile, BadFpsAndDurationExitTwo) {
  ScratchDir dir("bench-badflags");
  for (const std::vector<std::string>& args : {std::vector<std::string>{"bench", "--record", "--fps", "0"},
                                               std::vector<std::string>{"bench", "--duration", "-3"}}) {
    const CliResult r = runThrong(args, dir.path());
    EXPECT_EQ(r.exitCode, 2) << args[2] << "\n" << r.err;
    EXPECT_FALSE(r.err.empty());
  }
}

TEST(BenchScenarioFile, HelpDescribesTheNewValues) {
  ScratchDir dir("bench-help");
  const CliResult r = runThrong({"bench", "--help"}, dir.path());
  EXPECT_EQ(r.exitCode, 0) << r.err;
  for (const char* text : {"mall", "PATH.json", "--record", "--fps", "--duration", "x real time", "throng+rec"}) {
    EXPECT_TRUE(contains(r.out, text)) << text << "\n" << r.out;
  }
}

}  // namespace
}  // namespace throng::e2e
