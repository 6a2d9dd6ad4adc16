// throng::recording::Recorder — writes frames to SQLite (JuPedSim trajectory format v2 + throng_*
// tables, see recording_schema.hpp and docs/recording-format.md). open() checks the path and
// creates the schema on the caller's thread; push() hands frames to a bounded queue; a worker
// thread writes them in WAL transactions of framesPerBatch frames; close() drains, writes the
// final metadata, checkpoints and leaves a single self-contained file.
//
// The file is written at its final path from the start: WAL makes it valid after every commit,
// so a killed process leaves the path holding everything up to the last committed batch (plus a
// -wal file that the next opener folds in).
//
// The Common Ground tables (throng_coordinations, throng_script) are written by
// recorder_social.cpp; Recorder::Impl is declared in recorder_impl.hpp.
#include "throng/recording/recorder.hpp"

#include <unistd.h>

#include <atomic>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <filesystem>
#include <mutex>
#include <optional>
#include <system_error>
#include <thread>
#include <unordered_set>

#include "recorder_impl.hpp"
#include "throng/core/footprint.hpp"
#include "throng/core/simd.hpp"
#include "recording_scenario.hpp"
#include "recording_schema.hpp"
#include "recording_text.hpp"
#include "walkable_area_wkt.hpp"

#ifndef THRONG_VERSION
#define THRONG_VERSION "unknown"
#endif

