// The C API (libs/capi/src/throng_c.cpp), one test per function or per pair that only make sense
// together, each asserting the function's effect: versions, errors and their thread-local
// messages, scenario loading with `throng check`'s diagnostics, stepping and running, stats, the
// agent columns and their count/capacity protocol, guidance, crowds inserted and removed, events,
// and recordings (frame count read back with sqlite3).
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <string>
#include <thread>

#include "capi_fixtures.hpp"
#include "cli_runner.hpp"
#include "sqlite_query.hpp"
#include "temp_dir.hpp"
#include "throng/throng.h"

namespace throng::capi_test {
namespace {

const std::string kMuseum = std::string(THRONG_SOURCE_DIR) + "/scenarios/museum.json";

TEST(CApi, VersionsMatchTheProject) {
  EXPECT_STREQ(throng_version(), THRONG_PROJECT_VERSION);
  EXPECT_STREQ(THRONG_VERSION_STRING, THRONG_PROJECT_VERSION);
  EXPECT_EQ(std::to_string(THRONG_VERSION_MAJOR) + "." + std::to_string(THRONG_VERSION_MINOR) + "." +
                std::to_string(THRONG_VERSION_PATCH),
            THRONG_PROJECT_VERSION);
  EXPECT_EQ(throng_api_version(), static_cast<uint32_t>(THRONG_API_VERSION));
}

TEST(CApi, StatusNamesAreDistinct) {
  std::set<std::string> names;
  for (int s = THRONG_OK; s <= THRONG_ERROR_INTERNAL; ++s) names.insert(throng_status_name(static_cast<throng_status>(s)));
  EXPECT_EQ(names.size(), static_cast<std::size_t>(THRONG_ERROR_INTERNAL) + 1);
  EXPECT_EQ(names.count("unknown"), 0u);
  EXPECT_STREQ(throng_status_name(THRONG_ERROR_BAD_HANDLE), "THRONG_ERROR_BAD_HANDLE");
  EXPECT_STREQ(throng_status_name(static_cast<throng_status>(99)), "unknown");
}

TEST(CApi, LastErrorIsPerThreadAndClearedBySuccess) {
  EXPECT_EQ(throng_world_step(nullptr, 1, nullptr), THRONG_ERROR_NULL_ARGUMENT);
  const std::string mine = throng_last_error();
  EXPECT_NE(mine.find("world is NULL"), std::string::npos) << mine;
  std::string other;
  std::thread([&] {
    other = throng_last_error();  // nothing failed on this thread
    EXPECT_EQ(throng_scenario_load_json("{", nullptr, nullptr, nullptr), THRONG_ERROR_NULL_ARGUMENT);
  }).join();
  EXPECT_EQ(other, "");
  EXPECT_EQ(throng_last_error(), mine) << "another thread's failure left this thread's message alone";
  auto s = loadJson(corridor(2));
  EXPECT_STREQ(throng_last_error(), "");
}

TEST(CApi, StringFreeTakesNull) { throng_string_free(nullptr); }

TEST(CApi, ScenarioFromFileAndItsInfo) {
  throng_scenario* s = nullptr;
  char* diagnostics = reinterpret_cast<char*>(0x1);  // overwritten with NULL on success
  ASSERT_EQ(throng_scenario_load_file(kMuseum.c_str(), &s, &diagnostics), THRONG_OK) << throng_last_error();
  EXPECT_EQ(diagnostics, nullptr);
  throng_scenario_info info{};
  ASSERT_EQ(throng_scenario_info_get(s, &info), THRONG_OK);
  EXPECT_EQ(info.seed, 1997u);
  EXPECT_DOUBLE_EQ(info.duration, 300.0);
  EXPECT_NEAR(info.dt, 0.05, 1e-7);
  EXPECT_GT(info.populations, 0u);
  EXPECT_GT(info.points, 0u);
  EXPECT_GT(info.agents_min, 0u);
  EXPECT_LE(info.agents_min, info.agents_max);
  EXPECT_EQ(throng_scenario_info_get(s, nullptr), THRONG_ERROR_NULL_ARGUMENT);
  EXPECT_EQ(throng_scenario_free(s), THRONG_OK);
  EXPECT_EQ(throng_scenario_free(nullptr), THRONG_OK);
  EXPECT_EQ(throng_scenario_free(nullptr), THRONG_OK);
  int notAHandle = 0;
  EXPECT_EQ(throng_scenario_free(reinterpret_cast<throng_scenario*>(&notAHandle)), THRONG_ERROR_BAD_HANDLE);
  EXPECT_EQ(throng_scenario_info_get(reinterpret_cast<throng_scenario*>(&notAHandle), &info), THRONG_ERROR_BAD_HANDLE);
}

// The diagnostics are `throng check`'s own lines: file:line:column, JSON pointer, what was expected.
TEST(CApi, RefusedScenarioGivesTheDiagnosticsThrongCheckPrints) {
  test::TempDir dir("capi");
  std::string bad = corridor(2);
  bad.replace(bad.find("[\"exit\"]"), 8, "[\"exti\"]");
  const std::string path = dir.file("bad.json");
  std::ofstream(path) << bad;
  throng_scenario* s = nullptr;
  char* fromFile = nullptr;
  ASSERT_EQ(throng_scenario_load_file(path.c_str(), &s, &fromFile), THRONG_ERROR_INVALID_SCENARIO);
  ASSERT_NE(fromFile, nullptr);
  EXPECT_EQ(s, nullptr);
  EXPECT_STREQ(throng_last_error(), fromFile);
  const std::string text = fromFile;
  throng_string_free(fromFile);
  EXPECT_NE(text.find(path + ":"), std::string::npos) << text;
  EXPECT_NE(text.find("/populations/0/goals/0"), std::string::npos) << text;
  EXPECT_NE(text.find("did you mean \"exit\""), std::string::npos) << text;
  const e2e::CliResult check = e2e::runThrong({"check", path}, dir.path());
  EXPECT_EQ(check.exitCode, 1);
  EXPECT_EQ(e2e::lines(check.err), e2e::lines(text));

  char* fromJson = nullptr;
  EXPECT_EQ(throng_scenario_load_json(bad.c_str(), "inline.json", &s, &fromJson), THRONG_ERROR_INVALID_SCENARIO);
  ASSERT_NE(fromJson, nullptr);
  EXPECT_EQ(std::string(fromJson).rfind("inline.json:", 0), 0u) << fromJson;
  throng_string_free(fromJson);
  EXPECT_EQ(throng_scenario_load_json("{ not json", nullptr, &s, nullptr), THRONG_ERROR_INVALID_SCENARIO);
  EXPECT_EQ(std::string(throng_last_error()).rfind("<string>:1:", 0), 0u) << throng_last_error();
  EXPECT_EQ(throng_scenario_load_file((dir.path() + "/missing.json").c_str(), &s, nullptr), THRONG_ERROR_INVALID_SCENARIO);
  EXPECT_NE(std::string(throng_last_error()).find("missing.json"), std::string::npos);
  EXPECT_EQ(throng_scenario_load_file(nullptr, &s, nullptr), THRONG_ERROR_NULL_ARGUMENT);
  EXPECT_EQ(throng_scenario_load_file(path.c_str(), nullptr, nullptr), THRONG_ERROR_NULL_ARGUMENT);
}

TEST(CApi, WorldOptionsAreChecked) {
  auto s = loadJson(corridor(4));
  throng_world_options o = throng_world_options_default();
  EXPECT_EQ(o.threads, 1);
  EXPECT_EQ(o.use_seed, 0);
  throng_world* w = nullptr;
  o.threads = -1;
  EXPECT_EQ(throng_world_create(s.get(), &o, &w), THRONG_ERROR_INVALID_ARGUMENT);
  o.threads = 1025;
  EXPECT_EQ(throng_world_create(s.get(), &o, &w), THRONG_ERROR_INVALID_ARGUMENT);
  o = throng_world_options_default();
  o.duration = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(throng_world_create(s.get(), &o, &w), THRONG_ERROR_INVALID_ARGUMENT);
  o.duration = -1;
  EXPECT_EQ(throng_world_create(s.get(), &o, &w), THRONG_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(w, nullptr);
  EXPECT_EQ(throng_world_create(nullptr, nullptr, &w), THRONG_ERROR_NULL_ARGUMENT);
  EXPECT_EQ(throng_world_create(s.get(), nullptr, nullptr), THRONG_ERROR_NULL_ARGUMENT);
  // Seed and duration override the scenario's; the scenario may go before its world.
  o = throng_world_options_default();
  o.use_seed = 1, o.seed = 77, o.duration = 12.5;
  ASSERT_EQ(throng_world_create(s.get(), &o, &w), THRONG_OK);
  s.reset();
  WorldPtr world(w);
  const throng_world_stats st = stats(w);
  EXPECT_EQ(st.seed, 77u);
  EXPECT_DOUBLE_EQ(st.duration, 12.5);
  EXPECT_EQ(st.tick, 0u);
  EXPECT_EQ(st.spawned, 4u);
  EXPECT_EQ(st.active, 4u);
  EXPECT_EQ(st.groups, 4u);
  EXPECT_EQ(st.finished, 0);
  EXPECT_EQ(st.recording, 0);
  EXPECT_LT(st.last_exit_time, 0.0);
}

TEST(CApi, WorldFreeTakesNullAndRefusesStrangers) {
  EXPECT_EQ(throng_world_free(nullptr), THRONG_OK);
  EXPECT_EQ(throng_world_free(nullptr), THRONG_OK);
  double notAWorld = 0;
  EXPECT_EQ(throng_world_free(reinterpret_cast<throng_world*>(&notAWorld)), THRONG_ERROR_BAD_HANDLE);
  EXPECT_EQ(throng_world_step(reinterpret_cast<throng_world*>(&notAWorld), 1, nullptr), THRONG_ERROR_BAD_HANDLE);
}

TEST(CApi, StepAdvancesTimeAndAgentsWalk) {
  auto s = loadJson(corridor());
  auto w = makeWorld(s.get());
  const Agents start = readAgents(w.get());
  ASSERT_EQ(start.size(), 20u);
  uint64_t stepped = 0;
  ASSERT_EQ(throng_world_step(w.get(), 40, &stepped), THRONG_OK);
  EXPECT_EQ(stepped, 40u);
  const throng_world_stats st = stats(w.get());
  EXPECT_EQ(st.tick, 40u);
  EXPECT_NEAR(st.time, 2.0, 1e-5);
  EXPECT_EQ(st.agent_steps, 40u * 20u);
  const Agents later = readAgents(w.get());
  ASSERT_EQ(later.ids, start.ids);
  for (std::size_t i = 0; i < later.size(); ++i) {
    EXPECT_GT(later.x(i) - start.x(i), 1.0f) << "agent " << later.ids[i] << " walked towards the exit";
    EXPECT_EQ(later.modes[i], THRONG_MODE_WALKING);
  }
  EXPECT_EQ(throng_world_step(w.get(), 0, &stepped), THRONG_OK);
  EXPECT_EQ(stepped, 0u);
  EXPECT_EQ(stats(w.get()).tick, 40u);
}

TEST(CApi, RunEndsWhenEveryoneLeftAndAFinishedWorldDoesNotStep) {
  auto s = loadJson(corridor(3));
  auto w = makeWorld(s.get());
  EXPECT_EQ(throng_world_run(w.get(), 1.0), THRONG_OK);
  EXPECT_NEAR(stats(w.get()).time, 1.0, 1e-5);
  EXPECT_EQ(throng_world_run(w.get(), std::nan("")), THRONG_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(throng_world_run(w.get(), -1.0), THRONG_ERROR_INVALID_ARGUMENT);
  ASSERT_EQ(throng_world_run(w.get(), stats(w.get()).duration), THRONG_OK);
  const throng_world_stats st = stats(w.get());
  EXPECT_EQ(st.finished, 1);
  EXPECT_EQ(st.exited, 3u);
  EXPECT_EQ(st.active, 0u);
  EXPECT_GT(st.last_exit_time, 5.0);
  EXPECT_LT(st.time, 30.0);
  EXPECT_GT(st.mean_walking_speed, 0.8);
  uint64_t stepped = 99;
  EXPECT_EQ(throng_world_step(w.get(), 1, &stepped), THRONG_ERROR_WRONG_STATE);
  EXPECT_NE(std::string(throng_last_error()).find("finished"), std::string::npos);
}

TEST(CApi, AgentColumnsAndTheCountCapacityProtocol) {
  auto s = loadJson(corridor(12));
  auto w = makeWorld(s.get());
  ASSERT_EQ(throng_world_step(w.get(), 30, nullptr), THRONG_OK);
  std::vector<float> small(2 * 5, -7.0f);
  throng_agent_arrays arrays{};
  arrays.capacity = 5;
  arrays.positions = small.data();
  std::size_t count = 0;
  EXPECT_EQ(throng_world_agents(w.get(), &arrays, &count), THRONG_ERROR_BUFFER_TOO_SMALL);
  EXPECT_EQ(count, 12u);
  EXPECT_EQ(small, std::vector<float>(2 * 5, -7.0f)) << "nothing copied when the capacity is too small";
  arrays.capacity = std::numeric_limits<std::size_t>::max();
  arrays.positions = nullptr;  // a huge capacity with no columns copies nothing
  EXPECT_EQ(throng_world_agents(w.get(), &arrays, &count), THRONG_OK);
  EXPECT_EQ(throng_world_agents(w.get(), nullptr, &count), THRONG_ERROR_NULL_ARGUMENT);
  EXPECT_EQ(throng_world_agents(w.get(), &arrays, nullptr), THRONG_ERROR_NULL_ARGUMENT);

  const Agents a = readAgents(w.get());
  ASSERT_EQ(a.size(), 12u);
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (i > 0) EXPECT_LT(a.ids[i - 1], a.ids[i]) << "ascending ids";
    EXPECT_EQ(a.groups[i], a.ids[i]) << "one agent per group, groups spawned in order";
    EXPECT_EQ(a.heights[i], 0.0f) << "a flat world";
    EXPECT_NEAR(std::hypot(a.headings[2 * i], a.headings[2 * i + 1]), 1.0, 1e-3);
    EXPECT_LT(std::hypot(a.velocities[2 * i], a.velocities[2 * i + 1]), 2.5f);
    EXPECT_GT(a.velocities[2 * i], 0.2f) << "walking towards +x";
    EXPECT_GE(a.phases[i], 0.0f);
    EXPECT_LT(a.phases[i], 1.0f);
    EXPECT_GT(a.x(i), 0.0f);
    EXPECT_LT(a.x(i), 20.0f);
  }
}

TEST(CApi, GuidedGroupFollowsItsGuideAndIsReleased) {
  auto s = loadJson(corridor(3, 60));
  auto w = makeWorld(s.get());
  uint32_t g = 0;
  ASSERT_EQ(throng_world_group(w.get(), "walkers", 1, &g), THRONG_OK);
  EXPECT_EQ(throng_world_group(w.get(), "walkers", 99, &g), THRONG_ERROR_NOT_FOUND);
  EXPECT_EQ(throng_world_group(w.get(), "nobody", 0, &g), THRONG_ERROR_NOT_FOUND);
  EXPECT_EQ(throng_world_group(w.get(), nullptr, 0, &g), THRONG_ERROR_NULL_ARGUMENT);
  ASSERT_EQ(throng_world_guide(w.get(), g, 3.0, 2.0), THRONG_OK);
  EXPECT_EQ(throng_world_guide(w.get(), g, std::nan(""), 2.0), THRONG_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(throng_world_guide(w.get(), 999, 3.0, 2.0), THRONG_ERROR_NOT_FOUND);
  ASSERT_EQ(throng_world_step(w.get(), 200, nullptr), THRONG_OK);
  const Agents a = readAgents(w.get());
  int members = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a.groups[i] == g) {
      ++members;
      EXPECT_NEAR(a.x(i), 3.0f, 1.5f) << "the guided group stayed with its guide";
      EXPECT_NEAR(a.y(i), 2.0f, 1.5f);
    } else {
      EXPECT_GT(a.x(i), 15.0f) << "the others walked on";
    }
  }
  EXPECT_EQ(members, 1);
  const auto events = drainEvents(w.get());
  EXPECT_TRUE(std::any_of(events.begin(), events.end(),
                          [&](const throng_event& e) { return e.kind == THRONG_EVENT_GUIDE_START && e.a == g; }));
  // On a flat world the height is carried but changes nothing; then release.
  ASSERT_EQ(throng_world_guide_at_height(w.get(), g, 4.0, 2.0, 0.0), THRONG_OK);
  EXPECT_EQ(throng_world_guide_at_height(w.get(), g, 4.0, 2.0, INFINITY), THRONG_ERROR_INVALID_ARGUMENT);
  ASSERT_EQ(throng_world_release(w.get(), g), THRONG_OK);
  EXPECT_EQ(throng_world_release(w.get(), 999), THRONG_ERROR_NOT_FOUND);
  ASSERT_EQ(throng_world_run(w.get(), 60.0), THRONG_OK);
  EXPECT_EQ(stats(w.get()).finished, 1) << "released, the group went on to the exit";
}

const char* kCrowd = R"({"format": "throng-crowd/1", "id": "late",
  "populations": [{"id": "late-walkers", "groups": 4, "size": 1,
                   "spawn": {"polygon": [[1, 1], [4, 1], [4, 3], [1, 3]]}, "goals": ["exit"], "radius": 0.2}]})";

