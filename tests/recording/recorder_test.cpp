// Tests for throng::recording::Recorder (libs/recording/src/recorder.cpp, walkable_area_wkt.cpp): the file is
// read back with raw SQL exactly as PedPy and JuPedSim read it, plus throng's own tables, path
// checks, backpressure and a writer killed mid-run.
#include <gtest/gtest.h>
#include <sqlite3.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <boost/geometry.hpp>
#include <boost/geometry/geometries/multi_polygon.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <thread>
#include <vector>

#include "temp_dir.hpp"
#include "throng/core/simd.hpp"
#include "throng/recording/recorder.hpp"

namespace throng::recording {
namespace {

namespace fs = std::filesystem;

using throng::test::TempDir;

/// The bottleneck: a 20 m x 10 m room split by a wall at x = 9..10 with a 1 m gap at y = 4.5..5.5.
sim::ScenarioDesc bottleneck() {
  sim::ScenarioDesc s;
  s.name = "bottleneck";
  s.seed = 42;
  s.dt = 0.05f;
  s.walkable = {{{0, 0}, {20, 0}, {20, 10}, {0, 10}}};
  s.obstacles = {{{9, 0}, {10, 0}, {10, 4.5f}, {9, 4.5f}}, {{9, 5.5f}, {10, 5.5f}, {10, 10}, {9, 10}}};
  sim::PointDesc exit;
  exit.id = "exit";
  exit.kind = sim::PointKind::Exit;
  exit.polygon = {{19, 4}, {20, 4}, {20, 6}, {19, 6}};
  exit.position = {19.5f, 5};
  s.points.push_back(exit);
  for (const char* id : {"left", "late"}) {
    sim::PopulationDesc p;
    p.id = id;
    p.spawn.polygon = {{1, 1}, {8, 1}, {8, 9}, {1, 9}};
    p.goals = {0};
    s.populations.push_back(p);
  }
  return s;
}

/// n agents with ids 0..n-1 at x = frame + 0.25 id, y = 0.5 + id, heading +x.
sim::FramePtr makeFrame(std::uint64_t frame, std::uint32_t n, std::vector<sim::Event> events = {}) {
  auto f = std::make_shared<sim::Frame>();
  f->tick = frame * 2;
  f->time = static_cast<double>(frame) * 0.1;
  for (std::uint32_t id = 0; id < n; ++id) {
    f->ids.push_back(id);
    f->posX.push_back(static_cast<float>(frame) + 0.25f * static_cast<float>(id));
    f->posY.push_back(0.5f + static_cast<float>(id));
    f->velX.push_back(1.0f);
    f->velY.push_back(0.0f);
    f->oriX.push_back(1.0f);
    f->oriY.push_back(0.0f);
    f->mode.push_back(sim::AgentMode::Walking);
  }
  f->events = std::move(events);
  return f;
}

RecordingOptions optionsFor(const std::string& path) {
  RecordingOptions o;
  o.path = path;
  o.fps = 10.0;
  o.seed = 42;
  o.scenarioText = R"({"format":"throng/1","name":"bottleneck"})";
  o.framesPerBatch = 3;
  o.queueFrames = 4;
  return o;
}

/// Minimal read-only SQL access for the checks below.
class Db {
 public:
  explicit Db(const std::string& path, bool writable = false) {
    EXPECT_EQ(sqlite3_open_v2(path.c_str(), &db_, writable ? SQLITE_OPEN_READWRITE : SQLITE_OPEN_READONLY, nullptr),
              SQLITE_OK);
  }
  ~Db() { sqlite3_close(db_); }
  /// Every row of a query, each column as text ("NULL" for null).
  std::vector<std::vector<std::string>> rows(const std::string& sql) {
    std::vector<std::vector<std::string>> out;
    sqlite3_stmt* s = nullptr;
    if (sqlite3_prepare_v2(db_, sql.c_str(), -1, &s, nullptr) != SQLITE_OK) {
      ADD_FAILURE() << sql << ": " << sqlite3_errmsg(db_);
      return out;
    }
    while (sqlite3_step(s) == SQLITE_ROW) {
      std::vector<std::string> row;
      for (int c = 0; c < sqlite3_column_count(s); ++c) {
        const auto* t = sqlite3_column_text(s, c);
        row.emplace_back(t ? reinterpret_cast<const char*>(t) : "NULL");
      }
      out.push_back(std::move(row));
    }
    sqlite3_finalize(s);
    return out;
  }
  std::string one(const std::string& sql) {
    auto r = rows(sql);
    return r.empty() || r[0].empty() ? std::string("<none>") : r[0][0];
  }
  sqlite3* get() { return db_; }

