// throng::recording recording reader — readRecordingSummary: opens a recording read-only and summarises
// it (format version, frames, agents, rows, fps, throng's provenance), one named step per part. Accepts any JuPedSim
// trajectory file (versions 1–3); throng's own tables are optional. Any other file, however
// damaged, gives one diagnostic naming the file and what was expected; nothing is written.
#include <sqlite3.h>

#include <cmath>
#include <filesystem>
#include <optional>
#include <string>

#include "recording_schema.hpp"
#include "recording_text.hpp"
#include "throng/recording/recorder.hpp"

namespace throng::recording {
namespace {

using recording::ReadOnlyDb;
using recording::Statement;

constexpr const char* kExpectedFile = "a JuPedSim trajectory file (SQLite, format version 1, 2 or 3)";

core::Diagnostic diag(const std::string& path, std::string what, std::string expected = kExpectedFile) {
  core::Diagnostic d;
  d.source = path;
  d.what = std::move(what);
  d.expected = std::move(expected);
  return d;
}

/// A query's outcome: no row is not an error; a failed step is.
struct Cell {
  bool failed = false;
  bool present = false;
  std::int64_t integer = 0;
  double real = 0.0;
  std::string text;
};

Cell queryOne(const ReadOnlyDb& db, const std::string& sql, const std::string& bindText = {}) {
  Cell cell;
  Statement s(db.get(), sql);
  if (!s.ok()) {
    cell.failed = true;
    return cell;
  }
  if (!bindText.empty()) {
    sqlite3_bind_text(s.get(), 1, bindText.data(), static_cast<int>(bindText.size()), SQLITE_TRANSIENT);
  }
  const int rc = sqlite3_step(s.get());
  if (rc == SQLITE_ROW) {
    cell.present = sqlite3_column_type(s.get(), 0) != SQLITE_NULL;
    cell.integer = sqlite3_column_int64(s.get(), 0);
    cell.real = sqlite3_column_double(s.get(), 0);
    const unsigned char* t = sqlite3_column_text(s.get(), 0);
    if (t != nullptr) cell.text.assign(reinterpret_cast<const char*>(t), static_cast<std::size_t>(sqlite3_column_bytes(s.get(), 0)));
  } else if (rc != SQLITE_DONE) {
    cell.failed = true;
  }
  return cell;
}

/// True when `name` is a real table (not a view: a view could compute anything).
std::optional<bool> hasTable(const ReadOnlyDb& db, const char* name) {
  const Cell c = queryOne(db, "SELECT count(*) FROM sqlite_master WHERE type = 'table' AND name = ?", name);
  if (c.failed) return std::nullopt;
  return c.integer > 0;
}

std::string failure(const ReadOnlyDb& db) {
  if (db.interrupted()) return "the file is too large or too complex to summarise";
  return db.message();
}

using Failure = std::optional<core::Diagnostic>;

/// One summary being read: each step fills part of `sum` or fails with a diagnostic.
class SummaryReader {
 public:
  SummaryReader(const std::string& path, const ReadOnlyDb& db, RecordingSummary& sum) : path_(path), db_(db), sum_(sum) {}

  /// JuPedSim's two tables; the first query reads the header, so a non-SQLite file fails here.
  Failure checkTables() const {
    for (const char* table : {"trajectory_data", "metadata"}) {
      const auto has = hasTable(db_, table);
      if (!has) return diag(path_, "not a readable SQLite database (" + failure(db_) + ")");
      if (!*has) return diag(path_, std::string("SQLite database without a '") + table + "' table");
    }
    return std::nullopt;
  }

  /// Format version and frame rate (metadata).
  Failure readVersionAndFps() {
    const Cell version = meta(recording::kKeyVersion);
    if (version.failed) return diag(path_, "cannot read metadata (" + failure(db_) + ")");
    if (!version.present) return diag(path_, "metadata has no 'version'");
    const auto v = recording::parseInt(version.text);
    if (!v || *v < recording::kMinReadVersion || *v > recording::kMaxReadVersion) {
      return diag(path_, "unsupported format version '" + version.text.substr(0, 40) + "'");
    }
    sum_.formatVersion = static_cast<int>(*v);

    const Cell fps = meta(recording::kKeyFps);
    if (fps.failed || !fps.present) return diag(path_, "metadata has no 'fps'");
    const auto fpsValue = recording::parseDouble(fps.text);
    if (!fpsValue || !std::isfinite(*fpsValue) || *fpsValue <= 0.0) {
      return diag(path_, "metadata 'fps' is '" + fps.text.substr(0, 40) + "'", "a frame rate > 0 [1/s]");
    }
    sum_.fps = *fpsValue;
    return std::nullopt;
  }

  /// Trajectory rows, frames and the duration from the first to the last frame.
  Failure countRowsAndFrames() {
    const Cell rows = queryOne(db_, "SELECT count(*) FROM trajectory_data");
    if (rows.failed) return diag(path_, "cannot read trajectory_data (" + failure(db_) + ")");
    sum_.rows = static_cast<std::uint64_t>(std::max<std::int64_t>(0, rows.integer));

    // Frames: one frame_data row per frame (versions 2 and 3); version 1 has only trajectories.
    const auto hasFrameData = hasTable(db_, "frame_data");
    Cell frames;
    if (hasFrameData.value_or(false)) {
      frames = queryOne(db_, "SELECT count(*) FROM frame_data");
    } else {
      frames = queryOne(db_, "SELECT count(DISTINCT frame) FROM trajectory_data");
    }
    if (frames.failed) return diag(path_, "cannot count frames (" + failure(db_) + ")");
    sum_.frames = static_cast<std::uint64_t>(std::max<std::int64_t>(0, frames.integer));
    sum_.duration = sum_.frames > 1 ? static_cast<double>(sum_.frames - 1) / sum_.fps : 0.0;  // first to last frame
    return std::nullopt;
  }