TEST(CApi, CrowdsAreInsertedAndRemoved) {
  auto s = loadJson(corridor(2, 60));
  auto w = makeWorld(s.get());
  ASSERT_EQ(throng_world_step(w.get(), 10, nullptr), THRONG_OK);
  uint32_t index = 99;
  ASSERT_EQ(throng_world_insert_crowd(w.get(), kCrowd, nullptr, &index, nullptr), THRONG_OK) << throng_last_error();
  EXPECT_EQ(index, 0u);
  ASSERT_EQ(throng_world_step(w.get(), 1, nullptr), THRONG_OK);
  EXPECT_EQ(readAgents(w.get()).size(), 6u);
  EXPECT_EQ(stats(w.get()).active, 6u);
  char* diagnostics = nullptr;
  EXPECT_EQ(throng_world_insert_crowd(w.get(), kCrowd, "again.json", &index, &diagnostics), THRONG_ERROR_INVALID_SCENARIO);
  ASSERT_NE(diagnostics, nullptr);
  EXPECT_NE(std::string(diagnostics).find("again.json"), std::string::npos) << diagnostics;
  throng_string_free(diagnostics);

  ASSERT_EQ(throng_world_remove_crowd(w.get(), "late"), THRONG_OK);
  drainEvents(w.get());
  ASSERT_EQ(throng_world_step(w.get(), 1, nullptr), THRONG_OK);
  EXPECT_EQ(readAgents(w.get()).size(), 2u);
  EXPECT_EQ(stats(w.get()).removed, 4u);
  const auto events = drainEvents(w.get());
  EXPECT_EQ(std::count_if(events.begin(), events.end(),
                          [](const throng_event& e) { return e.kind == THRONG_EVENT_EXIT && e.a == 0xffffffffu; }),
            4);
  EXPECT_EQ(throng_world_remove_crowd(w.get(), "late"), THRONG_ERROR_NOT_FOUND);
  EXPECT_EQ(throng_world_remove_crowd(w.get(), nullptr), THRONG_ERROR_NULL_ARGUMENT);
}

