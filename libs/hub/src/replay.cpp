// throng::hub replay — Replay::open reads a `throng run` recording (trajectory_data for positions
// and headings, throng_animation for clips and phases, throng_frames for ticks and times, metadata
// for fps and the scenario JSON; docs/recording-format.md) into one immutable sim::Frame per frame;
// ReplayClock is the play / pause / seek / speed timeline. Reads the SQLite file read-only, once.
#include "throng/hub/replay.hpp"

#include <sqlite3.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <optional>
#include <vector>

namespace throng::hub {
namespace {

constexpr const char* kExpected =
    "a recording written by `throng run` (SQLite with trajectory_data and metadata holding throng_scenario)";
constexpr std::size_t kBytesPerRow = 32;     ///< estimate of one agent in one frame in memory
constexpr std::size_t kBytesPerFrame = 400;  ///< estimate of one empty sim::Frame with its control block
constexpr std::int64_t kMaxFrames = 100'000'000;
constexpr double kWalkCycle = 1.4;   ///< metres walked per walk cycle (docs/recording-format.md)
constexpr double kIdleCycle = 2.0;   ///< seconds per idle cycle
constexpr double kWalkSpeed = 0.1;   ///< slower than this counts as standing [m/s]
constexpr std::uint16_t kNoClip = 0xffff;
constexpr double kMinSpeed = 1.0 / 1024.0;  ///< slowest speed factor (stays > 0 as a float)

core::Diagnostic diag(const std::string& path, std::string what, std::string expected = kExpected) {
  core::Diagnostic d;
  d.source = path;
  d.what = std::move(what);
  d.expected = std::move(expected);
  return d;
}

class Db {
 public:
  explicit Db(const std::string& path) {
    rc_ = sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READONLY | SQLITE_OPEN_NOMUTEX, nullptr);
    if (rc_ == SQLITE_OK) {
      // Untrusted content: no schema-defined functions with side effects, no writable schema.
      sqlite3_db_config(db_, SQLITE_DBCONFIG_TRUSTED_SCHEMA, 0, nullptr);
      sqlite3_db_config(db_, SQLITE_DBCONFIG_DEFENSIVE, 1, nullptr);
    }
  }
  ~Db() { sqlite3_close(db_); }
  Db(const Db&) = delete;
  Db& operator=(const Db&) = delete;
  [[nodiscard]] bool ok() const { return rc_ == SQLITE_OK; }
  [[nodiscard]] sqlite3* get() const { return db_; }
  [[nodiscard]] std::string message() const { return db_ ? sqlite3_errmsg(db_) : "out of memory"; }

 private:
  sqlite3* db_ = nullptr;
  int rc_ = SQLITE_ERROR;
};

class Stmt {
 public:
  Stmt(const Db& db, const char* sql) { ok_ = sqlite3_prepare_v2(db.get(), sql, -1, &s_, nullptr) == SQLITE_OK && s_; }
  ~Stmt() { sqlite3_finalize(s_); }
  Stmt(const Stmt&) = delete;
  Stmt& operator=(const Stmt&) = delete;
  [[nodiscard]] bool ok() const { return ok_; }
  [[nodiscard]] sqlite3_stmt* get() const { return s_; }
  /// SQLITE_ROW, SQLITE_DONE or an error code.
  int step() { return sqlite3_step(s_); }
  [[nodiscard]] std::int64_t integer(int col) const { return sqlite3_column_int64(s_, col); }
  [[nodiscard]] double real(int col) const { return sqlite3_column_double(s_, col); }
  [[nodiscard]] bool isNull(int col) const { return sqlite3_column_type(s_, col) == SQLITE_NULL; }
  [[nodiscard]] std::string text(int col) const {
    const auto* t = sqlite3_column_text(s_, col);
    return t ? std::string(reinterpret_cast<const char*>(t), static_cast<std::size_t>(sqlite3_column_bytes(s_, col)))
             : std::string();
  }

