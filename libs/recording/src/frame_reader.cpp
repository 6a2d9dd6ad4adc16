// throng::recording recorded frames — readRecordedFrames (frame_reader.hpp): checks the file, reads the
// header (scenario, fps), sizes the frames (refusing what would not fit in memory), then fills them
// table by table — ticks and times, positions and headings, heights, clips and phases — and derives
// the clips and phases the file lacks. Reads the SQLite file read-only, once; writes nothing.
#include "throng/recording/frame_reader.hpp"

#include <sqlite3.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>

#include "recording_social_read.hpp"

namespace throng::recording {
namespace {

using recording::ReadOnlyDb;
using recording::Statement;

constexpr const char* kExpected =
    "a recording written by `throng run` (SQLite with trajectory_data and metadata holding throng_scenario)";
constexpr std::size_t kBytesPerRow = 32;     ///< estimate of one agent in one frame in memory
constexpr std::size_t kBytesPerFrame = 400;  ///< estimate of one empty sim::Frame with its control block
constexpr std::uint16_t kNoClip = 0xffff;    ///< not yet known: derived after every table is read
constexpr std::int64_t kMaxId = 0xffffffffLL;

using Failure = std::optional<core::Diagnostic>;

core::Diagnostic diag(const std::string& path, std::string what, std::string expected = kExpected) {
  core::Diagnostic d;
  d.source = path;
  d.what = std::move(what);
  d.expected = std::move(expected);
  return d;
}

/// The single value of `sql` (-1 for NULL); nullopt when the query fails.
std::optional<std::int64_t> scalar(const ReadOnlyDb& db, const char* sql) {
  Statement s(db.get(), sql);
  if (!s.ok() || sqlite3_step(s.get()) != SQLITE_ROW) return std::nullopt;
  return recording::columnNull(s.get(), 0) ? std::optional<std::int64_t>(-1) : sqlite3_column_int64(s.get(), 0);
}

/// A number with optional surrounding blanks (spaces, tabs); nullopt otherwise.
std::optional<double> parseNumber(std::string s) {
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.pop_back();
  std::size_t b = 0;
  while (b < s.size() && (s[b] == ' ' || s[b] == '\t')) ++b;
  double d = 0.0;
  const auto r = std::from_chars(s.data() + b, s.data() + s.size(), d);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size()) return std::nullopt;
  return d;
}

sim::AgentMode modeOf(std::uint16_t clip) {
  if (clip == sim::kClipIdle) return sim::AgentMode::Waiting;
  if (clip == sim::kClipWalk) return sim::AgentMode::Walking;
  return sim::AgentMode::Acting;
}

float wrapPhase(double p) {
  p -= std::floor(p);
  return p >= 1.0 ? 0.0f : static_cast<float>(p);
}

/// The row of agent `id` in a frame (ids ascending); nullopt when the frame has no such agent.
std::optional<std::size_t> rowOf(const sim::Frame& frame, std::int64_t id) {
  const auto it = std::lower_bound(frame.ids.begin(), frame.ids.end(), static_cast<std::uint32_t>(id));
  if (it == frame.ids.end() || *it != static_cast<std::uint32_t>(id)) return std::nullopt;
  return static_cast<std::size_t>(it - frame.ids.begin());
}

/// One recording being read: each step fills part of `out` and `frames`, or fails with a diagnostic.
class FrameReader {
 public:
  explicit FrameReader(const std::string& path) : path_(path), db_(path, recording::WorkLimit::Unbounded) {}

  /// The file opens as SQLite and has JuPedSim's two tables.
  Failure checkTables() {
    if (!db_.ok()) return diag(path_, "cannot open: " + db_.message());
    for (const char* table : {"trajectory_data", "metadata"}) {
      const auto has = recording::tableExists(db_, table);
      if (!has) return diag(path_, "not a readable SQLite database (" + db_.message() + ")");
      if (!*has) return diag(path_, std::string("SQLite database without a '") + table + "' table");
    }
    return std::nullopt;
  }

