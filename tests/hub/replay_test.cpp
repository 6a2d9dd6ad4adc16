// Tests for throng::hub::Replay and ReplayClock (libs/hub/src/replay.cpp): a short museum run is
// recorded with the io Recorder into a temporary directory and read back; frames come back at the
// recorded positions, clamped at both ends; clips and phases are derived when the file has none;
// bad files give one diagnostic naming the file; the clock's play / pause / seek / speed rules.
#include <gtest/gtest.h>
#include <sqlite3.h>
#include <stdlib.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "throng/core/parallel.hpp"
#include "throng/hub/replay.hpp"
#include "throng/recording/recorder.hpp"
#include "throng/io/scenario_loader.hpp"
#include "throng/sim/world.hpp"

namespace throng::hub {
namespace {

namespace fs = std::filesystem;

class TempDir {
 public:
  TempDir() {
    std::string tmpl = (fs::temp_directory_path() / "throng-replay-XXXXXX").string();
    path_ = ::mkdtemp(tmpl.data()) ? tmpl : std::string();
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  [[nodiscard]] std::string file(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

constexpr double kFps = 10.0;
constexpr double kSeconds = 4.0;

/// Runs scenarios/museum.json for kSeconds, recording at kFps; returns the frames pushed.
std::vector<sim::FramePtr> recordMuseum(const std::string& path, std::string& scenarioText) {
  auto loaded = io::loadScenarioFile(std::string(THRONG_SOURCE_DIR) + "/scenarios/museum.json");
  EXPECT_TRUE(loaded) << core::formatAll(loaded.errors());
  if (!loaded) return {};
  scenarioText = loaded->text;
  auto world = sim::World::create(loaded->desc, loaded->navmesh);
  EXPECT_TRUE(world) << core::formatAll(world.errors());
  if (!world) return {};
  recording::RecordingOptions options;
  options.path = path;
  options.fps = kFps;
  options.seed = loaded->desc.seed;
  options.scenarioText = loaded->text;
  auto recorder = recording::Recorder::open(loaded->desc, options);
  EXPECT_TRUE(recorder) << core::formatAll(recorder.errors());
  if (!recorder) return {};
  const auto stride = std::max<long>(1, std::lround(1.0 / (kFps * loaded->desc.dt)));
  const auto ticks = static_cast<long>(std::lround(kSeconds / loaded->desc.dt));
  const core::TaskSystem tasks(1);
  std::vector<sim::FramePtr> frames;
  auto push = [&](sim::FramePtr f) {
    frames.push_back(f);
    recorder.value()->push(std::move(f));
  };
  push((*world)->takeFrame());
  for (long tick = 1; tick <= ticks; ++tick) {
    (*world)->step(tasks);
    if (tick % stride == 0) push((*world)->takeFrame());
  }
  const auto closed = recorder.value()->close(true);
  EXPECT_TRUE(closed) << core::formatAll(closed.errors());
  return frames;
}

/// One recording shared by the tests of this file (made once: a few hundred ms).
struct Recording {
  TempDir dir;
  std::string path = dir.file("museum.sqlite");
  std::string scenarioText;
  std::vector<sim::FramePtr> frames = recordMuseum(path, scenarioText);
};

const Recording& recording() {
  static const Recording r;
  return r;
}

void expectSameAgents(const sim::Frame& got, const sim::Frame& want, const std::string& where) {
  ASSERT_EQ(got.ids, want.ids) << where;
  for (std::size_t i = 0; i < want.size(); ++i) {
    EXPECT_FLOAT_EQ(got.posX[i], want.posX[i]) << where << " agent " << want.ids[i];
    EXPECT_FLOAT_EQ(got.posY[i], want.posY[i]) << where << " agent " << want.ids[i];
    EXPECT_NEAR(got.oriX[i], want.oriX[i], 1e-5) << where;
    EXPECT_NEAR(got.oriY[i], want.oriY[i], 1e-5) << where;
    EXPECT_EQ(got.clip[i], want.clip[i]) << where << " agent " << want.ids[i];
    EXPECT_NEAR(got.phase[i], want.phase[i], 1e-6) << where << " agent " << want.ids[i];
  }
}

TEST(Replay, FramesComeBackAtTheRecordedPositions) {
  const Recording& rec = recording();
  ASSERT_GE(rec.frames.size(), 30u);
  auto replay = Replay::open(rec.path);
  ASSERT_TRUE(replay) << core::formatAll(replay.errors());
  const Replay& r = replay.value();
  EXPECT_EQ(r.frameCount(), rec.frames.size());
  EXPECT_DOUBLE_EQ(r.fps(), kFps);
  EXPECT_NEAR(r.duration(), static_cast<double>(rec.frames.size() - 1) / kFps, 1e-9);
  EXPECT_TRUE(r.hasAnimation());
  ASSERT_GT(rec.frames.front()->size(), 0u) << "the museum starts with agents present";

  for (const std::size_t k : {std::size_t{0}, std::size_t{1}, std::size_t{7}, rec.frames.size() / 2, rec.frames.size() - 1}) {
    const double t = static_cast<double>(k) / kFps;
    EXPECT_EQ(r.frameIndexAt(t), k);
    EXPECT_NEAR(r.frameTime(k), t, 1e-9);
    const sim::FramePtr f = r.frameAt(t);
    ASSERT_NE(f, nullptr);
    expectSameAgents(*f, *rec.frames[k], "frame " + std::to_string(k));
    EXPECT_EQ(f->tick, rec.frames[k]->tick);
    EXPECT_NEAR(f->time, t, 1e-9);
    ASSERT_EQ(f->mode.size(), f->size());
    for (std::size_t i = 0; i < f->size(); ++i) {
      EXPECT_EQ(f->mode[i], f->clip[i] == 0 ? sim::AgentMode::Waiting
                            : f->clip[i] == 1 ? sim::AgentMode::Walking
                                              : sim::AgentMode::Acting);
    }
  }
  // Between frames: the last frame at or before t.
  EXPECT_EQ(r.frameIndexAt(0.349), 3u);
  EXPECT_EQ(r.frameAt(0.349), r.frameAt(0.3));
  // Clamped at both ends.
  EXPECT_EQ(r.frameIndexAt(-5.0), 0u);
  EXPECT_EQ(r.frameIndexAt(std::nan("")), 0u);
  EXPECT_EQ(r.frameIndexAt(1e9), rec.frames.size() - 1);
  expectSameAgents(*r.frameAt(1e9), *rec.frames.back(), "after the end");
  expectSameAgents(*r.frameAt(-1.0), *rec.frames.front(), "before the start");
}

TEST(Replay, ScenarioTextIsTheRecordedScenario) {
  const Recording& rec = recording();
  auto replay = Replay::open(rec.path);
  ASSERT_TRUE(replay) << core::formatAll(replay.errors());
  EXPECT_EQ(replay->scenarioText(), rec.scenarioText);
  const auto j = nlohmann::json::parse(replay->scenarioText(), nullptr, false);
  ASSERT_FALSE(j.is_discarded());
  EXPECT_TRUE(j.contains("populations"));
  // Clip paths in the scenario are relative to its directory: parse it as if it were there.
  const auto parsed = io::parseScenario(replay->scenarioText(), std::string(THRONG_SOURCE_DIR) + "/scenarios/museum.json");
  EXPECT_TRUE(parsed) << core::formatAll(parsed.errors());
}

void exec(const std::string& path, const char* sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  char* err = nullptr;
  EXPECT_EQ(sqlite3_exec(db, sql, nullptr, nullptr, &err), SQLITE_OK) << (err ? err : "");
  sqlite3_free(err);
  sqlite3_close(db);
}

TEST(Replay, DerivesClipAndPhaseWhenTheFileHasNone) {
  const Recording& rec = recording();
  TempDir dir;
  const std::string copy = dir.file("no-animation.sqlite");
  fs::copy_file(rec.path, copy);
  exec(copy, "DROP TABLE throng_animation;");
  auto replay = Replay::open(copy);
  ASSERT_TRUE(replay) << core::formatAll(replay.errors());
  EXPECT_FALSE(replay->hasAnimation());
  // Positions unchanged; clip 1 exactly where the agent moved faster than 0.1 m/s.
  std::size_t walking = 0, idle = 0;
  for (std::size_t k = 1; k < rec.frames.size(); ++k) {
    const sim::Frame& f = *replay->frameAt(static_cast<double>(k) / kFps);
    const sim::Frame& prev = *rec.frames[k - 1];
    ASSERT_EQ(f.ids, rec.frames[k]->ids);
    for (std::size_t i = 0; i < f.size(); ++i) {
      EXPECT_GE(f.phase[i], 0.0f);
      EXPECT_LT(f.phase[i], 1.0f);
      const auto it = std::lower_bound(prev.ids.begin(), prev.ids.end(), f.ids[i]);
      if (it == prev.ids.end() || *it != f.ids[i]) continue;
      const std::size_t j = static_cast<std::size_t>(it - prev.ids.begin());
      const double speed = std::hypot(f.posX[i] - prev.posX[j], f.posY[i] - prev.posY[j]) * kFps;
      if (std::abs(speed - 0.1) < 1e-3) continue;
      EXPECT_EQ(f.clip[i], speed > 0.1 ? 1 : 0) << "frame " << k << " agent " << f.ids[i];
      (f.clip[i] == 1 ? walking : idle)++;
    }
  }
  EXPECT_GT(walking, 0u);
}

TEST(Replay, BadFilesNameTheFile) {
  TempDir dir;
  auto expectError = [](const std::string& path, const std::string& what) {
    auto r = Replay::open(path);
    ASSERT_FALSE(r) << path;
    ASSERT_EQ(r.errors().size(), 1u);
    const core::Diagnostic& d = r.errors()[0];
    EXPECT_EQ(d.source, path);
    EXPECT_NE(d.what.find(what), std::string::npos) << d.format();
    EXPECT_FALSE(d.expected.empty());
    EXPECT_NE(d.format().find(path), std::string::npos);
  };
  expectError(dir.file("missing.sqlite"), "no such file");
  fs::create_directory(dir.file("adir"));
  expectError(dir.file("adir"), "not a regular file");
  std::ofstream(dir.file("text.sqlite")) << "this is not a database, just some text long enough to read\n";
  expectError(dir.file("text.sqlite"), "not a readable SQLite database");
  exec(dir.file("other.sqlite"), "CREATE TABLE people(name TEXT);");
  expectError(dir.file("other.sqlite"), "without a 'trajectory_data' table");
  // A JuPedSim file from another writer: tables, but no throng scenario.
  exec(dir.file("jupedsim.sqlite"),
       "CREATE TABLE trajectory_data(frame INTEGER, id INTEGER, pos_x REAL, pos_y REAL, ori_x REAL, ori_y REAL);"
       "CREATE TABLE metadata(key TEXT, value TEXT); INSERT INTO metadata VALUES('version', '2'), ('fps', '10');");
  expectError(dir.file("jupedsim.sqlite"), "no 'throng_scenario'");
  // A throng recording with its fps damaged.
  const std::string badFps = dir.file("bad-fps.sqlite");
  fs::copy_file(recording().path, badFps);
  exec(badFps, "UPDATE metadata SET value = '-3' WHERE key = 'fps';");
  expectError(badFps, "metadata 'fps' is '-3'");
}

// --- ReplayClock ---------------------------------------------------------------------------

TEST(ReplayClock, PlaysAtSpeedAndPausesAtTheEnd) {
  ReplayClock c(10.0);
  EXPECT_TRUE(c.playing());
  EXPECT_EQ(c.time(), 0.0);
  EXPECT_EQ(c.speed(), 1.0);
  EXPECT_FALSE(c.advance(2.5));
  EXPECT_DOUBLE_EQ(c.time(), 2.5);
  EXPECT_TRUE(c.setSpeed(2.0));
  EXPECT_FALSE(c.setSpeed(2.0));  // no change
  EXPECT_FALSE(c.advance(1.0));
  EXPECT_DOUBLE_EQ(c.time(), 4.5);
  EXPECT_FALSE(c.advance(-1.0));
  EXPECT_FALSE(c.advance(std::nan("")));
  EXPECT_DOUBLE_EQ(c.time(), 4.5);
  EXPECT_TRUE(c.advance(100.0));  // reaches the end: pauses there
  EXPECT_DOUBLE_EQ(c.time(), 10.0);
  EXPECT_FALSE(c.playing());
  EXPECT_FALSE(c.advance(1.0));
  EXPECT_TRUE(c.play());  // at the end: starts again
  EXPECT_EQ(c.time(), 0.0);
  EXPECT_TRUE(c.playing());
}

TEST(ReplayClock, PauseSeekAndClamping) {
  ReplayClock c(10.0, false);
  EXPECT_FALSE(c.playing());
  EXPECT_FALSE(c.advance(3.0));
  EXPECT_EQ(c.time(), 0.0);  // paused: time stands
  EXPECT_FALSE(c.pause());
  EXPECT_TRUE(c.seek(7.25));
  EXPECT_EQ(c.time(), 7.25);
  EXPECT_FALSE(c.seek(7.25));
  EXPECT_TRUE(c.seek(50.0));
  EXPECT_EQ(c.time(), 10.0);
  EXPECT_TRUE(c.seek(-1.0));
  EXPECT_EQ(c.time(), 0.0);
  EXPECT_FALSE(c.seek(std::nan("")));
  EXPECT_TRUE(c.play());
  EXPECT_FALSE(c.play());
  EXPECT_TRUE(c.pause());
  EXPECT_TRUE(c.setSpeed(1000.0));
  EXPECT_EQ(c.speed(), protocol::kMaxReplaySpeed);
  EXPECT_TRUE(c.setSpeed(0.0));
  EXPECT_GT(c.speed(), 0.0);
  EXPECT_FALSE(c.setSpeed(std::nan("")));
  ReplayClock empty(std::nan(""));
  EXPECT_EQ(empty.duration(), 0.0);
  EXPECT_TRUE(empty.advance(1.0));  // nothing to play: ends at once
}

TEST(ReplayClock, AppliesReplayControlAndReportsStatus) {
  ReplayClock c(120.25);
  EXPECT_TRUE(c.apply(protocol::ReplayControl{0, protocol::ReplayCommand::Seek, 12.5}));
  EXPECT_TRUE(c.apply(protocol::ReplayCommand::Speed, 2.0));
  EXPECT_FALSE(c.apply(protocol::ReplayCommand::Play, 0.0));  // already playing
  protocol::ReplayStatus s = c.status();
  EXPECT_EQ(s.time, 12.5);
  EXPECT_EQ(s.duration, 120.25);
  EXPECT_TRUE(s.playing);
  EXPECT_EQ(s.speed, 2.0f);
  EXPECT_TRUE(c.apply(protocol::ReplayCommand::Pause, 0.0));
  EXPECT_FALSE(c.status().playing);
  // Whatever the clock reports decodes (speed > 0, times finite and ≥ 0).
  c.setSpeed(0.0);
  EXPECT_TRUE(protocol::decodeAny(protocol::encode(c.status())));
}

}  // namespace
}  // namespace throng::hub
