// throng::recording recording reader helpers — shared by recording_social.cpp (coordinations, scripts,
// tracks), the metrics queries and frame_reader.cpp (frames for replay): opening a recording
// read-only with the checks every reader makes, table/column probes, metadata values, NULL-aware
// column access and the diagnostics they give.
#pragma once
#include <sqlite3.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <cstdlib>
#include <string>
#include <vector>

#include "recording_schema.hpp"
#include "throng/core/diagnostic.hpp"

namespace throng::recording {

inline constexpr const char* kExpectedCgFile =
    "a recording made by 'throng run' of a scenario with a \"social\" section";

inline core::Diagnostic readDiag(const std::string& path, std::string what,
                                 std::string expected = kExpectedCgFile) {
  core::Diagnostic d;
  d.source = path;
  d.what = std::move(what);
  d.expected = std::move(expected);
  return d;
}

/// What went wrong in the last query, in words.
inline std::string dbFailure(const ReadOnlyDb& db) {
  if (db.interrupted()) return "the file is too large or too complex to read";
  return db.message();
}

/// True when `name` is a real table (a view could compute anything); nullopt when unreadable.
inline std::optional<bool> tableExists(const ReadOnlyDb& db, const char* name) {
  Statement s(db.get(), "SELECT count(*) FROM sqlite_master WHERE type = 'table' AND name = ?");
  if (!s.ok()) return std::nullopt;
  bindText(s.get(), 1, name);
  if (sqlite3_step(s.get()) != SQLITE_ROW) return std::nullopt;
  return sqlite3_column_int64(s.get(), 0) > 0;
}

inline bool columnExists(const ReadOnlyDb& db, const char* table, const char* column) {
  Statement s(db.get(), "SELECT count(*) FROM pragma_table_info(?) WHERE name = ?");
  if (!s.ok()) return false;
  bindText(s.get(), 1, table);
  bindText(s.get(), 2, column);
  return sqlite3_step(s.get()) == SQLITE_ROW && sqlite3_column_int64(s.get(), 0) > 0;
}

/// Opens `path` read-only and checks it is a JuPedSim trajectory file (trajectory_data, metadata).
/// Returns a diagnostic when it is not.
inline std::optional<core::Diagnostic> openRecordingFile(const std::string& path, ReadOnlyDb& db) {
  if (!db.ok()) return readDiag(path, "cannot open: " + db.message());
  for (const char* table : {"trajectory_data", "metadata"}) {
    const auto has = tableExists(db, table);
    if (!has) return readDiag(path, "not a readable SQLite database (" + dbFailure(db) + ")");
    if (!*has) return readDiag(path, std::string("SQLite database without a '") + table + "' table");
  }
  return std::nullopt;
}

/// The diagnostic for recordings without the Common Ground tables.
inline core::Diagnostic noCommonGround(const std::string& path) {
  return readDiag(path, "no Common Ground data in " + path + " (no throng_coordinations and throng_script tables)",
                  kExpectedCgFile);
}

/// Checks both Common Ground tables are present.
inline std::optional<core::Diagnostic> requireCommonGround(const std::string& path, const ReadOnlyDb& db) {
  for (const char* table : {"throng_coordinations", "throng_script"}) {
    const auto has = tableExists(db, table);
    if (!has) return readDiag(path, "not a readable SQLite database (" + dbFailure(db) + ")");
    if (!*has) return noCommonGround(path);
  }
  return std::nullopt;
}

inline std::string columnText(sqlite3_stmt* s, int i) {
  const unsigned char* t = sqlite3_column_text(s, i);
  if (t == nullptr) return {};
  return std::string(reinterpret_cast<const char*>(t), static_cast<std::size_t>(sqlite3_column_bytes(s, i)));
}

inline bool columnNull(sqlite3_stmt* s, int i) { return sqlite3_column_type(s, i) == SQLITE_NULL; }

/// A REAL column; NULL (written for a non-finite value) reads as NaN.
inline double columnReal(sqlite3_stmt* s, int i) {
  return columnNull(s, i) ? std::numeric_limits<double>::quiet_NaN() : sqlite3_column_double(s, i);
}

/// An id column: an integer in [0, 2^32); nullopt otherwise (NULL, text, negative, too large).
inline std::optional<std::uint32_t> columnId(sqlite3_stmt* s, int i) {
  if (sqlite3_column_type(s, i) != SQLITE_INTEGER) return std::nullopt;
  const sqlite3_int64 v = sqlite3_column_int64(s, i);
  if (v < 0 || v > 0xffffffffLL) return std::nullopt;
  return static_cast<std::uint32_t>(v);
}

/// A metadata value ("" when absent or unreadable).
inline std::string metaValue(const ReadOnlyDb& db, const char* key) {
  Statement s(db.get(), "SELECT value FROM metadata WHERE key = ?");
  if (!s.ok()) return {};
  bindText(s.get(), 1, key);
  if (sqlite3_step(s.get()) != SQLITE_ROW) return {};
  return columnText(s.get(), 0);
}

/// Frame number → simulation time: throng_frames.time where recorded, else frame / fps.
class FrameClock {
 public:
  /// Reads throng_frames when present; false when the table exists but cannot be read.
  bool load(const ReadOnlyDb& db, double fps) {
    fps_ = fps > 0.0 && std::isfinite(fps) ? fps : 1.0;
    if (!tableExists(db, "throng_frames").value_or(false)) return true;
    Statement s(db.get(), "SELECT frame, time FROM throng_frames ORDER BY frame");
    if (!s.ok()) return false;
    int rc = SQLITE_ROW;
    while ((rc = sqlite3_step(s.get())) == SQLITE_ROW) {
      const sqlite3_int64 f = sqlite3_column_int64(s.get(), 0);
      const double t = sqlite3_column_double(s.get(), 1);
      if (f < 0 || f >= kMaxDenseFrames || !std::isfinite(t)) continue;
      const auto i = static_cast<std::size_t>(f);
      if (i >= times_.size()) times_.resize(i + 1, std::numeric_limits<double>::quiet_NaN());
      times_[i] = t;
    }
    return rc == SQLITE_DONE;
  }
  [[nodiscard]] double time(std::int64_t frame) const {
    if (frame >= 0 && static_cast<std::uint64_t>(frame) < times_.size()) {
      const double t = times_[static_cast<std::size_t>(frame)];
      if (!std::isnan(t)) return t;
    }
    return static_cast<double>(frame) / fps_;
  }

 private:
  static constexpr std::int64_t kMaxDenseFrames = 1 << 26;  ///< a hostile frame number stays cheap
  double fps_ = 1.0;
  std::vector<double> times_;
};

/// The recording's fps (metadata), or nullopt when missing or not > 0.
inline std::optional<double> recordingFps(const ReadOnlyDb& db) {
  const std::string text = metaValue(db, "fps");
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end == text.c_str() || !std::isfinite(v) || v <= 0.0) return std::nullopt;
  return v;
}

}  // namespace throng::recording