namespace throng::recording {
namespace recorder_detail {

core::Diagnostic diag(const std::string& path, std::string what, std::string expected,
                      std::string hint) {
  core::Diagnostic d;
  d.source = path;
  d.what = std::move(what);
  d.expected = std::move(expected);
  d.hint = std::move(hint);
  return d;
}

/// "INSERT INTO table VALUES(?, ...), (...), ..." with kRowBlock rows of `columns` parameters.
std::string blockInsert(const char* table, int columns) {
  std::string row = "(";
  for (int c = 0; c < columns; ++c) row += c == 0 ? "?" : ", ?";
  row += ")";
  std::string sql = std::string("INSERT INTO ") + table + " VALUES";
  for (std::size_t r = 0; r < kRowBlock; ++r) sql += (r == 0 ? "" : ", ") + row;
  return sql;
}

}  // namespace recorder_detail

namespace {

namespace fs = std::filesystem;
using recording::Statement;
using recording::bindInt;
using recording::bindReal;
using recording::bindText;
using recording::writeScenarioTables;

using recorder_detail::diag;
using recorder_detail::kRowBlock;

/// Removes `path` and SQLite's companion files; ignores what is not there.
void removeWithCompanions(const std::string& path) {
  std::error_code ec;
  for (const char* suffix : {"", "-wal", "-shm", "-journal"}) fs::remove(path + suffix, ec);
}

/// Refuses an existing output without force and an unusable directory, before any work.
core::Status checkOutputPath(const RecordingOptions& options) {
  const std::string& path = options.path;
  if (path.empty()) return diag("<recording>", "empty output path", "a file path ending in .sqlite");
  std::error_code ec;
  const fs::path p(path);
  const fs::file_status st = fs::symlink_status(p, ec);
  if (fs::is_directory(st)) {
    return diag(path, "is a directory", "a file path for the recording");
  }
  if (fs::exists(st) && !options.force) {
    return diag(path, "file exists", "a new path", "pass --force to overwrite");
  }
  fs::path dir = p.parent_path();
  if (dir.empty()) dir = ".";
  const fs::file_status dst = fs::status(dir, ec);
  if (!fs::exists(dst)) {
    return diag(path, "directory \"" + dir.string() + "\" does not exist",
                "an existing, writable directory");
  }
  if (!fs::is_directory(dst)) {
    return diag(path, "\"" + dir.string() + "\" is not a directory", "an existing, writable directory");
  }
  if (::access(dir.c_str(), W_OK | X_OK) != 0) {
    return diag(path, "directory \"" + dir.string() + "\" is not writable",
                "an existing, writable directory");
  }
  return core::Ok{};
}



/// Agent ids below this are tracked in a bitmap (ids are dense spawn order); a stray larger id
/// goes to a hash set instead of growing the bitmap.
constexpr std::uint32_t kMaxTrackedAgentId = 1u << 26;

}  // namespace

void FrameCarry::add(const sim::Frame& frame) {
  carried_.events.insert(carried_.events.end(), frame.events.begin(), frame.events.end());
  carried_.script.insert(carried_.script.end(), frame.script.begin(), frame.script.end());
  carried_.coordinations.insert(carried_.coordinations.end(), frame.coordinations.begin(), frame.coordinations.end());
}

sim::FramePtr FrameCarry::merge(sim::FramePtr frame) {
  if (carried_.events.empty() && carried_.script.empty() && carried_.coordinations.empty()) return frame;
  auto merged = std::make_shared<sim::Frame>(*frame);
  merged->events.insert(merged->events.begin(), carried_.events.begin(), carried_.events.end());
  merged->script.insert(merged->script.begin(), carried_.script.begin(), carried_.script.end());
  merged->coordinations.insert(merged->coordinations.begin(), carried_.coordinations.begin(), carried_.coordinations.end());
  carried_ = {};
  return merged;
}

const char* eventKindName(sim::EventKind kind) {
  switch (kind) {
    case sim::EventKind::Spawn: return "spawn";
    case sim::EventKind::Exit: return "exit";
    case sim::EventKind::GoalReached: return "goal_reached";
    case sim::EventKind::ActionStart: return "action_start";
    case sim::EventKind::ActionEnd: return "action_end";
    case sim::EventKind::PathPartial: return "path_partial";
    case sim::EventKind::GroupWaitStart: return "group_wait_start";
    case sim::EventKind::GroupRelease: return "group_release";
    case sim::EventKind::GroupTimeout: return "group_timeout";
    case sim::EventKind::FollowStart: return "follow_start";
    case sim::EventKind::FollowEnd: return "follow_end";
    case sim::EventKind::GuideStart: return "guide_start";
    case sim::EventKind::GuideEnd: return "guide_end";
    case sim::EventKind::JoinGroup: return "join_group";
    case sim::EventKind::FollowAgent: return "follow_agent";
    case sim::EventKind::FollowAgentEnd: return "follow_agent_end";
    case sim::EventKind::LeaderChange: return "leader_change";
    case sim::EventKind::PathFallback: return "path_fallback";
    case sim::EventKind::GoalGenerated: return "goal_generated";
    case sim::EventKind::CoordinationStart: return "coordination_start";
    case sim::EventKind::CoordinationEnd: return "coordination_end";
    case sim::EventKind::VisitStart: return "visit_start";
    case sim::EventKind::VisitEnd: return "visit_end";
    case sim::EventKind::Reunited: return "reunited";
    case sim::EventKind::ExitChosen: return "exit_chosen";
    case sim::EventKind::WaypointChosen: return "waypoint_chosen";
    case sim::EventKind::Incapacitated: return "incapacitated";
  }
  return "unknown";
}

bool Recorder::Impl::writeScenario(const sim::ScenarioDesc& scenario) {
  using namespace recording;
  // JuPedSim's geometry is 2D: a multi-level world records the ground footprint of its floors.
  const WalkableAreaWkt area = [&] {
    if (scenario.terrain.empty()) return walkableAreaWkt(scenario.walkable, scenario.obstacles);
    const nav::TerrainMesh& t = scenario.terrain;
    std::vector<std::array<core::Vec2, 3>> triangles;
    for (std::size_t i = 0; i + 2 < t.walkable.size(); i += 3) {
      std::array<core::Vec2, 3> tri;
      for (int k = 0; k < 3; ++k) {
        const std::size_t v = 3 * static_cast<std::size_t>(t.walkable[i + static_cast<std::size_t>(k)]);
        tri[static_cast<std::size_t>(k)] = v + 1 < t.vertices.size() ? core::Vec2{t.vertices[v], t.vertices[v + 1]} : core::Vec2{};
      }
      triangles.push_back(tri);
    }
    const core::Footprint footprint = core::unionOfTriangles(triangles);
    return walkableAreaWkt(footprint.outer, footprint.holes);
  }();
  geometryHash = recording::geometryHash(area.wkt);
  for (const auto& pop : scenario.populations) populationIds.push_back(pop.id);

  if (!exec("BEGIN") || !exec(kCreateJuPedSim) || !exec(kCreateThrong) || !exec(kCreateFrameIndexes) || !prepareAll()) return false;
  if (!scenario.terrain.empty()) {
    hasHeights = true;
    if (!exec(kCreateHeights) || !exec(kCreateHeightsIndex) ||
        !prepare(insertHeight, "INSERT INTO throng_heights VALUES(?, ?, ?)")) {
      return false;
    }
  }

  // metadata: JuPedSim's keys (values as Python's str() writes them), then throng's.
  bool ok = putMeta(kKeyVersion, std::to_string(kFormatVersion)) &&
            putMeta(kKeyFps, pythonFloatText(options.fps)) &&
            putMeta(kKeyXMin, pythonFloatText(area.minX)) && putMeta(kKeyXMax, pythonFloatText(area.maxX)) &&
            putMeta(kKeyYMin, pythonFloatText(area.minY)) && putMeta(kKeyYMax, pythonFloatText(area.maxY)) &&
            putMeta(kKeyThrongVersion, THRONG_VERSION) && putMeta(kKeySchema, kSchemaNote) &&
            putMeta(kKeyScenarioName, scenario.name) && putMeta(kKeyScenario, options.scenarioText) &&
            putMeta(kKeySeed, std::to_string(options.seed)) &&
            putMeta(kKeyDt, pythonFloatText(floatAsDecimal(scenario.dt))) &&
            putMeta(kKeyCompleted, "0") && putMeta(kKeyFrames, "0") && putMeta(kKeyDuration, "0.0") &&
            putMeta(kKeyAgents, "0") && putMeta(kKeyModels, modelsJson(scenario)) &&
            putMeta(kKeySimd, std::string(core::simdPathName(core::simdPath())));
  if (ok && scenario.social.enabled) ok = putMeta(kKeyCommonGround, scenario.social.commonGround ? "on" : "off");
  if (ok && !options.worldFile.empty()) ok = putMeta(kKeyWorldFile, options.worldFile);
  if (!ok) return false;

  {
    Statement geo(db, "INSERT INTO geometry VALUES(?, ?)");
    if (!geo.ok()) return fail("SQLite: " + sqliteMessage());
    bindInt(geo.get(), 1, geometryHash);
    bindText(geo.get(), 2, area.wkt);
    if (!run(geo)) return false;
  }
  if (const std::string msg = writeScenarioTables(db, scenario); !msg.empty()) return fail("SQLite: " + msg);
  return exec("COMMIT");
}

bool Recorder::Impl::markSeen(std::uint32_t id) {
  if (id < kMaxTrackedAgentId) {
    if (id >= seenAgents.size()) seenAgents.resize(static_cast<std::size_t>(id) + 1024, false);
    if (seenAgents[id]) return true;
    seenAgents[id] = true;
  } else if (!seenHugeIds.insert(id).second) {
    return true;
  }
  ++agentCount;
  return false;
}

bool Recorder::Impl::writeFrame(const sim::Frame& f) {
  const auto frame = static_cast<std::int64_t>(nextFrame);
  return writeEvents(f, frame) && writeAgentsSeen(f, frame) && writeTrajectoryRows(f, frame) &&
         writeHeights(f, frame) && writeSocial(f) && writeFrameRows(f, frame);
}

bool Recorder::Impl::writeEvents(const sim::Frame& f, std::int64_t frame) {
  for (const sim::Event& e : f.events) {
    sqlite3_stmt* s = insertEvent.get();
    bindInt(s, 1, frame);
    bindInt(s, 2, static_cast<std::int64_t>(e.tick));
    bindInt(s, 3, e.agent);
    bindText(s, 4, eventKindName(e.kind));
    bindInt(s, 5, e.a);
    bindInt(s, 6, e.b);
    if (!run(insertEvent)) return false;
    if (e.kind == sim::EventKind::Spawn) {
      s = insertAgent.get();
      bindInt(s, 1, e.agent);
      bindInt(s, 2, e.a);
      if (e.a < populationIds.size()) bindText(s, 3, populationIds[e.a]); else sqlite3_bind_null(s, 3);
      bindInt(s, 4, e.b);
      bindInt(s, 5, frame);
      bindInt(s, 6, static_cast<std::int64_t>(e.tick));
      if (!run(insertAgent)) return false;
      markSeen(e.agent);
    } else if (e.kind == sim::EventKind::Exit) {
      s = updateExit.get();
      bindInt(s, 1, frame);
      bindInt(s, 2, static_cast<std::int64_t>(e.tick));
      bindInt(s, 3, e.agent);
      if (!run(updateExit)) return false;
    }
  }
  return true;
}

bool Recorder::Impl::writeAgentsSeen(const sim::Frame& f, std::int64_t frame) {
  const std::size_t n = f.ids.size();
  if (f.posX.size() < n || f.posY.size() < n) {
    return fail("frame " + std::to_string(frame) + ": " + std::to_string(n) + " ids but " +
                std::to_string(std::min(f.posX.size(), f.posY.size())) + " positions");
  }
  const bool hasOri = f.oriX.size() >= n && f.oriY.size() >= n;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = f.posX[i], y = f.posY[i];
    const double ox = hasOri ? f.oriX[i] : 1.0, oy = hasOri ? f.oriY[i] : 0.0;
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(ox) || !std::isfinite(oy)) {
      return fail("frame " + std::to_string(frame) + " agent " + std::to_string(f.ids[i]) +
                  ": position or orientation is not finite");
    }
    if (!markSeen(f.ids[i])) {
      sqlite3_stmt* s = insertAgentSeen.get();
      bindInt(s, 1, f.ids[i]);
      bindInt(s, 2, frame);
      if (!run(insertAgentSeen)) return false;
    }
  }
  return true;
}

