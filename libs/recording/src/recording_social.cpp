// throng::recording Common Ground recording readers — readCoordinations, readScript,
// readCoordinationScript and readAgentTrack (recording_social.hpp): read `throng_coordinations`,
// `throng_script`, `trajectory_data`, `throng_frames`, `throng_animation` and `throng_points`
// read-only and check every enum text and id, naming the table and row of the first bad value.
#include "throng/recording/recording_social.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <filesystem>
#include <sstream>

#include "recording_social_read.hpp"
#include "throng/common_ground/behaviour_db.hpp"

namespace throng::recording {
namespace {

using namespace recording;

bool oneOf(const std::string& v, std::initializer_list<const char*> allowed) {
  return std::any_of(allowed.begin(), allowed.end(), [&](const char* a) { return v == a; });
}

/// Checks the file and opens it; the diagnostic when it is not a recording.
std::optional<core::Diagnostic> openChecked(const std::string& path, ReadOnlyDb& db) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!fs::exists(st)) return readDiag(path, "no such file");
  if (!fs::is_regular_file(st)) return readDiag(path, "not a regular file");
  return openRecordingFile(path, db);
}

/// Point index → (id, category) from throng_points (category absent in old files).
std::vector<std::pair<std::string, std::string>> readPointNames(const ReadOnlyDb& db) {
  std::vector<std::pair<std::string, std::string>> out;
  if (!tableExists(db, "throng_points").value_or(false)) return out;
  const bool hasCategory = columnExists(db, "throng_points", "category");
  Statement s(db.get(), hasCategory ? "SELECT idx, id, category FROM throng_points ORDER BY idx"
                                    : "SELECT idx, id, NULL FROM throng_points ORDER BY idx");
  if (!s.ok()) return out;
  while (sqlite3_step(s.get()) == SQLITE_ROW) {
    const sqlite3_int64 idx = sqlite3_column_int64(s.get(), 0);
    if (idx < 0 || idx > 100000) continue;
    if (static_cast<std::size_t>(idx) >= out.size()) out.resize(static_cast<std::size_t>(idx) + 1);
    out[static_cast<std::size_t>(idx)] = {columnText(s.get(), 1), columnText(s.get(), 2)};
  }
  return out;
}

constexpr const char* kScriptColumns =
    "SELECT coordination, agent, seq, role, step, part, attempt, plan, motion, behaviour, target_type, "
    "target_agent, target_x, target_y, planned_start, planned_duration, start, duration, rowid FROM throng_script ";

/// Reads the script rows a statement returns, checking each; the first bad row is the diagnostic.
core::Result<std::vector<ScriptEntryInfo>> readScriptRows(const std::string& path, const ReadOnlyDb& db,
                                                          Statement& s) {
  std::vector<ScriptEntryInfo> out;
  int rc = SQLITE_ROW;
  while ((rc = sqlite3_step(s.get())) == SQLITE_ROW) {
    sqlite3_stmt* q = s.get();
    const std::string row = "throng_script row " + std::to_string(sqlite3_column_int64(q, 18));
    ScriptEntryInfo e;
    const auto coordination = columnId(q, 0), agent = columnId(q, 1), seq = columnId(q, 2);
    if (!coordination || !agent || !seq) {
      return readDiag(path, row + ": coordination, agent or seq is not an id",
                      "non-negative integers below 2^32");
    }
    e.coordination = *coordination;
    e.agent = *agent;
    e.seq = *seq;
    e.role = columnText(q, 3);
    if (!oneOf(e.role, {"initiator", "respondent", "companion"})) {
      return readDiag(path, row + ": role '" + e.role.substr(0, 40) + "'", "initiator, respondent or companion");
    }
    e.step = static_cast<int>(sqlite3_column_int64(q, 4));
    e.part = static_cast<int>(sqlite3_column_int64(q, 5));
    e.attempt = static_cast<int>(sqlite3_column_int64(q, 6));
    if (e.step < 1 || e.step > 7 || e.part < 0 || e.part > 26 || e.attempt < 0 || e.attempt > 1000) {
      return readDiag(path, row + ": step " + std::to_string(e.step) + ", part " + std::to_string(e.part) +
                                ", attempt " + std::to_string(e.attempt),
                      "step 1..7, part 0..26, attempt 0..1000");
    }
    e.plan = columnText(q, 7);
    if (!common_ground::planKindFromName(e.plan)) {
      return readDiag(path, row + ": plan '" + e.plan.substr(0, 40) + "'",
                      "divide_and_proceed, divide_and_wait, detour_together or resume");
    }
    e.motion = columnText(q, 8);
    e.behaviour = columnText(q, 9);
    e.targetType = columnText(q, 10);
    if (!oneOf(e.targetType, {"none", "point", "agent"})) {
      return readDiag(path, row + ": target_type '" + e.targetType.substr(0, 40) + "'", "none, point or agent");
    }
    if (e.targetType == "agent") {
      e.targetAgent = columnId(q, 11);
      if (!e.targetAgent) return readDiag(path, row + ": target_type is agent but target_agent is not an id");
    }
    e.targetX = columnReal(q, 12);
    e.targetY = columnReal(q, 13);
    e.plannedStart = columnReal(q, 14);
    e.plannedDuration = columnReal(q, 15);
    e.start = columnReal(q, 16);
    e.duration = columnReal(q, 17);
    out.push_back(std::move(e));
  }
  if (rc != SQLITE_DONE) return readDiag(path, "cannot read throng_script (" + dbFailure(db) + ")");
  return out;
}

}  // namespace

