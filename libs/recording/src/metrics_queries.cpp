// throng::recording metrics queries — computeMetrics (recording_social.hpp; definitions in
// docs/social-metrics.md): the evaluation of Park et al. (arrival rate at designated destinations
// over time, congestion at key points) plus group cohesion and Common Ground coordination
// statistics. This file reads: throng_frames, throng_points, throng_events, throng_coordinations,
// throng_script and throng_agents with a few queries, then trajectory_data in one pass ordered by
// frame; metrics_analysis.cpp turns what it reads into the metrics. Opens the file read-only.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <unordered_map>

#include "metrics_analysis.hpp"
#include "recording_social_read.hpp"
#include "throng/recording/recording_social.hpp"

namespace throng::recording {
namespace {

using namespace recording;
using metrics::KeyPoint;

constexpr std::uint32_t kMaxPointIndex = 100000;

/// Every option that must be > 0 and is not, as a diagnostic.
core::Diagnostics checkOptions(const std::string& path, const MetricsOptions& options) {
  core::Diagnostics bad;
  auto positive = [&](double v, const char* name, const char* unit) {
    if (!(std::isfinite(v) && v > 0.0)) bad.push_back(readDiag(path, std::string("metrics option ") + name + " is " +
                                                                         std::to_string(v), std::string("> 0 ") + unit));
  };
  positive(options.radius, "radius", "m");
  positive(options.bin, "bin", "s");
  positive(options.cohesionRadius, "cohesion radius", "m");
  return bad;
}

/// The points of a recording: every point's category (for arrivals) and the key points (those
/// with a category, for congestion).
struct Points {
  std::vector<std::string> category;  ///< by throng_points.idx
  std::vector<KeyPoint> keys;
};

/// The queries behind computeMetrics, over one recording opened read-only. Each step reads one
/// table (or one pass of trajectory_data) and fails with a diagnostic naming it.
class MetricsQueries {
 public:
  explicit MetricsQueries(const std::string& path) : path_(path), db_(path) {}

  /// A Common Ground recording with a frame rate; its frame times.
  std::optional<core::Diagnostic> open(double& fps) {
    if (auto d = openRecordingFile(path_, db_)) return d;
    if (auto d = requireCommonGround(path_, db_)) return d;
    const auto rate = recordingFps(db_);
    if (!rate) return readDiag(path_, "metadata 'fps' is missing or not > 0", "a frame rate > 0 [1/s]");
    fps = *rate;
    if (!clock_.load(db_, fps)) return cannotRead("throng_frames");
    return std::nullopt;
  }

  [[nodiscard]] std::string meta(const char* key) const { return metaValue(db_, key); }

  /// Frames (frame_data rows, else distinct trajectory frames) and the time from first to last.
  std::optional<core::Diagnostic> countFrames(SocialMetrics& m) const {
    const bool frameData = tableExists(db_, "frame_data").value_or(false);
    Statement s(db_.get(), frameData ? "SELECT count(*) FROM frame_data" : "SELECT count(DISTINCT frame) FROM trajectory_data");
    if (!s.ok() || sqlite3_step(s.get()) != SQLITE_ROW) {
      return readDiag(path_, "cannot count frames (" + dbFailure(db_) + ")");
    }
    m.frames = static_cast<std::uint64_t>(std::max<sqlite3_int64>(0, sqlite3_column_int64(s.get(), 0)));
    m.duration = m.frames > 1 ? clock_.time(static_cast<std::int64_t>(m.frames) - 1) - clock_.time(0) : 0.0;
    if (!std::isfinite(m.duration) || m.duration < 0.0) m.duration = 0.0;
    return std::nullopt;
  }

