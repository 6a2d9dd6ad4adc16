// End-to-end tests of the throng command line: flags, help, exit codes, error paths, and a full
// run → info round trip on a tiny scenario written by the test. Runs the built binary.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <map>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace throng::e2e {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// A 10 m × 4 m room; three agents spawned at the left walk to an exit at the right wall.
constexpr const char* kTinyScenario = R"({
  "format": "throng/1",
  "name": "tiny-room",
  "seed": 7,
  "duration": 60,
  "dt": 0.05,
  "walkable": [[[0, 0], [10, 0], [10, 4], [0, 4]]],
  "points": [{"id": "exit", "kind": "exit", "polygon": [[9, 1], [10, 1], [10, 3], [9, 3]]}],
  "populations": [{"id": "walkers", "groups": 3, "size": 1,
                   "spawn": {"polygon": [[1, 1], [3, 1], [3, 3], [1, 3]]}, "goals": ["exit"]}]
})";

/// Wanderers that never finish: a run ends only at its duration or on a signal.
constexpr const char* kWanderScenario = R"({
  "format": "throng/1",
  "name": "wander-room",
  "seed": 3,
  "duration": 100000,
  "dt": 0.05,
  "walkable": [[[0, 0], [20, 0], [20, 20], [0, 20]]],
  "populations": [{"id": "crowd", "groups": 200, "size": 1,
                   "spawn": {"polygon": [[1, 1], [19, 1], [19, 19], [1, 19]]}, "wander": true}]
})";

/// Several problems at once: wrong format, negative duration, unknown key, unknown goal.
constexpr const char* kBadScenario = R"({
  "format": "throng/9",
  "name": "bad",
  "duration": -5,
  "walkabel": [],
  "walkable": [[[0, 0], [10, 0], [10, 4], [0, 4]]],
  "populations": [{"groups": 3, "spawn": {"polygon": [[1, 1], [3, 1], [3, 3], [1, 3]]}, "goals": ["exitt"]}]
})";

// ---------------------------------------------------------------- help, version, bad flags

TEST(CliFlags, HelpListsEverySubcommand) {
  ScratchDir dir("help");
  const CliResult r = runThrong({"--help"}, dir.path());
  EXPECT_EQ(r.exitCode, 0) << r.err;
  for (const char* cmd : {"run", "check", "info", "bench"}) EXPECT_TRUE(contains(r.out, cmd)) << cmd << "\n" << r.out;
  EXPECT_TRUE(contains(r.out, "--version"));
}

TEST(CliFlags, EverySubcommandHelpMentionsEachFlag) {
  const std::map<std::string, std::vector<std::string>> flags{
      {"run", {"--seed", "--duration", "--threads", "--out", "--force", "--fps", "--quiet", "--json", "SCENARIO"}},
      {"check", {"--json", "SCENARIO"}},
      {"info", {"--json", "FILE.sqlite"}},
      {"bench",
       {"--agents", "--threads", "--scenario", "--ticks", "--warmup", "--seed", "--json", "--no-baseline",
        "--baseline-max"}},
  };
  ScratchDir dir("subhelp");
  for (const auto& [cmd, expected] : flags) {
    const CliResult r = runThrong({cmd, "--help"}, dir.path());
    EXPECT_EQ(r.exitCode, 0) << cmd << ": " << r.err;
    for (const auto& flag : expected) EXPECT_TRUE(contains(r.out, flag)) << cmd << " --help lacks " << flag << "\n" << r.out;
  }
}

TEST(CliFlags, HelpStatesUnitsAndDefaults) {
  ScratchDir dir("units");
  const CliResult run = runThrong({"run", "--help"}, dir.path());
  EXPECT_TRUE(contains(run.out, "[s]")) << run.out;   // --duration
  EXPECT_TRUE(contains(run.out, "[Hz]")) << run.out;  // --fps
  EXPECT_TRUE(contains(run.out, ".sqlite in the current directory")) << run.out;
  const CliResult bench = runThrong({"bench", "--help"}, dir.path());
  EXPECT_TRUE(contains(bench.out, "1000,10000,100000")) << bench.out;
}

