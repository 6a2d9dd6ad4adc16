// throng::crowd sub-regions (Musse & Thalmann, §3.1.3, Figure 5, "Individual position generation"):
// the region of an IP/AP is divided into four or more sub-regions depending on its size; each agent
// of a group takes the sub-region of highest priority (close to the point the agent comes from, low
// density; on a goal wide against its distance, only among those on its near side) and a uniformly
// random position inside it, so members of a group never aim at the same spot while free sub-regions
// remain there (Figure 8: a family of curves, never the same).
// divideRegion runs once per region when a world is built; pickSubregion/samplePoint when an agent
// enters a goal (decide phase). Pure: reads the region, occupancy counts and one Rng stream.
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "throng/core/rng.hpp"
#include "throng/crowd/region.hpp"

namespace throng::crowd {

using Triangle = std::array<Vec2, 3>;

struct Subregion {
  Vec2 centre;        ///< centroid [m]
  float area = 0.0f;  ///< [m²]
  // Disc regions: an annular sector {rInner <= |p - origin| <= rOuter, angle0 <= atan2 < angle1}.
  Vec2 origin;              ///< disc centre [m]
  float rInner = 0.0f;      ///< [m]
  float rOuter = 0.0f;      ///< [m]
  float angle0 = 0.0f;      ///< [rad], in [0, 2π)
  float angle1 = 0.0f;      ///< [rad], angle0 < angle1 <= 2π
  // Polygon regions: grid cells clipped to the polygon, as triangles (empty for a sector).
  std::vector<Triangle> triangles;

  [[nodiscard]] bool isSector() const { return triangles.empty(); }
};

struct SubregionParams {
  float cellArea = 4.0f;  ///< target sub-region area a [m²] [Limit: > 0]: n = max(4, ceil(A / a))
  float mergeFraction = 0.25f;  ///< polygon cells smaller than this fraction of a full cell are merged into the
                                ///< nearest larger one (no slivers) [-] [Limit: [0, 1)]
};

/// Divides `region` (area A) into sub-regions that partition it:
/// - disc of radius R: k = ceil(sqrt(max(4, ceil(A / a)) / 4)) rings of equal width R/k; ring i
///   (0 = innermost) is cut into 4(2i+1) equal sectors, so all n = 4k² sectors have area A/n and
///   near-square shapes;
/// - polygon: a square grid of side s = min(sqrt(a), sqrt(A/4)) over its bounding box, each cell
///   clipped to the polygon (triangulated), slivers merged (mergeFraction); halved s while fewer
///   than 4 sub-regions result (at most 4 halvings).
/// Deterministic: row-major cell order, ring then angle order for discs. Empty for an empty region.
[[nodiscard]] std::vector<Subregion> divideRegion(const Region& region, const SubregionParams& params = {});

/// Point inside the sub-region (closed)?
[[nodiscard]] bool subregionContains(const Subregion& sub, Vec2 p);

struct PickParams {
  float densityWeight = 2.0f;  ///< w [-] [Limit: > 1 + jitter]: any occupied candidate costs more than any free one
  float jitter = 0.1f;         ///< j [-] [Limit: >= 0]: random spread of the proximity term, so groups coming
                               ///< from the same side do not all fill the same order
  /// How much farther than the nearest sub-region a candidate may lie, as a fraction of the nearest
  /// one's distance [-] [Limit: >= 0]: a walk at most 5 % longer (our choice), so an exit as wide as
  /// 0.6 times the agent's distance from it is open across its whole width (sqrt(1.05² - 1) = 0.32 to
  /// either side), while a long strip is reached near straight ahead, never crossed sideways.
  float detourFraction = 0.05f;
  float detourMin = 2.0f;  ///< the same, at least [m] [Limit: >= 0]: an agent close to a goal still spreads
                           ///< over the cells beside the nearest (2 m = one side of a default 4 m² cell)
};

/// Index of the sub-region an agent coming from `from` should take (§3.1.3 Priority), among the
/// candidates: the sub-regions whose centre is at most max(detourMin, detourFraction · d_n) farther
/// from `from` than the nearest centre (d_n) — the near side of a wide goal, never a far free spot
/// along it. Among them the one of least cost
///     cost_i = d_i / D  +  j · u_i  +  w · (occupancy_i / area_i) · maxArea
/// where d_i = |centre_i - from|, D = max d_i over the candidates (proximity in [0, 1]), u_i uniform
/// in [0, 1) (one draw per sub-region, candidate or not, in index order), occupancy_i / area_i the
/// density [1/m²] and maxArea the largest candidate's area (a lone agent in the largest scores w).
/// With w > 1 + j a free candidate always beats an occupied one. Ties go to the lowest index. Where
/// every sub-region is a candidate (a goal small against its distance) this is the paper's rule over
/// the whole region. `occupancy` has one count per sub-region. Precondition: subregions not empty.
[[nodiscard]] std::size_t pickSubregion(std::span<const Subregion> subregions, Vec2 from,
                                        std::span<const std::uint32_t> occupancy, core::Rng& rng,
                                        const PickParams& params = {});

/// Uniform random point inside the sub-region (exactly 3 draws from rng). Sectors: radius
/// sqrt(uniform in [r0², r1²]), angle uniform; polygons: a triangle by area, then a uniform point in it.
[[nodiscard]] Vec2 samplePoint(const Subregion& sub, core::Rng& rng);

}  // namespace throng::crowd