  /// throng_points (absent: no points); the key points' categories, sorted, into m.categories.
  std::optional<core::Diagnostic> readPoints(Points& points, SocialMetrics& m) const {
    if (tableExists(db_, "throng_points").value_or(false)) {
      const bool hasCategory = columnExists(db_, "throng_points", "category");
      Statement s(db_.get(), hasCategory ? "SELECT idx, id, x, y, category FROM throng_points ORDER BY idx"
                                         : "SELECT idx, id, x, y, NULL FROM throng_points ORDER BY idx");
      if (!s.ok()) return cannotRead("throng_points");
      int rc = SQLITE_ROW;
      while ((rc = sqlite3_step(s.get())) == SQLITE_ROW) {
        const auto idx = columnId(s.get(), 0);
        if (!idx || *idx > kMaxPointIndex) {
          return readDiag(path_, "throng_points: idx '" + columnText(s.get(), 0).substr(0, 40) + "'", "an index 0..100000");
        }
        const std::string category = columnText(s.get(), 4);
        if (*idx >= points.category.size()) points.category.resize(*idx + 1);
        points.category[*idx] = category;
        if (category.empty()) continue;
        KeyPoint k;
        k.index = *idx;
        k.id = columnText(s.get(), 1);
        k.category = category;
        k.x = sqlite3_column_double(s.get(), 2);
        k.y = sqlite3_column_double(s.get(), 3);
        if (!std::isfinite(k.x) || !std::isfinite(k.y)) {
          return readDiag(path_, "throng_points idx " + std::to_string(*idx) + ": position is not finite");
        }
        points.keys.push_back(std::move(k));
        if (std::find(m.categories.begin(), m.categories.end(), category) == m.categories.end()) {
          m.categories.push_back(category);
        }
      }
      if (rc != SQLITE_DONE) return cannotRead("throng_points");
    }
    std::sort(m.categories.begin(), m.categories.end());
    return std::nullopt;
  }

  /// The visit, exit, reunion and goal events of throng_events (absent: none), timed.
  std::optional<core::Diagnostic> readEvents(metrics::ArrivalTally& arrivals) const {
    if (!tableExists(db_, "throng_events").value_or(false)) return std::nullopt;
    Statement s(db_.get(), "SELECT frame, kind, a FROM throng_events "
                           "WHERE kind IN ('visit_start', 'exit', 'reunited', 'goal_generated')");
    if (!s.ok()) return cannotRead("throng_events");
    int rc = SQLITE_ROW;
    while ((rc = sqlite3_step(s.get())) == SQLITE_ROW) {
      const std::string kind = columnText(s.get(), 1);
      const metrics::EventKind k = kind == "reunited"         ? metrics::EventKind::Reunited
                                   : kind == "goal_generated" ? metrics::EventKind::GoalGenerated
                                   : kind == "exit"           ? metrics::EventKind::Exit
                                                              : metrics::EventKind::VisitStart;
      arrivals.add(k, clock_.time(sqlite3_column_int64(s.get(), 0)), sqlite3_column_int64(s.get(), 2));
    }
    if (rc != SQLITE_DONE) return cannotRead("throng_events");
    return std::nullopt;
  }

  /// Performances of each micro-behaviour (script steps 1..6). One performance may be several
  /// entries (turn first, then the clip): each (coordination, agent, step, part, attempt,
  /// behaviour) counts once.
  std::optional<core::Diagnostic> readMicroBehaviours(std::map<std::string, std::uint64_t>& counts) const {
    Statement s(db_.get(), "SELECT behaviour, count(*) FROM (SELECT DISTINCT coordination, agent, step, part, attempt, behaviour "
                           "FROM throng_script WHERE step BETWEEN 1 AND 6) GROUP BY behaviour");
    if (!s.ok()) return cannotRead("throng_script");
    int rc = SQLITE_ROW;
    while ((rc = sqlite3_step(s.get())) == SQLITE_ROW) {
      counts[columnText(s.get(), 0)] += static_cast<std::uint64_t>(std::max<sqlite3_int64>(0, sqlite3_column_int64(s.get(), 1)));
    }
    if (rc != SQLITE_DONE) return cannotRead("throng_script");
    return std::nullopt;
  }

  /// Agents of groups with >= 2 agents (throng_agents.group_id; absent: none), each group given a
  /// dense index: agent id → group index; `groupCount` groups.
  std::optional<core::Diagnostic> readGroups(std::unordered_map<std::uint32_t, std::uint32_t>& groupOfAgent,
                                             std::size_t& groupCount) const {
    if (!tableExists(db_, "throng_agents").value_or(false)) return std::nullopt;
    Statement s(db_.get(), "SELECT id, group_id FROM throng_agents WHERE group_id IN "
                           "(SELECT group_id FROM throng_agents WHERE group_id IS NOT NULL "
                           "GROUP BY group_id HAVING count(*) >= 2)");
    if (!s.ok()) return cannotRead("throng_agents");
    std::unordered_map<std::uint32_t, std::uint32_t> dense;
    while (sqlite3_step(s.get()) == SQLITE_ROW) {
      const auto id = columnId(s.get(), 0), group = columnId(s.get(), 1);
      if (!id || !group) continue;
      const auto [it, added] = dense.emplace(*group, static_cast<std::uint32_t>(dense.size()));
      groupOfAgent[*id] = it->second;
    }
    groupCount = dense.size();
    return std::nullopt;
  }