 private:
  sqlite3_stmt* s_ = nullptr;
  bool ok_ = false;
};

/// True / false for a real table (not a view); nullopt when the query fails (not SQLite).
std::optional<bool> hasTable(const Db& db, const char* name) {
  Stmt s(db, "SELECT count(*) FROM sqlite_master WHERE type = 'table' AND name = ?");
  if (!s.ok()) return std::nullopt;
  sqlite3_bind_text(s.get(), 1, name, -1, SQLITE_TRANSIENT);
  if (s.step() != SQLITE_ROW) return std::nullopt;
  return s.integer(0) > 0;
}

std::optional<std::string> meta(const Db& db, const char* key) {
  Stmt s(db, "SELECT value FROM metadata WHERE key = ?");
  if (!s.ok()) return std::nullopt;
  sqlite3_bind_text(s.get(), 1, key, -1, SQLITE_TRANSIENT);
  if (s.step() != SQLITE_ROW || s.isNull(0)) return std::nullopt;
  return s.text(0);
}

std::optional<std::int64_t> scalar(const Db& db, const char* sql) {
  Stmt s(db, sql);
  if (!s.ok() || s.step() != SQLITE_ROW) return std::nullopt;
  return s.isNull(0) ? std::optional<std::int64_t>(-1) : s.integer(0);
}

std::optional<double> parseDouble(std::string s) {
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.pop_back();
  std::size_t b = 0;
  while (b < s.size() && (s[b] == ' ' || s[b] == '\t')) ++b;
  double d = 0.0;
  const auto r = std::from_chars(s.data() + b, s.data() + s.size(), d);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size()) return std::nullopt;
  return d;
}

sim::AgentMode modeOf(std::uint16_t clip) {
  if (clip == 0) return sim::AgentMode::Waiting;
  if (clip == 1) return sim::AgentMode::Walking;
  return sim::AgentMode::Acting;
}

float wrapPhase(double p) {
  p -= std::floor(p);
  return p >= 1.0 ? 0.0f : static_cast<float>(p);
}

}  // namespace

struct Replay::Data {
  std::string scenarioText;
  double fps = 0.0;
  bool hasAnimation = false;
  std::vector<double> times;  ///< per frame, relative to the first, non-decreasing [s]
  std::vector<sim::FramePtr> frames;
};

Replay::Replay(std::shared_ptr<const Data> data) : data_(std::move(data)) {}