bool Recorder::Impl::writeTrajectoryRows(const sim::Frame& f, std::int64_t frame) {
  const std::size_t n = f.ids.size();
  const bool hasOri = f.oriX.size() >= n && f.oriY.size() >= n;
  const bool hasAnimation = f.clip.size() >= n && f.phase.size() >= n;
  // Rows go in blocks of kRowBlock per statement (one VDBE run each), the rest one by one; the
  // table gets the same rows in the same order either way.
  auto bindRow = [&](sqlite3_stmt* s, int base, std::size_t i) {
    bindInt(s, base + 1, frame);
    bindInt(s, base + 2, f.ids[i]);
    bindReal(s, base + 3, f.posX[i]);
    bindReal(s, base + 4, f.posY[i]);
    bindReal(s, base + 5, hasOri ? f.oriX[i] : 1.0);
    bindReal(s, base + 6, hasOri ? f.oriY[i] : 0.0);
  };
  auto bindAnimation = [&](sqlite3_stmt* s, int base, std::size_t i) {
    bindInt(s, base + 1, frame);
    bindInt(s, base + 2, f.ids[i]);
    bindInt(s, base + 3, f.clip[i]);
    bindReal(s, base + 4, static_cast<double>(f.phase[i]));
  };
  std::size_t i = 0;
  for (; i + kRowBlock <= n; i += kRowBlock) {
    for (std::size_t k = 0; k < kRowBlock; ++k) bindRow(insertRowBlock.get(), static_cast<int>(6 * k), i + k);
    if (!run(insertRowBlock)) return false;
    if (hasAnimation) {
      for (std::size_t k = 0; k < kRowBlock; ++k) bindAnimation(insertAnimationBlock.get(), static_cast<int>(4 * k), i + k);
      if (!run(insertAnimationBlock)) return false;
    }
  }
  for (; i < n; ++i) {
    bindRow(insertRow.get(), 0, i);
    if (!run(insertRow)) return false;
    if (hasAnimation) {
      bindAnimation(insertAnimation.get(), 0, i);
      if (!run(insertAnimation)) return false;
    }
  }
  return true;
}

