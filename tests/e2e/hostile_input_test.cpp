// End-to-end tests of `throng check` and `throng run` on hostile scenario files (issue 15, items
// 10, 13, 17): a flood of problems is listed 50 at a time with a count, names that are not UTF-8
// are refused where they stand, control characters are escaped when echoed, Ctrl-C stops a long
// validation, a 200,000-vertex polygon is checked, and a point inside a wall is reported.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace throng::e2e {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

bool contains(const std::string& haystack, const std::string& needle) { return haystack.find(needle) != std::string::npos; }

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

/// A 10 m × 4 m room; two agents walk to an exit. `name` is inserted as written (JSON text).
std::string room(const std::string& name, const std::string& extraKeys = "") {
  return R"({
  "format": "throng/1",
  "name": )" + name + R"(,
  "duration": 20,)" + extraKeys + R"(
  "walkable": [[[0, 0], [10, 0], [10, 4], [0, 4]]],
  "points": [{"id": "exit", "kind": "exit", "polygon": [[9, 1], [10, 1], [10, 3], [9, 3]]}],
  "populations": [{"id": "walkers", "groups": 2, "size": 1,
                   "spawn": {"polygon": [[1, 1], [3, 1], [3, 3], [1, 3]]}, "goals": ["exit"]}]
})";
}

TEST(HostileInput, AFloodOfProblemsIsListedFiftyAtATime) {
  ScratchDir dir("flood");
  std::string keys;
  for (int i = 0; i < 3000; ++i) keys += "\n  \"unknown" + std::to_string(i) + "\": 1,";
  const fs::path scenario = dir.write("flood.json", room("\"flood\"", keys));
  const CliResult text = runThrong({"check", scenario.string()}, dir.path());
  EXPECT_EQ(text.exitCode, 1);
  const auto printed = lines(text.err);
  ASSERT_EQ(printed.size(), 51u) << text.err.substr(0, 2000);
  EXPECT_TRUE(contains(printed[0], "flood.json:5:3 /unknown0: unknown key \"unknown0\" in the scenario")) << printed[0];
  EXPECT_EQ(printed[50], "throng: ... and 2950 more problems (not listed; 3000 in all)");

  const CliResult asJson = runThrong({"check", "--json", scenario.string()}, dir.path());
  EXPECT_EQ(asJson.exitCode, 1);
  const json out = json::parse(asJson.out);
  EXPECT_EQ(out.at("diagnostics").size(), 50u);
  EXPECT_EQ(out.at("diagnostics_total").get<int>(), 3000);
}

TEST(HostileInput, NamesThatAreNotUtf8AreRefusedWhereTheyStand) {
  ScratchDir dir("utf8");
  const fs::path scenario = dir.write("bad.json", room("\"caf\xE9\""));  // Latin-1 é
  const CliResult check = runThrong({"check", scenario.string()}, dir.path());
  EXPECT_EQ(check.exitCode, 1);
  EXPECT_TRUE(contains(check.err, "bad.json:3:15: JSON syntax error: byte 0xE9 in a string is not UTF-8; expected UTF-8 text"))
      << check.err;
  const CliResult asJson = runThrong({"check", "--json", scenario.string()}, dir.path());
  EXPECT_EQ(asJson.exitCode, 1);
  EXPECT_FALSE(json::parse(asJson.out).at("ok").get<bool>());  // valid JSON, not an exception
  // `run` writes nothing: the recording used to be written, marked completed, and the run exit 1.
  const CliResult run = runThrong({"run", scenario.string(), "--json", "--out", "bad.sqlite"}, dir.path());
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_TRUE(contains(run.err, "not UTF-8")) << run.err;
  EXPECT_FALSE(fs::exists(dir / "bad.sqlite"));
}

