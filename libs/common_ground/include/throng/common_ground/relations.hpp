// throng::common_ground situation assessment — which of the six spatial relations A1..A6 (relation.hpp;
// Park et al., §3.2, Figure 2(b)) an initiator A stands in with respect to a group mate B, the
// approach points x_i (into B's view and hearing) and x_j (into B's hearing) that the planner uses
// for A3/A6, and which attention micro-behaviours (Table 2) each relation allows. Read in `decide`:
// it reads two bodies and the walls, writes nothing. docs/social-relations.md has the picture.
#pragma once
#include <span>
#include <string_view>

#include "throng/common_ground/relation.hpp"
#include "throng/common_ground/sensing.hpp"

namespace throng::common_ground {

/// The relation of initiator A to member B, from what B perceives of A (pB = perceive(B, A)) and,
/// for A3/A6, what A perceives of B (pA = perceive(A, B)); checked in this order:
///   A1  pB.touch
///   A2  pB.see and pB.hear
///   A4  pB.hear and not pB.see
///   A5  pB.see and not pB.hear
///   A3  neither, but pA.see
///   A6  neither, and not pA.see (with one SensoryParams hearing is symmetric, so A does not hear
///       B either: neither perceives the other)
[[nodiscard]] Relation assess(const Body& initiatorA, const Body& memberB, const SensoryParams& params,
                              const Occlusion& occlusion);

/// A place for A to walk to. `reachable` is false when no candidate point satisfies the sensing
/// condition (every candidate is occluded from B). Walkability and a path from A are NOT checked
/// here: the planner checks them with nav::NavQuery::reachable.
struct Approach {
  Vec2 point;              ///< target position for A's centre [m]
  bool reachable = false;  ///< a point meeting the condition was found
};

/// x_i: the point nearest to A's position from which B would both see and hear A. The region is
/// B's view cone ∩ hearing disc, kept a little inside its edges (kApproachMargin) and at least
/// max(standOff, rA + rB) from B (A should not walk into B), i.e. the annular sector
///   { B + r·u(θ) : r ∈ [rMin, R], |θ| <= α/2 − ε },  R = min(d_h, d_v) − margin,
/// with θ measured from B's facing. Nearest point of that sector to A (polar coordinates of A
/// around B, (ρ, φ)): if |φ| <= α/2 − ε it is B + clamp(ρ, rMin, R)·u(φ); otherwise it is the
/// nearest point on one of the two edge segments θ = ±(α/2 − ε), r ∈ [rMin, R]. If A already
/// stands in the region, A's own position. If the nearest point is occluded from B, the nearest of
/// a fan of unoccluded samples of the sector (9 angles × 4 radii) is taken instead.
[[nodiscard]] Approach pointInView(const Body& initiatorA, const Body& memberB, const SensoryParams& params,
                                   const Occlusion& occlusion, float standOff = 2.0f);

/// x_j: the point nearest to A within B's hearing range (walls do not block hearing):
/// A's position if |A − B| <= d_h − margin, else B + (d_h − margin)·(A − B)/|A − B|. Always reachable
/// in the sensing sense (the planner still checks the path).
[[nodiscard]] Approach pointInHearing(const Body& initiatorA, const Body& memberB, const SensoryParams& params);

/// How far inside the region's edges approach points are placed [m], and [rad] for the cone edges,
/// so that float rounding never puts them just outside.
inline constexpr float kApproachMargin = 0.01f;

/// Names of the attention micro-behaviours (Table 2, "request attention" / "initiate
/// communication"). A '+' joins a move and the signal performed on arrival.
namespace behaviour {
inline constexpr std::string_view kTap = "tap";
inline constexpr std::string_view kCallOut = "call_out";
inline constexpr std::string_view kWave = "wave";
inline constexpr std::string_view kLookAt = "look_at";
inline constexpr std::string_view kMoveIntoViewWave = "move_into_view+wave";
inline constexpr std::string_view kMoveIntoHearingCallOut = "move_into_hearing+call_out";
inline constexpr std::string_view kMoveToward = "move_toward";
}  // namespace behaviour

/// Which attention micro-behaviours A may use in relation r (data for the coordination planner;
/// the first entry is the preferred one):
///   A1 tap, call_out               (touching: B feels a tap; touch range < d_h so B hears)
///   A2 call_out, wave, look_at     (B sees and hears A)
///   A3 move_into_view+wave, move_into_hearing+call_out   (B perceives nothing; A sees B and moves)
///   A4 call_out                    (B hears only: a gesture would not be seen)
///   A5 wave                        (B sees only: a call would not be heard)
///   A6 move_toward                 (nobody perceives anybody: approach first, then reassess)
[[nodiscard]] std::span<const std::string_view> allowedAttentionBehaviours(Relation r);

}  // namespace throng::common_ground