bool Recorder::Impl::writeHeights(const sim::Frame& f, std::int64_t frame) {
  if (!hasHeights) return true;
  for (std::size_t k = 0; k < f.ids.size(); ++k) {
    bindInt(insertHeight.get(), 1, frame);
    bindInt(insertHeight.get(), 2, f.ids[k]);
    bindReal(insertHeight.get(), 3, static_cast<double>(f.height(k)));
    if (!run(insertHeight)) return false;
  }
  return true;
}

bool Recorder::Impl::writeFrameRows(const sim::Frame& f, std::int64_t frame) {
  bindInt(insertFrameData.get(), 1, frame);
  bindInt(insertFrameData.get(), 2, geometryHash);
  if (!run(insertFrameData)) return false;
  sqlite3_stmt* s = insertFrame.get();
  bindInt(s, 1, frame);
  bindInt(s, 2, static_cast<std::int64_t>(f.tick));
  bindReal(s, 3, f.time);
  bindInt(s, 4, static_cast<std::int64_t>(f.ids.size()));
  return run(insertFrame);
}

bool Recorder::Impl::commitBatch() {
  if (!inTransaction) return true;
  const bool ok = putMeta(recording::kKeyFrames, std::to_string(nextFrame)) &&
                  putMeta(recording::kKeyAgents, std::to_string(agentCount)) && run(commit);
  if (!ok) {
    run(rollback);
  } else {
    committed.store(nextFrame, std::memory_order_release);
  }
  inTransaction = false;
  pendingFrames = 0;
  return ok;
}

