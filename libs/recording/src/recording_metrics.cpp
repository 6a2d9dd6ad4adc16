// throng::io social metrics — computeMetrics (recording_social.hpp; definitions in
// docs/social-metrics.md): the evaluation of Park et al. (arrival rate at designated destinations
// over time, congestion at key points) plus group cohesion and Common Ground coordination
// statistics. Reads throng_events, throng_points, throng_agents, throng_coordinations and
// throng_script with a few queries, and trajectory_data in one pass ordered by frame (a uniform
// grid of key points answers "which points is this agent near" in constant time).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <unordered_map>

#include "recording_social_read.hpp"
#include "throng/recording/recording_social.hpp"

namespace throng::io {
namespace {

using namespace recording;

struct KeyPoint {
  std::uint32_t index = 0;
  std::string id, category;
  double x = 0.0, y = 0.0;
  std::vector<std::uint64_t> histogram;  ///< histogram[n] = frames with n agents within the radius
};

/// Key points bucketed in square cells of side `radius`: an agent is near a point only if the point
/// lies in the agent's cell or one of its 8 neighbours.
class PointGrid {
 public:
  PointGrid(const std::vector<KeyPoint>& points, double radius) : radius2_(radius * radius), cell_(radius) {
    if (points.empty()) return;
    minX_ = maxX_ = points[0].x;
    minY_ = maxY_ = points[0].y;
    for (const KeyPoint& p : points) {
      minX_ = std::min(minX_, p.x), maxX_ = std::max(maxX_, p.x);
      minY_ = std::min(minY_, p.y), maxY_ = std::max(maxY_, p.y);
    }
    // Coarser cells when the points are spread far apart relative to the radius (bounded memory).
    const double span = std::max(maxX_ - minX_, maxY_ - minY_);
    cell_ = std::max(cell_, span / 2048.0);
    nx_ = static_cast<int>((maxX_ - minX_) / cell_) + 1;
    ny_ = static_cast<int>((maxY_ - minY_) / cell_) + 1;
    cells_.resize(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_));
    for (std::size_t i = 0; i < points.size(); ++i) cells_[cellOf(points[i].x, points[i].y)].push_back(i);
  }

  /// Calls `f(point)` for every key point within the radius of (x, y).
  template <class F>
  void near(const std::vector<KeyPoint>& points, double x, double y, F&& f) const {
    if (cells_.empty() || !std::isfinite(x) || !std::isfinite(y)) return;
    const double r = std::sqrt(radius2_);
    if (x < minX_ - r || x > maxX_ + r || y < minY_ - r || y > maxY_ + r) return;
    const int cx = static_cast<int>(std::floor((x - minX_) / cell_));
    const int cy = static_cast<int>(std::floor((y - minY_) / cell_));
    for (int j = std::max(0, cy - 1); j <= std::min(ny_ - 1, cy + 1); ++j) {
      for (int i = std::max(0, cx - 1); i <= std::min(nx_ - 1, cx + 1); ++i) {
        for (const std::size_t p : cells_[static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(i)]) {
          const double dx = points[p].x - x, dy = points[p].y - y;
          if (dx * dx + dy * dy <= radius2_) f(p);
        }
      }
    }
  }

 private:
  std::size_t cellOf(double x, double y) const {
    const int i = std::clamp(static_cast<int>((x - minX_) / cell_), 0, nx_ - 1);
    const int j = std::clamp(static_cast<int>((y - minY_) / cell_), 0, ny_ - 1);
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(i);
  }
  double radius2_, cell_;
  double minX_ = 0, maxX_ = 0, minY_ = 0, maxY_ = 0;
  int nx_ = 0, ny_ = 0;
  std::vector<std::vector<std::size_t>> cells_;
};

void addHistogram(std::vector<std::uint64_t>& into, const std::vector<std::uint64_t>& from) {
  if (into.size() < from.size()) into.resize(from.size(), 0);
  for (std::size_t i = 0; i < from.size(); ++i) into[i] += from[i];
}

/// Mean, 95th percentile (nearest rank) and max of the counts a histogram holds, as densities.
DensityStats densityOf(const std::vector<std::uint64_t>& histogram, double area) {
  DensityStats d;
  std::uint64_t total = 0;
  double sum = 0.0;
  for (std::size_t n = 0; n < histogram.size(); ++n) {
    total += histogram[n];
    sum += static_cast<double>(n) * static_cast<double>(histogram[n]);
  }
  d.samples = total;
  if (total == 0) return d;
  d.mean = sum / static_cast<double>(total) / area;
  const auto rank = static_cast<std::uint64_t>(std::ceil(0.95 * static_cast<double>(total)));
  std::uint64_t seen = 0;
  for (std::size_t n = 0; n < histogram.size(); ++n) {
    seen += histogram[n];
    if (seen >= rank) {
      d.p95 = static_cast<double>(n) / area;
      break;
    }
  }
  for (std::size_t n = histogram.size(); n-- > 0;) {
    if (histogram[n] > 0) {
      d.max = static_cast<double>(n) / area;
      break;
    }
  }
  return d;
}

bool isDividePlan(const std::string& plan) { return plan == "divide_and_proceed" || plan == "divide_and_wait"; }

}  // namespace