TEST(HostileInput, ControlCharactersInNamesAreEscapedWhenPrinted) {
  ScratchDir dir("controls");
  // ESC [2J clears a terminal; a newline would forge a second output line.
  const fs::path scenario = dir.write("ctl.json", room(R"("lobby\u001b[2J\nok: forged")"));
  const CliResult check = runThrong({"check", scenario.string()}, dir.path());
  ASSERT_EQ(check.exitCode, 0) << check.err;
  ASSERT_EQ(lines(check.out).size(), 1u) << check.out;
  EXPECT_TRUE(contains(check.out, "ok: lobby\\u001B[2J\\nok: forged: 1 populations")) << check.out;
  EXPECT_FALSE(contains(check.out, "\x1b"));
  const json checked = json::parse(runThrong({"check", "--json", scenario.string()}, dir.path()).out);
  EXPECT_EQ(checked.at("name"), "lobby\x1b[2J\nok: forged");

  const CliResult run = runThrong({"run", scenario.string(), "--json", "--out", "ctl.sqlite"}, dir.path());
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(json::parse(run.out).at("scenario"), "lobby\x1b[2J\nok: forged");
  const CliResult info = runThrong({"info", "ctl.sqlite"}, dir.path());
  ASSERT_EQ(info.exitCode, 0) << info.err;
  EXPECT_TRUE(contains(info.out, "scenario     lobby\\u001B[2J\\nok: forged\n")) << info.out;
  EXPECT_TRUE(json::parse(runThrong({"info", "ctl.sqlite", "--json"}, dir.path()).out).at("completed").get<bool>());
}

/// 10,000 one-agent populations on a floor with 1,156 pillars: seconds of spawn checks.
std::string slowScenario() {
  json obstacles = json::array();
  for (int x = 0; x < 100; x += 3) {
    for (int y = 0; y < 100; y += 3) {
      obstacles.push_back({{x + 0.2, y + 0.2}, {x + 0.6, y + 0.2}, {x + 0.6, y + 0.6}, {x + 0.2, y + 0.6}});
    }
  }
  json populations = json::array();
  for (int i = 0; i < 10000; ++i) {
    const double x = i % 100, y = i / 100;
    populations.push_back({{"id", "p" + std::to_string(i)},
                           {"groups", 1},
                           {"wander", true},
                           {"spawn", {{"polygon", {{x + 0.1, y + 0.1}, {x + 0.9, y + 0.1}, {x + 0.9, y + 0.9}, {x + 0.1, y + 0.9}}}}}});
  }
  return json{{"format", "throng/1"},
              {"name", "slow"},
              {"walkable", {{{0, 0}, {100, 0}, {100, 100}, {0, 100}}}},
              {"obstacles", obstacles},
              {"populations", populations}}
      .dump();
}

TEST(HostileInput, CtrlCStopsALongValidation) {
  ScratchDir dir("sigcheck");
  const fs::path scenario = dir.write("slow.json", slowScenario());
  for (const std::string command : {"check", "run"}) {
    std::vector<std::string> args{command, scenario.string()};
    if (command == "run") args.insert(args.end(), {"--out", "slow.sqlite"});
    CliProcess process(args, dir.path());
    std::this_thread::sleep_for(std::chrono::milliseconds(700));
    process.signal(SIGINT);
    const CliResult r = process.wait();
    EXPECT_EQ(r.exitCode, 130) << command << ": " << r.err;
    // The handler answered (not the default action) and said validation was cut short; `run`
    // used to wait for the whole validation, then say "interrupted before simulating".
    EXPECT_TRUE(contains(r.err, command == "check" ? "throng: interrupted; " : "interrupted while checking the scenario"))
        << command << ": " << r.err;
    EXPECT_FALSE(fs::exists(dir / "slow.sqlite"));
  }
}

TEST(HostileInput, CtrlCStopsANavigationMeshBuild) {
  // A 700 m square at 5 cm cells: half a minute of Recast tiles on this machine's kind. Ctrl-C
  // one second in must end `check` between two tiles, not after the last one.
  ScratchDir dir("signav");
  const json scenario{{"format", "throng/1"},
                      {"name", "bignav"},
                      {"navCellSize", 0.05},
                      {"walkable", {{{0, 0}, {700, 0}, {700, 700}, {0, 700}}}},
                      {"points", {{{"id", "exit"}, {"kind", "exit"}, {"position", {690, 690}}, {"radius", 1}}}},
                      {"populations", {{{"id", "p"}, {"groups", 2}, {"spawn", {{"polygon", {{1, 1}, {5, 1}, {5, 5}, {1, 5}}}}}, {"goals", {"exit"}}}}}};
  const fs::path path = dir.write("bignav.json", scenario.dump());
  CliProcess process({"check", path.string()}, dir.path());
  std::this_thread::sleep_for(std::chrono::milliseconds(1000));
  process.signal(SIGINT);
  // Between two tiles is well under a second; 10 s leaves room for a loaded machine.
  const CliResult r = process.wait(std::chrono::seconds(10));
  EXPECT_EQ(r.exitCode, 130) << r.err;
  EXPECT_TRUE(contains(r.err, "throng: interrupted; ")) << r.err;
}

TEST(HostileInput, AHugePolygonIsChecked) {
  // A 200,000-vertex walkable circle (4 MB): the self-intersection test compared every pair of
  // edges and the navmesh rasterizer every edge for every row (over a minute); both are now
  // near-linear.
  ScratchDir dir("huge");
  json circle = json::array();
  for (int i = 0; i < 200000; ++i) {
    const double a = 2.0 * 3.14159265358979323846 * i / 200000.0;
    circle.push_back({std::round(55.0 * std::cos(a) * 1e4) / 1e4, std::round(55.0 * std::sin(a) * 1e4) / 1e4});
  }
  const json scenario{{"format", "throng/1"},
                      {"name", "huge"},
                      {"walkable", {circle}},
                      {"points", {{{"id", "exit"}, {"kind", "exit"}, {"position", {50, 0}}, {"radius", 1}}}},
                      {"populations", {{{"id", "p"}, {"groups", 10}, {"spawn", {{"polygon", {{-5, -5}, {5, -5}, {5, 5}, {-5, 5}}}}}, {"goals", {"exit"}}}}}};
  const fs::path path = dir.write("huge.json", scenario.dump());
  const CliResult r = runThrong({"check", path.string()}, dir.path());
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "ok: huge: 1 populations, 10 agents, 1 points")) << r.out;
}