 private:
  sqlite3* db_ = nullptr;
};

std::unique_ptr<Recorder> openOk(const sim::ScenarioDesc& s, const RecordingOptions& o) {
  auto r = Recorder::open(s, o);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : core::formatAll(r.errors()));
  return r.ok() ? std::move(r).value() : nullptr;
}

TEST(Recorder, TrajectoryRoundTripsThroughPedPysQueries) {
  TempDir dir;
  const std::string path = dir.file("out.sqlite");
  auto rec = openOk(bottleneck(), optionsFor(path));
  ASSERT_NE(rec, nullptr);
  for (std::uint64_t f = 0; f < 7; ++f) rec->push(makeFrame(f, 3));
  ASSERT_TRUE(rec->close(true).ok());
  EXPECT_EQ(rec->framesWritten(), 7u);

  Db db(path);
  // pedpy.load_trajectory_from_jupedsim_sqlite runs exactly these two queries.
  const auto rows = db.rows("select frame, id, pos_x as x, pos_y as y from trajectory_data");
  ASSERT_EQ(rows.size(), 21u);
  std::size_t i = 0;
  for (std::uint64_t f = 0; f < 7; ++f) {
    for (std::uint32_t id = 0; id < 3; ++id, ++i) {
      EXPECT_EQ(std::stoull(rows[i][0]), f);
      EXPECT_EQ(std::stoul(rows[i][1]), id);
      EXPECT_EQ(static_cast<float>(std::stod(rows[i][2])), static_cast<float>(f) + 0.25f * static_cast<float>(id));
      EXPECT_EQ(static_cast<float>(std::stod(rows[i][3])), 0.5f + static_cast<float>(id));
    }
  }
  EXPECT_EQ(db.one("select value from metadata where key = 'fps'"), "10.0");
  EXPECT_EQ(std::stod(db.one("select value from metadata where key = 'fps'")), 10.0);
  EXPECT_EQ(db.one("SELECT value FROM metadata WHERE key = 'version'"), "2");
  EXPECT_EQ(db.one("SELECT typeof(value) FROM metadata WHERE key = 'fps'"), "text");
  EXPECT_EQ(db.one("SELECT count(*) FROM trajectory_data WHERE ori_x = 1.0 AND ori_y = 0.0"), "21");
  EXPECT_EQ(db.one("SELECT typeof(frame) || typeof(id) || typeof(pos_x) FROM trajectory_data LIMIT 1"),
            "integerintegerreal");
}

TEST(Recorder, SchemaMatchesJuPedSimVersion2) {
  TempDir dir;
  const std::string path = dir.file("out.sqlite");
  auto rec = openOk(bottleneck(), optionsFor(path));
  ASSERT_NE(rec, nullptr);
  ASSERT_TRUE(rec->close(true).ok());
  Db db(path);
  // PRAGMA table_info: name, type, notnull.
  const auto cols = db.rows("SELECT name, type, \"notnull\" FROM pragma_table_info('trajectory_data')");
  const std::vector<std::vector<std::string>> want = {{"frame", "INTEGER", "1"}, {"id", "INTEGER", "1"},
                                                      {"pos_x", "REAL", "1"},    {"pos_y", "REAL", "1"},
                                                      {"ori_x", "REAL", "1"},    {"ori_y", "REAL", "1"}};
  EXPECT_EQ(cols, want);
  EXPECT_EQ(db.rows("SELECT name, type, pk FROM pragma_table_info('metadata')"),
            (std::vector<std::vector<std::string>>{{"key", "TEXT", "1"}, {"value", "TEXT", "0"}}));
  EXPECT_EQ(db.rows("SELECT name, type FROM pragma_table_info('geometry')"),
            (std::vector<std::vector<std::string>>{{"hash", "INTEGER"}, {"wkt", "TEXT"}}));
  EXPECT_EQ(db.rows("SELECT name, type FROM pragma_table_info('frame_data')"),
            (std::vector<std::vector<std::string>>{{"frame", "INTEGER"}, {"geometry_hash", "INTEGER"}}));
  EXPECT_EQ(db.one("SELECT tbl_name FROM sqlite_master WHERE type = 'index' AND name = 'frame_id_idx'"),
            "trajectory_data");
  EXPECT_EQ(db.one("SELECT \"unique\" FROM pragma_index_list('geometry') WHERE name = 'geometry_hash'"), "1");
  // JuPedSim's viewer reads the bounds from metadata.
  EXPECT_EQ(db.one("SELECT value FROM metadata WHERE key = 'xmin'"), "0.0");
  EXPECT_EQ(db.one("SELECT value FROM metadata WHERE key = 'xmax'"), "20.0");
  EXPECT_EQ(db.one("SELECT value FROM metadata WHERE key = 'ymax'"), "10.0");
  // A closed recording is one self-contained file in rollback-journal mode.
  EXPECT_EQ(db.one("PRAGMA journal_mode"), "delete");
  EXPECT_FALSE(fs::exists(path + "-wal"));
  EXPECT_FALSE(fs::exists(path + "-shm"));
}

// Issue 17: the recording says which avoidance model (and values) produced it, also for a
// population that named none; ids are JSON-escaped.
TEST(Recorder, MetadataNamesEachPopulationsModelWithItsValues) {
  TempDir dir;
  const std::string path = dir.file("models.sqlite");
  sim::ScenarioDesc s = bottleneck();
  s.populations[1].id = "late \"quoted\"";
  s.populations[1].model = sim::ModelDesc(sim::ModelKind::Orca);
  ASSERT_TRUE(s.populations[1].model.set("yieldResponsibility", 0.6f));
  auto rec = openOk(s, optionsFor(path));
  ASSERT_NE(rec, nullptr);
  ASSERT_TRUE(rec->close(true).ok());
  Db db(path);
  EXPECT_EQ(db.one("SELECT value FROM metadata WHERE key = 'throng_models'"),
            "{\"left\": {\"name\": \"avm\", \"timeGap\": 0.9, \"anticipationTime\": 0.5, \"reactionTime\": 0.1, "
            "\"neighbourStrength\": 4, \"neighbourRange\": 0.1, \"wallStrength\": 5, \"wallRange\": 0.02, \"passageRatio\": 0.65, \"visionRange\": 20, "
            "\"separationPasses\": 2, \"noPressing\": 1, \"overtakeDensity\": 1.3}, "
            "\"late \\\"quoted\\\"\": {\"name\": \"orca\", \"yieldResponsibility\": 0.6, \"lodNeighbours\": 4, \"wallMargin\": 0.01}}");
}

// Issue 22: the recording names the SIMD path that wrote it (throng_simd), and the summary reads it.
TEST(Recorder, MetadataNamesTheSimdPath) {
  TempDir dir;
  const core::SimdPath before = core::simdPath();
  for (core::SimdPath path : {core::SimdPath::Portable, core::SimdPath::Avx2}) {
    if (!core::setSimdPath(path)) continue;  // a CPU without AVX2 runs only the portable path
    const std::string file = dir.file(std::string(core::simdPathName(path)) + ".sqlite");
    auto rec = openOk(bottleneck(), optionsFor(file));
    ASSERT_NE(rec, nullptr);
    ASSERT_TRUE(rec->close(true).ok());
    Db db(file);
    EXPECT_EQ(db.one("SELECT value FROM metadata WHERE key = 'throng_simd'"), core::simdPathName(path));
    const auto summary = readRecordingSummary(file);
    ASSERT_TRUE(summary.ok()) << core::formatAll(summary.errors());
    EXPECT_EQ(summary->simd, core::simdPathName(path));
  }
  core::setSimdPath(before);
}

// Issue 20: a world read from a glTF file is named in the recording (a replay serves its materials
// when it finds the file again); a scenario JSON's recording has no such key.
TEST(Recorder, MetadataNamesTheGltfWorldFileOnlyWhenGiven) {
  TempDir dir;
  const std::string named = dir.file("hall.sqlite"), plain = dir.file("plain.sqlite");
  RecordingOptions o = optionsFor(named);
  o.worldFile = "tiled_hall.gltf";
  auto rec = openOk(bottleneck(), o);
  ASSERT_NE(rec, nullptr);
  ASSERT_TRUE(rec->close(true).ok());
  EXPECT_EQ(Db(named).one("SELECT value FROM metadata WHERE key = 'throng_world_file'"), "tiled_hall.gltf");
  auto other = openOk(bottleneck(), optionsFor(plain));
  ASSERT_NE(other, nullptr);
  ASSERT_TRUE(other->close(true).ok());
  EXPECT_EQ(Db(plain).one("SELECT count(*) FROM metadata WHERE key = 'throng_world_file'"), "0");
}

namespace bg = boost::geometry;
using BPoint = bg::model::d2::point_xy<double>;
using BMulti = bg::model::multi_polygon<bg::model::polygon<BPoint, false>>;

BMulti walkableOf(const sim::ScenarioDesc& scenario, std::string* wktOut = nullptr) {
  TempDir dir;
  const std::string path = dir.file("geo.sqlite");
  auto rec = openOk(scenario, optionsFor(path));
  BMulti multi;
  if (!rec) return multi;
  rec->push(makeFrame(0, 1));
  rec->push(makeFrame(1, 1));
  EXPECT_TRUE(rec->close(true).ok());
  Db db(path);
  const std::string wkt = db.one("SELECT wkt FROM geometry");
  if (wktOut) *wktOut = wkt;
  // One geometry, and one frame_data row per frame pointing at it (as JuPedSim v2 writes).
  EXPECT_EQ(db.one("SELECT count(*) FROM geometry"), "1");
  EXPECT_EQ(db.one("SELECT count(*) FROM frame_data f JOIN geometry g ON f.geometry_hash = g.hash"), "2");
  EXPECT_EQ(db.one("SELECT group_concat(frame) FROM frame_data"), "0,1");
  if (wkt.rfind("MULTIPOLYGON", 0) == 0) {
    bg::read_wkt(wkt, multi);
  } else {
    bg::model::polygon<BPoint, false> poly;
    bg::read_wkt(wkt, poly);
    multi.push_back(poly);
  }
  return multi;
}

TEST(Recorder, GeometryIsWalkableAreaMinusObstacles) {
  std::string wkt;
  const BMulti area = walkableOf(bottleneck(), &wkt);
  EXPECT_EQ(wkt.rfind("POLYGON ((", 0), 0u) << wkt;
  ASSERT_EQ(area.size(), 1u);
  EXPECT_TRUE(bg::is_valid(area)) << wkt;
  EXPECT_NEAR(bg::area(area), 191.0, 1e-9) << wkt;
  EXPECT_TRUE(bg::within(BPoint(9.5, 5.0), area));   // the gap
  EXPECT_FALSE(bg::within(BPoint(9.5, 2.0), area));  // inside a block
}

TEST(Recorder, ObstaclesCrossingTheBoundaryAndInnerHoles) {
  sim::ScenarioDesc s = bottleneck();
  // The lower block now sticks out below the room; a pillar makes a hole; a second walkable
  // polygon overlaps the first.
  s.obstacles[0] = {{9, -1}, {10, -1}, {10, 4.5f}, {9, 4.5f}};
  s.obstacles.push_back({{2, 2}, {3, 2}, {3, 3}, {2, 3}});
  s.walkable.push_back({{19, 4}, {25, 4}, {25, 6}, {19, 6}});
  std::string wkt;
  const BMulti area = walkableOf(s, &wkt);
  ASSERT_EQ(area.size(), 1u) << wkt;
  EXPECT_TRUE(bg::is_valid(area)) << wkt;
  EXPECT_NEAR(bg::area(area), 191.0 - 1.0 + 5.0 * 2.0, 1e-9) << wkt;
  EXPECT_EQ(area[0].inners().size(), 1u) << wkt;
}

TEST(Recorder, DisconnectedAreaIsAMultiPolygon) {
  sim::ScenarioDesc s = bottleneck();
  s.obstacles = {{{9, -1}, {10, -1}, {10, 11}, {9, 11}}};
  std::string wkt;
  const BMulti area = walkableOf(s, &wkt);
  EXPECT_EQ(wkt.rfind("MULTIPOLYGON (((", 0), 0u) << wkt;
  EXPECT_EQ(area.size(), 2u);
  EXPECT_TRUE(bg::is_valid(area)) << wkt;
  EXPECT_NEAR(bg::area(area), 190.0, 1e-9);
}

TEST(Recorder, ThrongTablesHoldAgentsEventsPointsAndProvenance) {
  TempDir dir;
  const std::string path = dir.file("out.sqlite");
  auto rec = openOk(bottleneck(), optionsFor(path));
  ASSERT_NE(rec, nullptr);
  using sim::EventKind;
  rec->push(makeFrame(0, 2, {{0, 0, EventKind::Spawn, 0, 7}, {0, 1, EventKind::Spawn, 1, 8}}));
  rec->push(makeFrame(1, 2, {{2, 0, EventKind::GoalReached, 0, 0}}));
  rec->push(makeFrame(2, 1, {{4, 1, EventKind::Exit, 0, 0}}));
  ASSERT_TRUE(rec->close(true).ok());
  Db db(path);
  EXPECT_EQ(db.rows("SELECT id, population, population_id, group_id, spawn_frame, exit_frame, exit_tick "
                    "FROM throng_agents ORDER BY id"),
            (std::vector<std::vector<std::string>>{{"0", "0", "left", "7", "0", "NULL", "NULL"},
                                                   {"1", "1", "late", "8", "0", "2", "4"}}));
  EXPECT_EQ(db.rows("SELECT frame, tick, agent, kind, a, b FROM throng_events ORDER BY rowid"),
            (std::vector<std::vector<std::string>>{{"0", "0", "0", "spawn", "0", "7"},
                                                   {"0", "0", "1", "spawn", "1", "8"},
                                                   {"1", "2", "0", "goal_reached", "0", "0"},
                                                   {"2", "4", "1", "exit", "0", "0"}}));
  EXPECT_EQ(db.rows("SELECT frame, tick, agents FROM throng_frames ORDER BY frame"),
            (std::vector<std::vector<std::string>>{{"0", "0", "2"}, {"1", "2", "2"}, {"2", "4", "1"}}));
  EXPECT_EQ(db.one("SELECT id || ' ' || kind || ' ' || wkt FROM throng_points"),
            "exit exit POLYGON ((19 4, 20 4, 20 6, 19 6, 19 4))");
  EXPECT_EQ(db.one("SELECT goals FROM throng_populations WHERE id = 'left'"), "[\"exit\"]");
  EXPECT_EQ(db.one("SELECT value FROM metadata WHERE key = 'throng_scenario'"),
            R"({"format":"throng/1","name":"bottleneck"})");
  EXPECT_EQ(db.one("SELECT value FROM metadata WHERE key = 'throng_scenario_name'"), "bottleneck");
  EXPECT_EQ(db.one("SELECT value FROM metadata WHERE key = 'throng_seed'"), "42");
  EXPECT_EQ(db.one("SELECT value FROM metadata WHERE key = 'throng_dt'"), "0.05");
  EXPECT_EQ(db.one("SELECT value FROM metadata WHERE key = 'throng_completed'"), "1");
  EXPECT_EQ(db.one("SELECT value FROM metadata WHERE key = 'throng_frames'"), "3");
  EXPECT_NE(db.one("SELECT value FROM metadata WHERE key = 'throng_version'"), "<none>");
}

TEST(Recorder, TacticalChoiceEventsAreWrittenByTheirNames) {
  // Exit choice (a = exit, b = the one before) and waypoint choice (a = point, b = goal slot).
  TempDir dir;
  const std::string path = dir.file("out.sqlite");
  auto rec = openOk(bottleneck(), optionsFor(path));
  ASSERT_NE(rec, nullptr);
  using sim::EventKind;
  rec->push(makeFrame(0, 2, {{0, 0, EventKind::ExitChosen, 0, 0xffffffffu}, {0, 1, EventKind::WaypointChosen, 0, 1}}));
  ASSERT_TRUE(rec->close(true).ok());
  Db db(path);
  EXPECT_EQ(db.rows("SELECT frame, tick, agent, kind, a, b FROM throng_events ORDER BY rowid"),
            (std::vector<std::vector<std::string>>{{"0", "0", "0", "exit_chosen", "0", "4294967295"},
                                                   {"0", "0", "1", "waypoint_chosen", "0", "1"}}));
  EXPECT_STREQ(eventKindName(EventKind::WaypointChosen), "waypoint_chosen");
}

TEST(Recorder, ExistingFileIsNotOverwrittenWithoutForce) {
  TempDir dir;
  const std::string path = dir.file("out.sqlite");
  { std::ofstream(path) << "precious"; }
  auto r = Recorder::open(bottleneck(), optionsFor(path));
  ASSERT_FALSE(r.ok());
  ASSERT_EQ(r.errors().size(), 1u);
  const core::Diagnostic& d = r.errors()[0];
  EXPECT_EQ(d.source, path);
  EXPECT_EQ(d.what, "file exists");
  EXPECT_EQ(d.expected, "a new path");
  EXPECT_EQ(d.hint, "pass --force to overwrite");
  EXPECT_EQ(d.format(), path + ": file exists; expected a new path (pass --force to overwrite)");
  std::ifstream in(path);
  std::string content;
  std::getline(in, content);
  EXPECT_EQ(content, "precious");
}

TEST(Recorder, ForceReplacesTheFileAndItsCompanions) {
  TempDir dir;
  const std::string path = dir.file("out.sqlite");
  { std::ofstream(path) << "old"; }
  { std::ofstream(path + "-wal") << "stale wal"; }
  { std::ofstream(path + "-shm") << "stale shm"; }
  RecordingOptions o = optionsFor(path);
  o.force = true;
  auto rec = openOk(bottleneck(), o);
  ASSERT_NE(rec, nullptr);
  rec->push(makeFrame(0, 2));
  ASSERT_TRUE(rec->close(true).ok());
  EXPECT_FALSE(fs::exists(path + "-wal"));
  Db db(path);
  EXPECT_EQ(db.one("SELECT count(*) FROM trajectory_data"), "2");
}

TEST(Recorder, MissingOrUnwritableDirectoryIsReportedUpFront) {
  TempDir dir;
  {
    auto r = Recorder::open(bottleneck(), optionsFor(dir.file("no/such/dir/out.sqlite")));
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.errors()[0].what.find("does not exist"), std::string::npos) << core::formatAll(r.errors());
    EXPECT_FALSE(fs::exists(dir.file("no")));
  }
  {
    { std::ofstream(dir.file("plain")) << "x"; }
    auto r = Recorder::open(bottleneck(), optionsFor(dir.file("plain/out.sqlite")));
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.errors()[0].what.find("not a directory"), std::string::npos) << core::formatAll(r.errors());
  }
  {
    auto r = Recorder::open(bottleneck(), optionsFor(dir.path()));
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.errors()[0].what, "is a directory");
  }
  if (::geteuid() != 0) {  // root writes anywhere: only a non-root run can test permissions
    const std::string ro = dir.file("readonly");
    fs::create_directory(ro);
    fs::permissions(ro, fs::perms::owner_read | fs::perms::owner_exec);
    auto r = Recorder::open(bottleneck(), optionsFor(ro + "/out.sqlite"));
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.errors()[0].what.find("not writable"), std::string::npos) << core::formatAll(r.errors());
    fs::permissions(ro, fs::perms::owner_all);
  }
}