TEST(CliFlags, VersionExitsZero) {
  ScratchDir dir("version");
  const CliResult r = runThrong({"--version"}, dir.path());
  EXPECT_EQ(r.exitCode, 0);
  EXPECT_FALSE(r.out.empty());
}

TEST(CliFlags, BadFlagsExitTwo) {
  ScratchDir dir("badflags");
  const std::vector<std::vector<std::string>> cases{
      {"run", "x.json", "--bogus"},
      {"run"},                                // missing SCENARIO
      {"run", "x.json", "--fps", "-1"},
      {"run", "x.json", "--threads", "many"},
      {"run", "x.json", "--duration", "0"},
      {"check", "--nope", "x.json"},
      {"bench", "--agents", "lots"},
      {"bench", "--scenario", "maze"},
      {"info"},
      {"--frobnicate"},
  };
  for (const auto& args : cases) {
    const CliResult r = runThrong(args, dir.path());
    std::string joined;
    for (const auto& a : args) joined += a + " ";
    EXPECT_EQ(r.exitCode, 2) << joined << "\n" << r.err;
    EXPECT_FALSE(r.err.empty()) << joined;
  }
}

TEST(CliFlags, UnknownOrMissingSubcommandExitsTwo) {
  ScratchDir dir("unknown");
  const CliResult unknown = runThrong({"chek", "x.json"}, dir.path());
  EXPECT_EQ(unknown.exitCode, 2);
  EXPECT_TRUE(contains(unknown.err, "chek")) << unknown.err;
  EXPECT_TRUE(contains(unknown.err, "did you mean 'check'")) << unknown.err;
  EXPECT_EQ(runThrong({}, dir.path()).exitCode, 2);
}

// ---------------------------------------------------------------- bad input: exit 1, nothing written

TEST(CliInput, MissingScenarioNamesTheFile) {
  ScratchDir dir("missing");
  for (const char* cmd : {"run", "check"}) {
    const CliResult r = runThrong({cmd, "no-such-scenario.json"}, dir.path());
    EXPECT_EQ(r.exitCode, 1) << cmd;
    EXPECT_TRUE(contains(r.err, "no-such-scenario.json")) << cmd << ": " << r.err;
  }
  EXPECT_FALSE(fs::exists(dir / "no-such-scenario.sqlite"));
}

TEST(CliInput, InvalidScenarioReportsEveryProblemAndWritesNothing) {
  ScratchDir dir("invalid");
  const fs::path scenario = dir.write("bad.json", kBadScenario);
  const CliResult r = runThrong({"run", scenario.string(), "--out", "out.sqlite"}, dir.path());
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_GE(lines(r.err).size(), 3u) << r.err;  // format, duration, unknown key, unknown goal…
  EXPECT_TRUE(contains(r.err, "bad.json")) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out.sqlite"));
  EXPECT_FALSE(fs::exists(dir / "bad.sqlite"));
}

TEST(CliInput, CheckListsProblemsOnePerLine) {
  ScratchDir dir("checkbad");
  const fs::path scenario = dir.write("bad.json", kBadScenario);
  const CliResult text = runThrong({"check", scenario.string()}, dir.path());
  EXPECT_EQ(text.exitCode, 1);
  const auto problems = lines(text.err);
  EXPECT_GE(problems.size(), 3u) << text.err;
  for (const auto& line : problems) EXPECT_TRUE(contains(line, "bad.json")) << line;

  const CliResult js = runThrong({"check", scenario.string(), "--json"}, dir.path());
  EXPECT_EQ(js.exitCode, 1);
  const json doc = json::parse(js.out);
  EXPECT_FALSE(doc.at("ok").get<bool>());
  ASSERT_GE(doc.at("diagnostics").size(), 3u);
  for (const auto& d : doc.at("diagnostics")) {
    for (const char* key : {"source", "line", "column", "pointer", "what", "expected", "hint"}) {
      EXPECT_TRUE(d.contains(key)) << key << " in " << d.dump();
    }
  }
}