TEST(HostileInput, AnInterestPointInsideAWallIsReportedWhereItStands) {
  ScratchDir dir("wall");
  const std::string text = R"({
  "format": "throng/1",
  "name": "wall",
  "walkable": [[[0, 0], [20, 0], [20, 10], [0, 10]]],
  "obstacles": [[[9, 0], [10, 0], [10, 10], [9, 10]]],
  "points": [
    {"id": "shop", "kind": "interest", "position": [9.5, 5], "radius": 0.3}
  ],
  "populations": [{"id": "visitors", "groups": 5, "size": 1,
                   "spawn": {"polygon": [[1, 1], [8, 1], [8, 9], [1, 9]]}, "goals": ["shop"]}]
})";
  const fs::path scenario = dir.write("wall.json", text);
  const CliResult r = runThrong({"check", scenario.string()}, dir.path());
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_TRUE(contains(r.err, "wall.json:7:52 /points/0/position: interest point \"shop\" cannot be reached: (9.5, 5) is "
                              "inside obstacle /obstacles/0 and its radius 0.3 m reaches no ground where agents can stand (their "
                              "centres keep 0.13 m from walls); the nearest walkable point is (8.84, 5), 0.66 m away; expected "
                              "a point whose disc reaches walkable ground clear of /obstacles (move it to (8.84, 5) or enlarge "
                              "\"radius\" to at least 0.66 m)"))
      << r.err;
}

}  // namespace
}  // namespace throng::e2e