TEST(Recorder, BadOptionsAreAllReported) {
  TempDir dir;
  RecordingOptions o = optionsFor(dir.file("out.sqlite"));
  o.fps = 0.0;
  o.framesPerBatch = 0;
  o.queueFrames = 0;
  auto r = Recorder::open(bottleneck(), o);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.errors().size(), 3u) << core::formatAll(r.errors());
  EXPECT_FALSE(fs::exists(o.path));
}

TEST(Recorder, TinyQueueLosesNothing) {
  TempDir dir;
  const std::string path = dir.file("out.sqlite");
  RecordingOptions o = optionsFor(path);
  o.queueFrames = 1;
  o.framesPerBatch = 7;
  auto rec = openOk(bottleneck(), o);
  ASSERT_NE(rec, nullptr);
  constexpr std::uint64_t kFrames = 500;
  for (std::uint64_t f = 0; f < kFrames; ++f) rec->push(makeFrame(f, 5));
  ASSERT_TRUE(rec->close(true).ok());
  EXPECT_EQ(rec->framesWritten(), kFrames);
  Db db(path);
  EXPECT_EQ(db.one("SELECT count(*) FROM trajectory_data"), std::to_string(kFrames * 5));
  EXPECT_EQ(db.one("SELECT count(DISTINCT frame) FROM trajectory_data"), std::to_string(kFrames));
  EXPECT_EQ(db.one("SELECT max(frame) FROM frame_data"), std::to_string(kFrames - 1));
  // Frames keep push order: frame k holds the positions of the k-th pushed frame.
  EXPECT_EQ(db.one("SELECT count(*) FROM trajectory_data WHERE pos_x <> frame + 0.25 * id"), "0");
}