TEST(CliInput, NotJsonAtAll) {
  ScratchDir dir("notjson");
  const fs::path scenario = dir.write("garbage.json", "this is { not json");
  const CliResult r = runThrong({"run", scenario.string(), "--out", "g.sqlite"}, dir.path());
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_TRUE(contains(r.err, "garbage.json")) << r.err;
  EXPECT_FALSE(fs::exists(dir / "g.sqlite"));
}

TEST(CliInput, ExistingOutputIsNotOverwrittenWithoutForce) {
  ScratchDir dir("existing");
  const fs::path scenario = dir.write("tiny.json", kTinyScenario);
  const std::string precious = "precious data, not a recording";
  dir.write("taken.sqlite", precious);
  const CliResult r = runThrong({"run", scenario.string(), "--out", "taken.sqlite", "--quiet"}, dir.path());
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_TRUE(contains(r.err, "taken.sqlite")) << r.err;
  EXPECT_EQ(readFile(dir / "taken.sqlite"), precious);
}

TEST(CliInput, InfoRejectsNonRecordings) {
  ScratchDir dir("infobad");
  dir.write("notes.sqlite", "just some text, definitely not SQLite");
  const CliResult r = runThrong({"info", "notes.sqlite"}, dir.path());
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_FALSE(r.err.empty());
  const CliResult missing = runThrong({"info", "nowhere.sqlite"}, dir.path());
  EXPECT_EQ(missing.exitCode, 1);
  EXPECT_TRUE(contains(missing.err, "nowhere.sqlite")) << missing.err;
}

// ---------------------------------------------------------------- full runs

TEST(CliRun, CheckSummarisesAValidScenario) {
  ScratchDir dir("checkok");
  const fs::path scenario = dir.write("tiny.json", kTinyScenario);
  const CliResult r = runThrong({"check", scenario.string()}, dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "ok: tiny-room: 1 populations, 3 agents, 1 points, navmesh")) << r.out;
  const CliResult js = runThrong({"check", scenario.string(), "--json"}, dir.path());
  ASSERT_EQ(js.exitCode, 0) << js.err;
  const json doc = json::parse(js.out);
  EXPECT_TRUE(doc.at("ok").get<bool>());
  EXPECT_EQ(doc.at("agents_max").get<int>(), 3);
  EXPECT_GT(doc.at("navmesh_polygons").get<int>(), 0);
  // The default model (avm) keeps centres passageRatio x radius from walls: 0.65 x 0.2 m.
  EXPECT_NEAR(doc.at("nav_margin_m").get<double>(), 0.13, 1e-6);
  EXPECT_TRUE(contains(r.out, "centres kept 0.13 m from walls")) << r.out;
}

TEST(CliRun, TinyEvacuationThenInfo) {
  ScratchDir dir("tiny");
  const fs::path scenario = dir.write("tiny.json", kTinyScenario);
  const CliResult r = runThrong({"run", scenario.string(), "--out", "tiny-out.sqlite", "--threads", "2"}, dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "3 spawned, 3 exited")) << r.out;
  EXPECT_TRUE(contains(r.out, "evacuation")) << r.out;
  EXPECT_TRUE(contains(r.out, "m/s")) << r.out;
  EXPECT_TRUE(contains(r.out, "agent-steps/s")) << r.out;
  EXPECT_TRUE(contains(r.out, "tiny-out.sqlite")) << r.out;
  EXPECT_FALSE(contains(r.err, "\r")) << "no progress bar off a terminal";
  ASSERT_TRUE(fs::exists(dir / "tiny-out.sqlite"));

  const CliResult info = runThrong({"info", "tiny-out.sqlite"}, dir.path());
  ASSERT_EQ(info.exitCode, 0) << info.err;
  EXPECT_TRUE(contains(info.out, "tiny-room")) << info.out;
  EXPECT_TRUE(contains(info.out, "walkers")) << info.out;
  EXPECT_TRUE(contains(info.out, "completed    yes")) << info.out;
}

