// `throng run` when the recording cannot be written (a full disk): the run stops at the first
// failed write, says why (the recorder's message) and where it stopped,
// exits 1 and leaves a valid recording of every batch committed before the error, marked not
// completed, without a stray -wal file. The disk is made "full" for the child process only with
// RLIMIT_FSIZE (SIGXFSZ ignored, so a write past it fails with EFBIG instead of killing it).
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <csignal>
#include <regex>
#include <sys/resource.h>

#include "cli_runner.hpp"
#include "sqlite_query.hpp"

namespace throng::e2e {
namespace {

namespace fs = std::filesystem;

/// 400 agents walking between four places for 15 minutes: far more than 2 MiB of recording.
const char* kScenario = R"({
  "format": "throng/1",
  "name": "busy square",
  "seed": 5,
  "duration": 900,
  "walkable": [ [[0,0],[40,0],[40,40],[0,40]] ],
  "points": [
    {"id": "a", "kind": "interest", "position": [5, 5], "radius": 2},
    {"id": "b", "kind": "interest", "position": [35, 5], "radius": 2},
    {"id": "c", "kind": "interest", "position": [35, 35], "radius": 2},
    {"id": "d", "kind": "interest", "position": [5, 35], "radius": 2}
  ],
  "populations": [
    {"id": "walkers", "groups": 200, "size": 2, "spawn": {"polygon": [[10,10],[30,10],[30,30],[10,30]]},
     "goals": ["a", "b", "c", "d"], "wander": true}
  ]
}
)";

/// Runs throng with files limited to `bytes` (the limit is inherited by the child; the test
/// process writes nothing while it is set).
CliResult runWithFileLimit(const std::vector<std::string>& args, const fs::path& cwd, rlim_t bytes) {
  rlimit old{};
  EXPECT_EQ(getrlimit(RLIMIT_FSIZE, &old), 0);
  rlimit small = old;
  small.rlim_cur = bytes;
  auto* previous = std::signal(SIGXFSZ, SIG_IGN);
  EXPECT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0) << "hard limit " << old.rlim_max;
  CliResult r = runThrong(args, cwd);
  setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, previous);
  return r;
}

TEST(DiskFull, RunStopsAtTheFirstWriteErrorLeavingAValidPartialFile) {
  ScratchDir dir("disk-full");
  dir.write("square.json", kScenario);
  const CliResult r = runWithFileLimit({"run", "square.json", "--out", "square.sqlite", "--quiet"}, dir.path(), 2u << 20);
  EXPECT_EQ(r.exitCode, 1) << r.out << r.err;
  // The recorder's message (as before, when it came only at the end), then where the run stopped.
  EXPECT_NE(r.err.find("square.sqlite: SQLite: disk I/O error; expected a writable recording"),
            std::string::npos)
      << r.err;
  std::smatch m;
  const std::regex stopped(R"(throng: stopped at the first write error at t = ([0-9.]+) s; square\.sqlite holds the ([0-9]+) frames written before the error and is marked not completed)");
  ASSERT_TRUE(std::regex_search(r.err, m, stopped)) << r.err;
  const double stoppedAt = std::stod(m[1].str());
  const std::string frames = m[2].str();
  // 2 MiB hold about half a minute of this crowd: the run must not go on towards 900 s. The
  // recorder may be a queue of frames behind the simulation (64 frames, 6.4 s) when it fails.
  EXPECT_LT(stoppedAt, 120.0) << r.err;
  EXPECT_GT(std::stoi(frames), 0) << r.err;
  // The partial file: one self-contained, consistent SQLite file holding the committed frames.
  EXPECT_FALSE(fs::exists(dir / "square.sqlite-wal"));
  EXPECT_FALSE(fs::exists(dir / "square.sqlite-journal"));
  EXPECT_EQ(queryText(dir / "square.sqlite", "PRAGMA integrity_check"), (std::vector<std::vector<std::string>>{{"ok"}}));
  EXPECT_EQ(queryText(dir / "square.sqlite", "SELECT value FROM metadata WHERE key = 'throng_completed'"),
            (std::vector<std::vector<std::string>>{{"0"}}));
  EXPECT_EQ(queryText(dir / "square.sqlite", "SELECT count(*) FROM throng_frames"), (std::vector<std::vector<std::string>>{{frames}}));
  const auto last = queryText(dir / "square.sqlite", "SELECT max(frame) FROM trajectory_data");
  ASSERT_EQ(last.size(), 1u);
  EXPECT_EQ(std::stoi(last[0][0]), std::stoi(frames) - 1);
  // `throng info` reads it.
  const CliResult info = runThrong({"info", "square.sqlite"}, dir.path());
  EXPECT_EQ(info.exitCode, 0) << info.out << info.err;
}

}  // namespace
}  // namespace throng::e2e