core::Result<Replay> Replay::open(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!fs::exists(st)) return diag(path, "no such file");
  if (!fs::is_regular_file(st)) return diag(path, "not a regular file");

  Db db(path);
  if (!db.ok()) return diag(path, "cannot open: " + db.message());
  for (const char* table : {"trajectory_data", "metadata"}) {
    const auto has = hasTable(db, table);
    if (!has) return diag(path, "not a readable SQLite database (" + db.message() + ")");
    if (!*has) return diag(path, std::string("SQLite database without a '") + table + "' table");
  }

  auto data = std::make_shared<Data>();
  const auto scenario = meta(db, "throng_scenario");
  if (!scenario || scenario->empty()) {
    return diag(path, "metadata has no 'throng_scenario' (not written by `throng run`)");
  }
  data->scenarioText = *scenario;
  const auto fpsText = meta(db, "fps");
  const auto fps = fpsText ? parseDouble(*fpsText) : std::nullopt;
  if (!fps || !std::isfinite(*fps) || *fps <= 0.0) {
    return diag(path, "metadata 'fps' is '" + fpsText.value_or("").substr(0, 40) + "'", "a frame rate > 0 [1/s]");
  }
  data->fps = *fps;

  // How many frames and rows: refuse what would not fit in memory before allocating.
  const bool hasFrames = hasTable(db, "throng_frames").value_or(false);
  const bool hasFrameData = hasTable(db, "frame_data").value_or(false);
  const auto rows = scalar(db, "SELECT count(*) FROM trajectory_data");
  const auto minFrame = scalar(db, "SELECT min(frame) FROM trajectory_data");
  const auto maxFrame = scalar(db, "SELECT max(frame) FROM trajectory_data");
  const auto listed = hasFrames      ? scalar(db, "SELECT count(*) FROM throng_frames")
                      : hasFrameData ? scalar(db, "SELECT count(*) FROM frame_data")
                                     : std::optional<std::int64_t>(0);
  if (!rows || !minFrame || !maxFrame || !listed) return diag(path, "cannot read trajectory_data (" + db.message() + ")");
  if (*rows > 0 && *minFrame < 0) return diag(path, "trajectory_data has frame " + std::to_string(*minFrame), "frames numbered from 0");
  const std::int64_t frameCount = std::max(*listed, *maxFrame + 1);
  if (frameCount <= 0) return diag(path, "the recording has no frames", "at least one recorded frame");
  if (frameCount > kMaxFrames) return diag(path, std::to_string(frameCount) + " frames", "at most " + std::to_string(kMaxFrames));
  const double bytes = static_cast<double>(*rows) * kBytesPerRow + static_cast<double>(frameCount) * kBytesPerFrame;
  if (bytes > static_cast<double>(kMaxReplayBytes)) {
    return diag(path, "recording of " + std::to_string(*rows) + " rows needs about " +
                          std::to_string(static_cast<long long>(bytes / (1 << 20))) + " MiB to replay",
                "at most " + std::to_string(kMaxReplayBytes >> 20) + " MiB");
  }

  const auto n = static_cast<std::size_t>(frameCount);
  std::vector<std::shared_ptr<sim::Frame>> frames(n);
  for (std::size_t f = 0; f < n; ++f) {
    frames[f] = std::make_shared<sim::Frame>();
    frames[f]->tick = f;
  }
  data->times.resize(n);
  for (std::size_t f = 0; f < n; ++f) data->times[f] = static_cast<double>(f) / data->fps;

  // Ticks and times of the frames, when throng_frames has them.
  if (hasFrames) {
    Stmt s(db, "SELECT frame, tick, time FROM throng_frames ORDER BY frame");
    if (!s.ok()) return diag(path, "cannot read throng_frames (" + db.message() + ")");
    int rc = 0;
    while ((rc = s.step()) == SQLITE_ROW) {
      const std::int64_t f = s.integer(0);
      if (f < 0 || f >= frameCount) continue;
      frames[static_cast<std::size_t>(f)]->tick = static_cast<std::uint64_t>(std::max<std::int64_t>(0, s.integer(1)));
      // tick × dt with a float dt (0.05f): rounded to the microsecond, 0.1000000015 s reads 0.1 s.
      const double t = std::round(s.real(2) * 1e6) / 1e6;
      if (std::isfinite(t)) data->times[static_cast<std::size_t>(f)] = t;
    }
    if (rc != SQLITE_DONE) return diag(path, "cannot read throng_frames (" + db.message() + ")");
  }
  const double t0 = data->times[0];
  for (std::size_t f = 0; f < n; ++f) {
    data->times[f] = std::max(0.0, data->times[f] - t0);
    if (f > 0) data->times[f] = std::max(data->times[f], data->times[f - 1]);
  }

  // Positions and headings.
  {
    Stmt s(db, "SELECT frame, id, pos_x, pos_y, ori_x, ori_y FROM trajectory_data ORDER BY frame, id");
    if (!s.ok()) return diag(path, "cannot read trajectory_data (" + db.message() + ")");
    int rc = 0;
    while ((rc = s.step()) == SQLITE_ROW) {
      const std::int64_t f = s.integer(0), id = s.integer(1);
      if (f < 0 || f >= frameCount) continue;
      if (id < 0 || id > 0xffffffffLL) {
        return diag(path, "trajectory_data: agent id " + std::to_string(id) + " in frame " + std::to_string(f),
                    "ids in [0, 2^32)");
      }
      sim::Frame& fr = *frames[static_cast<std::size_t>(f)];
      if (!fr.ids.empty() && fr.ids.back() == static_cast<std::uint32_t>(id)) continue;  // duplicate row
      const double x = s.real(2), y = s.real(3);
      if (!std::isfinite(x) || !std::isfinite(y)) {
        return diag(path, "trajectory_data: position of agent " + std::to_string(id) + " in frame " +
                              std::to_string(f) + " is not finite", "finite positions [m]");
      }
      double ox = s.real(4), oy = s.real(5);
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
    if (rc != SQLITE_DONE) return diag(path, "cannot read trajectory_data (" + db.message() + ")");
  }
  for (auto& f : frames) {
    const std::size_t k = f->ids.size();
    f->clip.assign(k, kNoClip);
    f->phase.assign(k, 0.0f);
    f->mode.assign(k, sim::AgentMode::Waiting);
  }

  // Heights, on a multi-level world.
  if (hasTable(db, "throng_heights").value_or(false)) {
    for (auto& f : frames) f->posZ.assign(f->ids.size(), 0.0f);
    Stmt s(db, "SELECT frame, id, z FROM throng_heights ORDER BY frame, id");
    if (!s.ok()) return diag(path, "cannot read throng_heights (" + db.message() + ")");
    int rc = 0;
    while ((rc = s.step()) == SQLITE_ROW) {
      const std::int64_t f = s.integer(0), id = s.integer(1);
      if (f < 0 || f >= frameCount || id < 0 || id > 0xffffffffLL) continue;
      sim::Frame& fr = *frames[static_cast<std::size_t>(f)];
      const auto it = std::lower_bound(fr.ids.begin(), fr.ids.end(), static_cast<std::uint32_t>(id));
      if (it == fr.ids.end() || *it != static_cast<std::uint32_t>(id)) continue;
      const double z = s.real(2);
      fr.posZ[static_cast<std::size_t>(it - fr.ids.begin())] = std::isfinite(z) ? static_cast<float>(z) : 0.0f;
    }
    if (rc != SQLITE_DONE) return diag(path, "cannot read throng_heights (" + db.message() + ")");
  }

  // Clips and phases, when recorded.
  if (hasTable(db, "throng_animation").value_or(false)) {
    Stmt s(db, "SELECT frame, id, clip, phase FROM throng_animation ORDER BY frame, id");
    if (!s.ok()) return diag(path, "cannot read throng_animation (" + db.message() + ")");
    int rc = 0;
    while ((rc = s.step()) == SQLITE_ROW) {
      const std::int64_t f = s.integer(0), id = s.integer(1), clip = s.integer(2);
      if (f < 0 || f >= frameCount || id < 0 || id > 0xffffffffLL || clip < 0 || clip >= kNoClip) continue;
      sim::Frame& fr = *frames[static_cast<std::size_t>(f)];
      const auto it = std::lower_bound(fr.ids.begin(), fr.ids.end(), static_cast<std::uint32_t>(id));
      if (it == fr.ids.end() || *it != static_cast<std::uint32_t>(id)) continue;
      const auto i = static_cast<std::size_t>(it - fr.ids.begin());
      const double phase = s.real(3);
      fr.clip[i] = static_cast<std::uint16_t>(clip);
      fr.phase[i] = std::isfinite(phase) ? wrapPhase(phase) : 0.0f;
      data->hasAnimation = true;
    }
    if (rc != SQLITE_DONE) return diag(path, "cannot read throng_animation (" + db.message() + ")");
  }

  // The clips and phases the file lacks (velocities are not kept: 8 bytes per row, unused by the hub).
  for (std::size_t f = 0; f < n; ++f) {
    sim::Frame& cur = *frames[f];
    cur.time = data->times[f];
    const sim::Frame* prev = f > 0 ? frames[f - 1].get() : nullptr;
    const double dt = prev ? data->times[f] - data->times[f - 1] : 0.0;
    std::size_t j = 0;
    for (std::size_t i = 0; i < cur.ids.size(); ++i) {
      bool seen = false;
      if (prev) {
        while (j < prev->ids.size() && prev->ids[j] < cur.ids[i]) ++j;
        seen = j < prev->ids.size() && prev->ids[j] == cur.ids[i];
      }
      if (cur.clip[i] == kNoClip) {
        const double dist = seen ? std::hypot(cur.posX[i] - prev->posX[j], cur.posY[i] - prev->posY[j]) : 0.0;
        const bool walking = dt > 0.0 && dist / dt > kWalkSpeed;
        const double before = seen ? prev->phase[j] : 0.0;
        cur.clip[i] = walking ? 1 : 0;
        cur.phase[i] = wrapPhase(before + (walking ? dist / kWalkCycle : dt / kIdleCycle));
      }
      cur.mode[i] = modeOf(cur.clip[i]);
    }
  }

  data->frames.assign(frames.begin(), frames.end());
  return Replay(std::move(data));
}