TEST(CApi, AClosedExitLetsNobodyOutUntilItOpens) {
  auto s = loadJson(corridor(6, 120));
  auto w = makeWorld(s.get());
  int32_t wall = -1;
  ASSERT_EQ(throng_world_exit_is_wall(w.get(), "exit", &wall), THRONG_OK);
  EXPECT_EQ(wall, 1);
  ASSERT_EQ(throng_world_exit_is_wall(w.get(), "nowhere", &wall), THRONG_OK);
  EXPECT_EQ(wall, 0);
  EXPECT_EQ(throng_world_exit_is_wall(w.get(), "exit", nullptr), THRONG_ERROR_NULL_ARGUMENT);
  ASSERT_EQ(throng_world_set_exit_open(w.get(), "exit", 0), THRONG_OK);
  ASSERT_EQ(throng_world_run(w.get(), 40.0), THRONG_OK);  // 20 m at 1.3 m/s: everyone at the door
  EXPECT_EQ(stats(w.get()).exited, 0u) << "nobody leaves by a closed exit";
  ASSERT_EQ(throng_world_set_exit_open(w.get(), "exit", 1), THRONG_OK);
  ASSERT_EQ(throng_world_run(w.get(), 100.0), THRONG_OK);
  EXPECT_EQ(stats(w.get()).exited, 6u) << "opened, it lets everyone out";
  EXPECT_EQ(throng_world_set_exit_open(w.get(), "nowhere", 0), THRONG_ERROR_NOT_FOUND);
  EXPECT_NE(std::string(throng_last_error()).find("nowhere"), std::string::npos);
  EXPECT_EQ(throng_world_set_exit_open(w.get(), nullptr, 0), THRONG_ERROR_NULL_ARGUMENT);
}