  /// One pass over trajectory_data ordered by frame, feeding both tallies and closing each frame;
  /// `progress` (may be empty) hears the fraction of `frames` done every 64 frames, then 1.
  std::optional<core::Diagnostic> passTrajectory(metrics::CongestionTally& congestion, metrics::CohesionTally& cohesion,
                                                 std::uint64_t frames, const std::function<void(double)>& progress) const {
    Statement s(db_.get(), "SELECT frame, id, pos_x, pos_y FROM trajectory_data ORDER BY frame");
    if (!s.ok()) return cannotRead("trajectory_data");
    std::uint64_t framesSeen = 0;
    auto endFrame = [&] {
      ++framesSeen;
      congestion.endFrame();
      cohesion.endFrame();
    };
    bool any = false;
    sqlite3_int64 current = 0;
    int rc = SQLITE_ROW;
    while ((rc = sqlite3_step(s.get())) == SQLITE_ROW) {
      sqlite3_stmt* q = s.get();
      const sqlite3_int64 frame = sqlite3_column_int64(q, 0);
      if (!any || frame != current) {
        if (any) {
          endFrame();
          if (progress && (framesSeen & 63) == 0 && frames > 0) {
            progress(std::min(1.0, static_cast<double>(framesSeen) / static_cast<double>(frames)));
          }
        }
        any = true;
        current = frame;
      }
      const double x = sqlite3_column_double(q, 2), y = sqlite3_column_double(q, 3);
      congestion.addAgent(x, y);
      if (!cohesion.tracksGroups()) continue;
      if (const auto id = columnId(q, 1)) cohesion.addAgent(*id, x, y);
    }
    if (rc != SQLITE_DONE) return cannotRead("trajectory_data");
    if (any) endFrame();
    if (progress) progress(1.0);
    return std::nullopt;
  }

 private:
  [[nodiscard]] core::Diagnostic cannotRead(const char* table) const {
    return readDiag(path_, std::string("cannot read ") + table + " (" + dbFailure(db_) + ")");
  }

  const std::string& path_;
  ReadOnlyDb db_;
  FrameClock clock_;
};

}  // namespace

core::Result<SocialMetrics> computeMetrics(const std::string& path, const MetricsOptions& options) {
  if (auto bad = checkOptions(path, options); !bad.empty()) return bad;
  try {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) return readDiag(path, "no such file");
    MetricsQueries queries(path);
    SocialMetrics m;
    m.path = path;
    if (auto d = queries.open(m.fps)) return *d;
    m.radius = options.radius;
    m.bin = options.bin;
    m.cohesionRadius = options.cohesionRadius;
    m.commonGround = queries.meta(kKeyCommonGround);
    if (auto d = queries.countFrames(m)) return *d;

    Points points;
    if (auto d = queries.readPoints(points, m)) return *d;
    metrics::ArrivalTally arrivals(options.bin, m.duration, std::move(points.category));
    if (auto d = queries.readEvents(arrivals)) return *d;
    auto coordinations = readCoordinations(path);
    if (!coordinations) return std::move(coordinations).takeErrors();
    std::map<std::string, std::uint64_t> microBehaviours;
    if (auto d = queries.readMicroBehaviours(microBehaviours)) return *d;
    std::unordered_map<std::uint32_t, std::uint32_t> groupOfAgent;
    std::size_t groupCount = 0;
    if (auto d = queries.readGroups(groupOfAgent, groupCount)) return *d;

    metrics::CongestionTally congestion(std::move(points.keys), options.radius);
    metrics::CohesionTally cohesion(std::move(groupOfAgent), groupCount, options.cohesionRadius);
    if (auto d = queries.passTrajectory(congestion, cohesion, m.frames, options.progress)) return *d;

    m.coordinations = metrics::coordinationStats(*coordinations);
    m.coordinations.microBehaviours = std::move(microBehaviours);
    arrivals.writeTo(m);
    congestion.writeTo(m, m.frames, options.worstPoints);
    m.cohesion = cohesion.result();
    return m;
  } catch (const std::exception& e) {
    return readDiag(path, std::string("cannot read: ") + e.what());
  }
}

}  // namespace throng::recording
