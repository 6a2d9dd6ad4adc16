// Tests for throng::recording::readRecordingSummary (libs/recording/src/recording_reader.cpp): throng's own
// recordings, foreign JuPedSim files of versions 1–3, and files that are not recordings at all,
// each of which must give one diagnostic naming the file.
#include <gtest/gtest.h>
#include <sqlite3.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "temp_dir.hpp"
#include "throng/recording/recorder.hpp"

namespace throng::recording {
namespace {

namespace fs = std::filesystem;

using throng::test::TempDir;

/// Creates an SQLite file from a script (tables of another writer, or damaged ones).
void makeDb(const std::string& path, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  char* msg = nullptr;
  const std::string script = "PRAGMA synchronous=OFF;" + sql;  // test files need no fsync
  EXPECT_EQ(sqlite3_exec(db, script.c_str(), nullptr, nullptr, &msg), SQLITE_OK) << (msg ? msg : "");
  sqlite3_free(msg);
  sqlite3_close(db);
}

/// The single diagnostic a bad file must produce.
core::Diagnostic onlyError(const std::string& path) {
  const auto r = readRecordingSummary(path);
  EXPECT_FALSE(r.ok());
  if (r.ok()) return {};
  EXPECT_EQ(r.errors().size(), 1u);
  EXPECT_EQ(r.errors()[0].source, path);
  EXPECT_FALSE(r.errors()[0].expected.empty());
  return r.errors()[0];
}

constexpr const char* kV2Tables =
    "CREATE TABLE trajectory_data (frame INTEGER NOT NULL, id INTEGER NOT NULL, pos_x REAL NOT NULL,"
    " pos_y REAL NOT NULL, ori_x REAL NOT NULL, ori_y REAL NOT NULL);"
    "CREATE TABLE metadata(key TEXT NOT NULL UNIQUE PRIMARY KEY, value TEXT NOT NULL);"
    "CREATE TABLE geometry(hash INTEGER NOT NULL, wkt TEXT NOT NULL);"
    "CREATE TABLE frame_data(frame INTEGER NOT NULL, geometry_hash INTEGER NOT NULL);";

TEST(RecordingReader, SummarisesAThrongRecording) {
  TempDir dir;
  const std::string path = dir.file("run.sqlite");
  sim::ScenarioDesc scenario;
  scenario.name = "corridor";
  scenario.walkable = {{{0, 0}, {10, 0}, {10, 2}, {0, 2}}};
  scenario.populations.resize(2);
  scenario.populations[0].id = "east";
  scenario.populations[1].id = "west";
  RecordingOptions o;
  o.path = path;
  o.fps = 20.0;
  o.seed = 7;
  o.framesPerBatch = 4;
  auto r = Recorder::open(scenario, o);
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  auto rec = std::move(r).value();
  for (std::uint32_t f = 0; f < 10; ++f) {
    auto frame = std::make_shared<sim::Frame>();
    const std::uint32_t n = f < 5 ? 2 : 3;
    for (std::uint32_t id = 0; id < n; ++id) {
      frame->ids.push_back(id);
      frame->posX.push_back(static_cast<float>(f));
      frame->posY.push_back(1.0f);
      frame->oriX.push_back(1.0f);
      frame->oriY.push_back(0.0f);
    }
    if (f == 0) {
      frame->events = {{0, 0, sim::EventKind::Spawn, 0, 0}, {0, 1, sim::EventKind::Spawn, 1, 1}};
    }
    if (f == 5) frame->events = {{10, 2, sim::EventKind::Spawn, 1, 2}};
    rec->push(frame);
  }
  ASSERT_TRUE(rec->close(true).ok());

  const auto s = readRecordingSummary(path);
  ASSERT_TRUE(s.ok()) << core::formatAll(s.errors());
  EXPECT_EQ(s->path, path);
  EXPECT_EQ(s->formatVersion, 2);
  EXPECT_EQ(s->scenarioName, "corridor");
  EXPECT_EQ(s->seed, 7u);
  EXPECT_EQ(s->fps, 20.0);
  EXPECT_EQ(s->frames, 10u);
  EXPECT_EQ(s->agents, 3u);
  EXPECT_EQ(s->rows, 5u * 2 + 5u * 3);
  EXPECT_DOUBLE_EQ(s->duration, 0.45);  // 10 frames at 20 fps span 9 intervals
  EXPECT_TRUE(s->completed);
  EXPECT_FALSE(s->throngVersion.empty());
  EXPECT_EQ(s->events, 3u);
  const std::vector<std::pair<std::string, std::uint64_t>> pops = {{"east", 1}, {"west", 2}};
  EXPECT_EQ(s->populations, pops);
}

TEST(RecordingReader, ReadsForeignJuPedSimFilesOfVersions1To3) {
  TempDir dir;
  const std::string v1 = dir.file("v1.sqlite");
  makeDb(v1,
         "CREATE TABLE trajectory_data (frame INTEGER NOT NULL, id INTEGER NOT NULL, pos_x REAL NOT NULL,"
         " pos_y REAL NOT NULL, ori_x REAL NOT NULL, ori_y REAL NOT NULL);"
         "CREATE TABLE metadata(key TEXT NOT NULL UNIQUE PRIMARY KEY, value TEXT NOT NULL);"
         "CREATE TABLE geometry(wkt TEXT NOT NULL);"
         "INSERT INTO metadata VALUES('version', 1), ('fps', 25.0);"
         "INSERT INTO trajectory_data VALUES(0,1,0,0,1,0),(0,2,1,0,1,0),(1,1,0.1,0,1,0),(2,1,0.2,0,1,0);");
  auto s = readRecordingSummary(v1);
  ASSERT_TRUE(s.ok()) << core::formatAll(s.errors());
  EXPECT_EQ(s->formatVersion, 1);
  EXPECT_EQ(s->fps, 25.0);
  EXPECT_EQ(s->frames, 3u);
  EXPECT_EQ(s->agents, 2u);
  EXPECT_EQ(s->rows, 4u);
  EXPECT_FALSE(s->completed);  // no throng provenance
  EXPECT_TRUE(s->scenarioName.empty());

  const std::string v3 = dir.file("v3.sqlite");
  makeDb(v3,
         "CREATE TABLE trajectory_data (frame INTEGER NOT NULL, id INTEGER NOT NULL, pos_x REAL NOT NULL,"
         " pos_y REAL NOT NULL);"
         "CREATE TABLE metadata(key TEXT NOT NULL UNIQUE PRIMARY KEY, value TEXT NOT NULL);"
         "CREATE TABLE geometry(hash INTEGER NOT NULL, wkt TEXT NOT NULL);"
         "CREATE TABLE frame_data(frame INTEGER NOT NULL, geometry_hash INTEGER NOT NULL);"
         "INSERT INTO metadata VALUES('version', '3'), ('fps', '2.5');"
         "INSERT INTO frame_data VALUES(0, 1), (1, 1);"
         "INSERT INTO trajectory_data VALUES(0,1,0,0),(1,1,1,0);");
  s = readRecordingSummary(v3);
  ASSERT_TRUE(s.ok()) << core::formatAll(s.errors());
  EXPECT_EQ(s->formatVersion, 3);
  EXPECT_EQ(s->frames, 2u);
  EXPECT_DOUBLE_EQ(s->duration, 0.4);
}

TEST(RecordingReader, MissingFileAndDirectory) {
  TempDir dir;
  EXPECT_EQ(onlyError(dir.file("nope.sqlite")).what, "no such file");
  EXPECT_EQ(onlyError(dir.path()).what, "not a regular file");
}

TEST(RecordingReader, NonSqliteFileIsADiagnostic) {
  TempDir dir;
  const std::string path = dir.file("scenario.json");
  { std::ofstream(path) << R"({"format": "throng/1", "name": "not a recording"})"; }
  const core::Diagnostic d = onlyError(path);
  EXPECT_NE(d.what.find("not a readable SQLite database"), std::string::npos) << d.what;
  EXPECT_NE(d.expected.find("JuPedSim"), std::string::npos);

  const std::string empty = dir.file("empty.sqlite");
  { std::ofstream out(empty); }
  EXPECT_NE(onlyError(empty).what.find("without a 'trajectory_data' table"), std::string::npos);
}

TEST(RecordingReader, TruncatedRecordingIsADiagnosticNotACrash) {
  TempDir dir;
  const std::string full = dir.file("full.sqlite");
  makeDb(full, std::string(kV2Tables) +
                   "INSERT INTO metadata VALUES('version','2'),('fps','10.0');"
                   "WITH RECURSIVE n(i) AS (SELECT 0 UNION ALL SELECT i + 1 FROM n WHERE i < 3000) "
                   "INSERT INTO trajectory_data SELECT i / 10, i % 10, i, i, 1, 0 FROM n;");
  const auto size = fs::file_size(full);
  std::ifstream in(full, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const std::size_t cut : {std::size_t{50}, std::size_t{100}, std::size_t{4096}, static_cast<std::size_t>(size / 2)}) {
    const std::string path = dir.file("cut" + std::to_string(cut) + ".sqlite");
    { std::ofstream(path, std::ios::binary) << bytes.substr(0, cut); }
    const auto r = readRecordingSummary(path);  // may succeed on a lucky cut; must not crash
    if (!r.ok()) EXPECT_EQ(r.errors()[0].source, path);
  }
}

TEST(RecordingReader, WrongOrMissingMetadata) {
  TempDir dir;
  const std::string noVersion = dir.file("a.sqlite");
  makeDb(noVersion, std::string(kV2Tables) + "INSERT INTO metadata VALUES('fps','10');");
  EXPECT_EQ(onlyError(noVersion).what, "metadata has no 'version'");

  const std::string v4 = dir.file("b.sqlite");
  makeDb(v4, std::string(kV2Tables) + "INSERT INTO metadata VALUES('version','4'),('fps','10');");
  EXPECT_EQ(onlyError(v4).what, "unsupported format version '4'");

  const std::string noFps = dir.file("c.sqlite");
  makeDb(noFps, std::string(kV2Tables) + "INSERT INTO metadata VALUES('version','2');");
  EXPECT_EQ(onlyError(noFps).what, "metadata has no 'fps'");

  const std::string badFps = dir.file("d.sqlite");
  makeDb(badFps, std::string(kV2Tables) + "INSERT INTO metadata VALUES('version','2'),('fps','-1');");
  EXPECT_EQ(onlyError(badFps).what, "metadata 'fps' is '-1'");

  const std::string noMeta = dir.file("e.sqlite");
  makeDb(noMeta, "CREATE TABLE trajectory_data(frame, id, pos_x, pos_y);");
  EXPECT_EQ(onlyError(noMeta).what, "SQLite database without a 'metadata' table");
}

TEST(RecordingReader, ViewsAreNotTables) {
  // A view could compute anything (an endless recursive query); the reader wants stored tables.
  TempDir dir;
  const std::string path = dir.file("view.sqlite");
  makeDb(path,
         "CREATE TABLE metadata(key TEXT, value TEXT);"
         "INSERT INTO metadata VALUES('version','2'),('fps','10');"
         "CREATE VIEW trajectory_data AS WITH RECURSIVE n(i) AS (SELECT 0 UNION ALL SELECT i + 1 FROM n) "
         "SELECT i AS frame, i AS id, 0.0 AS pos_x, 0.0 AS pos_y FROM n;");
  EXPECT_EQ(onlyError(path).what, "SQLite database without a 'trajectory_data' table");
}

TEST(RecordingReader, DoesNotModifyTheFile) {
  TempDir dir;
  const std::string path = dir.file("ro.sqlite");
  makeDb(path, std::string(kV2Tables) + "INSERT INTO metadata VALUES('version','2'),('fps','10');");
  const auto before = fs::last_write_time(path);
  const auto sizeBefore = fs::file_size(path);
  ASSERT_TRUE(readRecordingSummary(path).ok());
  EXPECT_EQ(fs::last_write_time(path), before);
  EXPECT_EQ(fs::file_size(path), sizeBefore);
  EXPECT_FALSE(fs::exists(path + "-journal"));
}

}  // namespace
}  // namespace throng::recording
