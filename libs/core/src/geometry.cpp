// throng::core geometry — polygon and segment predicates in the plane (metres). Reads polygons,
// writes nothing but its results. Predicates are evaluated in double precision so that float
// inputs (a few km at most) give exact orientation signs for well-separated points.
#include "throng/core/geometry.hpp"
#include "throng/core/polygon_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

namespace throng::core {

void Aabb::extend(Vec2 p) {
  min.x = std::min(min.x, p.x);
  min.y = std::min(min.y, p.y);
  max.x = std::max(max.x, p.x);
  max.y = std::max(max.y, p.y);
}

bool Aabb::contains(Vec2 p) const {
  return p.x >= min.x && p.x <= max.x && p.y >= min.y && p.y <= max.y;
}

namespace {

/// Orientation of c relative to a→b: > 0 left (CCW), < 0 right, 0 collinear.
double orient(Vec2 a, Vec2 b, Vec2 c) {
  return (double(b.x) - a.x) * (double(c.y) - a.y) - (double(b.y) - a.y) * (double(c.x) - a.x);
}

int sign(double v) { return (v > 0.0) - (v < 0.0); }

/// c lies within the bounding box of segment ab (used once collinearity is known).
bool onSegmentBox(Vec2 a, Vec2 b, Vec2 c) {
  return std::min(a.x, b.x) <= c.x && c.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= c.y &&
         c.y <= std::max(a.y, b.y);
}

}  // namespace

double signedArea(std::span<const Vec2> poly) {
  const std::size_t n = poly.size();
  if (n < 3) return 0.0;
  double twice = 0.0;
  // Relative to the first vertex: keeps precision for polygons far from the origin.
  const Vec2 o = poly[0];
  for (std::size_t i = 1; i + 1 < n; ++i) {
    twice += orient(o, poly[i], poly[i + 1]);
  }
  return 0.5 * twice;
}

Aabb bounds(std::span<const Vec2> poly) {
  Aabb box;
  for (const Vec2 p : poly) box.extend(p);
  return box;
}

bool pointInPolygon(std::span<const Vec2> poly, Vec2 p) {
  bool inside = false;
  const std::size_t n = poly.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2 a = poly[i];
    const Vec2 b = poly[j];
    if ((a.y > p.y) != (b.y > p.y)) {
      const double x = double(b.x - a.x) * (double(p.y) - a.y) / (double(b.y) - a.y) + a.x;
      if (double(p.x) < x) inside = !inside;
    }
  }
  return inside;
}

bool segmentsIntersect(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const int d1 = sign(orient(c, d, a));
  const int d2 = sign(orient(c, d, b));
  const int d3 = sign(orient(a, b, c));
  const int d4 = sign(orient(a, b, d));
  if (d1 * d2 < 0 && d3 * d4 < 0) return true;
  if (d1 == 0 && onSegmentBox(c, d, a)) return true;
  if (d2 == 0 && onSegmentBox(c, d, b)) return true;
  if (d3 == 0 && onSegmentBox(a, b, c)) return true;
  if (d4 == 0 && onSegmentBox(a, b, d)) return true;
  return false;
}

namespace {

/// Whether edges i < j of `poly` intersect (the rule findSelfIntersection documents).
bool edgesCross(std::span<const Vec2> poly, std::size_t i, std::size_t j) {
  const std::size_t n = poly.size();
  const Vec2 a = poly[i];
  const Vec2 b = poly[(i + 1) % n];
  const Vec2 c = poly[j];
  const Vec2 d = poly[(j + 1) % n];
  const bool adjacent = (j == i + 1) || (i == 0 && j == n - 1);
  if (!adjacent) return segmentsIntersect(a, b, c, d);
  // Adjacent edges share one vertex; they only cross if they fold back onto each other
  // (a spike: collinear, pointing the same way from the shared vertex).
  const Vec2 shared = (j == i + 1) ? b : a;
  const Vec2 p = (j == i + 1) ? a : b;
  const Vec2 q = (j == i + 1) ? d : c;
  if (sign(orient(shared, p, q)) != 0) return false;
  const double dp = (double(p.x) - shared.x) * (double(q.x) - shared.x) + (double(p.y) - shared.y) * (double(q.y) - shared.y);
  return dp > 0.0;
}

/// Counts edge-pair tests against a budget; past it the search gives up.
struct Budget {
  std::uint64_t left;
  bool exhausted = false;
  bool spend() {
    if (left == 0) {
      exhausted = true;
      return false;
    }
    --left;
    return true;
  }
};

std::optional<std::pair<std::size_t, std::size_t>> allPairs(std::span<const Vec2> poly, Budget& budget) {
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      if (!budget.spend()) return std::nullopt;
      if (edgesCross(poly, i, j)) return std::make_pair(i, j);
    }
  }
  return std::nullopt;
}