TEST(CliRun, JsonSummaryAndInfoAgree) {
  ScratchDir dir("tinyjson");
  const fs::path scenario = dir.write("tiny.json", kTinyScenario);
  const CliResult r = runThrong({"run", scenario.string(), "--out", "t.sqlite", "--seed", "42", "--json"}, dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const json run = json::parse(r.out);
  EXPECT_EQ(run.at("scenario"), "tiny-room");
  EXPECT_EQ(run.at("seed").get<std::uint64_t>(), 42u);
  EXPECT_EQ(run.at("status"), "finished");
  EXPECT_FALSE(run.at("interrupted").get<bool>());
  EXPECT_EQ(run.at("agents_spawned").get<int>(), 3);
  EXPECT_EQ(run.at("agents_exited").get<int>(), 3);
  ASSERT_TRUE(run.at("evacuation_time_s").is_number());
  const double evacuation = run.at("evacuation_time_s").get<double>();
  EXPECT_GT(evacuation, 3.0);   // at least 6 m at <= 2.5 m/s
  EXPECT_LT(evacuation, 60.0);
  EXPECT_LE(evacuation, run.at("simulated_time_s").get<double>());
  EXPECT_GT(run.at("mean_walking_speed_mps").get<double>(), 0.1);
  EXPECT_EQ(run.at("recording").at("path"), "t.sqlite");
  EXPECT_DOUBLE_EQ(run.at("recording").at("fps").get<double>(), 10.0);
  const auto frames = run.at("recording").at("frames").get<std::uint64_t>();
  // Frame 0 plus one every 2 ticks (dt 0.05 s at 10 fps), ending on a frame boundary.
  EXPECT_EQ(frames, run.at("ticks").get<std::uint64_t>() / 2 + 1);

  const CliResult i = runThrong({"info", "t.sqlite", "--json"}, dir.path());
  ASSERT_EQ(i.exitCode, 0) << i.err;
  const json info = json::parse(i.out);
  EXPECT_EQ(info.at("scenario"), "tiny-room");
  EXPECT_EQ(info.at("seed").get<std::uint64_t>(), 42u);
  EXPECT_EQ(info.at("agents").get<int>(), 3);
  EXPECT_EQ(info.at("frames").get<std::uint64_t>(), frames);
  EXPECT_DOUBLE_EQ(info.at("fps").get<double>(), 10.0);
  EXPECT_TRUE(info.at("completed").get<bool>());
  EXPECT_EQ(info.at("format_version").get<int>(), 2);
  ASSERT_EQ(info.at("populations").size(), 1u);
  EXPECT_EQ(info.at("populations")[0].at("id"), "walkers");
}

TEST(CliRun, DefaultOutputForceAndQuiet) {
  ScratchDir dir("defaults");
  const fs::path scenario = dir.write("tiny.json", kTinyScenario);
  const CliResult first = runThrong({"run", scenario.string(), "--quiet"}, dir.path());
  ASSERT_EQ(first.exitCode, 0) << first.err;
  EXPECT_TRUE(first.out.empty()) << first.out;
  EXPECT_TRUE(first.err.empty()) << first.err;
  EXPECT_TRUE(fs::exists(dir / "tiny.sqlite"));  // <scenario stem>.sqlite in the working directory

  EXPECT_EQ(runThrong({"run", scenario.string(), "--quiet"}, dir.path()).exitCode, 1);
  const CliResult forced = runThrong({"run", scenario.string(), "--quiet", "--force", "--duration", "1"}, dir.path());
  EXPECT_EQ(forced.exitCode, 0) << forced.err;
  const json info = json::parse(runThrong({"info", "tiny.sqlite", "--json"}, dir.path()).out);
  // --duration 1 replaced the first run: frame 0 plus 10 frames at 10 fps.
  EXPECT_EQ(info.at("frames").get<std::uint64_t>(), 11u);
}

TEST(CliRun, UnevenFpsIsRoundedWithAWarning) {
  ScratchDir dir("fps");
  const fs::path scenario = dir.write("tiny.json", kTinyScenario);
  // dt 0.05 s: 3 fps would be every 6.67 ticks; every 7 ticks = 2.857 fps is recorded.
  const CliResult r =
      runThrong({"run", scenario.string(), "--out", "f.sqlite", "--fps", "3", "--duration", "2", "--json"}, dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(contains(r.err, "warning")) << r.err;
  const json run = json::parse(r.out);
  EXPECT_NEAR(run.at("recording").at("fps").get<double>(), 1.0 / (7 * 0.05), 1e-6);
}

TEST(CliRun, InterruptClosesACompleteRecording) {
  ScratchDir dir("sigint");
  const fs::path scenario = dir.write("wander.json", kWanderScenario);
  CliProcess process({"run", scenario.string(), "--out", "w.sqlite", "--json"}, dir.path());
  // Wait until the recording exists (opened just before simulating), then a little more.
  for (int i = 0; i < 600 && !fs::exists(dir / "w.sqlite"); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ASSERT_TRUE(fs::exists(dir / "w.sqlite"));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  process.signal(SIGINT);
  const CliResult r = process.wait();
  ASSERT_EQ(r.exitCode, 130) << r.err;
  const json run = json::parse(r.out);
  EXPECT_TRUE(run.at("interrupted").get<bool>());
  EXPECT_EQ(run.at("status"), "interrupted");

  const CliResult i = runThrong({"info", "w.sqlite", "--json"}, dir.path());
  ASSERT_EQ(i.exitCode, 0) << i.err;
  const json info = json::parse(i.out);
  EXPECT_FALSE(info.at("completed").get<bool>());
  EXPECT_GE(info.at("frames").get<std::uint64_t>(), 1u);
  EXPECT_EQ(info.at("frames").get<std::uint64_t>(), run.at("recording").at("frames").get<std::uint64_t>());
}

TEST(CliBench, TinyBenchPrintsJsonLines) {
  ScratchDir dir("bench");
  for (const char* layout : {"random", "navmesh"}) {
    const CliResult r = runThrong({"bench", "--agents", "40,60", "--threads", "1", "--threads", "2", "--ticks", "3",
                                   "--warmup", "2", "--scenario", layout, "--no-baseline", "--json"},
                                  dir.path());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto rows = lines(r.out);
    ASSERT_EQ(rows.size(), 4u) << r.out;  // 2 agent counts × 2 thread counts
    for (const auto& row : rows) {
      const json m = json::parse(row);
      EXPECT_EQ(m.at("engine"), "throng");
      EXPECT_EQ(m.at("scenario"), layout);
      EXPECT_EQ(m.at("ticks").get<int>(), 3);
      EXPECT_GT(m.at("agent_steps_per_s").get<double>(), 0.0);
      EXPECT_LE(m.at("ms_per_tick_median").get<double>(), m.at("ms_per_tick_p99").get<double>());
      for (const char* key : {"agents", "threads", "bytes_per_agent", "peak_rss_bytes"}) EXPECT_TRUE(m.contains(key));
      EXPECT_TRUE(m.at("simd") == "avx2" || m.at("simd") == "portable") << m.dump();
    }
    EXPECT_EQ(json::parse(rows[0]).at("agents").get<int>(), 40);
    EXPECT_EQ(json::parse(rows[3]).at("agents").get<int>(), 60);
    EXPECT_EQ(json::parse(rows[3]).at("threads").get<int>(), 2);
  }
}

}  // namespace
}  // namespace throng::e2e