  /// The stored scenario and the frame rate.
  Failure readHeader() {
    out_.scenarioText = recording::metaValue(db_, "throng_scenario");
    if (out_.scenarioText.empty()) {
      return diag(path_, "metadata has no 'throng_scenario' (not written by `throng run`)");
    }
    out_.worldFile = recording::metaValue(db_, recording::kKeyWorldFile);
    const std::string fpsText = recording::metaValue(db_, "fps");
    const auto fps = parseNumber(fpsText);
    if (!fps || !std::isfinite(*fps) || *fps <= 0.0) {
      return diag(path_, "metadata 'fps' is '" + fpsText.substr(0, 40) + "'", "a frame rate > 0 [1/s]");
    }
    out_.fps = *fps;
    return std::nullopt;
  }

  /// How many frames and rows: refuses what would not fit in `maxBytes` before allocating, then
  /// makes one empty frame per frame number, timed frame / fps.
  Failure sizeFrames(std::size_t maxBytes) {
    hasFrameTable_ = recording::tableExists(db_, "throng_frames").value_or(false);
    const bool hasFrameData = recording::tableExists(db_, "frame_data").value_or(false);
    const auto rows = scalar(db_, "SELECT count(*) FROM trajectory_data");
    const auto minFrame = scalar(db_, "SELECT min(frame) FROM trajectory_data");
    const auto maxFrame = scalar(db_, "SELECT max(frame) FROM trajectory_data");
    const auto listed = hasFrameTable_ ? scalar(db_, "SELECT count(*) FROM throng_frames")
                        : hasFrameData ? scalar(db_, "SELECT count(*) FROM frame_data")
                                       : std::optional<std::int64_t>(0);
    if (!rows || !minFrame || !maxFrame || !listed) return cannotRead("trajectory_data");
    if (*rows > 0 && *minFrame < 0) return diag(path_, "trajectory_data has frame " + std::to_string(*minFrame), "frames numbered from 0");
    frameCount_ = std::max(*listed, *maxFrame + 1);
    if (frameCount_ <= 0) return diag(path_, "the recording has no frames", "at least one recorded frame");
    if (frameCount_ > kMaxRecordedFrames) {
      return diag(path_, std::to_string(frameCount_) + " frames", "at most " + std::to_string(kMaxRecordedFrames));
    }
    const double bytes = static_cast<double>(*rows) * kBytesPerRow + static_cast<double>(frameCount_) * kBytesPerFrame;
    if (bytes > static_cast<double>(maxBytes)) {
      return diag(path_, "recording of " + std::to_string(*rows) + " rows needs about " +
                             std::to_string(static_cast<long long>(bytes / (1 << 20))) + " MiB to replay",
                  "at most " + std::to_string(maxBytes >> 20) + " MiB");
    }
    const auto n = static_cast<std::size_t>(frameCount_);
    frames_.resize(n);
    out_.times.resize(n);
    for (std::size_t f = 0; f < n; ++f) {
      frames_[f] = std::make_shared<sim::Frame>();
      frames_[f]->tick = f;
      out_.times[f] = static_cast<double>(f) / out_.fps;
    }
    return std::nullopt;
  }

  /// Ticks and times from throng_frames when the file has it; then times relative to the first
  /// frame, never decreasing.
  Failure readTicksAndTimes() {
    if (hasFrameTable_) {
      Statement s(db_.get(), "SELECT frame, tick, time FROM throng_frames ORDER BY frame");
      if (!s.ok()) return cannotRead("throng_frames");
      int rc = 0;
      while ((rc = sqlite3_step(s.get())) == SQLITE_ROW) {
        const std::int64_t f = sqlite3_column_int64(s.get(), 0);
        if (f < 0 || f >= frameCount_) continue;
        frames_[static_cast<std::size_t>(f)]->tick =
            static_cast<std::uint64_t>(std::max<std::int64_t>(0, sqlite3_column_int64(s.get(), 1)));
        // tick × dt with a float dt (0.05f): rounded to the microsecond, 0.1000000015 s reads 0.1 s.
        const double t = std::round(sqlite3_column_double(s.get(), 2) * 1e6) / 1e6;
        if (std::isfinite(t)) out_.times[static_cast<std::size_t>(f)] = t;
      }
      if (rc != SQLITE_DONE) return cannotRead("throng_frames");
    }
    std::vector<double>& times = out_.times;
    const double t0 = times[0];
    for (std::size_t f = 0; f < times.size(); ++f) {
      times[f] = std::max(0.0, times[f] - t0);
      if (f > 0) times[f] = std::max(times[f], times[f - 1]);
    }
    return std::nullopt;
  }

