// End-to-end tests of `throng script` and `throng metrics` on the hand-built Common Ground
// recording of tests/recording/social_recording_fixture.hpp: text and JSON output, exit codes for an
// unknown agent (1), bad flags (2) and a recording without Common Ground tables (1).
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "social_recording_fixture.hpp"

namespace throng::e2e {
namespace {

using nlohmann::json;

class SocialCommands : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = (dir_ / "cg.sqlite").string();
    ASSERT_EQ(throng::testing::writeSocialRecording(path_), "");
  }
  ScratchDir dir_{"social"};
  std::string path_;
};

TEST_F(SocialCommands, ScriptPrintsTheTableOfEveryCoordination) {
  const CliResult r = runThrong({"script", "cg.sqlite", "--agent", "0"}, dir_.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "coordination 1  group 7  initiator A 0  respondents B 1")) << r.out;
  EXPECT_TRUE(contains(r.out, "goal point 0 (wc, restroom)")) << r.out;
  EXPECT_TRUE(contains(r.out, "relation A3  plan divide_and_wait  outcome grounded")) << r.out;
  EXPECT_TRUE(contains(r.out, "coordination 3")) << r.out;  // agent 0 is B there
  EXPECT_FALSE(contains(r.out, "coordination 2")) << r.out;
  for (const char* s : {"4a", "5b", "wave", "turn_toward", "agent 1 (5.00, 6.00)", "B 1", "trajectory   agent 0 (group 7): 4 frames"}) {
    EXPECT_TRUE(contains(r.out, s)) << s << "\n" << r.out;
  }
  const CliResult one = runThrong({"script", "cg.sqlite", "--agent", "0", "--coordination", "3"}, dir_.path());
  ASSERT_EQ(one.exitCode, 0) << one.err;
  EXPECT_FALSE(contains(one.out, "coordination 1 ")) << one.out;
  const CliResult none = runThrong({"script", "cg.sqlite", "--agent", "2", "--coordination", "1"}, dir_.path());
  EXPECT_EQ(none.exitCode, 1);
  EXPECT_TRUE(contains(none.err, "agent 2 took no part in coordination 1; expected one of: 2")) << none.err;
}

TEST_F(SocialCommands, ScriptJsonIsTheActionScriptPerCharacter) {
  const CliResult r = runThrong({"script", "cg.sqlite", "--agent", "1", "--json"}, dir_.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["agent"], 1);
  EXPECT_EQ(j["group"], 7);
  ASSERT_EQ(j["coordinations"].size(), 2u);
  const json& c = j["coordinations"][0];
  EXPECT_EQ(c["plan"], "divide_and_wait");
  EXPECT_EQ(c["goal_point"]["category"], "restroom");
  EXPECT_EQ(c["t8"], 2.5);
  ASSERT_EQ(c["entries"].size(), 10u);
  EXPECT_EQ(c["entries"][3]["step"], "4a");
  EXPECT_EQ(c["entries"][3]["actor"], "A");
  EXPECT_EQ(c["entries"][2]["actor"], "B");
  EXPECT_EQ(c["entries"][1]["target"]["agent"], 1);
  ASSERT_EQ(j["trajectory"].size(), 4u);
  EXPECT_NEAR(j["trajectory"][2]["vy"].get<double>(), 35.0, 1e-4);
  EXPECT_EQ(j["trajectory"][0]["ori_y"], 1.0);
}