core::Result<SocialMetrics> computeMetrics(const std::string& path, const MetricsOptions& options) {
  core::Diagnostics bad;
  auto positive = [&](double v, const char* name, const char* unit) {
    if (!(std::isfinite(v) && v > 0.0)) bad.push_back(readDiag(path, std::string("metrics option ") + name + " is " +
                                                                         std::to_string(v), std::string("> 0 ") + unit));
  };
  positive(options.radius, "radius", "m");
  positive(options.bin, "bin", "s");
  positive(options.cohesionRadius, "cohesion radius", "m");
  if (!bad.empty()) return bad;

  try {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return readDiag(path, "no such file");
    ReadOnlyDb db(path);
    if (auto d = openRecordingFile(path, db)) return *d;
    if (auto d = requireCommonGround(path, db)) return *d;
    const auto fps = recordingFps(db);
    if (!fps) return readDiag(path, "metadata 'fps' is missing or not > 0", "a frame rate > 0 [1/s]");
    FrameClock clock;
    if (!clock.load(db, *fps)) return readDiag(path, "cannot read throng_frames (" + dbFailure(db) + ")");

    SocialMetrics m;
    m.path = path;
    m.fps = *fps;
    m.radius = options.radius;
    m.bin = options.bin;
    m.cohesionRadius = options.cohesionRadius;
    m.commonGround = metaValue(db, kKeyCommonGround);
    {
      const bool frameData = tableExists(db, "frame_data").value_or(false);
      Statement s(db.get(), frameData ? "SELECT count(*) FROM frame_data" : "SELECT count(DISTINCT frame) FROM trajectory_data");
      if (!s.ok() || sqlite3_step(s.get()) != SQLITE_ROW) return readDiag(path, "cannot count frames (" + dbFailure(db) + ")");
      m.frames = static_cast<std::uint64_t>(std::max<sqlite3_int64>(0, sqlite3_column_int64(s.get(), 0)));
    }
    m.duration = m.frames > 1 ? clock.time(static_cast<std::int64_t>(m.frames) - 1) - clock.time(0) : 0.0;
    if (!std::isfinite(m.duration) || m.duration < 0.0) m.duration = 0.0;

    // Points: every point's category (for arrivals), key points (with a category) for congestion.
    std::vector<std::string> pointCategory;
    std::vector<KeyPoint> keys;
    if (tableExists(db, "throng_points").value_or(false)) {
      const bool hasCategory = columnExists(db, "throng_points", "category");
      Statement s(db.get(), hasCategory ? "SELECT idx, id, x, y, category FROM throng_points ORDER BY idx"
                                        : "SELECT idx, id, x, y, NULL FROM throng_points ORDER BY idx");
      if (!s.ok()) return readDiag(path, "cannot read throng_points (" + dbFailure(db) + ")");
      int rc = SQLITE_ROW;
      while ((rc = sqlite3_step(s.get())) == SQLITE_ROW) {
        const auto idx = columnId(s.get(), 0);
        if (!idx || *idx > 100000) {
          return readDiag(path, "throng_points: idx '" + columnText(s.get(), 0).substr(0, 40) + "'", "an index 0..100000");
        }
        const std::string category = columnText(s.get(), 4);
        if (*idx >= pointCategory.size()) pointCategory.resize(*idx + 1);
        pointCategory[*idx] = category;
        if (category.empty()) continue;
        KeyPoint k;
        k.index = *idx;
        k.id = columnText(s.get(), 1);
        k.category = category;
        k.x = sqlite3_column_double(s.get(), 2);
        k.y = sqlite3_column_double(s.get(), 3);
        if (!std::isfinite(k.x) || !std::isfinite(k.y)) {
          return readDiag(path, "throng_points idx " + std::to_string(*idx) + ": position is not finite");
        }
        keys.push_back(std::move(k));
        if (std::find(m.categories.begin(), m.categories.end(), category) == m.categories.end()) {
          m.categories.push_back(category);
        }
      }
      if (rc != SQLITE_DONE) return readDiag(path, "cannot read throng_points (" + dbFailure(db) + ")");
    }
    std::sort(m.categories.begin(), m.categories.end());

    // (a) arrivals and exits per bin; Reunited and GoalGenerated counts.
    constexpr std::size_t kMaxBins = 100000;
    const std::size_t bins = std::min<std::size_t>(kMaxBins, static_cast<std::size_t>(m.duration / options.bin) + 1);
    m.arrivals.resize(bins);
    for (std::size_t i = 0; i < bins; ++i) m.arrivals[i].start = static_cast<double>(i) * options.bin;
    if (tableExists(db, "throng_events").value_or(false)) {
      Statement s(db.get(), "SELECT frame, kind, a FROM throng_events "
                            "WHERE kind IN ('visit_start', 'exit', 'reunited', 'goal_generated')");
      if (!s.ok()) return readDiag(path, "cannot read throng_events (" + dbFailure(db) + ")");
      int rc = SQLITE_ROW;
      while ((rc = sqlite3_step(s.get())) == SQLITE_ROW) {
        const std::string kind = columnText(s.get(), 1);
        if (kind == "reunited") {
          ++m.coordinations.reunited;
          continue;
        }
        if (kind == "goal_generated") {
          ++m.coordinations.goalsGenerated;
          continue;
        }
        const double t = clock.time(sqlite3_column_int64(s.get(), 0));
        if (!std::isfinite(t) || t < 0.0) continue;
        const double b = std::floor(t / options.bin);
        if (b >= static_cast<double>(kMaxBins)) continue;
        const auto bi = static_cast<std::size_t>(b);
        while (m.arrivals.size() <= bi) {
          ArrivalBin extra;
          extra.start = static_cast<double>(m.arrivals.size()) * options.bin;
          m.arrivals.push_back(extra);
        }
        ArrivalBin& bin = m.arrivals[bi];
        if (kind == "exit") {
          ++bin.exits;
          ++m.exits;
        } else {
          const sqlite3_int64 point = sqlite3_column_int64(s.get(), 2);
          const std::string category = point >= 0 && static_cast<std::uint64_t>(point) < pointCategory.size()
                                           ? pointCategory[static_cast<std::size_t>(point)] : std::string();
          ++bin.visits;
          ++bin.byCategory[category];
          ++m.visits;
          ++m.visitsByCategory[category];
        }
      }
      if (rc != SQLITE_DONE) return readDiag(path, "cannot read throng_events (" + dbFailure(db) + ")");
    }
    const double minutes = m.duration / 60.0;
    if (minutes > 0.0) {
      m.visitsPerMinute = static_cast<double>(m.visits) / minutes;
      m.exitsPerMinute = static_cast<double>(m.exits) / minutes;
    }

    // (d) coordinations and micro-behaviours.
    auto coordinations = readCoordinations(path);
    if (!coordinations) return std::move(coordinations).takeErrors();
    CoordinationStats& cs = m.coordinations;
    double groundingSum = 0.0, divideSum = 0.0;
    for (const CoordinationInfo& c : *coordinations) {
      ++cs.total;
      ++cs.byPlan[c.plan];
      ++cs.byOutcome[c.outcome];
      ++cs.byTrigger[c.trigger];
      ++cs.byRelation[c.relation.empty() ? "none" : c.relation];
      if (c.outcome == "alone") continue;
      const double grounding = c.execute - c.start;
      if (std::isfinite(grounding)) {
        ++cs.groundingSamples;
        groundingSum += grounding;
        cs.maxGrounding = std::max(cs.maxGrounding, grounding);
      }
      const double divide = c.end - c.execute;
      if (isDividePlan(c.plan) && std::isfinite(divide)) {
        ++cs.divideSamples;
        divideSum += divide;
      }
    }
    if (cs.groundingSamples > 0) cs.meanGrounding = groundingSum / static_cast<double>(cs.groundingSamples);
    if (cs.divideSamples > 0) cs.meanDivide = divideSum / static_cast<double>(cs.divideSamples);
    {
      // One performance of a behaviour may be several entries (turn first, then the clip): count
      // each (coordination, agent, step, part, attempt, behaviour) once.
      Statement s(db.get(), "SELECT behaviour, count(*) FROM (SELECT DISTINCT coordination, agent, step, part, attempt, behaviour "
                     "FROM throng_script WHERE step BETWEEN 1 AND 6) GROUP BY behaviour");
      if (!s.ok()) return readDiag(path, "cannot read throng_script (" + dbFailure(db) + ")");
      int rc = SQLITE_ROW;
      while ((rc = sqlite3_step(s.get())) == SQLITE_ROW) {
        cs.microBehaviours[columnText(s.get(), 0)] += static_cast<std::uint64_t>(std::max<sqlite3_int64>(0, sqlite3_column_int64(s.get(), 1)));
      }
      if (rc != SQLITE_DONE) return readDiag(path, "cannot read throng_script (" + dbFailure(db) + ")");
    }

    // Groups with >= 2 agents (throng_agents.group_id) get a dense index for the cohesion pass.
    std::unordered_map<std::uint32_t, std::uint32_t> groupOfAgent;  // agent id -> dense group index
    std::size_t groupCount = 0;
    if (tableExists(db, "throng_agents").value_or(false)) {
      Statement s(db.get(), "SELECT id, group_id FROM throng_agents WHERE group_id IN "
                            "(SELECT group_id FROM throng_agents WHERE group_id IS NOT NULL "
                            "GROUP BY group_id HAVING count(*) >= 2)");
      if (!s.ok()) return readDiag(path, "cannot read throng_agents (" + dbFailure(db) + ")");
      std::unordered_map<std::uint32_t, std::uint32_t> dense;
      while (sqlite3_step(s.get()) == SQLITE_ROW) {
        const auto id = columnId(s.get(), 0), group = columnId(s.get(), 1);
        if (!id || !group) continue;
        const auto [it, added] = dense.emplace(*group, static_cast<std::uint32_t>(dense.size()));
        groupOfAgent[*id] = it->second;
      }
      groupCount = dense.size();
    }

    // (b) + (c): one pass over trajectory_data ordered by frame.
    const PointGrid grid(keys, options.radius);
    std::vector<std::uint32_t> nearCount(keys.size(), 0);
    std::vector<double> sumX(groupCount, 0.0), sumY(groupCount, 0.0), sumDist(groupCount, 0.0);
    std::vector<std::uint32_t> members(groupCount, 0);
    std::vector<bool> apart(groupCount, false), everPaired(groupCount, false);
    std::vector<std::uint32_t> touched;
    struct Member { std::uint32_t group; double x, y; };
    std::vector<Member> frameMembers;
    std::uint64_t framesSeen = 0, togetherFrames = 0;
    double cohesionSum = 0.0;
    const double cohesion2 = options.cohesionRadius * options.cohesionRadius;

    auto finishFrame = [&] {
      ++framesSeen;
      for (std::size_t p = 0; p < keys.size(); ++p) {
        auto& h = keys[p].histogram;
        if (h.size() <= nearCount[p]) h.resize(nearCount[p] + 1, 0);
        ++h[nearCount[p]];
        nearCount[p] = 0;
      }
      for (const Member& mb : frameMembers) {
        const double n = members[mb.group];
        if (n < 2) continue;
        const double dx = mb.x - sumX[mb.group] / n, dy = mb.y - sumY[mb.group] / n;
        const double d2 = dx * dx + dy * dy;
        sumDist[mb.group] += std::sqrt(d2);
        if (d2 > cohesion2) apart[mb.group] = true;
      }
      for (const std::uint32_t g : touched) {
        if (members[g] >= 2) {
          ++m.cohesion.groupFrames;
          cohesionSum += sumDist[g] / members[g];
          if (!apart[g]) ++togetherFrames;
          everPaired[g] = true;
        }
        sumX[g] = sumY[g] = sumDist[g] = 0.0;
        members[g] = 0;
        apart[g] = false;
      }
      touched.clear();
      frameMembers.clear();
    };

    Statement s(db.get(), "SELECT frame, id, pos_x, pos_y FROM trajectory_data ORDER BY frame");
    if (!s.ok()) return readDiag(path, "cannot read trajectory_data (" + dbFailure(db) + ")");
    bool any = false;
    sqlite3_int64 current = 0;
    int rc = SQLITE_ROW;
    while ((rc = sqlite3_step(s.get())) == SQLITE_ROW) {
      sqlite3_stmt* q = s.get();
      const sqlite3_int64 frame = sqlite3_column_int64(q, 0);
      if (!any || frame != current) {
        if (any) {
          finishFrame();
          if (options.progress && (framesSeen & 63) == 0 && m.frames > 0) {
            options.progress(std::min(1.0, static_cast<double>(framesSeen) / static_cast<double>(m.frames)));
          }
        }
        any = true;
        current = frame;
      }
      const double x = sqlite3_column_double(q, 2), y = sqlite3_column_double(q, 3);
      grid.near(keys, x, y, [&](std::size_t p) { ++nearCount[p]; });
      if (groupCount == 0 || !std::isfinite(x) || !std::isfinite(y)) continue;
      const auto id = columnId(q, 1);
      if (!id) continue;
      const auto it = groupOfAgent.find(*id);
      if (it == groupOfAgent.end()) continue;
      const std::uint32_t g = it->second;
      if (members[g] == 0) touched.push_back(g);
      ++members[g];
      sumX[g] += x;
      sumY[g] += y;
      frameMembers.push_back({g, x, y});
    }
    if (rc != SQLITE_DONE) return readDiag(path, "cannot read trajectory_data (" + dbFailure(db) + ")");
    if (any) finishFrame();
    if (options.progress) options.progress(1.0);

    // Frames without any agent (no trajectory rows) still count: nobody is near any point.
    const std::uint64_t emptyFrames = m.frames > framesSeen ? m.frames - framesSeen : 0;
    for (KeyPoint& k : keys) {
      if (k.histogram.empty()) k.histogram.resize(1, 0);
      k.histogram[0] += emptyFrames;
    }
    const double area = std::numbers::pi * options.radius * options.radius;
    std::vector<DensityStats> perPoint;
    for (const std::string& category : m.categories) {
      std::vector<std::uint64_t> merged;
      std::size_t count = 0;
      for (const KeyPoint& k : keys) {
        if (k.category != category) continue;
        addHistogram(merged, k.histogram);
        ++count;
      }
      DensityStats d = densityOf(merged, area);
      d.category = category;
      d.points = count;
      m.congestion.push_back(d);
    }
    for (const KeyPoint& k : keys) {
      DensityStats d = densityOf(k.histogram, area);
      d.category = k.category;
      d.point = k.id;
      d.pointIndex = k.index;
      d.points = 1;
      perPoint.push_back(d);
    }
    std::stable_sort(perPoint.begin(), perPoint.end(), [](const DensityStats& a, const DensityStats& b) {
      return a.mean != b.mean ? a.mean > b.mean : a.max > b.max;
    });
    perPoint.resize(std::min(perPoint.size(), options.worstPoints));
    m.worstPoints = std::move(perPoint);

    if (m.cohesion.groupFrames > 0) {
      m.cohesion.meanDistance = cohesionSum / static_cast<double>(m.cohesion.groupFrames);
      m.cohesion.shareTogether = static_cast<double>(togetherFrames) / static_cast<double>(m.cohesion.groupFrames);
    }
    m.cohesion.groups = static_cast<std::uint64_t>(std::count(everPaired.begin(), everPaired.end(), true));
    return m;
  } catch (const std::exception& e) {
    return readDiag(path, std::string("cannot read: ") + e.what());
  }
}

}  // namespace throng::io
