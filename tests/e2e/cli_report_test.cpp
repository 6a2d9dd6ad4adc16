// What the CLI reports: the `throng run` summary (evacuation only for evacuations, a "finished"
// status that agrees with the counts, stalled agents with their spans), `throng bench` (the
// DetourCrowd row, mean speeds, progress during the baseline), the progress line past 100 s of
// simulated time, `throng metrics` column headers and `throng check`'s warning of exits closed for
// good. The pure helpers (progress.cpp, stall_tracker.cpp) are compiled into this test; the rest
// runs the built binary (cli_runner.hpp).
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "cli_runner.hpp"
#include "progress.hpp"
#include "social_recording_fixture.hpp"
#include "stall_tracker.hpp"

namespace throng::e2e {
namespace {

using nlohmann::json;

// --- throng run: the summary -------------------------------------------------------------------

/// A gallery: visitors walk to a bench (an interest point) and stay there; later two others walk
/// in and out through the door.
const char* kGallery = R"({
  "format": "throng/1", "name": "gallery", "seed": 3, "duration": 120,
  "walkable": [[[0,0],[20,0],[20,10],[0,10]]],
  "points": [
    {"id": "bench", "kind": "interest", "position": [10, 8.5], "radius": 1},
    {"id": "door", "kind": "exit", "polygon": [[19,4],[20,4],[20,6],[19,6]]}
  ],
  "populations": [
    {"id": "stay", "groups": 3, "spawn": {"polygon": [[1,1],[5,1],[5,9],[1,9]]}, "goals": ["bench"]},
    {"id": "leave", "groups": 2, "start": 90, "spawn": {"polygon": [[1,1],[5,1],[5,9],[1,9]]}, "goals": ["door"]}
  ]
})";

TEST(RunSummary, FinishedWithAgentsInsideIsNotAnIncompleteEvacuation) {
  ScratchDir dir("summary");
  dir.write("gallery.json", kGallery);
  const CliResult r = runThrong({"run", "gallery.json"}, dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "finished (every agent reached its last goal; 3 stay there)")) << r.out;
  EXPECT_TRUE(contains(r.out, "2 spawned") || contains(r.out, "5 spawned, 2 exited, 3 still inside")) << r.out;
  EXPECT_FALSE(contains(r.out, "no agent left")) << r.out;
  EXPECT_FALSE(contains(r.out, "evacuation")) << r.out;
  EXPECT_TRUE(contains(r.out, "exits         2 agents left, the last at")) << r.out;

  const CliResult j = runThrong({"run", "gallery.json", "--force", "--json"}, dir.path());
  ASSERT_EQ(j.exitCode, 0) << j.err;
  const json s = json::parse(j.out);
  EXPECT_EQ(s.at("status"), "finished");
  EXPECT_FALSE(s.at("evacuation").get<bool>());
  EXPECT_TRUE(s.at("evacuation_time_s").is_null());
  EXPECT_GT(s.at("last_exit_time_s").get<double>(), 0.0);
  EXPECT_EQ(s.at("agents_active"), 3);
}