  /// Positions and unit headings from trajectory_data (a duplicate row of an agent is skipped; a
  /// zero or non-finite heading reads as +x); clips not yet known, phases 0.
  Failure readPositions() {
    Statement s(db_.get(), "SELECT frame, id, pos_x, pos_y, ori_x, ori_y FROM trajectory_data ORDER BY frame, id");
    if (!s.ok()) return cannotRead("trajectory_data");
    int rc = 0;
    while ((rc = sqlite3_step(s.get())) == SQLITE_ROW) {
      const std::int64_t f = sqlite3_column_int64(s.get(), 0), id = sqlite3_column_int64(s.get(), 1);
      if (f < 0 || f >= frameCount_) continue;
      if (id < 0 || id > kMaxId) {
        return diag(path_, "trajectory_data: agent id " + std::to_string(id) + " in frame " + std::to_string(f),
                    "ids in [0, 2^32)");
      }
      sim::Frame& fr = *frames_[static_cast<std::size_t>(f)];
      if (!fr.ids.empty() && fr.ids.back() == static_cast<std::uint32_t>(id)) continue;  // duplicate row
      const double x = sqlite3_column_double(s.get(), 2), y = sqlite3_column_double(s.get(), 3);
      if (!std::isfinite(x) || !std::isfinite(y)) {
        return diag(path_, "trajectory_data: position of agent " + std::to_string(id) + " in frame " +
                               std::to_string(f) + " is not finite", "finite positions [m]");
      }
      double ox = sqlite3_column_double(s.get(), 4), oy = sqlite3_column_double(s.get(), 5);
      const double len = std::hypot(ox, oy);
      if (std::isfinite(len) && len > 1e-9) {
        ox /= len;
        oy /= len;
      } else {
        ox = 1.0;
        oy = 0.0;
      }
      fr.ids.push_back(static_cast<std::uint32_t>(id));
      fr.posX.push_back(static_cast<float>(x));
      fr.posY.push_back(static_cast<float>(y));
      fr.oriX.push_back(static_cast<float>(ox));
      fr.oriY.push_back(static_cast<float>(oy));
    }
    if (rc != SQLITE_DONE) return cannotRead("trajectory_data");
    for (auto& f : frames_) {
      const std::size_t k = f->ids.size();
      f->clip.assign(k, kNoClip);
      f->phase.assign(k, 0.0f);
      f->mode.assign(k, sim::AgentMode::Waiting);
    }
    return std::nullopt;
  }

  /// Heights from throng_heights, on a multi-level world (rows of unknown agents are skipped).
  Failure readHeights() {
    if (!recording::tableExists(db_, "throng_heights").value_or(false)) return std::nullopt;
    for (auto& f : frames_) f->posZ.assign(f->ids.size(), 0.0f);
    Statement s(db_.get(), "SELECT frame, id, z FROM throng_heights ORDER BY frame, id");
    if (!s.ok()) return cannotRead("throng_heights");
    int rc = 0;
    while ((rc = sqlite3_step(s.get())) == SQLITE_ROW) {
      const std::int64_t f = sqlite3_column_int64(s.get(), 0), id = sqlite3_column_int64(s.get(), 1);
      if (f < 0 || f >= frameCount_ || id < 0 || id > kMaxId) continue;
      sim::Frame& fr = *frames_[static_cast<std::size_t>(f)];
      const auto row = rowOf(fr, id);
      if (!row) continue;
      const double z = sqlite3_column_double(s.get(), 2);
      fr.posZ[*row] = std::isfinite(z) ? static_cast<float>(z) : 0.0f;
    }
    if (rc != SQLITE_DONE) return cannotRead("throng_heights");
    return std::nullopt;
  }