void Recorder::Impl::workerLoop() {
  for (;;) {
    sim::FramePtr frame;
    {
      std::unique_lock lock(mutex);
      notEmpty.wait(lock, [&] { return !queue.empty() || stopping; });
      if (queue.empty()) break;  // stopping and drained
      frame = std::move(queue.front());
      queue.pop_front();
    }
    notFull.notify_one();
    if (error || !frame) continue;  // keep draining so push() never blocks forever
    try {
      if (!inTransaction) {
        if (!run(begin)) continue;
        inTransaction = true;
      }
      if (!writeFrame(*frame)) {
        run(rollback);
        inTransaction = false;
        continue;
      }
      ++nextFrame;
      if (++pendingFrames >= options.framesPerBatch) commitBatch();
    } catch (const std::exception& e) {
      fail(std::string("recorder: ") + e.what());
    }
  }
  if (!error) commitBatch();
}

void Recorder::Impl::writeFinal(bool completed) {
  // Best effort even after an error, so the file says it is incomplete.
  const bool wasOk = !error;
  if (!exec("BEGIN")) return;
  const bool ok = putMeta(recording::kKeyCompleted, completed && wasOk ? "1" : "0") &&
                  putMeta(recording::kKeyFrames, std::to_string(committed.load())) &&
                  putMeta(recording::kKeyDuration,
                          recording::pythonFloatText(committed.load() > 1 ? static_cast<double>(committed.load() - 1) / options.fps : 0.0)) &&
                  putMeta(recording::kKeyAgents, std::to_string(agentCount));
  if (ok) exec("COMMIT"); else exec("ROLLBACK");
}

Recorder::Recorder() : impl_(std::make_unique<Impl>()) {}

Recorder::~Recorder() {
  if (impl_ && !impl_->closed) (void)close(false);
}

