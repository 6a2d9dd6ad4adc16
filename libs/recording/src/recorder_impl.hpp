// throng::recording::Recorder::Impl — the recorder's state shared by its source files: the SQLite
// connection and prepared statements, the frame queue between push() and the worker thread, and
// the worker's bookkeeping. recorder.cpp opens, writes frames and closes (see its header comment);
// recorder_social.cpp writes the Common Ground tables. Private to throng_recording.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <unordered_set>
#include <vector>

#include "throng/recording/recorder.hpp"

#include "recording_schema.hpp"

namespace throng::recording {
namespace recorder_detail {

/// Rows per multi-row INSERT of the per-frame tables.
constexpr std::size_t kRowBlock = 32;

/// A recording problem at `path` (defined in recorder.cpp).
core::Diagnostic diag(const std::string& path, std::string what, std::string expected = {},
                      std::string hint = {});

/// "INSERT INTO table VALUES(?, ...), (...), ..." with kRowBlock rows of `columns` parameters
/// (defined in recorder.cpp).
std::string blockInsert(const char* table, int columns);

}  // namespace recorder_detail

struct Recorder::Impl {
  using Statement = recording::Statement;

  RecordingOptions options;
  sqlite3* db = nullptr;
  std::int64_t geometryHash = 0;
  std::vector<std::string> populationIds;

  Statement insertRowBlock, insertAnimationBlock;  // kRowBlock rows per statement
  Statement begin, commit, rollback, insertRow, insertFrameData, insertFrame, insertEvent,
      insertAgent, insertAgentSeen, updateExit, upsertMeta, insertAnimation, insertCoordination,
      insertScript;
  Statement insertHeight;  // multi-level worlds only (throng_heights)
  bool hasHeights = false;

  // Queue shared by push() and the worker.
  std::mutex mutex;
  std::condition_variable notEmpty, notFull;
  std::deque<sim::FramePtr> queue;
  bool stopping = false;
  std::thread worker;

  // Worker-only state (read by close() after join).
  std::uint64_t nextFrame = 0;
  std::uint64_t pendingFrames = 0;
  bool inTransaction = false;
  std::vector<bool> seenAgents;               ///< ids below kMaxTrackedAgentId (recorder.cpp) already recorded
  std::unordered_set<std::uint32_t> seenHugeIds;  ///< the rest
  std::uint64_t agentCount = 0;
  std::optional<core::Diagnostic> error;

  std::atomic<std::uint64_t> committed{0};
  std::atomic<bool> failed{false};  ///< set with `error`: the caller stops simulating (Recorder::failed)
  std::atomic<bool> closed{false};  ///< push() after close() is ignored
  std::optional<core::Status> closeResult;

  ~Impl() {
    if (db != nullptr) {
      // Statements must be finalized before sqlite3_close.
      for (Statement* s : {&begin, &commit, &rollback, &insertRow, &insertFrameData, &insertFrame,
                           &insertEvent, &insertAgent, &insertAgentSeen, &updateExit, &upsertMeta, &insertAnimation,
                           &insertCoordination, &insertScript, &insertRowBlock, &insertAnimationBlock, &insertHeight}) {
        *s = Statement();
      }
      sqlite3_close(db);
    }
  }

  /// Records the first write error; returns false for `return fail(...)`.
  bool fail(std::string what) {
    if (!error) error = recorder_detail::diag(options.path, std::move(what), "a writable recording");
    failed.store(true, std::memory_order_release);
    return false;
  }
  std::string sqliteMessage() const { return db ? sqlite3_errmsg(db) : "cannot open database"; }

  bool exec(const char* sql) {
    char* msg = nullptr;
    if (sqlite3_exec(db, sql, nullptr, nullptr, &msg) != SQLITE_OK) {
      fail(std::string("SQLite: ") + (msg ? msg : sqliteMessage()));
      sqlite3_free(msg);
      return false;
    }
    return true;
  }

  /// Steps a statement once and resets it; records the first failure.
  bool run(const Statement& s) {
    const int rc = sqlite3_step(s.get());
    const bool ok = rc == SQLITE_DONE || rc == SQLITE_ROW;
    if (!ok) fail("SQLite: " + sqliteMessage());
    sqlite3_reset(s.get());
    sqlite3_clear_bindings(s.get());
    return ok;
  }

  bool prepare(Statement& s, const std::string& sql) {
    s = Statement(db, sql.c_str());
    if (!s.ok()) fail("SQLite: " + sqliteMessage() + " in " + sql.substr(0, 200));
    return s.ok();
  }

  bool putMeta(const std::string& key, const std::string& value) {
    recording::bindText(upsertMeta.get(), 1, key);
    recording::bindText(upsertMeta.get(), 2, value);
    return run(upsertMeta);
  }

  bool prepareAll() {
    return prepare(begin, "BEGIN") && prepare(commit, "COMMIT") && prepare(rollback, "ROLLBACK") &&
           prepare(insertRow, "INSERT INTO trajectory_data VALUES(?, ?, ?, ?, ?, ?)") &&
           prepare(insertRowBlock, recorder_detail::blockInsert("trajectory_data", 6)) &&
           prepare(insertAnimationBlock, recorder_detail::blockInsert("throng_animation", 4)) &&
           prepare(insertFrameData, "INSERT INTO frame_data VALUES(?, ?)") &&
           prepare(insertFrame, "INSERT INTO throng_frames VALUES(?, ?, ?, ?)") &&
           prepare(insertEvent, "INSERT INTO throng_events VALUES(?, ?, ?, ?, ?, ?)") &&
           prepare(insertAgent,
                   "INSERT OR REPLACE INTO throng_agents(id, population, population_id, group_id, "
                   "spawn_frame, spawn_tick) VALUES(?, ?, ?, ?, ?, ?)") &&
           prepare(insertAgentSeen, "INSERT OR IGNORE INTO throng_agents(id, spawn_frame) VALUES(?, ?)") &&
           prepare(updateExit, "UPDATE throng_agents SET exit_frame = ?, exit_tick = ? WHERE id = ?") &&
           prepare(upsertMeta, "INSERT OR REPLACE INTO metadata(key, value) VALUES(?, ?)") &&
           prepare(insertAnimation, "INSERT INTO throng_animation VALUES(?, ?, ?, ?)") &&
           // A coordination published twice (a simulation bug) replaces the first: never a write error.
           prepare(insertCoordination,
                   "INSERT OR REPLACE INTO throng_coordinations VALUES(?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)") &&
           prepare(insertScript,
                   "INSERT INTO throng_script VALUES(?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  }

  bool writeScenario(const sim::ScenarioDesc& scenario);
  /// One frame, in the order readers rely on: events (a Spawn names the agent before its first
  /// row), agents first seen, trajectory and animation rows, heights, Common Ground, frame rows.
  bool writeFrame(const sim::Frame& frame);
  bool writeEvents(const sim::Frame& frame, std::int64_t index);
  bool writeAgentsSeen(const sim::Frame& frame, std::int64_t index);  ///< also checks the frame's columns
  bool writeTrajectoryRows(const sim::Frame& frame, std::int64_t index);
  bool writeHeights(const sim::Frame& frame, std::int64_t index);
  bool writeFrameRows(const sim::Frame& frame, std::int64_t index);
  bool writeSocial(const sim::Frame& frame);
  bool markSeen(std::uint32_t id);
  void workerLoop();
  bool commitBatch();
  void writeFinal(bool completed);
};

}  // namespace throng::recording
