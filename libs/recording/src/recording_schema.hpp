// throng::recording recording schema — the table layout shared by the recorder (writes) and the
// recording reader (reads): JuPedSim's SQLite trajectory format, version 2, plus throng's own
// `throng_*` tables. docs/recording-format.md documents every table; keep the two in step.
//
// The JuPedSim part reproduces python_modules/jupedsim/jupedsim/sqlite_serialization.py as it
// was while DATABASE_VERSION was 2 (column types, NOT NULL, index names, metadata keys), because
// PedPy's loaders (pedpy/io/jupedsim_loader.py) read versions 1 and 2 only.
#pragma once
#include <sqlite3.h>

#include <cstdint>
#include <string>
#include <string>
#include <string_view>

namespace throng::recording {

inline constexpr int kFormatVersion = 2;  ///< metadata `version` written
inline constexpr int kMinReadVersion = 1; ///< versions the reader accepts
inline constexpr int kMaxReadVersion = 3;

// Metadata keys (JuPedSim's first, then throng's).
inline constexpr const char* kKeyVersion = "version";
inline constexpr const char* kKeyFps = "fps";
inline constexpr const char* kKeyXMin = "xmin";
inline constexpr const char* kKeyXMax = "xmax";
inline constexpr const char* kKeyYMin = "ymin";
inline constexpr const char* kKeyYMax = "ymax";
inline constexpr const char* kKeyThrongVersion = "throng_version";
inline constexpr const char* kKeySchema = "throng_schema";
inline constexpr const char* kKeyScenarioName = "throng_scenario_name";
inline constexpr const char* kKeyScenario = "throng_scenario";
inline constexpr const char* kKeySeed = "throng_seed";
inline constexpr const char* kKeyDt = "throng_dt";
inline constexpr const char* kKeyCompleted = "throng_completed";
inline constexpr const char* kKeyFrames = "throng_frames";
inline constexpr const char* kKeyDuration = "throng_duration";
inline constexpr const char* kKeyAgents = "throng_agents";
/// "on" / "off": whether the scenario's social section had Common Ground enabled; absent when the
/// scenario has no social section (no goals were generated).
inline constexpr const char* kKeyCommonGround = "throng_common_ground";
/// JSON object: each population's id → its avoidance model, {"name": …, every parameter: value}
/// (the scenario's choice with the model's defaults filled in, so a recording says which model
/// and values produced it even when the scenario named none).
inline constexpr const char* kKeyModels = "throng_models";
/// The SIMD path of the hot loops that wrote the recording ("avx2" or "portable", core::simdPath()):
/// every path gives the same trajectories, so this says how, not what; absent in older recordings.
inline constexpr const char* kKeySimd = "throng_simd";
/// The glTF / GLB world file's name (no directory) when the scenario was read from one; absent else.
inline constexpr const char* kKeyWorldFile = "throng_world_file";

inline constexpr const char* kSchemaNote =
    "JuPedSim trajectory format version 2 (trajectory_data, metadata, geometry, frame_data) "
    "plus throng_* tables; see docs/recording-format.md";

/// JuPedSim v2 tables, byte for byte the column definitions of its writer.
inline constexpr const char* kCreateJuPedSim =
    "CREATE TABLE trajectory_data ("
    "   frame INTEGER NOT NULL,"
    "   id INTEGER NOT NULL,"
    "   pos_x REAL NOT NULL,"
    "   pos_y REAL NOT NULL,"
    "   ori_x REAL NOT NULL,"
    "   ori_y REAL NOT NULL);"
    "CREATE TABLE metadata(key TEXT NOT NULL UNIQUE PRIMARY KEY, value TEXT NOT NULL);"
    "CREATE TABLE geometry("
    "   hash INTEGER NOT NULL, "
    "   wkt TEXT NOT NULL);"
    "CREATE UNIQUE INDEX geometry_hash on geometry( hash);"
    "CREATE TABLE frame_data("
    "   frame INTEGER NOT NULL,"
    "   geometry_hash INTEGER NOT NULL);";

/// Multi-level worlds only (a scenario with `terrain`): the height of every trajectory_data row.
/// JuPedSim's format is 2D; its readers ignore this table.
inline constexpr const char* kCreateHeights =
    "CREATE TABLE throng_heights("
    "   frame INTEGER NOT NULL,"
    "   id INTEGER NOT NULL,"
    "   z REAL NOT NULL);";
inline constexpr const char* kCreateHeightsIndex = "CREATE INDEX IF NOT EXISTS throng_heights_idx ON throng_heights(frame, id);";

/// The indexes over the two big per-frame tables (JuPedSim's frame_id_idx, throng_animation's),
/// created with the tables and kept up to date row by row: frames come in ascending order, so each
/// row's key goes at the end of its index, which costs the writer about a fifth more than the rows
/// alone, where building the index when the recording closes sorted every row again (the mall's
/// 1,300 s: 13 million rows a table, 6.3 s at close; docs/performance.md). A recording cut short
/// by a kill has its indexes too.
inline constexpr const char* kCreateFrameIndexes =
    "CREATE INDEX IF NOT EXISTS frame_id_idx ON trajectory_data(frame, id);"
    "CREATE INDEX IF NOT EXISTS throng_animation_idx ON throng_animation(frame, id);";

/// throng's own tables; JuPedSim's and PedPy's readers ignore them.
inline constexpr const char* kCreateThrong =
    "CREATE TABLE throng_frames("
    "   frame INTEGER NOT NULL PRIMARY KEY,"
    "   tick INTEGER NOT NULL,"
    "   time REAL NOT NULL,"
    "   agents INTEGER NOT NULL);"
    "CREATE TABLE throng_agents("
    "   id INTEGER NOT NULL PRIMARY KEY,"
    "   population INTEGER,"
    "   population_id TEXT,"
    "   group_id INTEGER,"
    "   spawn_frame INTEGER NOT NULL,"
    "   spawn_tick INTEGER,"
    "   exit_frame INTEGER,"
    "   exit_tick INTEGER);"
    "CREATE TABLE throng_events("
    "   frame INTEGER NOT NULL,"
    "   tick INTEGER NOT NULL,"
    "   agent INTEGER NOT NULL,"
    "   kind TEXT NOT NULL,"
    "   a INTEGER NOT NULL,"
    "   b INTEGER NOT NULL);"
    "CREATE INDEX throng_events_frame_idx ON throng_events(frame);"
    "CREATE TABLE throng_points("
    "   idx INTEGER NOT NULL PRIMARY KEY,"
    "   id TEXT NOT NULL,"
    "   kind TEXT NOT NULL,"
    "   x REAL NOT NULL,"
    "   y REAL NOT NULL,"
    "   radius REAL NOT NULL,"
    "   wkt TEXT,"
    "   stop INTEGER NOT NULL,"
    "   ori_x REAL NOT NULL,"
    "   ori_y REAL NOT NULL,"
    "   action TEXT NOT NULL,"
    "   action_duration REAL NOT NULL,"
    "   category TEXT);"
    "CREATE TABLE throng_clips("
    "   idx INTEGER NOT NULL PRIMARY KEY,"
    "   name TEXT NOT NULL,"
    "   file TEXT NOT NULL,"
    "   duration REAL NOT NULL,"
    "   loops INTEGER NOT NULL);"
    "CREATE TABLE throng_animation("
    "   frame INTEGER NOT NULL,"
    "   id INTEGER NOT NULL,"
    "   clip INTEGER NOT NULL,"
    "   phase REAL NOT NULL);"