TEST(CApi, CrowdFromAFile) {
  test::TempDir dir("capi");
  std::string crowd = kCrowd;
  crowd.replace(crowd.find("\"late\""), 6, "\"from-file\"");
  std::ofstream(dir.file("crowd.json")) << crowd;
  auto s = loadJson(corridor(2, 60));
  auto w = makeWorld(s.get());
  uint32_t index = 99;
  ASSERT_EQ(throng_world_insert_crowd_file(w.get(), dir.file("crowd.json").c_str(), &index, nullptr), THRONG_OK)
      << throng_last_error();
  EXPECT_EQ(index, 0u);
  ASSERT_EQ(throng_world_step(w.get(), 1, nullptr), THRONG_OK);
  EXPECT_EQ(stats(w.get()).active, 6u);
  char* diagnostics = nullptr;
  EXPECT_EQ(throng_world_insert_crowd_file(w.get(), dir.file("none.json").c_str(), &index, &diagnostics),
            THRONG_ERROR_INVALID_SCENARIO);
  ASSERT_NE(diagnostics, nullptr);
  EXPECT_NE(std::string(diagnostics).find("none.json"), std::string::npos);
  throng_string_free(diagnostics);
  EXPECT_EQ(throng_world_insert_crowd_file(w.get(), nullptr, &index, nullptr), THRONG_ERROR_NULL_ARGUMENT);
}