TEST_F(SocialCommands, ScriptMarksUnfinishedCoordinationsInTheTrajectorysGroups) {
  // Coordination 1 still running when the recording stopped: its start event, no row yet.
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path_.c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db,
                         "DELETE FROM throng_coordinations WHERE id = 1; INSERT INTO throng_events(frame, tick, agent, "
                         "kind, a, b) VALUES (0, 0, 0, 'coordination_start', 1, 7);",
                         nullptr, nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(db);
  const CliResult r = runThrong({"script", "cg.sqlite", "--agent", "1"}, dir_.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "coordination 1  group 7  initiator A 0  respondents B 1  (unfinished at end of recording)"))
      << r.out;
  EXPECT_TRUE(contains(r.out, "goal point 0 (wc, restroom)  goal by need  outcome unfinished at end of recording")) << r.out;
  EXPECT_TRUE(contains(r.out, "t0 0.00 s  t8 -  end -")) << r.out;
  EXPECT_FALSE(contains(r.out, "respondents none")) << r.out;
  EXPECT_TRUE(contains(r.out, "trajectory   agent 1 (group 7)")) << r.out;
  const CliResult j = runThrong({"script", "cg.sqlite", "--agent", "1", "--json"}, dir_.path());
  ASSERT_EQ(j.exitCode, 0) << j.err;
  const json out = json::parse(j.out);
  const json& c = out["coordinations"][0];
  EXPECT_EQ(c["id"], 1);
  EXPECT_FALSE(c["finished"].get<bool>());
  EXPECT_EQ(c["outcome"], "unfinished");
  EXPECT_EQ(c["group"], out["group"]);
  EXPECT_EQ(c["respondents"], json::array({1}));
  EXPECT_TRUE(c["plan"].is_null());
  EXPECT_TRUE(out["coordinations"][1]["finished"].get<bool>());

  // No start event either (a file cut short): the entries still name the actors, the trajectory the group.
  ASSERT_EQ(sqlite3_open(path_.c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, "DELETE FROM throng_events WHERE kind = 'coordination_start';", nullptr, nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(db);
  const CliResult cut = runThrong({"script", "cg.sqlite", "--agent", "1"}, dir_.path());
  ASSERT_EQ(cut.exitCode, 0) << cut.err;
  EXPECT_TRUE(contains(cut.out, "coordination 1  group 7  initiator A 0  respondents B 1  (unfinished at end of recording)"))
      << cut.out;
}

TEST_F(SocialCommands, MetricsReportAndJson) {
  const CliResult text = runThrong({"metrics", "cg.sqlite", "--bin", "0.25"}, dir_.path());
  ASSERT_EQ(text.exitCode, 0) << text.err;
  for (const char* s : {"Arrivals", "restroom", "Congestion", "Group cohesion", "grounding        mean 2.75 s"}) {
    EXPECT_TRUE(contains(text.out, s)) << s << "\n" << text.out;
  }
  const CliResult r = runThrong({"metrics", "cg.sqlite", "--json", "--radius", "2", "--bin", "0.25"}, dir_.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["arrivals"]["visits"], 2);
  EXPECT_EQ(j["arrivals"]["bins"].size(), 2u);
  EXPECT_NEAR(j["congestion"]["by_category"][0]["max"].get<double>(), 2.0 / (3.141592653589793 * 4.0), 1e-9);
  EXPECT_NEAR(j["cohesion"]["share_together"].get<double>(), 0.75, 1e-12);
  EXPECT_EQ(j["coordinations"]["by_outcome"]["grounded"], 1);
  EXPECT_EQ(j["coordinations"]["reunited"], 1);
}

TEST_F(SocialCommands, UnknownAgentExitsOne) {
  const CliResult r = runThrong({"script", "cg.sqlite", "--agent", "999"}, dir_.path());
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_TRUE(contains(r.err, "agent 999 not found")) << r.err;
}

TEST_F(SocialCommands, BadFlagsExitTwo) {
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"script", "cg.sqlite"}, {"script", "cg.sqlite", "--agent", "x"},
        {"script", "cg.sqlite", "--agent", "0", "--bogus"}, {"metrics", "cg.sqlite", "--radius", "-1"},
        {"metrics", "cg.sqlite", "--bin", "0"}, {"metrics"}}) {
    const CliResult r = runThrong(args, dir_.path());
    EXPECT_EQ(r.exitCode, 2) << args[0] << " " << (args.size() > 2 ? args[2] : "") << "\n" << r.err;
  }
}

TEST_F(SocialCommands, RecordingWithoutCommonGroundTablesSaysSo) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path_.c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, "DROP TABLE throng_script; DROP TABLE throng_coordinations;", nullptr, nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(db);
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"script", "cg.sqlite", "--agent", "0"}, {"metrics", "cg.sqlite"}}) {
    const CliResult r = runThrong(args, dir_.path());
    EXPECT_EQ(r.exitCode, 1) << args[0];
    EXPECT_TRUE(contains(r.err, "no Common Ground data in cg.sqlite")) << r.err;
  }
  EXPECT_EQ(runThrong({"info", "cg.sqlite"}, dir_.path()).exitCode, 0);
  const CliResult missing = runThrong({"metrics", "nope.sqlite"}, dir_.path());
  EXPECT_EQ(missing.exitCode, 1);
}

}  // namespace
}  // namespace throng::e2e