TEST(RunSummary, EvacuationsKeepTheirEvacuationLine) {
  ScratchDir dir("summary-evac");
  std::string text = kGallery;
  text.replace(text.find(R"("goals": ["bench"])"), 18, R"("goals": ["bench", "door"])");
  dir.write("out.json", text);
  const CliResult r = runThrong({"run", "out.json", "--json"}, dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const json s = json::parse(r.out);
  EXPECT_TRUE(s.at("evacuation").get<bool>());
  EXPECT_GT(s.at("evacuation_time_s").get<double>(), 0.0);
  EXPECT_EQ(s.at("agents_active"), 0);
  const CliResult t = runThrong({"run", "out.json", "--force"}, dir.path());
  EXPECT_TRUE(contains(t.out, "finished (every agent left)")) << t.out;
  EXPECT_TRUE(contains(t.out, "evacuation    ")) << t.out;
}

TEST(StallTracker, NamesAgentsThatStoodStillWithTheirSpans) {
  cli::StallTracker tracker(60.0, 0.5f);
  auto frame = [](double t, std::vector<std::uint32_t> ids, std::vector<float> xs, sim::AgentMode mode = sim::AgentMode::Walking) {
    sim::Frame f;
    f.time = t;
    f.ids = std::move(ids);
    f.posX = std::move(xs);
    f.posY.assign(f.ids.size(), 0.0f);
    f.mode.assign(f.ids.size(), mode);
    return f;
  };
  // Agent 24 walks until 36 s, then stands (jiggling 0.2 m) to the end at 264 s; agent 3 walks on;
  // agent 5 stands all along, but by design; agent 9 stands 100 s, then leaves the world.
  for (int k = 0; k <= 264; ++k) {
    const double t = k;
    const float x24 = k <= 36 ? 0.5f * static_cast<float>(k) : 18.0f + (k % 2 ? 0.2f : 0.0f);
    std::vector<std::uint32_t> ids{3, 5, 24};
    std::vector<float> xs{static_cast<float>(k), 100.0f, x24};
    if (k <= 120) {
      ids.push_back(9);
      xs.push_back(k < 20 ? static_cast<float>(k) : 20.0f);
    }
    tracker.observe(frame(t, ids, xs), [](std::uint32_t id) -> std::optional<std::string> {
      if (id == 5) return std::nullopt;
      return id == 9 ? "waiting" : "walking";
    });
  }
  const auto spans = tracker.finish(264.0);
  ASSERT_EQ(spans.size(), 2u);
  EXPECT_EQ(spans[0].agent, 9u);
  EXPECT_DOUBLE_EQ(spans[0].from, 20.0);
  EXPECT_DOUBLE_EQ(spans[0].to, 120.0);
  EXPECT_EQ(spans[0].state, "waiting");
  EXPECT_EQ(spans[1].agent, 24u);
  EXPECT_DOUBLE_EQ(spans[1].from, 36.0);
  EXPECT_DOUBLE_EQ(spans[1].to, 264.0);
  EXPECT_EQ(spans[1].state, "walking");
}

TEST(StallTracker, ActingIsNotAStall) {
  cli::StallTracker tracker(60.0, 0.5f);
  for (int k = 0; k <= 200; ++k) {
    sim::Frame f;
    f.time = k;
    f.ids = {0};
    f.posX = {1.0f};
    f.posY = {1.0f};
    f.mode = {sim::AgentMode::Acting};
    tracker.observe(f, [](std::uint32_t) -> std::optional<std::string> { return "walking"; });
  }
  EXPECT_TRUE(tracker.finish(200.0).empty());
}

TEST(RunSummary, StalledAgentsAreNamedInTextAndJson) {
  // The three at the bench stand from their arrival (about 10 s) until the run ends (about 100 s).
  ScratchDir dir("stall");
  dir.write("gallery.json", kGallery);
  const CliResult j = runThrong({"run", "gallery.json", "--json"}, dir.path());
  ASSERT_EQ(j.exitCode, 0) << j.err;
  const json s = json::parse(j.out);
  const json& stalled = s.at("stalled_agents");
  ASSERT_EQ(stalled.size(), 3u) << j.out;
  std::set<int> agents;
  for (int k = 0; k < 3; ++k) {
    agents.insert(stalled[k].at("agent").get<int>());
    EXPECT_LT(stalled[k].at("from_s").get<double>(), 30.0) << j.out;
    EXPECT_EQ(stalled[k].at("to_s").get<double>(), s.at("simulated_time_s").get<double>()) << j.out;
    EXPECT_EQ(stalled[k].at("state"), "done: stays at its last goal");
    if (k > 0) EXPECT_LE(stalled[k - 1].at("from_s").get<double>(), stalled[k].at("from_s").get<double>());
  }
  EXPECT_EQ(agents, (std::set<int>{0, 1, 2}));  // the "stay" population
  const CliResult t = runThrong({"run", "gallery.json", "--force"}, dir.path());
  ASSERT_EQ(t.exitCode, 0) << t.err;
  EXPECT_TRUE(contains(t.out, "stalled       3 agents stood still (within 0.5 m) for 60 s or more: agent ")) << t.out;
  EXPECT_TRUE(contains(t.out, "(done: stays at its last goal)")) << t.out;
}

TEST(RunSummary, QueuingForALiftIsNotAStall) {
  // NIST 2.7's 28 persons wait up to 100 s at the lift's upper stop: that is their task, not a stall
  // (before, 12 of them were named).
  ScratchDir dir("lift");
  const std::string scenario = std::string(THRONG_SOURCE_DIR) + "/verification/nist/2.7-elevators.json";
  const CliResult j = runThrong({"run", scenario, "--json", "--out", (dir / "lift.sqlite").string()}, dir.path());
  ASSERT_EQ(j.exitCode, 0) << j.err;
  const json s = json::parse(j.out);
  EXPECT_EQ(s.at("agents_exited"), 28) << j.out;
  EXPECT_TRUE(s.at("stalled_agents").empty()) << j.out;
}

// --- throng check: spawn capacity ---------------------------------------------------------------

TEST(CheckCapacity, PopulationsSharingASpawnAreaAreRefusedWithTheirPlace) {
  // 2 x 150 agents of radius 0.2 m in one 56 m² room: each would fit alone; together they spawned
  // partly outside the room (at the world origin, before) — now check refuses the file.
  ScratchDir dir("capacity");
  dir.write("shared.json", R"({
  "format": "throng/1", "name": "shared",
  "walkable": [[[0,0],[20,0],[20,10],[0,10]]],
  "points": [{"id": "exit", "kind": "exit", "polygon": [[19,4],[20,4],[20,6],[19,6]]}],
  "populations": [
    {"id": "a", "groups": 150, "spawn": {"polygon": [[1,1],[8,1],[8,9],[1,9]]}, "goals": ["exit"]},
    {"id": "b", "groups": 150, "spawn": {"polygon": [[1,1],[8,1],[8,9],[1,9]]}, "goals": ["exit"]}
  ]
})");
  const CliResult r = runThrong({"check", "shared.json"}, dir.path());
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_TRUE(contains(r.err, "shared.json:7:53 /populations/1/spawn/polygon: spawn areas of populations \"a\" (150 at "
                              "/populations/0/spawn/polygon) and \"b\" (150 at /populations/1/spawn/polygon) overlap and "
                              "start at 0 s: 56 m² of walkable ground is too small for their 300 agents"))
      << r.err;
}