TEST(CApi, EventsAreDrainedInOrderWithoutLossOrRepeats) {
  auto s = loadJson(corridor(5));
  auto w = makeWorld(s.get());
  std::size_t pending = 0;
  ASSERT_EQ(throng_world_pending_events(w.get(), &pending), THRONG_OK);
  EXPECT_EQ(pending, 5u);
  std::size_t n = 99;
  EXPECT_EQ(throng_world_events(w.get(), nullptr, 0, &n), THRONG_OK);
  EXPECT_EQ(n, 0u);
  EXPECT_EQ(throng_world_events(w.get(), nullptr, 3, &n), THRONG_ERROR_NULL_ARGUMENT);
  const auto spawns = drainEvents(w.get(), 2);
  ASSERT_EQ(spawns.size(), 5u);
  for (std::size_t i = 0; i < spawns.size(); ++i) {
    EXPECT_EQ(spawns[i].kind, THRONG_EVENT_SPAWN);
    EXPECT_EQ(spawns[i].agent, i);
    EXPECT_EQ(spawns[i].tick, 0u);
  }
  ASSERT_EQ(throng_world_pending_events(w.get(), &pending), THRONG_OK);
  EXPECT_EQ(pending, 0u);
  ASSERT_EQ(throng_world_run(w.get(), 30.0), THRONG_OK);
  const auto rest = drainEvents(w.get(), 3);
  std::set<uint32_t> exited;
  for (std::size_t i = 0; i < rest.size(); ++i) {
    if (i > 0) EXPECT_LE(rest[i - 1].tick, rest[i].tick) << "oldest first";
    EXPECT_NEAR(rest[i].time, static_cast<double>(rest[i].tick) * 0.05, 1e-5);
    if (rest[i].kind == THRONG_EVENT_EXIT) EXPECT_TRUE(exited.insert(rest[i].agent).second) << "no repeats";
  }
  EXPECT_EQ(exited.size(), 5u);
}