core::Result<std::unique_ptr<Recorder>> Recorder::open(const sim::ScenarioDesc& scenario,
                                                       const RecordingOptions& options) {
  core::Diagnostics problems;
  if (!(std::isfinite(options.fps) && options.fps > 0.0)) {
    problems.push_back(diag(options.path, "fps is " + recording::shortestText(options.fps),
                            "a frame rate > 0 [1/s]"));
  }
  if (options.framesPerBatch < 1) problems.push_back(diag(options.path, "framesPerBatch is 0", ">= 1"));
  if (options.queueFrames < 1) problems.push_back(diag(options.path, "queueFrames is 0", ">= 1"));
  if (auto st = checkOutputPath(options); !st) {
    for (const auto& d : st.errors()) problems.push_back(d);
  }
  if (!problems.empty()) return problems;

  try {
    if (options.force) removeWithCompanions(options.path);
    std::unique_ptr<Recorder> rec(new Recorder());
    Impl& impl = *rec->impl_;
    impl.options = options;
    const int rc = sqlite3_open_v2(options.path.c_str(), &impl.db,
                                   SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_NOMUTEX, nullptr);
    bool ok = rc == SQLITE_OK;
    if (!ok) impl.fail("cannot create the recording: " + impl.sqliteMessage());
    // WAL: readers see every committed batch and a killed writer loses only the open batch.
    // NORMAL sync: commits are not fsync'd one by one (durable against a process kill; a power
    // loss may drop the last batches but never corrupts the file).
    ok = ok && impl.exec("PRAGMA journal_mode=WAL") && impl.exec("PRAGMA synchronous=NORMAL") &&
         impl.writeScenario(scenario);
    if (!ok) {
      core::Diagnostic d = impl.error ? *impl.error : diag(options.path, "cannot create the recording");
      rec->impl_->closed = true;
      rec.reset();  // closes the connection before removing the file
      removeWithCompanions(options.path);
      return d;
    }
    impl.worker = std::thread([&impl] { impl.workerLoop(); });
    return rec;
  } catch (const std::exception& e) {
    removeWithCompanions(options.path);
    return diag(options.path, std::string("cannot create the recording: ") + e.what());
  }
}

bool Recorder::failed() const { return impl_ && impl_->failed.load(std::memory_order_acquire); }

void Recorder::push(sim::FramePtr frame) {
  if (!impl_ || impl_->closed || !frame || failed()) return;
  {
    std::unique_lock lock(impl_->mutex);
    impl_->notFull.wait(lock, [&] { return impl_->queue.size() < impl_->options.queueFrames || impl_->stopping; });
    if (impl_->stopping) return;
    impl_->queue.push_back(std::move(frame));
  }
  impl_->notEmpty.notify_one();
}

core::Status Recorder::close(bool completed) {
  Impl& impl = *impl_;
  if (impl.closed) return impl.closeResult ? *impl.closeResult : core::Status(core::Ok{});
  impl.closed = true;
  {
    std::lock_guard lock(impl.mutex);
    impl.stopping = true;
  }
  impl.notEmpty.notify_all();
  impl.notFull.notify_all();
  if (impl.worker.joinable()) impl.worker.join();

  if (impl.inTransaction) {  // only after an error: drop the failed batch
    impl.run(impl.rollback);
    impl.inTransaction = false;
  }
  impl.writeFinal(completed);
  // Fold the WAL into the main file and leave rollback-journal mode: one self-contained file.
  impl.exec("PRAGMA wal_checkpoint(TRUNCATE)");
  impl.exec("PRAGMA journal_mode=DELETE");
  for (Statement* s : {&impl.begin, &impl.commit, &impl.rollback, &impl.insertRow, &impl.insertFrameData,
                       &impl.insertFrame, &impl.insertEvent, &impl.insertAgent, &impl.insertAgentSeen,
                       &impl.updateExit, &impl.upsertMeta, &impl.insertAnimation, &impl.insertCoordination,
                       &impl.insertScript, &impl.insertRowBlock, &impl.insertAnimationBlock, &impl.insertHeight}) {
    *s = Statement();
  }
  if (impl.db != nullptr && sqlite3_close(impl.db) != SQLITE_OK) impl.fail("SQLite: cannot close the recording");
  impl.db = nullptr;
  impl.closeResult = impl.error ? core::Status(*impl.error) : core::Status(core::Ok{});
  return *impl.closeResult;
}

std::uint64_t Recorder::framesWritten() const {
  return impl_ ? impl_->committed.load(std::memory_order_acquire) : 0;
}

}  // namespace throng::recording