std::string scriptStepLabel(int step, int part, int attempt) {
  std::string label = std::to_string(step);
  if (part >= 1 && part <= 26) label += static_cast<char>('a' + part - 1);
  if (attempt > 0) label += "/retry " + std::to_string(attempt);
  return label;
}

core::Result<bool> hasCommonGroundData(const std::string& path) {
  try {
    ReadOnlyDb db(path);
    if (auto d = openChecked(path, db)) return *d;
    const auto d = requireCommonGround(path, db);
    if (!d) return true;
    if (d->what.rfind("no Common Ground", 0) == 0) return false;
    return *d;
  } catch (const std::exception& e) {
    return readDiag(path, std::string("cannot read: ") + e.what());
  }
}

core::Result<std::vector<CoordinationInfo>> readCoordinations(const std::string& path) {
  try {
    ReadOnlyDb db(path);
    if (auto d = openChecked(path, db)) return *d;
    if (auto d = requireCommonGround(path, db)) return *d;
    const auto points = readPointNames(db);
    Statement s(db.get(),
                "SELECT id, group_id, initiator, respondents, goal_point, goal_kind, trigger, relation, plan, "
                "outcome, retries, start, execute, end_time FROM throng_coordinations ORDER BY id");
    if (!s.ok()) return readDiag(path, "cannot read throng_coordinations (" + dbFailure(db) + ")");
    std::vector<CoordinationInfo> out;
    int rc = SQLITE_ROW;
    while ((rc = sqlite3_step(s.get())) == SQLITE_ROW) {
      sqlite3_stmt* q = s.get();
      const auto id = columnId(q, 0);
      if (!id) return readDiag(path, "throng_coordinations: id '" + columnText(q, 0).substr(0, 40) + "'", "an id");
      const std::string row = "throng_coordinations id " + std::to_string(*id);
      CoordinationInfo c;
      c.id = *id;
      const auto group = columnId(q, 1), initiator = columnId(q, 2), goal = columnId(q, 4), retries = columnId(q, 10);
      if (!group || !initiator || !goal || !retries) {
        return readDiag(path, row + ": group_id, initiator, goal_point or retries is not an id",
                        "non-negative integers below 2^32");
      }
      c.group = *group;
      c.initiator = *initiator;
      c.goalPoint = *goal;
      c.retries = *retries;
      std::istringstream respondents(columnText(q, 3));
      for (std::string word; respondents >> word;) {
        std::uint64_t v = 0;
        const bool digits = !word.empty() && word.size() <= 10 &&
                            std::all_of(word.begin(), word.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
        if (digits) v = std::stoull(word);
        if (!digits || v > 0xffffffffULL) {
          return readDiag(path, row + ": respondents has '" + word.substr(0, 40) + "'", "space-separated agent ids");
        }
        c.respondents.push_back(static_cast<std::uint32_t>(v));
      }
      if (c.goalPoint < points.size()) {
        c.goalPointId = points[c.goalPoint].first;
        c.goalCategory = points[c.goalPoint].second;
      }
      c.goalKind = columnText(q, 5);
      if (!common_ground::goalKindFromName(c.goalKind)) {
        return readDiag(path, row + ": goal_kind '" + c.goalKind.substr(0, 40) + "'", "personal or shared");
      }
      c.trigger = columnText(q, 6);
      if (!oneOf(c.trigger, {"need", "attraction"})) {
        return readDiag(path, row + ": trigger '" + c.trigger.substr(0, 40) + "'", "need or attraction");
      }
      c.relation = columnText(q, 7);
      if (!c.relation.empty() && !common_ground::relationFromName(c.relation)) {
        return readDiag(path, row + ": relation '" + c.relation.substr(0, 40) + "'", "A1..A6 or NULL");
      }
      c.plan = columnText(q, 8);
      if (!common_ground::planKindFromName(c.plan)) {
        return readDiag(path, row + ": plan '" + c.plan.substr(0, 40) + "'",
                        "divide_and_proceed, divide_and_wait, detour_together or resume");
      }
      c.outcome = columnText(q, 9);
      if (!oneOf(c.outcome, {"grounded", "failed", "alone"})) {
        return readDiag(path, row + ": outcome '" + c.outcome.substr(0, 40) + "'", "grounded, failed or alone");
      }
      c.start = columnReal(q, 11);
      c.execute = columnReal(q, 12);
      c.end = columnReal(q, 13);
      out.push_back(std::move(c));
    }
    if (rc != SQLITE_DONE) return readDiag(path, "cannot read throng_coordinations (" + dbFailure(db) + ")");
    return out;
  } catch (const std::exception& e) {
    return readDiag(path, std::string("cannot read: ") + e.what());
  }
}

core::Result<std::vector<CoordinationInfo>> readUnfinishedCoordinations(const std::string& path) {
  try {
    ReadOnlyDb db(path);
    if (auto d = openChecked(path, db)) return *d;
    if (auto d = requireCommonGround(path, db)) return *d;
    std::vector<CoordinationInfo> out;
    if (!tableExists(db, "throng_events").value_or(false)) return out;
    const auto points = readPointNames(db);
    const std::string dtText = metaValue(db, "throng_dt");
    char* endPtr = nullptr;
    const double dt = std::strtod(dtText.c_str(), &endPtr);
    const bool haveDt = !dtText.empty() && endPtr != dtText.c_str() && std::isfinite(dt) && dt > 0.0;
    FrameClock clock;
    if (!clock.load(db, recordingFps(db).value_or(1.0))) {
      return readDiag(path, "cannot read throng_frames (" + dbFailure(db) + ")");
    }
    Statement s(db.get(),
                "SELECT a, b, agent, tick, frame FROM throng_events WHERE kind = 'coordination_start' AND "
                "a NOT IN (SELECT id FROM throng_coordinations) ORDER BY a");
    Statement goal(db.get(),
                   "SELECT a, b FROM throng_events WHERE kind = 'goal_generated' AND agent = ? AND tick <= ? "
                   "ORDER BY tick DESC LIMIT 1");
    Statement actors(db.get(),
                     "SELECT agent, max(role = 'respondent') AS b, min(start) AS first FROM throng_script "
                     "WHERE coordination = ? GROUP BY agent ORDER BY b DESC, first, agent");
    if (!s.ok() || !goal.ok() || !actors.ok()) return readDiag(path, "cannot read throng_events (" + dbFailure(db) + ")");
    int rc = SQLITE_ROW;
    while ((rc = sqlite3_step(s.get())) == SQLITE_ROW) {
      sqlite3_stmt* q = s.get();
      const auto id = columnId(q, 0), group = columnId(q, 1), initiator = columnId(q, 2);
      if (!id || !group || !initiator) {
        return readDiag(path, "throng_events: a coordination_start with agent, a or b not an id",
                        "non-negative integers below 2^32");
      }
      CoordinationInfo c;
      c.finished = false;
      c.id = *id;
      c.group = *group;
      c.initiator = *initiator;
      const sqlite3_int64 tick = sqlite3_column_int64(q, 3);
      c.start = haveDt ? static_cast<double>(tick) * dt : clock.time(sqlite3_column_int64(q, 4));
      c.execute = c.end = std::numeric_limits<double>::quiet_NaN();
      sqlite3_reset(goal.get());
      bindInt(goal.get(), 1, c.initiator);
      bindInt(goal.get(), 2, tick);
      if (sqlite3_step(goal.get()) == SQLITE_ROW) {
        if (const auto point = columnId(goal.get(), 0)) {
          c.goalPoint = *point;
          if (c.goalPoint < points.size()) {
            c.goalPointId = points[c.goalPoint].first;
            c.goalCategory = points[c.goalPoint].second;
          }
        }
        c.trigger = sqlite3_column_int64(goal.get(), 1) == 1 ? "attraction" : "need";
      }
      sqlite3_reset(actors.get());
      bindInt(actors.get(), 1, c.id);
      while (sqlite3_step(actors.get()) == SQLITE_ROW) {
        const auto agent = columnId(actors.get(), 0);
        if (agent && *agent != c.initiator) c.respondents.push_back(*agent);
      }
      out.push_back(std::move(c));
    }
    if (rc != SQLITE_DONE) return readDiag(path, "cannot read throng_events (" + dbFailure(db) + ")");
    return out;
  } catch (const std::exception& e) {
    return readDiag(path, std::string("cannot read: ") + e.what());
  }
}

core::Result<std::vector<ScriptEntryInfo>> readScript(const std::string& path, std::uint32_t agent) {
  try {
    ReadOnlyDb db(path);
    if (auto d = openChecked(path, db)) return *d;
    if (auto d = requireCommonGround(path, db)) return *d;
    Statement s(db.get(), std::string(kScriptColumns) + "WHERE agent = ? ORDER BY coordination, seq");
    if (!s.ok()) return readDiag(path, "cannot read throng_script (" + dbFailure(db) + ")");
    bindInt(s.get(), 1, agent);
    return readScriptRows(path, db, s);
  } catch (const std::exception& e) {
    return readDiag(path, std::string("cannot read: ") + e.what());
  }
}

core::Result<std::vector<ScriptEntryInfo>> readCoordinationScript(const std::string& path,
                                                                  std::uint32_t coordination) {
  try {
    ReadOnlyDb db(path);
    if (auto d = openChecked(path, db)) return *d;
    if (auto d = requireCommonGround(path, db)) return *d;
    Statement s(db.get(), std::string(kScriptColumns) + "WHERE coordination = ? ORDER BY start, agent, seq");
    if (!s.ok()) return readDiag(path, "cannot read throng_script (" + dbFailure(db) + ")");
    bindInt(s.get(), 1, coordination);
    return readScriptRows(path, db, s);
  } catch (const std::exception& e) {
    return readDiag(path, std::string("cannot read: ") + e.what());
  }
}

core::Result<AgentTrack> readAgentTrack(const std::string& path, std::uint32_t agent) {
  try {
    ReadOnlyDb db(path);
    if (auto d = openChecked(path, db)) return *d;
    const auto fps = recordingFps(db);
    if (!fps) return readDiag(path, "metadata 'fps' is missing or not > 0", "a frame rate > 0 [1/s]");
    FrameClock clock;
    if (!clock.load(db, *fps)) return readDiag(path, "cannot read throng_frames (" + dbFailure(db) + ")");

    AgentTrack track;
    track.agent = agent;
    // The agent's lifetime bounds the frame range, so the (frame, id) index serves the query.
    std::int64_t first = 0, last = std::numeric_limits<std::int64_t>::max();
    if (tableExists(db, "throng_agents").value_or(false)) {
      Statement a(db.get(), "SELECT group_id, population_id, spawn_frame, exit_frame FROM throng_agents WHERE id = ?");
      if (!a.ok()) return readDiag(path, "cannot read throng_agents (" + dbFailure(db) + ")");
      bindInt(a.get(), 1, agent);
      if (sqlite3_step(a.get()) == SQLITE_ROW) {
        track.known = true;
        track.group = columnId(a.get(), 0);
        track.population = columnText(a.get(), 1);
        if (!columnNull(a.get(), 2)) first = std::max<std::int64_t>(0, sqlite3_column_int64(a.get(), 2));
        if (!columnNull(a.get(), 3)) last = sqlite3_column_int64(a.get(), 3);
      }
    }
    if (tableExists(db, "throng_clips").value_or(false)) {
      Statement c(db.get(), "SELECT idx, name FROM throng_clips ORDER BY idx");
      while (c.ok() && sqlite3_step(c.get()) == SQLITE_ROW) {
        const sqlite3_int64 idx = sqlite3_column_int64(c.get(), 0);
        if (idx < 0 || idx > 65535) continue;
        if (static_cast<std::size_t>(idx) >= track.clips.size()) track.clips.resize(static_cast<std::size_t>(idx) + 1);
        track.clips[static_cast<std::size_t>(idx)] = columnText(c.get(), 1);
      }
    }
    const bool hasAnimation = tableExists(db, "throng_animation").value_or(false);
    const std::string sql =
        std::string("SELECT t.frame, t.pos_x, t.pos_y, t.ori_x, t.ori_y, ") +
        (hasAnimation ? "a.clip, a.phase FROM trajectory_data t LEFT JOIN throng_animation a "
                        "ON a.frame = t.frame AND a.id = t.id "
                      : "NULL, NULL FROM trajectory_data t ") +
        "WHERE t.frame >= ? AND t.frame <= ? AND t.id = ? ORDER BY t.frame";
    Statement s(db.get(), sql);
    if (!s.ok()) return readDiag(path, "cannot read trajectory_data (" + dbFailure(db) + ")");
    bindInt(s.get(), 1, first);
    bindInt(s.get(), 2, last);
    bindInt(s.get(), 3, agent);
    int rc = SQLITE_ROW;
    while ((rc = sqlite3_step(s.get())) == SQLITE_ROW) {
      sqlite3_stmt* q = s.get();
      TrackSample t;
      const sqlite3_int64 frame = sqlite3_column_int64(q, 0);
      t.frame = static_cast<std::uint64_t>(std::max<sqlite3_int64>(0, frame));
      t.time = clock.time(frame);
      t.x = sqlite3_column_double(q, 1);
      t.y = sqlite3_column_double(q, 2);
      t.oriX = sqlite3_column_double(q, 3);
      t.oriY = sqlite3_column_double(q, 4);
      if (!columnNull(q, 5)) {
        t.clip = static_cast<int>(std::clamp<sqlite3_int64>(sqlite3_column_int64(q, 5), -1, 65535));
        t.phase = sqlite3_column_double(q, 6);
      }
      track.samples.push_back(t);
    }
    if (rc != SQLITE_DONE) return readDiag(path, "cannot read trajectory_data (" + dbFailure(db) + ")");
    if (!track.samples.empty()) track.known = true;
    // Velocity: central differences of the recorded positions.
    const std::size_t n = track.samples.size();
    for (std::size_t i = 0; i < n && n > 1; ++i) {
      const TrackSample& a = track.samples[i == 0 ? 0 : i - 1];
      const TrackSample& b = track.samples[i + 1 == n ? n - 1 : i + 1];
      const double dt = b.time - a.time;
      if (dt > 0.0 && std::isfinite(dt)) {
        track.samples[i].vx = (b.x - a.x) / dt;
        track.samples[i].vy = (b.y - a.y) / dt;
      }
    }
    return track;
  } catch (const std::exception& e) {
    return readDiag(path, std::string("cannot read: ") + e.what());
  }
}

}  // namespace throng::recording