TEST(CApi, EventKindNamesAreTheRecordings) {
  EXPECT_STREQ(throng_event_kind_name(THRONG_EVENT_SPAWN), "spawn");
  EXPECT_STREQ(throng_event_kind_name(THRONG_EVENT_EXIT), "exit");
  EXPECT_STREQ(throng_event_kind_name(THRONG_EVENT_GUIDE_START), "guide_start");
  EXPECT_STREQ(throng_event_kind_name(THRONG_EVENT_REUNITED), "reunited");
  EXPECT_STREQ(throng_event_kind_name(THRONG_EVENT_EXIT_CHOSEN), "exit_chosen");
  EXPECT_STREQ(throng_event_kind_name(THRONG_EVENT_WAYPOINT_CHOSEN), "waypoint_chosen");
  EXPECT_STREQ(throng_event_kind_name(THRONG_EVENT_INCAPACITATED), "incapacitated");
  EXPECT_STREQ(throng_event_kind_name(THRONG_EVENT_INCAPACITATED + 1), "unknown");
  EXPECT_STREQ(throng_event_kind_name(0xffffffffu), "unknown");
}

int64_t countRows(const std::string& db, const std::string& sql) {
  const auto rows = e2e::queryText(db, sql);
  return rows.empty() ? -1 : std::stoll(rows[0][0]);
}