std::optional<std::pair<std::size_t, std::size_t>> findWithin(std::span<const Vec2> poly, Budget& budget);

}  // namespace

std::optional<std::pair<std::size_t, std::size_t>> findSelfIntersection(std::span<const Vec2> poly) {
  Budget unlimited{std::numeric_limits<std::uint64_t>::max()};
  return findWithin(poly, unlimited);
}

SimplicityCheck checkSimple(std::span<const Vec2> poly, std::uint64_t maxTests) {
  Budget budget{maxTests};
  SimplicityCheck out;
  out.crossing = findWithin(poly, budget);
  out.tooComplex = budget.exhausted && !out.crossing;
  return out;
}

namespace {

std::optional<std::pair<std::size_t, std::size_t>> findWithin(std::span<const Vec2> poly, Budget& budget) {
  const std::size_t n = poly.size();
  if (n < 3) return std::nullopt;
  if (n <= 64) return allPairs(poly, budget);
  // A uniform grid over the bounding box with about 2n cells: every edge is listed in the cells
  // its bounding box covers, and only edges sharing a cell are tested, each pair once (in the
  // first cell both cover). Near-linear for polygons whose edges are short compared with the
  // whole; never more tests than all pairs (it falls back to them). Every crossing pair shares a
  // cell, and the smallest (i, j) found is the one the all-pairs scan finds first.
  const Aabb box = bounds(poly);
  const double width = std::max(double(box.max.x) - box.min.x, 1e-9);
  const double height = std::max(double(box.max.y) - box.min.y, 1e-9);
  const double cells = 2.0 * double(n);
  const auto nx = static_cast<std::size_t>(std::clamp(std::ceil(std::sqrt(cells * width / height)), 1.0, cells));
  const auto ny = static_cast<std::size_t>(std::clamp(std::ceil(cells / double(nx)), 1.0, cells));
  const auto cellX = [&](float x) {
    return static_cast<std::size_t>(std::clamp((double(x) - box.min.x) / width * double(nx), 0.0, double(nx - 1)));
  };
  const auto cellY = [&](float y) {
    return static_cast<std::size_t>(std::clamp((double(y) - box.min.y) / height * double(ny), 0.0, double(ny - 1)));
  };
  struct Range {
    std::size_t x0, x1, y0, y1;
  };
  std::vector<Range> ranges(n);
  std::vector<std::size_t> count(nx * ny + 1, 0);
  std::size_t entries = 0;
  for (std::size_t e = 0; e < n; ++e) {
    const Vec2 a = poly[e];
    const Vec2 b = poly[(e + 1) % n];
    Range& r = ranges[e];
    r.x0 = cellX(std::min(a.x, b.x));
    r.x1 = cellX(std::max(a.x, b.x));
    r.y0 = cellY(std::min(a.y, b.y));
    r.y1 = cellY(std::max(a.y, b.y));
    entries += (r.x1 - r.x0 + 1) * (r.y1 - r.y0 + 1);
    if (entries > 32 * n) return allPairs(poly, budget);  // long edges crossing much of the box
  }
  for (const Range& r : ranges) {
    for (std::size_t y = r.y0; y <= r.y1; ++y) {
      for (std::size_t x = r.x0; x <= r.x1; ++x) ++count[y * nx + x + 1];
    }
  }
  double pairs = 0.0;
  for (std::size_t c = 1; c < count.size(); ++c) {
    pairs += 0.5 * double(count[c]) * double(count[c] > 0 ? count[c] - 1 : 0);
    count[c] += count[c - 1];
  }
  if (pairs > 0.5 * double(n) * double(n - 1)) return allPairs(poly, budget);
  std::vector<std::size_t> edges(entries);
  std::vector<std::size_t> fill(count.begin(), count.end() - 1);
  for (std::size_t e = 0; e < n; ++e) {  // edges in increasing order within every cell
    const Range& r = ranges[e];
    for (std::size_t y = r.y0; y <= r.y1; ++y) {
      for (std::size_t x = r.x0; x <= r.x1; ++x) edges[fill[y * nx + x]++] = e;
    }
  }
  std::optional<std::pair<std::size_t, std::size_t>> best;
  for (std::size_t cy = 0; cy < ny; ++cy) {
    for (std::size_t cx = 0; cx < nx; ++cx) {
      const std::size_t c = cy * nx + cx;
      for (std::size_t u = count[c]; u < count[c + 1]; ++u) {
        const std::size_t i = edges[u];
        if (best && i > best->first) break;
        for (std::size_t v = u + 1; v < count[c + 1]; ++v) {
          const std::size_t j = edges[v];
          if (best && i == best->first && j >= best->second) break;
          const Range& ri = ranges[i];
          const Range& rj = ranges[j];
          if (std::max(ri.x0, rj.x0) != cx || std::max(ri.y0, rj.y0) != cy) continue;  // tested in another cell
          if (ri.x1 < rj.x0 || rj.x1 < ri.x0 || ri.y1 < rj.y0 || rj.y1 < ri.y0) continue;
          if (!budget.spend()) return best;
          if (edgesCross(poly, i, j)) {
            best = std::make_pair(i, j);
            break;
          }
        }
      }
    }
  }
  return best;
}

}  // namespace