namespace throng::e2e {
namespace {

/// A small Common Ground scenario in `dir` (with a copy of the bundled clips): a corridor, a
/// restroom off it, three groups of three with a high restroom rate.
std::string writeSocialScenario(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  fs::create_directories(dir / "motions");
  for (const auto& e : fs::directory_iterator(fs::path(THRONG_SOURCE_DIR) / "scenarios" / "motions")) {
    fs::copy_file(e.path(), dir / "motions" / e.path().filename(), fs::copy_options::overwrite_existing);
  }
  std::ofstream(dir / "cg.json") << R"({"format": "throng/1", "name": "cg", "seed": 4, "duration": 300,
  "walkable": [[[0,0],[60,0],[60,10],[0,10]], [[40,10],[46,10],[46,16],[40,16]]],
  "points": [{"id": "wc", "kind": "interest", "position": [43, 13], "radius": 1.5, "category": "restroom"},
             {"id": "out", "kind": "exit", "polygon": [[58,0],[60,0],[60,10],[58,10]]}],
  "populations": [{"id": "g", "groups": 3, "size": 3, "spawn": {"polygon": [[1,1],[10,1],[10,9],[1,9]]}, "goals": ["out"]}],
  "social": {"needs": [{"category": "restroom", "rate": 0.05}], "cooldown": 1000}})";
  return "cg.json";
}

TEST(SocialRun, CommonGroundOnAndOffFromTheCommandLine) {
  ScratchDir dir{"social-run"};
  const std::string scenario = writeSocialScenario(dir.path());
  for (const std::string mode : {"on", "off"}) {
    const std::string out = "cg-" + mode + ".sqlite";
    const CliResult run = runThrong({"run", scenario, "--common-ground", mode, "--out", out, "--quiet"}, dir.path());
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const CliResult metrics = runThrong({"metrics", out, "--json"}, dir.path());
    ASSERT_EQ(metrics.exitCode, 0) << metrics.err;
    const json m = json::parse(metrics.out);
    EXPECT_EQ(m["common_ground"], mode);
    const json& outcomes = m["coordinations"]["by_outcome"];
    ASSERT_GE(m["coordinations"]["total"].get<int>(), 1);
    if (mode == "on") {
      EXPECT_GE(outcomes.value("grounded", 0) + outcomes.value("failed", 0), 1) << m.dump();
    } else {
      EXPECT_EQ(outcomes.value("alone", 0), m["coordinations"]["total"].get<int>()) << m.dump();
    }
    EXPECT_EQ(m["arrivals"]["exits"], 9) << "everybody left";
    const CliResult info = runThrong({"info", out, "--json"}, dir.path());
    ASSERT_EQ(info.exitCode, 0) << info.err;
    const json i = json::parse(info.out);
    EXPECT_EQ(i["common_ground"], mode);
    EXPECT_EQ(i["coordinations"], m["coordinations"]["total"]);
  }
  // The initiator's script: the grounding steps, then the plan, with planned and simulated times.
  const CliResult first = runThrong({"script", "cg-on.sqlite", "--agent", "0", "--json"}, dir.path());
  ASSERT_EQ(first.exitCode, 0) << first.err;
  EXPECT_TRUE(json::parse(first.out).contains("trajectory"));
  const CliResult bad = runThrong({"run", scenario, "--common-ground", "maybe", "--out", "x.sqlite"}, dir.path());
  EXPECT_EQ(bad.exitCode, 2) << bad.err;
  EXPECT_TRUE(contains(bad.err, "--common-ground")) << bad.err;
}

TEST(SocialRun, CommonGroundSwitchNeedsASocialSection) {
  ScratchDir dir{"social-run-none"};
  const std::string corridor = std::string(THRONG_SOURCE_DIR) + "/scenarios/corridor.json";
  const CliResult r = runThrong({"run", corridor, "--common-ground", "off", "--out", "x.sqlite", "--quiet"}, dir.path());
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_TRUE(contains(r.err, "no \"social\" section")) << r.err;
}

}  // namespace
}  // namespace throng::e2e
