// Every bundled scenario, end to end through the CLI as a user runs it, with the behavioural checks
// from the literature on the recordings: free walking speed and RiMEA test 1 in the corridor, flow
// through the 1 m door, everyone out of the evacuation room, identical recordings for any --threads.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sqlite3.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "bodies.hpp"
#include "cli_runner.hpp"

namespace fs = std::filesystem;
using throng::e2e::runThrong;
using throng::e2e::ScratchDir;

namespace {

fs::path scenario(const std::string& name) { return fs::path(THRONG_SOURCE_DIR) / "scenarios" / (name + ".json"); }

/// Runs a bundled scenario with --json and returns the parsed summary.
nlohmann::json runScenario(const std::string& name, const fs::path& out, const std::vector<std::string>& extra = {}) {
  std::vector<std::string> args{"run", scenario(name).string(), "--out", out.string(), "--force", "--json"};
  args.insert(args.end(), extra.begin(), extra.end());
  const auto r = runThrong(args, out.parent_path());
  EXPECT_EQ(r.exitCode, 0) << r.err;
  if (r.exitCode != 0) return {};
  return nlohmann::json::parse(r.out);
}

/// Rows of a query on a recording, as doubles.
std::vector<std::vector<double>> query(const fs::path& db, const std::string& sql) {
  std::vector<std::vector<double>> rows;
  sqlite3* h = nullptr;
  if (sqlite3_open_v2(db.c_str(), &h, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
    ADD_FAILURE() << "cannot open " << db;
    sqlite3_close(h);
    return rows;
  }
  sqlite3_stmt* st = nullptr;
  if (sqlite3_prepare_v2(h, sql.c_str(), -1, &st, nullptr) != SQLITE_OK) {
    ADD_FAILURE() << sqlite3_errmsg(h) << " in " << sql;
  } else {
    while (sqlite3_step(st) == SQLITE_ROW) {
      std::vector<double> row;
      for (int c = 0; c < sqlite3_column_count(st); ++c) row.push_back(sqlite3_column_double(st, c));
      rows.push_back(row);
    }
  }
  sqlite3_finalize(st);
  sqlite3_close(h);
  return rows;
}

double fps(const fs::path& db) {
  const auto rows = query(db, "SELECT value FROM metadata WHERE key = 'fps'");
  return rows.empty() ? 0.0 : rows[0][0];
}

}  // namespace

TEST(Scenarios, CorridorFreeWalkingAndRimeaTest1) {
  ScratchDir dir("corridor");
  const auto s = runScenario("corridor", dir / "corridor.sqlite");
  ASSERT_FALSE(s.is_null());
  EXPECT_EQ(s["agents_spawned"], 1);
  EXPECT_EQ(s["agents_exited"], 1);
  // Free walking speed within 5% of the desired 1.33 m/s.
  EXPECT_NEAR(s["mean_walking_speed_mps"].get<double>(), 1.33, 1.33 * 0.05);
  // RiMEA test 1: 40 m at 1.33 m/s must take 26..34 s.
  const double t = s["evacuation_time_s"].get<double>();
  EXPECT_GE(t, 26.0);
  EXPECT_LE(t, 34.0);
}

TEST(Scenarios, BottleneckFlowThroughOneMetreDoor) {
  ScratchDir dir("bottleneck");
  const fs::path db = dir / "bottleneck.sqlite";
  const auto s = runScenario("bottleneck", db);
  ASSERT_FALSE(s.is_null());
  EXPECT_EQ(s["agents_spawned"], 100);
  EXPECT_EQ(s["agents_exited"], 100);
  // Passing times through the door (x = 10 m, the downstream face of the wall).
  const auto rows = query(db, "SELECT id, MIN(frame) FROM trajectory_data WHERE pos_x > 10.0 GROUP BY id ORDER BY 2");
  ASSERT_EQ(rows.size(), 100u);
  const double f = fps(db);
  ASSERT_GT(f, 0.0);
  // Steady flow: between the 10th and the 90th person through.
  const double t10 = rows[10][1] / f, t90 = rows[90][1] / f;
  const double flow = 80.0 / (t90 - t10);
  EXPECT_GE(flow, 1.0) << "persons/s";
  EXPECT_LE(flow, 2.5) << "persons/s";
  // Nobody walks through the walls: no recorded position inside either wall block.
  const auto inside = query(db,
                            "SELECT COUNT(*) FROM trajectory_data WHERE pos_x > 9.0 AND pos_x < 10.0 AND "
                            "(pos_y < 4.5 OR pos_y > 5.5)");
  EXPECT_EQ(inside[0][0], 0.0);
}

TEST(Scenarios, CrossingStreamsBothArrive) {
  ScratchDir dir("crossing");
  const auto s = runScenario("crossing", dir / "crossing.sqlite");
  ASSERT_FALSE(s.is_null());
  EXPECT_EQ(s["agents_spawned"], 100);
  EXPECT_EQ(s["agents_exited"], 100);
}

TEST(Scenarios, EvacuationEmptiesTheRoom) {
  ScratchDir dir("evacuation");
  const fs::path db = dir / "evacuation.sqlite";
  const auto s = runScenario("evacuation", db);
  ASSERT_FALSE(s.is_null());
  EXPECT_EQ(s["agents_spawned"], 200);
  EXPECT_EQ(s["agents_exited"], 200);
  // Two 1.2 m doors, 100 people each. The steady flow through each (10th to 90th person into the
  // door's passage) must lie in the measured range for doors of this width: specific flow
  // 1.5..2.2 persons/(m·s) (Jülich bottleneck series, Seyfried et al. 2009, Transp. Sci. 43(3);
  // Liddle et al. 2011: 1.6..2.0 /(m·s) at widths 0.8..1.2 m, widened by ~10 %), i.e. 1.8..2.64 /s.
  const double f = fps(db);
  ASSERT_GT(f, 0.0);
  for (const char* door : {"pos_x < 0.0", "pos_x > 20.0"}) {
    const auto rows = query(db, std::string("SELECT id, MIN(frame) FROM trajectory_data WHERE ") + door +
                                    " GROUP BY id ORDER BY 2");
    ASSERT_EQ(rows.size(), 100u) << door;
    const double flow = 80.0 / ((rows[90][1] - rows[10][1]) / f);
    EXPECT_GE(flow, 1.8) << door << ": persons/s";
    EXPECT_LE(flow, 2.64) << door << ": persons/s";
  }
  // Hence the evacuation time: 100 people at 1.8..2.64 /s per door after a walk of at most ~10 m
  // to it (a few seconds at 1.34 m/s) — 38..66 s.
  EXPECT_GE(s["evacuation_time_s"].get<double>(), 38.0);
  EXPECT_LE(s["evacuation_time_s"].get<double>(), 66.0);
  // Bodies: the default model's are ellipses 0.4 m wide and 0.26 m deep (passageRatio 0.65) facing
  // their heading, so two touch at 0.26..0.4 m between centres depending on how they stand. Bodies
  // in contact step apart (the model's contact term), so nobody is pressed into anyone: no overlap
  // deeper than 0.15 m (0.10 measured; 0.33, two walkers stacked at a wall, before the contact
  // term), and overlaps deeper than 10 cm stay rare (under 1 % of agent-frames). The dense-room
  // target of issue 17 (no overlap deeper than 3 cm) is stricter and not met yet:
  // scripts/validate.py --only room reports it (docs/validation.md).
  const auto pairs = query(db,
                           "SELECT a.pos_x - b.pos_x, a.pos_y - b.pos_y, a.ori_x, a.ori_y, b.ori_x, b.ori_y "
                           "FROM trajectory_data a JOIN trajectory_data b ON a.frame = b.frame AND a.id < b.id "
                           "AND ABS(a.pos_x - b.pos_x) < 0.4 AND ABS(a.pos_y - b.pos_y) < 0.4");
  const auto agentFrames = query(db, "SELECT COUNT(*) FROM trajectory_data");
  double deepest = 0.0;
  int over10cm = 0;
  for (const auto& p : pairs) {
    if (std::hypot(p[0], p[1]) >= 0.4) continue;
    const double depth = throng::test::ellipseOverlap(p[0], p[1], p[2], p[3], p[4], p[5]);
    deepest = std::max(deepest, depth);
    if (depth > 0.1) ++over10cm;
  }
  EXPECT_LT(deepest, 0.15) << "deepest overlap of two bodies [m]";
  ASSERT_GT(agentFrames[0][0], 10000.0);
  EXPECT_LT(over10cm, 0.01 * agentFrames[0][0]) << over10cm << " pair-frames overlap by more than 10 cm";
}

TEST(Scenarios, ExitChoiceUsesEveryExitAndLeavesTheClosedOne) {
  // scenarios/exit_choice.json: 400 people choose among three exits by the quickest rule; the east
  // exit closes at 30 s (docs/crowd-model.md "Tactical level: exit choice").
  ScratchDir dir("exit_choice");
  const fs::path db = dir / "exit_choice.sqlite";
  const auto s = runScenario("exit_choice", db);
  ASSERT_FALSE(s.is_null());
  EXPECT_EQ(s["agents_exited"], 400);
  const auto by = query(db, "SELECT p.id, COUNT(*), MAX(e.tick) FROM throng_events e JOIN throng_points p ON p.idx = e.a "
                            "WHERE e.kind = 'exit' GROUP BY p.id ORDER BY p.id");
  ASSERT_EQ(by.size(), 3u) << "every exit is used";
  // Rows: east, north, west (by id). The 2 m north exit takes the most; nobody leaves by the east
  // one after it closed (tick 600 at dt 0.05 s; a person already inside its region leaves at once).
  EXPECT_GT(by[1][1], by[0][1]);
  EXPECT_GT(by[1][1], by[2][1]);
  EXPECT_LE(by[0][2], 601.0);
  // Those heading east when it closed chose again at once.
  const auto moved = query(db, "SELECT COUNT(*) FROM throng_events e JOIN throng_points p ON p.idx = e.b "
                               "WHERE e.kind = 'exit_chosen' AND p.id = 'east' AND e.tick = 600");
  EXPECT_GT(moved[0][0], 10.0);
}

TEST(Scenarios, AtriumPeopleChangeFloorsOnlyByEscalatorsAndTheLift) {
  // scenarios/atrium.json: two floors joined by nothing walkable; 150 go up by escalator to the
  // cinema, 150 come down by the other to the street, 16 take the lift down (docs/crowd-model.md,
  // "Tactical level: lifts and escalators").
  ScratchDir dir("atrium");
  const fs::path db = dir / "atrium.sqlite";
  const auto s = runScenario("atrium", db);
  ASSERT_FALSE(s.is_null());
  EXPECT_EQ(s["agents_exited"], 316);
  EXPECT_TRUE(s["stalled_agents"].empty()) << "queuing for a transport is no stall";
  const auto byExit = query(db, "SELECT p.id, COUNT(*) FROM throng_events e JOIN throng_points p ON p.idx = e.a "
                                "WHERE e.kind = 'exit' GROUP BY p.id ORDER BY p.id");
  ASSERT_EQ(byExit.size(), 2u);
  EXPECT_EQ(byExit[0][1], 150.0) << "up to the cinema";
  EXPECT_EQ(byExit[1][1], 166.0) << "down to the street, by escalator or lift";
  // Each escalator lets one person on every 0.8 s: 150 reach its head over at least 149 x 0.8 s
  // (119.2 s when its queue never runs dry; session 44's up escalator has one 0.2 s gap in it:
  // 119.4 s). At most one slot's worth of gaps is allowed.
  for (const char* head : {"up-head", "down-foot"}) {
    const auto span = query(db, std::string("SELECT COUNT(*), (MAX(e.tick) - MIN(e.tick)) * 0.05 FROM throng_events e JOIN "
                                            "throng_points p ON p.idx = e.a WHERE e.kind = 'goal_reached' AND p.id = '") +
                                    head + "'");
    ASSERT_EQ(span.size(), 1u);
    EXPECT_EQ(span[0][0], 150.0) << head;
    EXPECT_GE(span[0][1], 119.2 - 0.06) << head << ": faster than one every 0.8 s";
    EXPECT_LE(span[0][1], 119.2 + 0.8 + 0.06) << head << ": more than one slot missed while the queue lasts";
  }
  // Lift riders arrive downstairs in batches of at most 8.
  const auto lift = query(db, "SELECT e.tick FROM throng_events e JOIN throng_points p ON p.idx = e.a "
                              "WHERE e.kind = 'goal_reached' AND p.id = 'lift-ground' ORDER BY e.tick");
  ASSERT_EQ(lift.size(), 16u);
  int batch = 1, largest = 1;
  for (std::size_t i = 1; i < lift.size(); ++i) {
    batch = lift[i][0] - lift[i - 1][0] <= 24.0 ? batch + 1 : 1;  // 1.2 s transfers
    largest = std::max(largest, batch);
  }
  EXPECT_LE(largest, 8);
  // Everyone was carried between the floors (heights between 0 and 4.5 only on a car or a belt).
  const auto between = query(db, "SELECT COUNT(DISTINCT id) FROM throng_heights WHERE z > 0.01 AND z < 4.49");
  EXPECT_EQ(between[0][0], 316.0);
}

TEST(Scenarios, DepartmentStoreShoppersChooseTheEscalatorsTheLiftAndTheStairsThemselves) {
  // scenarios/department_store.json (scripts/make_department_store.py): two floors joined by an
  // escalator each way, a stair beside them and a lift; no population names a stop, so every ride is
  // the shoppers' own choice (docs/crowd-model.md, "Choosing a lift, an escalator or the stairs").
  ScratchDir dir("department_store");
  const fs::path db = dir / "department_store.sqlite";
  const auto s = runScenario("department_store", db);
  ASSERT_FALSE(s.is_null());
  EXPECT_EQ(s["agents_exited"], s["agents_spawned"]) << "everyone shops on both floors and leaves";
  EXPECT_TRUE(s["stalled_agents"].empty());
  const auto chosen = query(db, "SELECT COUNT(DISTINCT p.id), SUM(p.id LIKE 'lift-%'), SUM(p.id NOT LIKE 'lift-%') "
                                "FROM throng_events e JOIN throng_points p ON p.idx = e.a WHERE e.kind = 'waypoint_chosen'");
  ASSERT_EQ(chosen.size(), 1u);
  EXPECT_EQ(chosen[0][0], 4.0) << "both escalators, and the lift from both floors";
  EXPECT_GT(chosen[0][2], 3 * chosen[0][1]) << "the escalators carry most; the lift takes those its queue suits";
  EXPECT_GT(chosen[0][1], 10.0) << "groups that chose the lift";
  // The stair (x 14-22.1, y 10.5-13.5): the climbers' share (stairs.climb, 20 % up and 31 % down by
  // default) take it, each shopper changing floors twice: 170 of the 344 shoppers on seed 1, 130-154
  // on seeds 2-6. Weighing the stairs by time alone, everyone took them and jammed at the foot (84
  // out after 600 s); nobody at all: the store empties after 396 s, with the stair after 320 s.
  const auto climbed = query(db,
                             "SELECT COUNT(DISTINCT h.id) FROM throng_heights h JOIN trajectory_data t ON t.frame = h.frame "
                             "AND t.id = h.id WHERE h.z > 0.3 AND h.z < 4.2 AND t.pos_x BETWEEN 14 AND 22.2 AND t.pos_y "
                             "BETWEEN 10.5 AND 13.5");
  ASSERT_EQ(climbed.size(), 1u);
  const double spawned = s["agents_spawned"].get<double>();
  EXPECT_GT(climbed[0][0], 0.2 * spawned) << "shoppers who took the stairs";
  EXPECT_LT(climbed[0][0], 0.7 * spawned) << "most floor changes are rides";
}

TEST(Scenarios, PlazaFlagshipRuns) {
  ScratchDir dir("plaza");
  const fs::path db = dir / "plaza.sqlite";
  const auto s = runScenario("plaza", db);
  ASSERT_FALSE(s.is_null());
  EXPECT_GT(s["agents_spawned"].get<int>(), 1500) << "eight waves over 175 s";
  // Every commuter of the first wave crosses the plaza and leaves (about 40 m: 30 s at 1.34 m/s
  // when free; the waves crossing at the centre slow them), half of them within 60 s.
  const auto wave1 = query(db,
                           "SELECT COUNT(*), SUM(exit_frame IS NOT NULL) FROM throng_agents "
                           "WHERE population_id LIKE 'commuters-%-wave1'");
  ASSERT_EQ(wave1.size(), 1u);
  EXPECT_GE(wave1[0][0], 140.0);
  EXPECT_EQ(wave1[0][1], wave1[0][0]) << "every first-wave commuter exits";
  const auto times = query(db,
                           "SELECT (exit_frame - spawn_frame) FROM throng_agents WHERE population_id LIKE "
                           "'commuters-%-wave1' AND exit_frame IS NOT NULL ORDER BY 1");
  const double fpsRec = fps(db);
  ASSERT_GT(fpsRec, 0.0);
  ASSERT_FALSE(times.empty());
  EXPECT_LT(times[times.size() / 2][0] / fpsRec, 60.0) << "median crossing time of the first wave [s]";
  // Commuters of waves 1..4 (spawned at least 165 s before the end) get out: at least 90 % of them.
  // Where the waves cross, knots form and dissolve by chance: over seeds 1-10 the share is 0.80-1.00
  // (mean 0.93, with or without avm's overtaking; session 41), so one seed is held to 90 %, not 95.
  const auto early = query(db,
                           "SELECT COUNT(*), SUM(exit_frame IS NOT NULL) FROM throng_agents WHERE population_id "
                           "LIKE 'commuters-%' AND spawn_tick * 0.05 <= 75.5");
  ASSERT_EQ(early.size(), 1u);
  EXPECT_GE(early[0][1], 0.90 * early[0][0]) << early[0][1] << " of " << early[0][0];
  const auto info = runThrong({"info", db.string(), "--json"}, dir.path());
  EXPECT_EQ(info.exitCode, 0) << info.err;
}

TEST(Scenarios, RecordingIdenticalForAnyThreadCount) {
  ScratchDir dir("threads");
  const fs::path a = dir / "t1.sqlite", b = dir / "t2.sqlite";
  runScenario("bottleneck", a, {"--threads", "1", "--duration", "20"});
  runScenario("bottleneck", b, {"--threads", "2", "--duration", "20"});
  const std::string sql = "SELECT frame, id, pos_x, pos_y, ori_x, ori_y FROM trajectory_data ORDER BY frame, id";
  const auto ra = query(a, sql), rb = query(b, sql);
  ASSERT_GT(ra.size(), 1000u);
  ASSERT_EQ(ra.size(), rb.size());
  for (std::size_t i = 0; i < ra.size(); ++i) ASSERT_EQ(ra[i], rb[i]) << "row " << i;
}

TEST(Scenarios, EveryBundledScenarioPassesCheck) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(THRONG_SOURCE_DIR) / "scenarios")) {
    if (entry.path().extension() != ".json") continue;
    const auto r = runThrong({"check", entry.path().string()}, fs::temp_directory_path());
    EXPECT_EQ(r.exitCode, 0) << entry.path() << "\n" << r.out << r.err;
    ++count;
  }
  EXPECT_GE(count, 5);
}