Vec2 closestPointOnSegment(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const float len2 = lengthSq(ab);
  if (len2 <= 0.0f) return a;
  const float t = std::clamp(dot(p - a, ab) / len2, 0.0f, 1.0f);
  return a + ab * t;
}

float distanceToSegmentSq(Vec2 p, Vec2 a, Vec2 b) { return lengthSq(p - closestPointOnSegment(p, a, b)); }

float distanceToBoundary(std::span<const Vec2> poly, Vec2 p) {
  const std::size_t n = poly.size();
  if (n == 0) return std::numeric_limits<float>::infinity();
  float best = std::numeric_limits<float>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    best = std::min(best, distanceToSegmentSq(p, poly[i], poly[(i + 1) % n]));
  }
  return std::sqrt(best);
}

Vec2 centroid(std::span<const Vec2> poly) {
  const std::size_t n = poly.size();
  if (n == 0) return {};
  const Vec2 o = poly[0];
  double cx = 0.0, cy = 0.0, twiceArea = 0.0;
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double w = orient(o, poly[i], poly[i + 1]);
    cx += w * ((double(poly[i].x) - o.x) + (double(poly[i + 1].x) - o.x)) / 3.0;
    cy += w * ((double(poly[i].y) - o.y) + (double(poly[i + 1].y) - o.y)) / 3.0;
    twiceArea += w;
  }
  if (std::abs(twiceArea) < 1e-12) {
    // Degenerate (zero area): fall back to the vertex average.
    double sx = 0.0, sy = 0.0;
    for (const Vec2 p : poly) {
      sx += p.x;
      sy += p.y;
    }
    return {static_cast<float>(sx / double(n)), static_cast<float>(sy / double(n))};
  }
  return {static_cast<float>(o.x + cx / twiceArea), static_cast<float>(o.y + cy / twiceArea)};
}

std::vector<std::array<std::size_t, 3>> triangulate(std::span<const Vec2> poly) {
  std::vector<std::array<std::size_t, 3>> tris;
  const std::size_t n = poly.size();
  if (n < 3) return tris;
  // Work on a CCW index list so that "convex" is "left turn" whatever the input winding.
  std::vector<std::size_t> idx(n);
  for (std::size_t i = 0; i < n; ++i) idx[i] = i;
  if (signedArea(poly) < 0.0) std::reverse(idx.begin(), idx.end());
  tris.reserve(n - 2);

  auto isEar = [&](std::size_t k) {
    const std::size_t m = idx.size();
    const Vec2 a = poly[idx[(k + m - 1) % m]];
    const Vec2 b = poly[idx[k]];
    const Vec2 c = poly[idx[(k + 1) % m]];
    if (orient(a, b, c) <= 0.0) return false;  // reflex or flat
    for (std::size_t t = 0; t < m; ++t) {
      if (t == k || t == (k + m - 1) % m || t == (k + 1) % m) continue;
      const Vec2 p = poly[idx[t]];
      if (p == a || p == b || p == c) continue;
      if (orient(a, b, p) >= 0.0 && orient(b, c, p) >= 0.0 && orient(c, a, p) >= 0.0) return false;
    }
    return true;
  };

  std::size_t k = 0;
  std::size_t misses = 0;
  while (idx.size() > 3) {
    const std::size_t m = idx.size();
    k %= m;
    if (isEar(k) || misses >= m) {
      // After a full pass without an ear the input is not simple (or has flat runs): clip anyway
      // so the loop always terminates; callers validate simplicity first.
      tris.push_back({idx[(k + m - 1) % m], idx[k], idx[(k + 1) % m]});
      idx.erase(idx.begin() + static_cast<std::ptrdiff_t>(k));
      misses = 0;
    } else {
      ++k;
      ++misses;
    }
  }
  tris.push_back({idx[0], idx[1], idx[2]});
  return tris;
}

}  // namespace throng::core