double Replay::duration() const { return data_->times.back(); }
double Replay::fps() const { return data_->fps; }
std::size_t Replay::frameCount() const { return data_->frames.size(); }
const std::string& Replay::scenarioText() const { return data_->scenarioText; }
bool Replay::hasAnimation() const { return data_->hasAnimation; }

std::size_t Replay::frameIndexAt(double t) const {
  const auto& times = data_->times;
  if (!(t > 0.0)) return 0;  // also NaN
  const auto it = std::upper_bound(times.begin(), times.end(), t);
  return static_cast<std::size_t>(it - times.begin()) - 1;  // times[0] == 0 ≤ t: it > begin
}

double Replay::frameTime(std::size_t index) const {
  return data_->times[std::min(index, data_->times.size() - 1)];
}

sim::FramePtr Replay::frameAt(double t) const { return data_->frames[frameIndexAt(t)]; }

// --- ReplayClock ----------------------------------------------------------------------------

ReplayClock::ReplayClock(double duration, bool playing)
    : duration_(std::isfinite(duration) && duration > 0.0 ? duration : 0.0), playing_(playing) {}

bool ReplayClock::play() {
  bool changed = !playing_;
  if (time_ >= duration_ && duration_ > 0.0) {  // at the end: start again
    time_ = 0.0;
    changed = true;
  }
  playing_ = true;
  return changed;
}