  /// Clips and phases from throng_animation, when recorded.
  Failure readAnimation() {
    if (!recording::tableExists(db_, "throng_animation").value_or(false)) return std::nullopt;
    Statement s(db_.get(), "SELECT frame, id, clip, phase FROM throng_animation ORDER BY frame, id");
    if (!s.ok()) return cannotRead("throng_animation");
    int rc = 0;
    while ((rc = sqlite3_step(s.get())) == SQLITE_ROW) {
      const std::int64_t f = sqlite3_column_int64(s.get(), 0), id = sqlite3_column_int64(s.get(), 1),
                         clip = sqlite3_column_int64(s.get(), 2);
      if (f < 0 || f >= frameCount_ || id < 0 || id > kMaxId || clip < 0 || clip >= kNoClip) continue;
      sim::Frame& fr = *frames_[static_cast<std::size_t>(f)];
      const auto row = rowOf(fr, id);
      if (!row) continue;
      const double phase = sqlite3_column_double(s.get(), 3);
      fr.clip[*row] = static_cast<std::uint16_t>(clip);
      fr.phase[*row] = std::isfinite(phase) ? wrapPhase(phase) : 0.0f;
      out_.hasAnimation = true;
    }
    if (rc != SQLITE_DONE) return cannotRead("throng_animation");
    return std::nullopt;
  }

  /// The clips and phases the file lacks, from each agent's motion since the previous frame (see
  /// kWalkCycle); every agent's mode from its clip; each frame's time.
  void deriveAnimation() {
    for (std::size_t f = 0; f < frames_.size(); ++f) {
      sim::Frame& cur = *frames_[f];
      cur.time = out_.times[f];
      const sim::Frame* prev = f > 0 ? frames_[f - 1].get() : nullptr;
      const double dt = prev ? out_.times[f] - out_.times[f - 1] : 0.0;
      std::size_t j = 0;
      for (std::size_t i = 0; i < cur.ids.size(); ++i) {
        bool seen = false;
        if (prev) {
          while (j < prev->ids.size() && prev->ids[j] < cur.ids[i]) ++j;
          seen = j < prev->ids.size() && prev->ids[j] == cur.ids[i];
        }
        if (cur.clip[i] == kNoClip) {
          const double dist = seen ? std::hypot(cur.posX[i] - prev->posX[j], cur.posY[i] - prev->posY[j]) : 0.0;
          const bool walking = dt > 0.0 && dist / dt > kStandingSpeed;
          const double before = seen ? prev->phase[j] : 0.0;
          cur.clip[i] = walking ? sim::kClipWalk : sim::kClipIdle;
          cur.phase[i] = wrapPhase(before + (walking ? dist / kWalkCycle : dt / kIdleCycle));
        }
        cur.mode[i] = modeOf(cur.clip[i]);
      }
    }
  }

  /// What was read, the frames made immutable.
  RecordedFrames finish() && {
    out_.frames.assign(frames_.begin(), frames_.end());
    return std::move(out_);
  }

 private:
  core::Diagnostic cannotRead(const char* table) const {
    return diag(path_, std::string("cannot read ") + table + " (" + db_.message() + ")");
  }

  const std::string& path_;
  ReadOnlyDb db_;
  RecordedFrames out_;
  std::vector<std::shared_ptr<sim::Frame>> frames_;
  std::int64_t frameCount_ = 0;
  bool hasFrameTable_ = false;
};

}  // namespace

core::Result<RecordedFrames> readRecordedFrames(const std::string& path, const FrameReadOptions& options) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!fs::exists(st)) return diag(path, "no such file");
  if (!fs::is_regular_file(st)) return diag(path, "not a regular file");

  FrameReader reader(path);
  if (auto e = reader.checkTables()) return *e;
  if (auto e = reader.readHeader()) return *e;
  if (auto e = reader.sizeFrames(options.maxBytes)) return *e;
  if (auto e = reader.readTicksAndTimes()) return *e;
  if (auto e = reader.readPositions()) return *e;
  if (auto e = reader.readHeights()) return *e;
  if (auto e = reader.readAnimation()) return *e;
  reader.deriveAnimation();
  return std::move(reader).finish();
}

}  // namespace throng::recording
