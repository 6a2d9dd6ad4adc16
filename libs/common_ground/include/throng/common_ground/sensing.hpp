// throng::common_ground sensing — the sensory model of a character (Park, Peng, Quek, Cao, "Common Ground",
// §3.2, Figure 2(a)): touch within the body radius, omnidirectional hearing up to d_h, and vision
// along the body direction (gaze = body orientation) up to d_v within a field of view α, occluded by
// walls. Read in the `sense` phase: it reads positions, headings and radii of an agent and of the
// candidates the spatial grid supplies, and writes one Perception per perceived candidate. Pure
// functions; no state. docs/social-relations.md has the picture and the choices made here.
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "throng/core/diagnostic.hpp"
#include "throng/core/geometry.hpp"
#include "throng/core/vec2.hpp"
#include "throng/common_ground/relation.hpp"

namespace throng::nav {
class NavQuery;
}

namespace throng::common_ground {

using core::Vec2;

/// Ranges of the senses. Defaults (see docs/social-relations.md for the sources):
/// hearing 7 m ≈ the far end of Hall's "public distance, close phase" (3.7–7.6 m), where a raised
/// voice still reaches a companion (E. T. Hall, The Hidden Dimension, 1966); vision 25 m: a chosen
/// value at which a companion and a waving arm are still recognisable (face identification itself
/// degrades strongly beyond ~15–20 m, Loftus & Harley 2005, so this is an attention range, not a
/// face-recognition range); field of view 120° ≈ the human binocular field (~114–120°), the part of
/// the ~200° visual field where a gesture is reliably noticed.
struct SensoryParams {
  float touchMargin = 0.1f;   ///< touch reach beyond the sum of the two body radii [m] [Limit: >= 0]
  float hearingRange = 7.0f;  ///< d_h, centre-to-centre [m] [Limit: >= 0]; walls do not block hearing
  float visionRange = 25.0f;  ///< d_v, centre-to-centre [m] [Limit: >= 0]
  float fieldOfView = 2.0944f;  ///< α, full opening angle of the view cone [rad] [Limit: 0 < α <= 2π]; 120°
};

/// One problem per out-of-range field ("/fieldOfView: 7.0 rad is out of range; expected 0 < α <= 2π").
/// `pointer` prefixes each field's JSON pointer (e.g. "/social/senses").
[[nodiscard]] core::Diagnostics validate(const SensoryParams& params, const std::string& pointer = "");

/// What the sensory model needs of a character.
struct Body {
  Vec2 position;          ///< body centre [m]
  Vec2 facing{0.0f, 1.0f};  ///< body orientation = gaze direction, unit length; zero = sees nothing
  float radius = 0.2f;    ///< body radius [m] [Limit: >= 0]
};

/// Whether walls block the line of sight between two points. One virtual call per candidate that
/// is already inside range and field of view (not per pair in the grid cell).
class Occlusion {
 public:
  virtual ~Occlusion() = default;
  /// True when the straight segment a→b is blocked.
  [[nodiscard]] virtual bool blocked(Vec2 a, Vec2 b) const = 0;
};

/// Open space: nothing is ever blocked.
class NoOcclusion final : public Occlusion {
 public:
  [[nodiscard]] bool blocked(Vec2, Vec2) const override { return false; }
};

/// Walls as a list of segments (tests, small scenes): blocked when a→b crosses or touches any wall.
/// Linear in the number of walls.
class SegmentOcclusion final : public Occlusion {
 public:
  explicit SegmentOcclusion(std::vector<core::Segment> walls) : walls_(std::move(walls)) {}
  [[nodiscard]] bool blocked(Vec2 a, Vec2 b) const override;
  [[nodiscard]] std::span<const core::Segment> walls() const { return walls_; }

 private:
  std::vector<core::Segment> walls_;
};

/// Walls from the navigation mesh (Detour raycast, nav::NavQuery::visible): a segment that leaves
/// the walkable mesh counts as blocked, and so does one whose start is off the mesh. The mesh is
/// eroded by the agent radius, so sight lines grazing a corner are blocked slightly early
/// (conservative). NavQuery is not thread-safe: use one NavMeshOcclusion per thread.
class NavMeshOcclusion final : public Occlusion {
 public:
  explicit NavMeshOcclusion(const nav::NavQuery& query) : query_(&query) {}
  [[nodiscard]] bool blocked(Vec2 a, Vec2 b) const override;

 private:
  const nav::NavQuery* query_;
};

/// What `observer` perceives of `other` (all distances centre to centre, d = |other − observer|):
///   touch: d <= r_observer + r_other + touchMargin (symmetric);
///   hear:  d <= d_h; walls are ignored (sound travels around walls and through doors; the paper's
///          hearing is omnidirectional with a range limit only);
///   see:   d <= d_v, the angle between observer.facing and (other − observer) is <= α/2 (inclusive),
///          and the sight line is not blocked. A coincident `other` (d = 0) counts as in view.
[[nodiscard]] Perception perceive(const Body& observer, const Body& other, const SensoryParams& params,
                                  const Occlusion& occlusion);

/// Grid query: what `observer` perceives of each candidate (the spatial grid supplies candidates;
/// the caller leaves the observer itself out). Clears `out`, then appends (index into `candidates`,
/// perception) for every candidate perceived in at least one way, in candidate order. Equal to
/// calling perceive() per candidate; occlusion is consulted only for candidates in range and view.
void perceivedBy(const Body& observer, std::span<const Body> candidates, const SensoryParams& params,
                 const Occlusion& occlusion, std::vector<std::pair<std::uint32_t, Perception>>& out);

/// As above, but reports ids[i] instead of i (ids.size() must equal candidates.size(); e.g. the
/// rows the grid returned).
void perceivedBy(const Body& observer, std::span<const Body> candidates, std::span<const std::uint32_t> ids,
                 const SensoryParams& params, const Occlusion& occlusion,
                 std::vector<std::pair<std::uint32_t, Perception>>& out);

}  // namespace throng::common_ground