TEST(Scenarios, MuseumEveryGroupVisitsItsPaintings) {
  ScratchDir dir("museum");
  const fs::path db = dir / "museum.sqlite";
  const auto s = runScenario("museum", db);
  ASSERT_FALSE(s.is_null());
  const auto scenarioJson = nlohmann::json::parse(throng::e2e::readFile(scenario("museum")));
  std::map<std::string, std::string> kindOf;
  for (const auto& p : scenarioJson["points"]) kindOf[p["id"].get<std::string>()] = p["kind"].get<std::string>();
  // Paintings each agent stood at (action_start), by population.
  const auto rows = query(db,
                          "SELECT e.agent, a.population, e.a FROM throng_events e JOIN throng_agents a ON a.id = e.agent "
                          "WHERE e.kind = 'action_start'");
  std::map<int, std::set<std::string>> visited;  // agent → painting ids
  std::map<int, int> populationOf;
  std::vector<std::string> pointIds;
  for (const auto& p : scenarioJson["points"]) pointIds.push_back(p["id"].get<std::string>());
  for (const auto& r : rows) {
    visited[static_cast<int>(r[0])].insert(pointIds.at(static_cast<std::size_t>(r[2])));
    populationOf[static_cast<int>(r[0])] = static_cast<int>(r[1]);
  }
  const auto agents = query(db, "SELECT id, population FROM throng_agents");
  const auto& pops = scenarioJson["populations"];
  for (const auto& a : agents) {
    const auto& pop = pops.at(static_cast<std::size_t>(a[1]));
    const std::string id = pop["id"].get<std::string>();
    std::set<std::string> expected;
    if (pop.contains("follow")) {
      // A permanent follower goes where the followed group goes: the class's paintings.
      for (const auto& p : pops) {
        if (p["id"] == pop["follow"]["population"]) for (const auto& g : p["goals"]) if (kindOf[g] == "action") expected.insert(g);
      }
    } else if (pop["goals"].is_array() && !pop.contains("sociological") && !pop.contains("guide")) {
      for (const auto& g : pop["goals"]) if (kindOf[g] == "action") expected.insert(g);
    } else if (pop["goals"] == "auto") {
      EXPECT_EQ(visited[static_cast<int>(a[0])].size(), 1u) << "automatic goals end at one action point: agent " << a[0];
      continue;
    } else {
      continue;  // sociable visitors may change group; the guided tour goes where its guide leads
    }
    for (const std::string& painting : expected) {
      EXPECT_TRUE(visited[static_cast<int>(a[0])].count(painting)) << id << " agent " << a[0] << " never looked at " << painting;
    }
  }
  // The guided tour was guided, then released, and left with everyone else who had an exit to go to.
  const auto guide = query(db, "SELECT COUNT(*) FROM throng_events WHERE kind IN ('guide_start', 'guide_end')");
  EXPECT_GE(guide[0][0], 2.0);
  const auto following = query(db, "SELECT COUNT(*) FROM throng_events WHERE kind = 'follow_start'");
  EXPECT_GE(following[0][0], 1.0);
  // Action clips play while looking: the animation table names the "look" clip with phases in [0, 1).
  const auto look = query(db,
                          "SELECT COUNT(*), MIN(phase), MAX(phase) FROM throng_animation n JOIN throng_clips c ON c.idx = n.clip "
                          "WHERE c.name = 'look'");
  EXPECT_GT(look[0][0], 100.0);
  EXPECT_GE(look[0][1], 0.0);
  EXPECT_LT(look[0][2], 1.0);
}