TEST(CheckWarnings, AnExitTheTimelineClosesForGoodIsAWarningForWhoeverNeedsIt) {
  // "fixed" walks to "a", closed at 10 s for good; "choosers" may take "a" or "b", both closed for
  // good; "fine" keeps "c", which closes and opens again, as does "reopened"'s goal.
  ScratchDir dir("check-doors");
  dir.write("doors.json", R"({"format": "throng/1", "name": "doors", "duration": 100,
 "walkable": [[[0,0],[20,0],[20,10],[0,10]]],
 "points": [{"id": "a", "kind": "exit", "polygon": [[19,1],[20,1],[20,3],[19,3]]},
            {"id": "b", "kind": "exit", "polygon": [[19,7],[20,7],[20,9],[19,9]]},
            {"id": "c", "kind": "exit", "polygon": [[0,4],[1,4],[1,6],[0,6]]}],
 "populations": [
   {"id": "fixed", "groups": 3, "spawn": {"polygon": [[5,1],[8,1],[8,9],[5,9]]}, "goals": ["a"]},
   {"id": "choosers", "groups": 3, "spawn": {"polygon": [[5,1],[8,1],[8,9],[5,9]]}, "exits": ["a", "b"]},
   {"id": "fine", "groups": 3, "spawn": {"polygon": [[5,1],[8,1],[8,9],[5,9]]}, "exits": ["a", "c"]},
   {"id": "reopened", "groups": 3, "spawn": {"polygon": [[5,1],[8,1],[8,9],[5,9]]}, "goals": ["c"]}],
 "timeline": [{"time": 10, "close": "a"}, {"time": 20, "close": "b"}, {"time": 30, "close": "c"}, {"time": 40, "open": "c"}]})");
  const CliResult r = runThrong({"check", "doors.json"}, dir.path());
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "ok: doors: 4 populations")) << r.out;
  EXPECT_TRUE(contains(r.err, "throng check: warning: doors.json: /populations/0/goals/0: exit \"a\" closes at 10 s "
                              "(/timeline/0) and never opens again; population \"fixed\" walks to it")) << r.err;
  EXPECT_TRUE(contains(r.err, "/populations/1/exits: every exit of population \"choosers\" closes for good (exit \"a\" "
                              "closes at 10 s (/timeline/0) and never opens again; exit \"b\" closes at 20 s (/timeline/1)"))
      << r.err;
  EXPECT_FALSE(contains(r.err, "fine") || contains(r.err, "reopened") || contains(r.err, "\"c\"")) << r.err;
  const CliResult j = runThrong({"check", "--json", "doors.json"}, dir.path());
  EXPECT_EQ(j.exitCode, 0);
  const json answer = json::parse(j.out);
  EXPECT_EQ(answer["ok"], true);
  ASSERT_EQ(answer["warnings"].size(), 2u) << j.out;
  EXPECT_TRUE(contains(answer["warnings"][1].get<std::string>(), "/populations/1/exits")) << j.out;
  // Without a door closed for good: no warning, and the JSON answer has no "warnings" key.
  dir.write("open.json", R"({"format": "throng/1", "name": "open", "walkable": [[[0,0],[20,0],[20,10],[0,10]]],
 "points": [{"id": "a", "kind": "exit", "polygon": [[19,1],[20,1],[20,3],[19,3]]}],
 "populations": [{"id": "p", "groups": 3, "spawn": {"polygon": [[5,1],[8,1],[8,9],[5,9]]}, "goals": ["a"]}],
 "timeline": [{"time": 10, "close": "a"}, {"time": 20, "open": "a"}]})");
  const CliResult quiet = runThrong({"check", "open.json"}, dir.path());
  EXPECT_EQ(quiet.exitCode, 0);
  EXPECT_EQ(quiet.err, "");
  EXPECT_FALSE(json::parse(runThrong({"check", "--json", "open.json"}, dir.path()).out).contains("warnings"));
}