TEST(Recorder, InterruptedRunIsMarkedIncomplete) {
  TempDir dir;
  const std::string path = dir.file("out.sqlite");
  auto rec = openOk(bottleneck(), optionsFor(path));
  ASSERT_NE(rec, nullptr);
  rec->push(makeFrame(0, 1));
  ASSERT_TRUE(rec->close(false).ok());
  ASSERT_TRUE(rec->close(false).ok());  // idempotent
  rec->push(makeFrame(1, 1));           // ignored after close
  Db db(path);
  EXPECT_EQ(db.one("SELECT value FROM metadata WHERE key = 'throng_completed'"), "0");
  EXPECT_EQ(db.one("SELECT count(*) FROM trajectory_data"), "1");
}

TEST(Recorder, NonFinitePositionIsAWriteError) {
  TempDir dir;
  const std::string path = dir.file("out.sqlite");
  auto rec = openOk(bottleneck(), optionsFor(path));
  ASSERT_NE(rec, nullptr);
  auto bad = std::make_shared<sim::Frame>(*makeFrame(0, 2));
  bad->posX[1] = std::nanf("");
  rec->push(bad);
  for (std::uint64_t f = 1; f < 20; ++f) rec->push(makeFrame(f, 2));  // must not block
  const core::Status st = rec->close(true);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.errors()[0].what.find("not finite"), std::string::npos) << core::formatAll(st.errors());
  Db db(path);  // still a valid file, marked incomplete
  EXPECT_EQ(db.one("SELECT value FROM metadata WHERE key = 'throng_completed'"), "0");
}

