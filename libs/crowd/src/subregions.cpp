// throng::crowd sub-regions (§3.1.3, Figure 5): division of an IP/AP region into sectors (discs)
// or clipped grid cells (polygons), priority choice by proximity and density among the sub-regions
// on the agent's near side of the region, uniform sampling.
#include "throng/crowd/subregions.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "throng/core/assert.hpp"

namespace throng::crowd {

namespace {

constexpr double kTwoPi = 6.283185307179586;
constexpr float kContainEps = 1e-4f;  ///< closed-containment tolerance for float round-off [m]

double triangleArea(const Triangle& t) {
  return 0.5 * std::abs((double(t[1].x) - t[0].x) * (double(t[2].y) - t[0].y) -
                        (double(t[1].y) - t[0].y) * (double(t[2].x) - t[0].x));
}

std::vector<Subregion> divideDisc(const Region& region, const SubregionParams& params) {
  std::vector<Subregion> out;
  const double r = region.radius;
  if (r <= 0.0) {
    Subregion s;
    s.centre = s.origin = region.centre;
    s.angle1 = static_cast<float>(kTwoPi);
    out.push_back(s);
    return out;
  }
  const double area = regionArea(region);
  const double wanted = std::max(4.0, std::ceil(area / params.cellArea));
  const int k = std::max(1, static_cast<int>(std::ceil(std::sqrt(wanted / 4.0) - 1e-9)));
  out.reserve(static_cast<std::size_t>(4 * k * k));
  for (int ring = 0; ring < k; ++ring) {
    const double r0 = r * ring / k;
    const double r1 = r * (ring + 1) / k;
    const int m = 4 * (2 * ring + 1);
    const double width = kTwoPi / m;
    const double halfAngle = 0.5 * width;
    // Centroid of an annular sector: (2/3)(r1³ - r0³)/(r1² - r0²) · sin(h)/h from the origin.
    const double dist = (2.0 / 3.0) * (r1 * r1 * r1 - r0 * r0 * r0) / (r1 * r1 - r0 * r0) * std::sin(halfAngle) / halfAngle;
    for (int j = 0; j < m; ++j) {
      Subregion s;
      s.origin = region.centre;
      s.rInner = static_cast<float>(r0);
      s.rOuter = static_cast<float>(r1);
      s.angle0 = static_cast<float>(j * width);
      s.angle1 = static_cast<float>(j + 1 == m ? kTwoPi : (j + 1) * width);
      s.area = static_cast<float>(halfAngle * (r1 * r1 - r0 * r0));
      const double mid = (j + 0.5) * width;
      s.centre = {static_cast<float>(region.centre.x + dist * std::cos(mid)),
                  static_cast<float>(region.centre.y + dist * std::sin(mid))};
      out.push_back(std::move(s));
    }
  }
  return out;
}

/// Sutherland–Hodgman: the convex polygon `poly` (<= 3 + 4 vertices after four cuts) clipped to the
/// half-plane sign * (p[axis] - value) <= 0.
std::vector<Vec2> clipHalf(const std::vector<Vec2>& poly, int axis, float value, float sign) {
  std::vector<Vec2> out;
  const std::size_t n = poly.size();
  auto f = [&](Vec2 p) { return sign * ((axis == 0 ? p.x : p.y) - value); };
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = poly[i];
    const Vec2 b = poly[(i + 1) % n];
    const float fa = f(a);
    const float fb = f(b);
    if (fa <= 0.0f) out.push_back(a);
    if ((fa < 0.0f && fb > 0.0f) || (fa > 0.0f && fb < 0.0f)) {
      const float t = fa / (fa - fb);
      Vec2 p = a + (b - a) * t;
      if (axis == 0) p.x = value; else p.y = value;  // exactly on the cut
      out.push_back(p);
    }
  }
  return out;
}

struct Cell {
  std::vector<Triangle> triangles;
  double area = 0.0;
};

std::vector<Subregion> gridCells(const Polygon& poly, const std::vector<std::array<std::size_t, 3>>& tris, float s,
                                 float mergeFraction) {
  const Aabb box = core::bounds(poly);
  const int nx = std::max(1, static_cast<int>(std::ceil((box.max.x - box.min.x) / s)));
  const int ny = std::max(1, static_cast<int>(std::ceil((box.max.y - box.min.y) / s)));
  std::vector<Cell> cells(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny));
  auto cellX = [&](int i) { return i == nx ? box.max.x : box.min.x + s * float(i); };
  auto cellY = [&](int j) { return j == ny ? box.max.y : box.min.y + s * float(j); };
  for (const auto& t : tris) {
    const Triangle tri{poly[t[0]], poly[t[1]], poly[t[2]]};
    const Aabb tb = core::bounds(tri);
    const int i0 = std::clamp(static_cast<int>(std::floor((tb.min.x - box.min.x) / s)), 0, nx - 1);
    const int i1 = std::clamp(static_cast<int>(std::floor((tb.max.x - box.min.x) / s)), 0, nx - 1);
    const int j0 = std::clamp(static_cast<int>(std::floor((tb.min.y - box.min.y) / s)), 0, ny - 1);
    const int j1 = std::clamp(static_cast<int>(std::floor((tb.max.y - box.min.y) / s)), 0, ny - 1);
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) {
        std::vector<Vec2> p{tri[0], tri[1], tri[2]};
        p = clipHalf(p, 0, cellX(i), -1.0f);  // x >= x0
        if (p.size() >= 3) p = clipHalf(p, 0, cellX(i + 1), 1.0f);  // x <= x1
        if (p.size() >= 3) p = clipHalf(p, 1, cellY(j), -1.0f);
        if (p.size() >= 3) p = clipHalf(p, 1, cellY(j + 1), 1.0f);
        Cell& cell = cells[static_cast<std::size_t>(j) * nx + i];
        for (std::size_t v = 1; v + 1 < p.size(); ++v) {
          const Triangle piece{p[0], p[v], p[v + 1]};
          const double a = triangleArea(piece);
          if (a <= 1e-10) continue;
          cell.triangles.push_back(piece);
          cell.area += a;
        }
      }
    }
  }
  std::vector<Subregion> out;
  for (Cell& c : cells) {
    if (c.triangles.empty()) continue;
    Subregion sub;
    sub.area = static_cast<float>(c.area);
    sub.triangles = std::move(c.triangles);
    out.push_back(std::move(sub));
  }
  auto updateCentre = [](Subregion& sub) {
    double cx = 0.0, cy = 0.0, total = 0.0;
    for (const Triangle& t : sub.triangles) {
      const double a = triangleArea(t);
      cx += a * (double(t[0].x) + t[1].x + t[2].x) / 3.0;
      cy += a * (double(t[0].y) + t[1].y + t[2].y) / 3.0;
      total += a;
    }
    sub.area = static_cast<float>(total);
    if (total > 0.0) sub.centre = {static_cast<float>(cx / total), static_cast<float>(cy / total)};
  };
  for (Subregion& sub : out) updateCentre(sub);
  // Merge slivers into the nearest (by centre) full-size sub-region, lowest index on ties.
  const float threshold = mergeFraction * s * s;
  std::vector<bool> small(out.size());
  bool anyLarge = false;
  for (std::size_t i = 0; i < out.size(); ++i) {
    small[i] = out[i].area < threshold;
    anyLarge = anyLarge || !small[i];
  }
  if (!anyLarge) return out;
  std::vector<Subregion> merged;
  std::vector<std::size_t> largeIndex;
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (!small[i]) {
      largeIndex.push_back(i);
    }
  }
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (!small[i]) continue;
    std::size_t best = largeIndex[0];
    float bestD = std::numeric_limits<float>::infinity();
    for (std::size_t l : largeIndex) {
      const float d = core::distance(out[i].centre, out[l].centre);
      if (d < bestD) {
        bestD = d;
        best = l;
      }
    }
    auto& dst = out[best].triangles;
    dst.insert(dst.end(), out[i].triangles.begin(), out[i].triangles.end());
  }
  for (std::size_t l : largeIndex) {
    updateCentre(out[l]);
    merged.push_back(std::move(out[l]));
  }
  return merged;
}

