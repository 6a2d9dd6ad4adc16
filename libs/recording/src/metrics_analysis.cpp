// throng::recording metrics analysis — the tallies and statistics of metrics_analysis.hpp: arrival bins,
// the key-point grid and congestion histograms, group cohesion, coordination statistics. Pure
// functions of the values they are given; reads and writes memory only.
#include "metrics_analysis.hpp"

#include <numbers>

namespace throng::recording::metrics {

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

// --- (a) arrivals ------------------------------------------------------------------------------

ArrivalTally::ArrivalTally(double bin, double duration, std::vector<std::string> pointCategory)
    : bin_(bin), duration_(duration), pointCategory_(std::move(pointCategory)) {
  const std::size_t bins = std::min<std::size_t>(kMaxBins, static_cast<std::size_t>(duration / bin) + 1);
  arrivals_.resize(bins);
  for (std::size_t i = 0; i < bins; ++i) arrivals_[i].start = static_cast<double>(i) * bin;
}

void ArrivalTally::add(EventKind kind, double time, std::int64_t point) {
  if (kind == EventKind::Reunited) {
    ++reunited_;
    return;
  }
  if (kind == EventKind::GoalGenerated) {
    ++goalsGenerated_;
    return;
  }
  if (!std::isfinite(time) || time < 0.0) return;
  const double b = std::floor(time / bin_);
  if (b >= static_cast<double>(kMaxBins)) return;
  const auto bi = static_cast<std::size_t>(b);
  while (arrivals_.size() <= bi) {
    ArrivalBin extra;
    extra.start = static_cast<double>(arrivals_.size()) * bin_;
    arrivals_.push_back(extra);
  }
  ArrivalBin& bin = arrivals_[bi];
  if (kind == EventKind::Exit) {
    ++bin.exits;
    ++exits_;
    return;
  }
  const std::string category = point >= 0 && static_cast<std::uint64_t>(point) < pointCategory_.size()
                                   ? pointCategory_[static_cast<std::size_t>(point)] : std::string();
  ++bin.visits;
  ++bin.byCategory[category];
  ++visits_;
  ++visitsByCategory_[category];
}

void ArrivalTally::writeTo(SocialMetrics& m) const {
  m.arrivals = arrivals_;
  m.visitsByCategory = visitsByCategory_;
  m.visits = visits_;
  m.exits = exits_;
  const double minutes = duration_ / 60.0;
  if (minutes > 0.0) {
    m.visitsPerMinute = static_cast<double>(visits_) / minutes;
    m.exitsPerMinute = static_cast<double>(exits_) / minutes;
  }
  m.coordinations.reunited = reunited_;
  m.coordinations.goalsGenerated = goalsGenerated_;
}

// --- (b) congestion ----------------------------------------------------------------------------

PointGrid::PointGrid(const std::vector<KeyPoint>& points, double radius) : radius2_(radius * radius), cell_(radius) {
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

std::size_t PointGrid::cellOf(double x, double y) const {
  const int i = std::clamp(static_cast<int>((x - minX_) / cell_), 0, nx_ - 1);
  const int j = std::clamp(static_cast<int>((y - minY_) / cell_), 0, ny_ - 1);
  return static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(i);
}

CongestionTally::CongestionTally(std::vector<KeyPoint> keys, double radius)
    : keys_(std::move(keys)),
      grid_(keys_, radius),
      area_(std::numbers::pi * radius * radius),
      nearCount_(keys_.size(), 0),
      histograms_(keys_.size()) {}

void CongestionTally::addAgent(double x, double y) {
  grid_.near(keys_, x, y, [&](std::size_t p) { ++nearCount_[p]; });
}

void CongestionTally::endFrame() {
  ++framesEnded_;
  for (std::size_t p = 0; p < keys_.size(); ++p) {
    auto& h = histograms_[p];
    if (h.size() <= nearCount_[p]) h.resize(nearCount_[p] + 1, 0);
    ++h[nearCount_[p]];
    nearCount_[p] = 0;
  }
}

namespace {

void addHistogram(std::vector<std::uint64_t>& into, const std::vector<std::uint64_t>& from) {
  if (into.size() < from.size()) into.resize(from.size(), 0);
  for (std::size_t i = 0; i < from.size(); ++i) into[i] += from[i];
}

}  // namespace

void CongestionTally::writeTo(SocialMetrics& m, std::uint64_t frames, std::size_t worst) {
  // Frames without any agent (no trajectory rows) still count: nobody is near any point.
  const std::uint64_t emptyFrames = frames > framesEnded_ ? frames - framesEnded_ : 0;
  for (auto& h : histograms_) {
    if (h.empty()) h.resize(1, 0);
    h[0] += emptyFrames;
  }
  for (const std::string& category : m.categories) {
    std::vector<std::uint64_t> merged;
    std::size_t count = 0;
    for (std::size_t p = 0; p < keys_.size(); ++p) {
      if (keys_[p].category != category) continue;
      addHistogram(merged, histograms_[p]);
      ++count;
    }
    DensityStats d = densityOf(merged, area_);
    d.category = category;
    d.points = count;
    m.congestion.push_back(d);
  }
  std::vector<DensityStats> perPoint;
  for (std::size_t p = 0; p < keys_.size(); ++p) {
    DensityStats d = densityOf(histograms_[p], area_);
    d.category = keys_[p].category;
    d.point = keys_[p].id;
    d.pointIndex = keys_[p].index;
    d.points = 1;
    perPoint.push_back(d);
  }
  std::stable_sort(perPoint.begin(), perPoint.end(), [](const DensityStats& a, const DensityStats& b) {
    return a.mean != b.mean ? a.mean > b.mean : a.max > b.max;
  });
  perPoint.resize(std::min(perPoint.size(), worst));
  m.worstPoints = std::move(perPoint);
}

// --- (c) cohesion ------------------------------------------------------------------------------

CohesionTally::CohesionTally(std::unordered_map<std::uint32_t, std::uint32_t> groupOfAgent, std::size_t groupCount,
                             double cohesionRadius)
    : groupOfAgent_(std::move(groupOfAgent)),
      groupCount_(groupCount),
      cohesion2_(cohesionRadius * cohesionRadius),
      sumX_(groupCount, 0.0),
      sumY_(groupCount, 0.0),
      sumDist_(groupCount, 0.0),
      members_(groupCount, 0),
      apart_(groupCount, false),
      everPaired_(groupCount, false) {}

void CohesionTally::addAgent(std::uint32_t id, double x, double y) {
  if (groupCount_ == 0 || !std::isfinite(x) || !std::isfinite(y)) return;
  const auto it = groupOfAgent_.find(id);
  if (it == groupOfAgent_.end()) return;
  const std::uint32_t g = it->second;
  if (members_[g] == 0) touched_.push_back(g);
  ++members_[g];
  sumX_[g] += x;
  sumY_[g] += y;
  frameMembers_.push_back({g, x, y});
}

void CohesionTally::endFrame() {
  for (const Member& mb : frameMembers_) {
    const double n = members_[mb.group];
    if (n < 2) continue;
    const double dx = mb.x - sumX_[mb.group] / n, dy = mb.y - sumY_[mb.group] / n;
    const double d2 = dx * dx + dy * dy;
    sumDist_[mb.group] += std::sqrt(d2);
    if (d2 > cohesion2_) apart_[mb.group] = true;
  }
  for (const std::uint32_t g : touched_) {
    if (members_[g] >= 2) {
      ++groupFrames_;
      cohesionSum_ += sumDist_[g] / members_[g];
      if (!apart_[g]) ++togetherFrames_;
      everPaired_[g] = true;
    }
    sumX_[g] = sumY_[g] = sumDist_[g] = 0.0;
    members_[g] = 0;
    apart_[g] = false;
  }
  touched_.clear();
  frameMembers_.clear();
}

CohesionStats CohesionTally::result() const {
  CohesionStats c;
  c.groupFrames = groupFrames_;
  if (groupFrames_ > 0) {
    c.meanDistance = cohesionSum_ / static_cast<double>(groupFrames_);
    c.shareTogether = static_cast<double>(togetherFrames_) / static_cast<double>(groupFrames_);
  }
  c.groups = static_cast<std::uint64_t>(std::count(everPaired_.begin(), everPaired_.end(), true));
  return c;
}

// --- (d) coordinations -------------------------------------------------------------------------

namespace {

bool isDividePlan(const std::string& plan) { return plan == "divide_and_proceed" || plan == "divide_and_wait"; }

}  // namespace

CoordinationStats coordinationStats(const std::vector<CoordinationInfo>& coordinations) {
  CoordinationStats cs;
  double groundingSum = 0.0, divideSum = 0.0;
  for (const CoordinationInfo& c : coordinations) {
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
  return cs;
}

}  // namespace throng::recording::metrics