TEST(Recorder, FailedIsSaidAtTheFirstWriteErrorNotOnlyAtClose) {
  // The app polls failed() to stop simulating at once (throng run); frames pushed after it are dropped.
  TempDir dir;
  const std::string path = dir.file("out.sqlite");
  RecordingOptions options = optionsFor(path);
  options.framesPerBatch = 2;
  auto rec = openOk(bottleneck(), options);
  ASSERT_NE(rec, nullptr);
  for (std::uint64_t f = 0; f < 4; ++f) rec->push(makeFrame(f, 2));  // two batches committed
  EXPECT_FALSE(rec->failed());
  auto bad = std::make_shared<sim::Frame>(*makeFrame(4, 2));
  bad->posY[0] = std::numeric_limits<float>::infinity();
  rec->push(bad);
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (!rec->failed() && std::chrono::steady_clock::now() < until) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_TRUE(rec->failed()) << "failed() must turn true without close()";
  EXPECT_EQ(rec->framesWritten(), 4u);
  for (std::uint64_t f = 5; f < 9; ++f) rec->push(makeFrame(f, 2));  // dropped, never blocks
  const core::Status st = rec->close(false);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.errors()[0].what.find("frame 4 agent 0: position or orientation is not finite"), std::string::npos)
      << core::formatAll(st.errors());
  EXPECT_FALSE(fs::exists(path + "-wal"));
  Db db(path);
  EXPECT_EQ(db.one("SELECT count(*) FROM throng_frames"), "4");
  EXPECT_EQ(db.one("SELECT value FROM metadata WHERE key = 'throng_completed'"), "0");
}