bool ReplayClock::pause() {
  const bool changed = playing_;
  playing_ = false;
  return changed;
}

bool ReplayClock::seek(double seconds) {
  if (std::isnan(seconds)) return false;
  const double t = std::clamp(seconds, 0.0, duration_);
  const bool changed = t != time_;
  time_ = t;
  return changed;
}

bool ReplayClock::setSpeed(double factor) {
  if (std::isnan(factor)) return false;
  const double s = std::clamp(factor, kMinSpeed, protocol::kMaxReplaySpeed);
  const bool changed = s != speed_;
  speed_ = s;
  return changed;
}

bool ReplayClock::apply(protocol::ReplayCommand command, double value) {
  switch (command) {
    case protocol::ReplayCommand::Play: return play();
    case protocol::ReplayCommand::Pause: return pause();
    case protocol::ReplayCommand::Seek: return seek(value);
    case protocol::ReplayCommand::Speed: return setSpeed(value);
  }
  return false;
}

bool ReplayClock::advance(double wallSeconds) {
  if (!playing_ || !(wallSeconds > 0.0)) return false;
  time_ = std::min(duration_, time_ + wallSeconds * speed_);
  if (time_ >= duration_) {
    playing_ = false;
    return true;
  }
  return false;
}

protocol::ReplayStatus ReplayClock::status() const {
  return protocol::ReplayStatus{time_, duration_, playing_, static_cast<float>(speed_)};
}

}  // namespace throng::hub