TEST(CApi, RecordingHoldsFrameZeroAndEveryStrideThTick) {
  test::TempDir dir("capi");
  const std::string path = dir.file("run.sqlite");
  auto s = loadJson(corridor(6, 4.0));
  auto w = makeWorld(s.get());
  EXPECT_EQ(throng_world_record_close(w.get(), nullptr), THRONG_ERROR_WRONG_STATE);
  EXPECT_EQ(throng_world_record(w.get(), path.c_str(), std::nan(""), 0), THRONG_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(throng_world_record(w.get(), path.c_str(), 0.0, 0), THRONG_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(throng_world_record(w.get(), nullptr, 10.0, 0), THRONG_ERROR_NULL_ARGUMENT);
  ASSERT_EQ(throng_world_record(w.get(), path.c_str(), 5.0, 0), THRONG_OK) << throng_last_error();  // every 4th tick
  EXPECT_EQ(throng_world_record(w.get(), path.c_str(), 5.0, 1), THRONG_ERROR_WRONG_STATE) << "already recording";
  EXPECT_EQ(stats(w.get()).recording, 1);
  ASSERT_EQ(throng_world_step(w.get(), 21, nullptr), THRONG_OK);
  readAgents(w.get());  // a look between recorded ticks takes nothing from the recording
  ASSERT_EQ(throng_world_run(w.get(), stats(w.get()).duration), THRONG_OK);
  EXPECT_EQ(stats(w.get()).tick, 80u);
  uint64_t frames = 0;
  ASSERT_EQ(throng_world_record_close(w.get(), &frames), THRONG_OK) << throng_last_error();
  EXPECT_EQ(frames, 21u) << "frame 0, then ticks 4, 8, ..., 80";
  EXPECT_EQ(stats(w.get()).recording, 0);
  EXPECT_EQ(countRows(path, "SELECT count(*) FROM frame_data"), 21);
  EXPECT_EQ(countRows(path, "SELECT count(DISTINCT frame) FROM trajectory_data"), 21);
  EXPECT_EQ(countRows(path, "SELECT max(tick) FROM throng_frames"), 80);
  EXPECT_EQ(countRows(path, "SELECT count(*) FROM throng_events WHERE kind = 'spawn'"), 6);
  EXPECT_EQ(e2e::queryText(path, "SELECT value FROM metadata WHERE key = 'throng_completed'")[0][0], "1");
  // Stepping goes on unrecorded; a world past tick 0 cannot start a recording.
  EXPECT_EQ(throng_world_step(w.get(), 1, nullptr), THRONG_OK);
  EXPECT_EQ(throng_world_record(w.get(), dir.file("late.sqlite").c_str(), 10.0, 0), THRONG_ERROR_WRONG_STATE);
}

TEST(CApi, ExistingRecordingIsKeptUnlessForced) {
  test::TempDir dir("capi");
  const std::string path = dir.file("keep.sqlite");
  std::ofstream(path) << "keep me";
  auto s = loadJson(corridor(2, 2.0));
  auto w = makeWorld(s.get());
  EXPECT_EQ(throng_world_record(w.get(), path.c_str(), 10.0, 0), THRONG_ERROR_INVALID_SCENARIO);
  EXPECT_NE(std::string(throng_last_error()).find("keep.sqlite"), std::string::npos) << throng_last_error();
  EXPECT_EQ(e2e::readFile(path), "keep me");
  ASSERT_EQ(throng_world_record(w.get(), path.c_str(), 10.0, 1), THRONG_OK) << throng_last_error();
  ASSERT_EQ(throng_world_run(w.get(), 2.0), THRONG_OK);
  w.reset();  // throng_world_free closes the recording, completed
  EXPECT_EQ(countRows(path, "SELECT count(*) FROM frame_data"), 21);
}

// One thread at a time per world: the others get THRONG_ERROR_BUSY, nothing is lost or torn.
TEST(CApi, ConcurrentCallsOnOneWorldAreRefusedNotRaced) {
  // Wanderers never leave, so the world cannot finish (WRONG_STATE) however few calls overlap.
  std::string json = corridor(30, 120);
  const std::string goals = "\"goals\": [\"exit\"]";
  json.replace(json.find(goals), goals.size(), "\"goals\": [], \"wander\": true");
  auto s = loadJson(json);
  auto w = makeWorld(s.get());
  std::atomic<uint64_t> stepped{0};
  std::atomic<int> busy{0};
  auto worker = [&] {
    for (int i = 0; i < 300; ++i) {
      uint64_t n = 0;
      const throng_status st = throng_world_step(w.get(), 1, &n);
      if (st == THRONG_OK) stepped += n;
      else if (st == THRONG_ERROR_BUSY) ++busy;
      else ADD_FAILURE() << throng_status_name(st);
    }
  };
  std::thread a(worker), b(worker);
  a.join();
  b.join();
  EXPECT_EQ(stats(w.get()).tick, stepped.load());
  EXPECT_EQ(stepped.load() + static_cast<uint64_t>(busy.load()), 600u);
}

}  // namespace
}  // namespace throng::capi_test