  /// throng's provenance (absent in files from other writers).
  void readProvenance() {
    sum_.throngVersion = meta(recording::kKeyThrongVersion).text;
    sum_.commonGround = meta(recording::kKeyCommonGround).text;
    sum_.models = meta(recording::kKeyModels).text;
    sum_.simd = meta(recording::kKeySimd).text;
    sum_.scenarioName = meta(recording::kKeyScenarioName).text;
    if (const auto seed = recording::parseInt(meta(recording::kKeySeed).text)) {
      sum_.seed = static_cast<std::uint64_t>(*seed);
    }
    sum_.completed = meta(recording::kKeyCompleted).text == "1";
  }

  /// Agents (throng_agents, else distinct trajectory ids) and, with throng_agents, per population.
  Failure countAgents() {
    const bool hasAgents = hasTable(db_, "throng_agents").value_or(false);
    const Cell agents = hasAgents ? queryOne(db_, "SELECT count(*) FROM throng_agents")
                                  : queryOne(db_, "SELECT count(DISTINCT id) FROM trajectory_data");
    if (agents.failed) return diag(path_, "cannot count agents (" + failure(db_) + ")");
    sum_.agents = static_cast<std::uint64_t>(std::max<std::int64_t>(0, agents.integer));
    if (!hasAgents) return std::nullopt;
    Statement s(db_.get(),
                "SELECT coalesce(population_id, '?'), count(*) FROM throng_agents "
                "GROUP BY population ORDER BY population");
    if (!s.ok()) return diag(path_, "cannot read throng_agents (" + failure(db_) + ")");
    int rc = SQLITE_ROW;
    while ((rc = sqlite3_step(s.get())) == SQLITE_ROW) {
      const unsigned char* t = sqlite3_column_text(s.get(), 0);
      std::string name = t ? std::string(reinterpret_cast<const char*>(t),
                                         static_cast<std::size_t>(sqlite3_column_bytes(s.get(), 0)))
                           : std::string("?");
      sum_.populations.emplace_back(std::move(name),
                                    static_cast<std::uint64_t>(std::max<sqlite3_int64>(0, sqlite3_column_int64(s.get(), 1))));
    }
    if (rc != SQLITE_DONE) return diag(path_, "cannot read throng_agents (" + failure(db_) + ")");
    return std::nullopt;
  }

  /// Events, Common Ground coordinations and the height range, each when its table exists.
  Failure readOptionalTables() {
    if (auto e = countIfPresent("throng_events", sum_.events)) return e;
    if (auto e = countIfPresent("throng_coordinations", sum_.coordinations)) return e;
    if (hasTable(db_, "throng_heights").value_or(false)) {
      const Cell low = queryOne(db_, "SELECT min(z) FROM throng_heights");
      const Cell high = queryOne(db_, "SELECT max(z) FROM throng_heights");
      if (low.failed || high.failed) return diag(path_, "cannot read throng_heights (" + failure(db_) + ")");
      if (low.present && high.present && std::isfinite(low.real) && std::isfinite(high.real)) {
        sum_.heights = std::make_pair(low.real, high.real);
      }
    }
    return std::nullopt;
  }

 private:
  [[nodiscard]] Cell meta(const char* key) const { return queryOne(db_, "SELECT value FROM metadata WHERE key = ?", key); }

  /// count(*) of `table` into `count` when the table exists.
  Failure countIfPresent(const char* table, std::uint64_t& count) const {
    if (!hasTable(db_, table).value_or(false)) return std::nullopt;
    const Cell rows = queryOne(db_, std::string("SELECT count(*) FROM ") + table);
    if (rows.failed) return diag(path_, std::string("cannot read ") + table + " (" + failure(db_) + ")");
    count = static_cast<std::uint64_t>(std::max<std::int64_t>(0, rows.integer));
    return std::nullopt;
  }

  const std::string& path_;
  const ReadOnlyDb& db_;
  RecordingSummary& sum_;
};

}  // namespace

core::Result<RecordingSummary> readRecordingSummary(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!fs::exists(st)) return diag(path, "no such file", kExpectedFile);
  if (!fs::is_regular_file(st)) return diag(path, "not a regular file", kExpectedFile);

  try {
    ReadOnlyDb db(path);
    if (!db.ok()) return diag(path, "cannot open: " + db.message());
    RecordingSummary sum;
    sum.path = path;
    SummaryReader reader(path, db, sum);
    if (auto e = reader.checkTables()) return *e;
    if (auto e = reader.readVersionAndFps()) return *e;
    if (auto e = reader.countRowsAndFrames()) return *e;
    reader.readProvenance();
    if (auto e = reader.countAgents()) return *e;
    if (auto e = reader.readOptionalTables()) return *e;
    return sum;
  } catch (const std::exception& e) {
    return diag(path, std::string("cannot read: ") + e.what());
  }
}

}  // namespace throng::recording