TEST(Recorder, KilledWriterLeavesEverythingUpToTheLastCommittedBatch) {
  TempDir dir;
  const std::string path = dir.file("killed.sqlite");
  constexpr std::uint64_t kCommitted = 9;  // three batches of 3
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    auto r = Recorder::open(bottleneck(), optionsFor(path));
    if (!r.ok()) ::_exit(3);
    std::unique_ptr<Recorder> rec = std::move(r).value();
    for (std::uint64_t f = 0; f < kCommitted + 2; ++f) rec->push(makeFrame(f, 4));
    for (int i = 0; i < 5000 && rec->framesWritten() < kCommitted; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    ::kill(::getpid(), SIGKILL);  // no close, no destructors
    ::_exit(4);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status)) << "child exited with " << WEXITSTATUS(status);
  EXPECT_EQ(WTERMSIG(status), SIGKILL);

  const auto summary = readRecordingSummary(path);
  ASSERT_TRUE(summary.ok()) << core::formatAll(summary.errors());
  EXPECT_EQ(summary->formatVersion, 2);
  EXPECT_GE(summary->frames, kCommitted);
  EXPECT_EQ(summary->rows, summary->frames * 4);
  EXPECT_FALSE(summary->completed);
  // Any SQLite client (here a read-write one, as PedPy's) sees the same committed frames.
  Db db(path, /*writable=*/true);
  EXPECT_EQ(db.one("SELECT count(DISTINCT frame) FROM trajectory_data"), std::to_string(summary->frames));
  EXPECT_EQ(db.one("PRAGMA integrity_check"), "ok");
  // The frame indexes are kept row by row from the start: a killed run has them too.
  EXPECT_EQ(db.one("SELECT count(*) FROM sqlite_master WHERE type = 'index' AND name IN ('frame_id_idx', 'throng_animation_idx')"), "2");
}

}  // namespace
}  // namespace throng::recording