    "CREATE TABLE throng_populations("
    "   idx INTEGER NOT NULL PRIMARY KEY,"
    "   id TEXT NOT NULL,"
    "   groups INTEGER NOT NULL,"
    "   size_min INTEGER NOT NULL,"
    "   size_max INTEGER NOT NULL,"
    "   start REAL NOT NULL,"
    "   speed_mean REAL NOT NULL,"
    "   speed_sd REAL NOT NULL,"
    "   speed_min REAL NOT NULL,"
    "   speed_max REAL NOT NULL,"
    "   radius REAL NOT NULL,"
    "   wander INTEGER NOT NULL,"
    "   goals TEXT NOT NULL,"
    "   spawn_kind TEXT NOT NULL,"
    "   spawn_wkt TEXT);"
    // Common Ground (Park, Peng, Quek, Cao): one row per interaction, one per action-script entry.
    "CREATE TABLE throng_coordinations("
    "   id INTEGER NOT NULL PRIMARY KEY,"
    "   group_id INTEGER NOT NULL,"
    "   initiator INTEGER NOT NULL,"
    "   respondents TEXT NOT NULL,"
    "   goal_point INTEGER NOT NULL,"
    "   goal_kind TEXT NOT NULL,"
    "   trigger TEXT NOT NULL,"
    "   relation TEXT,"
    "   plan TEXT NOT NULL,"
    "   outcome TEXT NOT NULL,"
    "   retries INTEGER NOT NULL,"
    "   start REAL,"
    "   execute REAL,"
    "   end_time REAL);"
    "CREATE TABLE throng_script("
    "   coordination INTEGER NOT NULL,"
    "   agent INTEGER NOT NULL,"
    "   seq INTEGER NOT NULL,"
    "   role TEXT NOT NULL,"
    "   step INTEGER NOT NULL,"
    "   part INTEGER NOT NULL,"
    "   attempt INTEGER NOT NULL,"
    "   plan TEXT NOT NULL,"
    "   motion TEXT NOT NULL,"
    "   behaviour TEXT NOT NULL,"
    "   target_type TEXT NOT NULL,"
    "   target_agent INTEGER,"
    "   target_x REAL,"
    "   target_y REAL,"
    "   planned_start REAL,"
    "   planned_duration REAL,"
    "   start REAL,"
    "   duration REAL);"
    "CREATE INDEX throng_script_agent_idx ON throng_script(agent);"
    "CREATE INDEX throng_script_coordination_idx ON throng_script(coordination, seq);";

/// Owns a prepared statement; finalized on destruction.
class Statement {
 public:
  Statement() = default;
  Statement(sqlite3* db, std::string_view sql) {
    rc_ = sqlite3_prepare_v2(db, sql.data(), static_cast<int>(sql.size()), &stmt_, nullptr);
  }
  ~Statement() { sqlite3_finalize(stmt_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  Statement(Statement&& o) noexcept : stmt_(o.stmt_), rc_(o.rc_) { o.stmt_ = nullptr; }
  Statement& operator=(Statement&& o) noexcept {
    if (this != &o) {
      sqlite3_finalize(stmt_);
      stmt_ = o.stmt_;
      rc_ = o.rc_;
      o.stmt_ = nullptr;
    }
    return *this;
  }

  [[nodiscard]] bool ok() const { return rc_ == SQLITE_OK && stmt_ != nullptr; }
  [[nodiscard]] sqlite3_stmt* get() const { return stmt_; }

 private:
  sqlite3_stmt* stmt_ = nullptr;
  int rc_ = SQLITE_ERROR;
};

inline void bindText(sqlite3_stmt* s, int i, std::string_view v) {
  sqlite3_bind_text(s, i, v.data(), static_cast<int>(v.size()), SQLITE_TRANSIENT);
}
inline void bindInt(sqlite3_stmt* s, int i, std::int64_t v) { sqlite3_bind_int64(s, i, v); }
inline void bindReal(sqlite3_stmt* s, int i, double v) { sqlite3_bind_double(s, i, v); }

/// Bounds the work one query may do (SQLite VM steps, checked every kProgressPeriod): a hostile
/// file cannot make the reader spin forever. Generous enough for recordings of 10^8 rows.
inline constexpr int kProgressPeriod = 10000;
inline constexpr std::uint64_t kMaxProgressCalls = 2'000'000;

/// Whether queries are bounded by kMaxProgressCalls (Bounded: summaries and metrics) or may read a
/// whole recording however large (Unbounded: the frame reader, whose caller bounds the size first).
enum class WorkLimit { Bounded, Unbounded };

class ReadOnlyDb {
 public:
  explicit ReadOnlyDb(const std::string& path, WorkLimit limit = WorkLimit::Bounded) {
    rc_ = sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READONLY | SQLITE_OPEN_NOMUTEX, nullptr);
    if (rc_ == SQLITE_OK) {
      // Untrusted content: no schema-defined functions with side effects, no writable schema.
      sqlite3_db_config(db_, SQLITE_DBCONFIG_TRUSTED_SCHEMA, 0, nullptr);
      sqlite3_db_config(db_, SQLITE_DBCONFIG_DEFENSIVE, 1, nullptr);
      if (limit == WorkLimit::Bounded) sqlite3_progress_handler(db_, kProgressPeriod, &ReadOnlyDb::onProgress, this);
    }
  }
  ~ReadOnlyDb() { sqlite3_close(db_); }
  ReadOnlyDb(const ReadOnlyDb&) = delete;
  ReadOnlyDb& operator=(const ReadOnlyDb&) = delete;

  [[nodiscard]] bool ok() const { return rc_ == SQLITE_OK; }
  [[nodiscard]] sqlite3* get() const { return db_; }
  [[nodiscard]] std::string message() const { return db_ ? sqlite3_errmsg(db_) : "out of memory"; }
  [[nodiscard]] bool interrupted() const { return progressCalls_ > kMaxProgressCalls; }

 private:
  static int onProgress(void* self) {
    auto* db = static_cast<ReadOnlyDb*>(self);
    return ++db->progressCalls_ > kMaxProgressCalls ? 1 : 0;
  }
  sqlite3* db_ = nullptr;
  int rc_ = SQLITE_ERROR;
  std::uint64_t progressCalls_ = 0;
};

/// FNV-1a (64 bit) of the WKT, as a signed integer: the `geometry.hash` key. JuPedSim uses
/// Python's salted hash(); readers only join on it, so any stable 64-bit value fits.
inline std::int64_t geometryHash(std::string_view wkt) {
  std::uint64_t h = 14695981039346656037ull;
  for (const unsigned char c : wkt) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return static_cast<std::int64_t>(h);
}

}  // namespace throng::recording