// --- the progress line ----------------------------------------------------------------------------

TEST(ProgressLine, BarStaysPastOneHundredSeconds) {
  for (const double t : {5.0, 99.9, 100.0, 150.0, 999.9, 1700.0}) {
    const std::string line = cli::formatRunProgress({t, 1800.0, 1234, 567, 2.0}, 80);
    EXPECT_LE(line.size(), 79u) << line;
    EXPECT_TRUE(contains(line, "[")) << "t = " << t << ": " << line;
    EXPECT_TRUE(contains(line, "ETA")) << line;
  }
  // Same width for every time: the bar does not jump as the time grows a digit.
  EXPECT_EQ(cli::formatRunProgress({5.0, 1800.0, 12, 5, 2.0}, 80).find('['),
            cli::formatRunProgress({500.0, 1800.0, 12, 5, 2.0}, 80).find('['));
}

// --- throng bench ---------------------------------------------------------------------------------

TEST(BenchReport, DetourCrowdRowHasItsSpeedAndThrongRowsTheRatio) {
  ScratchDir dir("bench-dc");
  const CliResult r = runThrong({"bench", "--agents", "30", "--threads", "1", "--ticks", "3", "--warmup", "2", "--json"},
                                dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto rows = lines(r.out);
  ASSERT_EQ(rows.size(), 2u) << r.out;  // DetourCrowd, then throng
  const json dc = json::parse(rows[0]);
  const json th = json::parse(rows[1]);
  EXPECT_EQ(dc.at("engine"), "detourcrowd");
  EXPECT_FALSE(dc.contains("speedup_vs_detourcrowd")) << rows[0];
  EXPECT_GT(dc.at("mean_speed_mps").get<double>(), 0.0) << rows[0];
  EXPECT_EQ(th.at("engine"), "throng");
  ASSERT_TRUE(th.at("speedup_vs_detourcrowd").is_number()) << rows[1];
  EXPECT_GT(th.at("speedup_vs_detourcrowd").get<double>(), 0.0);
  EXPECT_GT(th.at("mean_speed_mps").get<double>(), 0.0) << rows[1];
}

TEST(BenchReport, BaselineShowsProgressOnATerminal) {
  ScratchDir dir("bench-tty");
  const CliResult r = runThrongInTerminal(
      {"bench", "--agents", "30", "--threads", "1", "--ticks", "3", "--warmup", "2"}, dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(contains(r.err, "detourcrowd random N=30: tick 3/3")) << r.err;
  EXPECT_TRUE(contains(r.out, "speed m/s")) << r.out;
}

// --- throng metrics ------------------------------------------------------------------------------

TEST(MetricsReport, LongCategoryNamesAreNotCut) {
  ScratchDir dir("metrics-cols");
  const std::string path = (dir / "cg.sqlite").string();
  ASSERT_EQ(throng::testing::writeSocialRecording(path), "");
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, "UPDATE throng_points SET category = 'electronics' WHERE id = 'wc'", nullptr, nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(db);
  const CliResult r = runThrong({"metrics", "cg.sqlite", "--bin", "0.25"}, dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  bool header = false;
  for (const std::string& line : lines(r.out)) {
    if (!contains(line, "from [s]")) continue;
    header = true;
    EXPECT_TRUE(contains(line, " electronics ")) << line;
  }
  EXPECT_TRUE(header) << r.out;
}

}  // namespace
}  // namespace throng::e2e