std::vector<Subregion> dividePolygon(const Region& region, const SubregionParams& params) {
  const double area = regionArea(region);
  if (region.polygon.size() < 3 || area <= 0.0) return {};
  const auto tris = core::triangulate(region.polygon);
  float s = static_cast<float>(std::min(std::sqrt(double(params.cellArea)), std::sqrt(area / 4.0)));
  std::vector<Subregion> out = gridCells(region.polygon, tris, s, params.mergeFraction);
  for (int halvings = 0; out.size() < 4 && halvings < 4; ++halvings) {
    s *= 0.5f;
    out = gridCells(region.polygon, tris, s, params.mergeFraction);
  }
  return out;
}

bool inTriangle(const Triangle& t, Vec2 p) {
  // Closed, with a tolerance in metres: each edge's signed distance >= -eps (works for either winding).
  const double area2 = (double(t[1].x) - t[0].x) * (double(t[2].y) - t[0].y) - (double(t[1].y) - t[0].y) * (double(t[2].x) - t[0].x);
  const double s = area2 >= 0.0 ? 1.0 : -1.0;
  for (int i = 0; i < 3; ++i) {
    const Vec2 a = t[i];
    const Vec2 b = t[(i + 1) % 3];
    const double len = core::distance(a, b);
    const double o = s * ((double(b.x) - a.x) * (double(p.y) - a.y) - (double(b.y) - a.y) * (double(p.x) - a.x));
    if (o < -kContainEps * std::max(len, 1e-9)) return false;
  }
  return true;
}

}  // namespace

