// throng::recording metrics analysis — the pure half of computeMetrics (recording_social.hpp, definitions
// in docs/social-metrics.md): (a) arrivals and exits per time bin, (b) congestion — the density
// of agents around key points, (c) group cohesion, (d) coordination statistics. Computed from plain
// values that metrics_queries.cpp reads from a recording; no SQLite, no files. The trajectory is
// never held in memory: the tallies are fed one row at a time, told where each frame ends, then
// write their results into a SocialMetrics.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "throng/recording/recording_social.hpp"

namespace throng::recording::metrics {

/// A point with a category: a key point of the congestion measure.
struct KeyPoint {
  std::uint32_t index = 0;       ///< throng_points.idx
  std::string id, category;
  double x = 0.0, y = 0.0;       ///< [m], finite
};

/// Mean, 95th percentile (nearest rank) and max of the counts a histogram holds (histogram[n] =
/// samples with n agents), as densities: count / area [1/m²]. Only the statistics and `samples`
/// are set.
[[nodiscard]] DensityStats densityOf(const std::vector<std::uint64_t>& histogram, double area);

enum class EventKind { VisitStart, Exit, Reunited, GoalGenerated };

/// (a) Arrivals: VisitStart and Exit events per time bin, VisitStart per point category; also
/// counts Reunited and GoalGenerated events.
class ArrivalTally {
 public:
  /// Bins of `bin` seconds from t = 0 covering `duration` (at most kMaxBins; a later event adds
  /// bins up to its own). pointCategory[i]: the category of point i ("" = none).
  ArrivalTally(double bin, double duration, std::vector<std::string> pointCategory);
  /// One event at recording time `time` [s]; `point` is the visited point (VisitStart only).
  /// Visits and exits at a negative, non-finite or too late time are not counted.
  void add(EventKind kind, double time, std::int64_t point);
  /// Writes arrivals, visitsByCategory, visits, exits, the per-minute rates over `duration` and
  /// coordinations.reunited / goalsGenerated.
  void writeTo(SocialMetrics& m) const;

  static constexpr std::size_t kMaxBins = 100000;

 private:
  double bin_, duration_;
  std::vector<std::string> pointCategory_;
  std::vector<ArrivalBin> arrivals_;
  std::map<std::string, std::uint64_t> visitsByCategory_;
  std::uint64_t visits_ = 0, exits_ = 0, reunited_ = 0, goalsGenerated_ = 0;
};

/// Key points bucketed in square cells of side `radius` (coarser when the points lie far apart,
/// for bounded memory): an agent is near a point only if the point lies in the agent's cell or one
/// of its 8 neighbours.
class PointGrid {
 public:
  PointGrid(const std::vector<KeyPoint>& points, double radius);

  /// Calls `f(i)` for every point i within the radius of (x, y) (nothing for non-finite x, y).
  template <class F>
  void near(const std::vector<KeyPoint>& points, double x, double y, F&& f) const;

 private:
  [[nodiscard]] std::size_t cellOf(double x, double y) const;
  double radius2_, cell_;
  double minX_ = 0, maxX_ = 0, minY_ = 0, maxY_ = 0;
  int nx_ = 0, ny_ = 0;
  std::vector<std::vector<std::size_t>> cells_;
};

/// (b) Congestion: per frame, how many agents are within `radius` of each key point.
class CongestionTally {
 public:
  CongestionTally(std::vector<KeyPoint> keys, double radius);
  void addAgent(double x, double y);
  /// Closes the frame the agents since the last call belong to.
  void endFrame();
  /// Writes congestion (one entry per m.categories, in that order) and the `worst` points with the
  /// highest mean density (ties: higher max). `frames`: frames of the recording — those never
  /// ended here (no agent at all) count as frames with nobody near any point.
  void writeTo(SocialMetrics& m, std::uint64_t frames, std::size_t worst);

 private:
  std::vector<KeyPoint> keys_;
  PointGrid grid_;
  double area_;
  std::vector<std::uint32_t> nearCount_;
  std::vector<std::vector<std::uint64_t>> histograms_;  ///< per key point: [n] = frames with n agents near
  std::uint64_t framesEnded_ = 0;
};

/// (c) Cohesion: per frame, each group with >= 2 members present — their mean distance to the
/// group's centroid, and whether all are within `cohesionRadius` of it.
class CohesionTally {
 public:
  /// groupOfAgent: agent id → dense group index < groupCount (groups of >= 2 agents).
  CohesionTally(std::unordered_map<std::uint32_t, std::uint32_t> groupOfAgent, std::size_t groupCount,
                double cohesionRadius);
  [[nodiscard]] bool tracksGroups() const { return groupCount_ > 0; }
  /// An agent's position this frame (ignored when not finite or not in a group).
  void addAgent(std::uint32_t id, double x, double y);
  void endFrame();
  [[nodiscard]] CohesionStats result() const;

 private:
  struct Member {
    std::uint32_t group;
    double x, y;
  };
  std::unordered_map<std::uint32_t, std::uint32_t> groupOfAgent_;
  std::size_t groupCount_;
  double cohesion2_;
  std::vector<double> sumX_, sumY_, sumDist_;
  std::vector<std::uint32_t> members_;
  std::vector<bool> apart_, everPaired_;
  std::vector<std::uint32_t> touched_;
  std::vector<Member> frameMembers_;
  std::uint64_t groupFrames_ = 0, togetherFrames_ = 0;
  double cohesionSum_ = 0.0;
};

/// (d) Coordination statistics: counts by plan, outcome, trigger and relation ("none" when
/// alone); grounding time (execute − start) over coordinations not alone; divide time (end −
/// execute) over those with a divide plan. microBehaviours, reunited and goalsGenerated are left 0.
[[nodiscard]] CoordinationStats coordinationStats(const std::vector<CoordinationInfo>& coordinations);

// --- PointGrid::near --------------------------------------------------------------------------

template <class F>
void PointGrid::near(const std::vector<KeyPoint>& points, double x, double y, F&& f) const {
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

}  // namespace throng::recording::metrics
