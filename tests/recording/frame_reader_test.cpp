// Tests for libs/recording/src/frame_reader.cpp (readRecordedFrames) on hand-made SQLite files:
// positions, unit headings, ticks and times from throng_frames, heights, recorded clips and phases,
// the clips and phases derived when a file has none, duplicate and stray rows, and every refusal
// (with the file named).
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "temp_dir.hpp"
#include "throng/recording/frame_reader.hpp"

namespace throng::recording {
namespace {

using throng::test::TempDir;

/// Creates an SQLite file from `sql`; ADD_FAILURE on a bad statement.
std::string makeDb(const TempDir& dir, const std::string& name, const std::string& sql) {
  const std::string path = dir.path() + "/" + name;
  sqlite3* db = nullptr;
  EXPECT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  char* err = nullptr;
  if (sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &err) != SQLITE_OK) ADD_FAILURE() << (err ? err : "?") << "\n" << sql;
  sqlite3_free(err);
  sqlite3_close(db);
  return path;
}

/// JuPedSim's two tables, the stored scenario and fps = 10.
const std::string kBase =
    "CREATE TABLE trajectory_data(frame INTEGER, id INTEGER, pos_x REAL, pos_y REAL, ori_x REAL, ori_y REAL);"
    "CREATE TABLE metadata(key TEXT, value TEXT);"
    "INSERT INTO metadata VALUES('fps', ' 10 '), ('throng_scenario', '{\"name\": \"t\"}');";

std::string failure(const core::Result<RecordedFrames>& r) {
  return r.ok() ? std::string() : core::formatAll(r.errors());
}

TEST(FrameReader, PositionsHeadingsTicksAndTimes) {
  TempDir dir;
  const std::string path = makeDb(dir, "a.sqlite", kBase +
      "CREATE TABLE throng_frames(frame INTEGER, tick INTEGER, time REAL, agents INTEGER);"
      "INSERT INTO throng_frames VALUES(0, 4, 0.2000000030, 2), (1, 6, 0.3000000045, 2), (2, 8, 0.4, 1);"
      // Out of order on purpose; agent 7's heading is not a unit vector, agent 3's is zero.
      "INSERT INTO trajectory_data VALUES(1, 7, 1.5, 2.0, 0, 1), (0, 7, 1.0, 2.0, 3, 4), (0, 3, -1.0, 0.5, 0, 0),"
      "  (0, 3, 9.0, 9.0, 1, 0), (1, 3, -1.0, 0.5, 1, 0), (2, 3, -1.0, 0.5, 1, 0), (5, 99, 0, 0, 1, 0);");
  const auto r = readRecordedFrames(path);
  ASSERT_TRUE(r.ok()) << failure(r);
  EXPECT_EQ(r->scenarioText, "{\"name\": \"t\"}");
  EXPECT_DOUBLE_EQ(r->fps, 10.0);
  // Frames 0..5: frame 5 holds agent 99, frames 3 and 4 are empty and timed frame / fps.
  ASSERT_EQ(r->frames.size(), 6u);
  ASSERT_EQ(r->times.size(), 6u);
  EXPECT_DOUBLE_EQ(r->times[0], 0.0);
  EXPECT_NEAR(r->times[1], 0.1, 1e-12);  // rounded to the microsecond, relative to frame 0
  EXPECT_NEAR(r->times[2], 0.2, 1e-12);
  EXPECT_NEAR(r->times[3], 0.2, 1e-12);  // 0.3 - 0.2 = 0.1, raised to stay non-decreasing
  EXPECT_NEAR(r->times[5], 0.3, 1e-12);
  const sim::Frame& f0 = *r->frames[0];
  EXPECT_EQ(f0.tick, 4u);
  EXPECT_EQ(f0.ids, (std::vector<std::uint32_t>{3, 7}));
  EXPECT_FLOAT_EQ(f0.posX[0], -1.0f);  // the duplicate row of agent 3 is skipped
  EXPECT_FLOAT_EQ(f0.oriX[0], 1.0f);   // zero heading → +x
  EXPECT_FLOAT_EQ(f0.oriX[1], 0.6f);   // (3, 4) normalised
  EXPECT_FLOAT_EQ(f0.oriY[1], 0.8f);
  EXPECT_TRUE(f0.velX.empty());
  EXPECT_TRUE(f0.posZ.empty());  // no throng_heights: a flat world
  EXPECT_EQ(r->frames[1]->tick, 6u);
  EXPECT_EQ(r->frames[4]->tick, 4u);  // not listed: its frame number
  EXPECT_TRUE(r->frames[4]->ids.empty());
  EXPECT_NEAR(r->frames[5]->time, r->times[5], 0.0);
}

TEST(FrameReader, DerivesWalkAndIdleWhenTheFileHasNoAnimation) {
  TempDir dir;
  // Agent 1 walks 0.35 m per frame (3.5 m/s); agent 2 moves 0.005 m per frame (0.05 m/s: standing).
  const std::string path = makeDb(dir, "b.sqlite", kBase +
      "INSERT INTO trajectory_data VALUES(0, 1, 0, 0, 1, 0), (1, 1, 0.35, 0, 1, 0), (2, 1, 0.7, 0, 1, 0),"
      "  (0, 2, 5, 5, 1, 0), (1, 2, 5.005, 5, 1, 0), (2, 2, 5.01, 5, 1, 0);");
  const auto r = readRecordedFrames(path);
  ASSERT_TRUE(r.ok()) << failure(r);
  EXPECT_FALSE(r->hasAnimation);
  const sim::Frame& f0 = *r->frames[0];
  const sim::Frame& f1 = *r->frames[1];
  const sim::Frame& f2 = *r->frames[2];
  // The first frame: nothing before it, so idle at phase 0.
  EXPECT_EQ(f0.clip[0], sim::kClipIdle);
  EXPECT_FLOAT_EQ(f0.phase[0], 0.0f);
  EXPECT_EQ(f0.mode[0], sim::AgentMode::Waiting);
  // Walking: a quarter cycle (0.35 m of kWalkCycle = 1.4 m) per frame.
  EXPECT_EQ(f1.clip[0], sim::kClipWalk);
  EXPECT_EQ(f1.mode[0], sim::AgentMode::Walking);
  EXPECT_NEAR(f1.phase[0], 0.25, 1e-6);
  EXPECT_NEAR(f2.phase[0], 0.5, 1e-6);
  // Standing: the idle phase advances with time, 0.1 s of kIdleCycle = 2 s per frame.
  EXPECT_EQ(f1.clip[1], sim::kClipIdle);
  EXPECT_NEAR(f1.phase[1], 0.1 / kIdleCycle, 1e-6);
  EXPECT_NEAR(f2.phase[1], 0.2 / kIdleCycle, 1e-6);
}

TEST(FrameReader, RecordedClipsPhasesAndHeights) {
  TempDir dir;
  const std::string path = makeDb(dir, "c.sqlite", kBase +
      "CREATE TABLE throng_animation(frame INTEGER, id INTEGER, clip INTEGER, phase REAL);"
      "CREATE TABLE throng_heights(frame INTEGER, id INTEGER, z REAL);"
      "INSERT INTO trajectory_data VALUES(0, 1, 0, 0, 1, 0), (0, 2, 1, 0, 1, 0), (1, 1, 0, 0, 1, 0);"
      // Agent 2 plays action clip 4 at phase 1.25 (wraps to 0.25); a stray row for agent 9 and a
      // negative clip are skipped; agent 1 in frame 1 has no row: derived (idle).
      "INSERT INTO throng_animation VALUES(0, 1, 1, 0.5), (0, 2, 4, 1.25), (0, 9, 1, 0.5), (1, 1, -3, 0.5);"
      "INSERT INTO throng_heights VALUES(0, 1, 3.0), (0, 2, 'nan'), (1, 1, 3.5), (1, 9, 7.0);");
  const auto r = readRecordedFrames(path);
  ASSERT_TRUE(r.ok()) << failure(r);
  EXPECT_TRUE(r->hasAnimation);
  const sim::Frame& f0 = *r->frames[0];
  EXPECT_EQ(f0.clip, (std::vector<std::uint16_t>{1, 4}));
  EXPECT_FLOAT_EQ(f0.phase[0], 0.5f);
  EXPECT_FLOAT_EQ(f0.phase[1], 0.25f);
  EXPECT_EQ(f0.mode[1], sim::AgentMode::Acting);
  EXPECT_EQ(f0.posZ, (std::vector<float>{3.0f, 0.0f}));  // text z reads as 0
  const sim::Frame& f1 = *r->frames[1];
  EXPECT_EQ(f1.clip[0], sim::kClipIdle);
  EXPECT_EQ(f1.posZ, (std::vector<float>{3.5f}));
}

TEST(FrameReader, RefusalsNameTheFileAndWhatWasWrong) {
  TempDir dir;
  auto expectError = [](const std::string& path, const std::string& what, const FrameReadOptions& options = {}) {
    const auto r = readRecordedFrames(path, options);
    ASSERT_FALSE(r.ok()) << path;
    ASSERT_EQ(r.errors().size(), 1u);
    const core::Diagnostic& d = r.errors().front();
    EXPECT_EQ(d.source, path);
    EXPECT_NE(d.what.find(what), std::string::npos) << d.format();
    EXPECT_FALSE(d.expected.empty()) << d.format();
  };
  expectError(dir.path() + "/missing.sqlite", "no such file");
  expectError(dir.path(), "not a regular file");
  {
    std::ofstream(dir.path() + "/text.sqlite") << "not a database at all, just some text that is long enough";
  }
  expectError(dir.path() + "/text.sqlite", "not a readable SQLite database");
  expectError(makeDb(dir, "nometa.sqlite", "CREATE TABLE trajectory_data(frame, id);"), "without a 'metadata' table");
  expectError(makeDb(dir, "noscenario.sqlite",
                     "CREATE TABLE trajectory_data(frame, id, pos_x, pos_y, ori_x, ori_y);"
                     "CREATE TABLE metadata(key, value); INSERT INTO metadata VALUES('fps', '10');"),
              "no 'throng_scenario'");
  expectError(makeDb(dir, "fps.sqlite",
                     "CREATE TABLE trajectory_data(frame, id, pos_x, pos_y, ori_x, ori_y);"
                     "CREATE TABLE metadata(key, value);"
                     "INSERT INTO metadata VALUES('fps', '-2'), ('throng_scenario', '{}');"),
              "metadata 'fps' is '-2'");
  expectError(makeDb(dir, "empty.sqlite", kBase), "no frames");
  expectError(makeDb(dir, "negative.sqlite", kBase + "INSERT INTO trajectory_data VALUES(-1, 1, 0, 0, 1, 0);"),
              "frame -1");
  expectError(makeDb(dir, "id.sqlite", kBase + "INSERT INTO trajectory_data VALUES(0, 4294967296, 0, 0, 1, 0);"),
              "agent id 4294967296");
  expectError(makeDb(dir, "inf.sqlite", kBase + "INSERT INTO trajectory_data VALUES(0, 1, 1e999, 0, 1, 0);"),
              "is not finite");
  expectError(makeDb(dir, "many.sqlite", kBase + "INSERT INTO trajectory_data VALUES(200000000, 1, 0, 0, 1, 0);"),
              "200000001 frames");
  // 3 frames of 400 bytes plus 3 rows of 32 bytes: refused under 1 KiB, read at 2 KiB.
  const std::string small = makeDb(dir, "small.sqlite", kBase +
      "INSERT INTO trajectory_data VALUES(0, 1, 0, 0, 1, 0), (1, 1, 0, 0, 1, 0), (2, 1, 0, 0, 1, 0);");
  expectError(small, "rows needs about", FrameReadOptions{1024});
  EXPECT_TRUE(readRecordedFrames(small, FrameReadOptions{2048}).ok());
}

}  // namespace
}  // namespace throng::recording