std::vector<Subregion> divideRegion(const Region& region, const SubregionParams& params) {
  THRONG_ASSERT(params.cellArea > 0.0f && params.mergeFraction >= 0.0f && params.mergeFraction < 1.0f);
  return region.isDisc() ? divideDisc(region, params) : dividePolygon(region, params);
}

bool subregionContains(const Subregion& sub, Vec2 p) {
  if (!sub.isSector()) {
    for (const Triangle& t : sub.triangles) {
      if (inTriangle(t, p)) return true;
    }
    return false;
  }
  const Vec2 d = p - sub.origin;
  const float r = core::length(d);
  if (r < sub.rInner - kContainEps || r > sub.rOuter + kContainEps) return false;
  if (r <= kContainEps) return true;  // the centre belongs to every innermost sector
  double a = std::atan2(double(d.y), double(d.x));
  if (a < 0.0) a += kTwoPi;
  const double tol = kContainEps / r;  // metres along the arc → radians
  return (a >= sub.angle0 - tol && a <= sub.angle1 + tol) || (sub.angle0 <= tol && a >= kTwoPi - tol) ||
         (sub.angle1 >= kTwoPi - tol && a <= tol);
}

std::size_t pickSubregion(std::span<const Subregion> subregions, Vec2 from, std::span<const std::uint32_t> occupancy,
                          core::Rng& rng, const PickParams& params) {
  THRONG_ASSERT(!subregions.empty() && occupancy.size() == subregions.size());
  THRONG_ASSERT(params.jitter >= 0.0f && params.densityWeight > 1.0f + params.jitter);
  THRONG_ASSERT(params.detourFraction >= 0.0f && params.detourMin >= 0.0f);
  float nearest = std::numeric_limits<float>::infinity();
  for (const Subregion& s : subregions) nearest = std::min(nearest, core::distance(s.centre, from));
  const float reach = nearest + std::max(params.detourMin, params.detourFraction * nearest);
  float maxDist = 0.0f;
  float maxArea = 0.0f;
  for (const Subregion& s : subregions) {
    const float d = core::distance(s.centre, from);
    if (d > reach) continue;
    maxDist = std::max(maxDist, d);
    maxArea = std::max(maxArea, s.area);
  }
  std::size_t best = 0;
  double bestCost = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < subregions.size(); ++i) {
    const double u = rng.uniform();  // one draw per sub-region, always
    const Subregion& s = subregions[i];
    const float d = core::distance(s.centre, from);
    if (d > reach) continue;  // beyond the near side of the goal
    const double proximity = maxDist > 0.0f ? d / double(maxDist) : 0.0;
    const double density = s.area > 0.0f ? double(occupancy[i]) / s.area * maxArea : double(occupancy[i]);
    const double cost = proximity + params.jitter * u + params.densityWeight * density;
    if (cost < bestCost) {
      bestCost = cost;
      best = i;
    }
  }
  return best;
}

Vec2 samplePoint(const Subregion& sub, core::Rng& rng) {
  const double u1 = rng.uniform();
  const double u2 = rng.uniform();
  const double u3 = rng.uniform();
  if (sub.isSector()) {
    const double r0 = sub.rInner, r1 = sub.rOuter;
    const double r = std::sqrt(r0 * r0 + u1 * (r1 * r1 - r0 * r0));
    const double a = sub.angle0 + u2 * (double(sub.angle1) - sub.angle0);
    return {static_cast<float>(sub.origin.x + r * std::cos(a)), static_cast<float>(sub.origin.y + r * std::sin(a))};
  }
  double total = 0.0;
  for (const Triangle& t : sub.triangles) total += triangleArea(t);
  double pick = u1 * total;
  const Triangle* chosen = &sub.triangles.back();
  for (const Triangle& t : sub.triangles) {
    pick -= triangleArea(t);
    if (pick < 0.0) {
      chosen = &t;
      break;
    }
  }
  double a = u2, b = u3;
  if (a + b > 1.0) {
    a = 1.0 - a;
    b = 1.0 - b;
  }
  const Triangle& t = *chosen;
  return {static_cast<float>(t[0].x + a * (double(t[1].x) - t[0].x) + b * (double(t[2].x) - t[0].x)),
          static_cast<float>(t[0].y + a * (double(t[1].y) - t[0].y) + b * (double(t[2].y) - t[0].y))};
}

}  // namespace throng::crowd
