// The anticipation velocity model: throng's calibrated pedestrian model (docs/crowd-model.md,
// "Operational models"). A first-order model after Xu, Chraibi, Seyfried, "Anticipation in a
// velocity-based model for pedestrian dynamics" (Transportation Research C 133, 2021), which extends
// the collision-free speed model of Tordeux, Chraibi, Seyfried (2016): the velocity is a speed
// times a direction, each from its own rule.
//
// Looking ahead (visionRange, 20 m by default; 0 turns it off). First the desired direction
// (the steer phase's preferred velocity) turns round a knot of people within the vision range that
// stands between the walker and its target (Moussaïd, Helbing, Theraulaz 2011; seeAhead and
// CrowdGrid below), looked at every kLookPeriod and kept in between (AgentStore::lookTurn): that
// is e0 from here on.
//
// Direction. The desired direction e0 is turned aside by
// every neighbour j in front (not those of i's own group, whose formation steer keeps), at the point
// of closest approach within the anticipation time t_a
// (both walking on: j with its velocity, i with its preferred one):
//   d_ij = min over t in [0, t_a] of |(x_j + v_j t) − (x_i + u_i t)|, as the vector c_ij from i,
//   R_ij = a · exp((ℓ_ij − |c_ij|) / D) · w_ij · side_ij,
// where side_ij is the unit vector perpendicular to e0 pointing away from c_ij (to the right when j
// is dead ahead; and to the right of anyone coming the other way unless they pass more than ℓ_ij
// to i's right: the keep-right convention that makes counter-flows form lanes), ℓ_ij = r_i + r_j
// and w_ij = (1 + cos φ_ij) / 2 weighs neighbours by the angle φ between e0 and the direction to j
// (those behind are ignored); the sum of these sideways pushes is scaled by the room to a wall on
// that side, and by the room beside j on that side: nobody swerves to pass someone where there is
// no body width between them and the wall (a corridor too narrow to overtake is walked in line).
// Only when two discs already overlap does a push act along the line of centres, and
// backwards only when the ellipses (below) really interpenetrate or i has been wedged for half the
// deadlock patience, so a queue does not walk backwards to make room. Walls push along their
// normal as in the collision-free speed model (strength b, range D_w), never backwards. The walking
// direction relaxes towards the result over the reaction time τ.
//
// Speed. Bodies are ellipses: shoulders across the walking direction (semi-axis r) and chest to
// back along it (semi-axis passageRatio · r). The gap along the walking direction e to the first
// body ahead — the distance i can walk before the two touch, s_ij = e·x_ij − q·ℓ_ij·sqrt(1 − (e × x_ij / ℓ_ij)²)
// for |e × x_ij| < ℓ_ij, q the passage ratio — gives
//   v_i = min(v0, max(0, min_j (s_ij − s0·f_ij) / (T·f_ij))),   f_ij = (1 − (e × x_ij / ℓ_ij)²)²,
// the time-gap law of the collision-free speed model (Tordeux et al.'s (s − ℓ)/T, measured along
// the walking direction, so a neighbour diagonally ahead blocks only as much as it really does).
// Someone straight ahead (f = 1) is followed at the single-file headway d = ℓ_depth + s0 + T·v
// (Seyfried et al. 2005: d = 0.36 + 1.06 v; kStandingGap); someone half a body to the side, whose
// steps do not fall where i's do, is followed closer in time and space (the zipper of Hoogendoorn
// and Daamen 2005: staggered walkers follow at shorter headways than those in line), which is what
// lets the same law give the single-file and the two-dimensional corridor data (kStaggerExponent).
// Cross and oncoming traffic (after Yamamoto et al. 2019 and Moussaïd et al. 2011; see the constants
// below): two people whose desired directions are more than 60° apart turn their shoulders, so one
// blocks the other only within passageRatio · ℓ of its walking line; a walker held below
// kSlipSpeed · v0 by someone whose desired direction is more than 60° off (or who stands at a spot)
// takes, of the directions within ±90° of e0, the one that makes the most progress (or, making
// none, steps sideways into the widest gap). Overtaking: a walker held below 0.9 v0 by someone
// walking its way at 0.9 or more of their own desired speed takes the nearest of those directions
// with a free walk of v0 · T (a lane to overtake in), while the crowd within 1.2 m of it is thinner than overtakeDensity (Fruin 1971's
// levels of service). And a walker
// within kSqueezeIn of its own target squeezes in beside people standing there. Neighbours' desired
// directions are those of the previous tick (ModelInput::priorDesiredX/Y), so the result does not depend on the
// thread or rank that steers them.
// Contact: bodies overlapping deeper than 1 cm step apart along their line of centres, each half the
// excess within the tick (contact), and the walking direction relaxes from the one meant a tick ago
// when the navmesh slid the walker along a wall away from its goal.
// Merging (two people converging less than 90° apart) the one nearer the shared space goes first,
// the other yields (the merge rule, gapLanes); without that both see the other ahead and both stop, which clogs
// every door. The navmesh keeps centres q·r from walls (ScenarioDesc::navRadius): people turn
// their shoulders to pass a narrow door, so the default body passes 0.5 m.
//
// Reads the steer phase's preferred velocities, positions, velocities, headings, modes, stuck times,
// radii, look turns, neighbours and walls; writes newVel, holdHeading and lookTurn of the rows it is given. Deterministic: one row's result depends only on the
// neighbours sense found, in their order.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <numbers>
#include <span>
#include <vector>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "../lanes.hpp"
#include "operational_model.hpp"
#include "throng/core/exp.hpp"
#include "throng/core/simd.hpp"

namespace throng::sim {
namespace {

using Lanes4 = simd::Lanes<4>;

/// For each mask of four lanes, the lanes set in it in ascending order (the rest: anything), and
/// how many are set (no popcnt instruction in the baseline x86-64), for pick's compaction.
struct PickOrder {
  alignas(16) std::int32_t lanes[16][4];
  std::uint8_t count[16];
};
constexpr PickOrder kPickOrder = [] {
  PickOrder t{};
  for (std::uint32_t mask = 0; mask < 16; ++mask) {
    std::uint8_t at = 0;
    for (std::int32_t lane = 0; lane < 4; ++lane) {
      if ((mask >> lane) & 1u) t.lanes[mask][at++] = lane;
    }
    t.count[mask] = at;
  }
  return t;
}();

constexpr std::string_view kCalibrated =
    "calibrated on the Juelich corridor uo-145-180-180, its jam uo-180-180-070 and the Wuppertal 0.5 m bottleneck "
    "(docs/validation.md, scripts/validate.py)";
constexpr std::string_view kWalls = "Tordeux et al. 2016; JuPedSim's collision-free speed model defaults";
constexpr ModelParameter kParameters[] = {
    {"timeGap", "s", 0.0, true, 10.0, false, 0.9f, "time gap T kept to the person straight ahead (shorter to someone half a body aside)",
     "Seyfried et al. 2005 single file (1.06 s), calibrated with the Juelich corridor uo-145-180-180 (docs/validation.md)"},
    {"anticipationTime", "s", 0.0, false, 10.0, false, 0.5f, "how far ahead t_a neighbours' paths are anticipated", kCalibrated},
    {"reactionTime", "s", 0.0, true, 10.0, false, 0.1f, "time τ over which the walking direction turns", kCalibrated},
    {"neighbourStrength", "1", 0.0, false, 100.0, false, 4.0f, "strength a of the sideways push from neighbours", kCalibrated},
    {"neighbourRange", "m", 0.0, true, 5.0, false, 0.1f, "range D of the push from neighbours", kWalls},
    {"wallStrength", "1", 0.0, false, 100.0, false, 5.0f, "strength b of the push from walls", kWalls},
    {"wallRange", "m", 0.0, true, 5.0, false, 0.02f, "range D_w of the push from walls", kWalls},
    {"passageRatio", "1", 0.3, false, 1.0, false, 0.65f,
     "body depth over shoulder breadth: bodies are ellipses this much shallower than wide, and the navmesh keeps centres radius × this from walls (shoulders turned)",
     "calibrated (docs/validation.md); adults' chest depth is about 0.55-0.65 of their shoulder breadth (DIN 33402-2)"},
    {"visionRange", "m", 0.0, false, 50.0, false, 20.0f,
     "how far a walker looks ahead to go round a knot of people between it and its target (0: off)",
     "the heuristic of Moussaid, Helbing, Theraulaz 2011 (PNAS 108), who use 10 m; 20 m measured on the bundled "
     "square and plaza, where 10 m still lets knots of people crossing every way grow (docs/crowd-model.md)"},
    {"separationPasses", "", 0.0, false, 4.0, true, 2.0f,
     "position correction after each move: bodies still overlapping are pushed apart this many times (0: off; of two "
     "merging, the one behind yields)",
     "measured on the dense room of scripts/validate.py with noPressing 1 (docs/crowd-model.md, Overlaps): deepest "
     "overlap after 1 s 0.021 m on seeds 1-5 with 2 (band 0.03), 0.071 m with 0; 3 passes walk people back from the door"},
    {"noPressing", "", 0.0, false, 1.0, true, 1.0f,
     "1: no step and no turn takes a body deeper into another (a merging walker squeezes by, slowly; two passing head "
     "on turn their shoulders); 0: off",
     "measured on the dense room, the bottlenecks and the bundled plaza (docs/crowd-model.md, No step into a body): with "
     "separationPasses 2 the dense room's deepest overlap 0.021 m and 0-9 agents over 1 cm, against 0.050 m and 19-43 without"},
    {"overtakeDensity", "1/m²", 0.0, false, 10.0, false, 1.3f,
     "a walker held up by someone slower ahead overtakes by a free lane while the crowd within 1.2 m of it is thinner than this (0: never)",
     "Fruin 1971 (levels of service D/E: passing slower people gets difficult from about 0.7 and impossible above about "
     "1.1-2.2 /m²); 1.3 measured on the ring against Weidmann and on the Juelich corridor (docs/crowd-model.md, Overtaking)"},
};
enum Parameter : std::size_t {
  kTimeGap,
  kAnticipationTime,
  kReactionTime,
  kNeighbourStrength,
  kNeighbourRange,
  kWallStrength,
  kWallRange,
  kPassageRatio,
  kVisionRange,
  kSeparationPasses,
  kNoPressing,
  kOvertakeDensity
};

struct AvmParams {
  float timeGap = 0.9f;            ///< T [s]
  float anticipationTime = 0.5f;   ///< t_a [s]
  float reactionTime = 0.1f;       ///< τ [s]
  float neighbourStrength = 4.0f;  ///< a [1]
  float neighbourRange = 0.1f;     ///< D [m]
  float wallStrength = 5.0f;       ///< b [1]
  float wallRange = 0.02f;         ///< D_w [m]
  float passageRatio = 0.65f;      ///< body depth / shoulder breadth [1]
  float visionRange = 20.0f;       ///< H of seeAhead [m]; 0: off
  int separationPasses = 2;        ///< position corrections after the move (separation); 0: off
  bool noPressing = true;          ///< clampToBodies and turnDeepens (and kOnWall in pushes); false: off
  float overtakeDensity = 1.3f;    ///< local density [1/m²] below which a walker overtakes (overtaking); 0: never
};

class AvmScratch final : public ModelScratch {
 public:
  std::vector<std::uint32_t> wallIds;
  std::vector<std::uint32_t> visionWalls;  ///< seeAhead's walls along one ray (roomAlong)
  /// slip's neighbours near enough to block some direction, with what gapAhead asks of each that
  /// does not depend on the direction tried (worked out once for the twelve).
  struct NearBlocker {
    core::Vec2 d;      ///< from i to o
    core::Vec2 eo;     ///< o's walking direction (the merge rule, gapLanes)
    float l;           ///< r_i + r_o
    float aheadOfO;    ///< how far i is ahead of o along eo
    bool turned;       ///< the two turn their shoulders to pass (opposed beyond kRotateCos)
    bool walking;      ///< o walks (the merge rule; otherwise an obstacle)
    bool lowerId;      ///< i's id is below o's (the merge rule's tie)
  };
  std::vector<NearBlocker> near;
  std::vector<std::uint32_t> lane;  ///< pick's buffer for the neighbours a pass looks at further (pushes, gapAhead)
  /// The walker's neighbours as seen from it (lookAround): offset d = x_o − x_i and ℓ = r_i + r_o,
  /// in the order sense listed them, padded with zeros to a multiple of four.
  std::vector<float> aroundX, aroundY, aroundL;
  /// clampToBodies: a neighbour the step may reach, and how deep it may press into it [m] while the
  /// step loses what presses (`first`) and while it is shortened (`then`).
  struct NearBody {
    std::uint32_t o;
    core::Vec2 d;
    float first, then;
    bool leads;
  };
  std::vector<NearBody> nearBodies;
};

/// Two walkers whose directions are less than this far apart (cos 120°) settle who goes first
/// (the merge rule, gapLanes); nearer head on, both slow down and step aside.
constexpr float kGiveWayCos = -0.5f;

/// Of two walkers merging (i and o, d from i to o, desired directions ei and eo), whether i is the
/// one further along their common way: o stands behind i along the sum of their unit desired
/// directions (within 0.1 mm: the lower id goes first). noPressing lets the leader squeeze on; the
/// position correction has the other one yield.
bool furtherAlong(core::Vec2 d, core::Vec2 ei, core::Vec2 eo, std::uint32_t idI, std::uint32_t idO) {
  const float lead = -core::dot(d, core::normalize(ei) + core::normalize(eo));
  return lead > 1e-4f || (lead > -1e-4f && idI < idO);
}

/// A standing agent pressed by others steps away at most this fast [m/s], kMakeRoomGain [m/s] per
/// unit of push (a push of 1 is a neighbour's disc overlapping by about 0.14 m at the defaults).
constexpr float kMakeRoomSpeed = 0.3f;
constexpr float kMakeRoomGain = 0.05f;

/// Shoulder rotation (Yamamoto, Yanagisawa, Feliciani, Nishinari 2019, "Body-rotation behavior of
/// pedestrians for collision avoidance in passing and cross flow", Transp. Res. B 122): two people
/// whose desired directions are more than 60° apart (cos < kRotateCos: counter-flow and crossing
/// flow alike) turn their shoulders to pass, so one blocks the other only within
/// passageRatio · (r_i + r_j) of its walking line. (90° before session 31: with 60°, crowds crossing
/// in every direction keep moving better and the harness is unchanged; docs/crowd-model.md.)
constexpr float kRotateCos = 0.5f;

/// Slipping through cross traffic (the heuristic direction choice of Moussaïd, Helbing, Theraulaz
/// 2011, "How simple rules determine pedestrian behavior and crowd disasters", PNAS 108): a walker
/// held below kSlipSpeed · v0 by someone whose desired direction is more than 60° off its own
/// (cos < kSlipCos) takes, of the directions within ±90° of its desired one, the one that makes the
/// most progress (speed from the time-gap law times the cosine to the desired direction); when none
/// makes any, it steps sideways into the widest gap that lets it walk at least kSidestepSpeed, so
/// people wedged in a crossing crowd shuffle past each other instead of standing for ever.
constexpr float kSlipCos = 0.5f;
/// Within this distance of its own target [m] a walker is not held up by people standing there (the
/// group waiting at its spot, others acting): it squeezes in beside them.
constexpr float kSqueezeIn = 0.6f;
/// Held below this share of the desired speed, a walker facing cross traffic slips through (0.4:
/// chosen on the harness and the verification suite, docs/validation.md; 0.5-0.6 raise the 0.5 m
/// door's and the dense room's flows past their bands).
constexpr float kSlipSpeed = 0.4f;
/// Overtaking (docs/crowd-model.md, "Overtaking"): a walker held below kOvertakeShare · v0 by
/// someone walking its way at kOvertakeShare or more of their own desired speed (slower by nature,
/// not held up in turn) looks, among the slip's directions, for a lane it can walk at its own speed
/// (a gap of v0 · T) and takes the one that makes the most progress, as long as fewer people than
/// overtakeDensity per m² stand within kOvertakeRadius of it (Fruin 1971: passing slower people
/// gets difficult at levels of service D and E). Without it, fast walkers followed slow ones at the
/// time gap for ever: the ring at 0.25 and 0.5 /m² walked 1.20 and 1.09 m/s against Weidmann's 1.34
/// and 1.30, and the Jülich corridor about 0.09 m/s below the experiment in every density class.
constexpr float kOvertakeShare = 0.9f;
constexpr float kOvertakeRadius = 1.2f;  ///< [m] the circle the local density is counted in
constexpr int kSlipSteps = 6;                   ///< candidates each side of e0 (15° apart: ±90°)
constexpr float kSidestepSpeed = 0.05f;         ///< the slowest sideways step worth taking [m/s]
constexpr float kSlipStep = 0.2617994f;         ///< 15° between candidates [rad]

/// Looking ahead (seeAhead) is done every kLookPeriod seconds [s], the agents taking turns by id; in
/// between, a walker keeps the turn it chose (AgentStore::lookTurn) from its desired direction as
/// that changes. People take in a scene about three times a second (gaze fixations in natural tasks
/// last 0.2-0.4 s: Land and Tatler 2009, "Looking and Acting", Oxford UP), and looking every tick
/// was a sixth of avm's time at 10,000 agents (docs/performance.md).
constexpr float kLookPeriod = 0.3f;
/// lookTurn's "look now".
constexpr int kLookAgain = 127;

/// cos and sin of k · kSlipStep for k = −kSlipSteps … kSlipSteps (index k + kSlipSteps), worked out
/// once with the expressions the look ahead and the slip used per walker: the same values without
/// two dozen calls for every walker held up (a tenth of avm's time at 100k agents).
struct SlipAngles {
  std::array<float, 2 * kSlipSteps + 1> cos{}, sin{};
  SlipAngles() {
    for (int k = -kSlipSteps; k <= kSlipSteps; ++k) {
      cos[static_cast<std::size_t>(k + kSlipSteps)] = std::cos(static_cast<float>(k) * kSlipStep);
      sin[static_cast<std::size_t>(k + kSlipSteps)] = std::sin(static_cast<float>(k) * kSlipStep);
    }
  }
  [[nodiscard]] float c(int k) const { return cos[static_cast<std::size_t>(k + kSlipSteps)]; }
  [[nodiscard]] float s(int k) const { return sin[static_cast<std::size_t>(k + kSlipSteps)]; }
};
const SlipAngles kSlipAngles;

/// Seeing the crowd ahead (the cognitive heuristic of Moussaïd, Helbing, Theraulaz 2011, "How simple
/// rules determine pedestrian behavior and crowd disasters", PNAS 108): a walker looks H =
/// visionRange metres along the directions within ±90° of its desired one and takes the one that brings it
/// nearest its destination, d(α)² = H² + f(α)² − 2·H·f(α)·cos(α0 − α), where f(α) is how far it can
/// see along α before a wall or a crowded cell (kCrowdedCount agents or more in a cell of
/// kCrowdCell m: 3 /m², not a stream going i's way: kJoinCos, kOrderedShare). So walkers go round a
/// knot of people instead of into it, which keeps crowds crossing in every direction from locking up
/// (the bundled square, 1000 strollers in groups of 4 between random points: 0.87–0.96 m/s over three seeds
/// against 0.32 m/s and a 700-agent knot without it; docs/crowd-model.md). Only when the crowd lies
/// between the walker and its target (more than kVisionBeyond beyond the crowded cell): a queue at
/// one's own door is followed, not walked round. The default range, 20 m, is measured: the paper's
/// H = 10 m still lets knots grow on the square and the plaza (docs/crowd-model.md).
constexpr float kCrowdCell = 1.0f;
constexpr std::uint16_t kCrowdedCount = 3;
constexpr float kVisionBeyond = 2.0f;
/// A crowded cell is a stream i joins, not a knot it walks round, when its people go one way (the
/// mean of their unit desired directions is at least kOrderedShare long) and that way is within about
/// 70° of i's (the mean projects on i's desired direction by at least kJoinCos): the fan of people
/// converging on a door is followed, which keeps the bottlenecks' longest gaps and the room's flow in
/// their bands (docs/validation.md), while a knot of people going every which way, or a stream
/// crossing or coming the other way, is walked round.
constexpr float kJoinCos = 0.3f;
constexpr float kOrderedShare = 0.6f;
/// Contact (AnticipationVelocityModel::contact): overlaps of the bodies up to this depth are left
/// alone [m]; deeper, the two step apart, at most kContactSpeed [m/s].
constexpr float kContactSlack = 0.01f;
constexpr float kContactSpeed = 1.0f;
constexpr float kContactShare = 0.5f;
/// noPressing: in room(), a walker this close to a wall line, or past it, has
/// no room that way [m]. Without it a walker pressed onto the navmesh's edge at a narrow door's
/// mouth saw room to swerve into the wall, and with clampToBodies two of them stood side by side at
/// the 0.5 m door for 5-9 s (docs/crowd-model.md).
constexpr float kOnWall = 0.02f;
/// noPressing, no step deeper into a body (clampToBodies): of two merging walkers the one further along may
/// still squeeze by the other, at most this fast [m/s] and this deep [m], and so may two coming
/// head on offset enough to pass with shoulders turned. Chosen on the harness (docs/validation.md):
/// with 0.3 m/s the corridor's densest class fell to 0.77 m/s (band from 0.79), with 0.03 m two
/// people wedged side by side at the 0.5 m door for 28 s.
constexpr float kSqueezeSpeed = 0.6f;
constexpr float kSqueezeDepth = 0.05f;
/// Separation (separationPasses): each of two overlapping bodies moves this share of the depth.
constexpr float kSeparationShare = 0.5f;
/// The time-gap law's weight of a neighbour at lateral offset y (in units of ℓ_ij) ahead:
/// f = (1 − y²)^kStaggerExponent, 1 straight ahead, falling to 0 at the edge of the shoulder band.
/// A neighbour half a body aside (y = 0.5) is followed at 0.56 of the headway of one in line: the
/// zipper (Hoogendoorn, Daamen 2005, "Pedestrian behavior at bottlenecks", Transp. Sci. 39: walkers
/// in staggered lanes follow closer than in one line). 2 measured on the harness (docs/validation.md):
/// 1 keeps the corridor's dense classes too slow, 3 the single file too fast.
constexpr float kStaggerExponent = 2.0f;
/// The extra distance kept to the person straight ahead, over the two bodies' depth [m]: Seyfried,
/// Steffen, Klingsch, Boltes 2005 (J. Stat. Mech. P10002) measured people in single file standing
/// 0.36 m apart (centre to centre), against the ellipses' 0.26 m at the default body.
constexpr float kStandingGap = 0.1f;
/// Swerving to pass someone ahead needs this many body widths between them and the wall on that
/// side (kPassRamp more for the full push): in a corridor too narrow to overtake people walk in line.
constexpr float kPassWidths = 1.0f;
constexpr float kPassRamp = 0.1f;  ///< [m]
/// Floors of a multi-level world are told apart in bins of this height [m] (a storey is 2.5–4 m).
constexpr float kCrowdStorey = 2.5f;

#if defined(__x86_64__)
/// CrowdGrid::clearAhead's scan on the AVX2 path, eight points t, t + 0.5, … at a time (the same
/// IEEE operations as the scan's, so the same cells): from `t` on, skips every block of eight points
/// whose cells hold no crowd, and stops at the first block with one — `t` left at its first point,
/// the index entries of its eight cells in `entries`, the lanes holding a crowd returned as a mask —
/// or, returning 0, at the first block that reaches past `last`. The points must lie on the dense
/// index's grid, whose entries fit 32-bit offsets. Not inlined: its instructions need the AVX2 target.
[[gnu::target("avx2"), gnu::noinline]] unsigned nextCrowdedAvx2(const std::int32_t* dense, std::int32_t layer, std::int32_t nx,
                                                                core::Vec2 pos, core::Vec2 dir, core::Vec2 origin, float& t,
                                                                float last, std::int32_t* entries) {
  constexpr float kStep = 0.5f;  // clearAhead's, for cells of 1 m
  const __m256 px = _mm256_set1_ps(pos.x), py = _mm256_set1_ps(pos.y), dx = _mm256_set1_ps(dir.x), dy = _mm256_set1_ps(dir.y);
  const __m256 ox = _mm256_set1_ps(origin.x), oy = _mm256_set1_ps(origin.y);
  const __m256 lanes = _mm256_setr_ps(0.0f, kStep, 2.0f * kStep, 3.0f * kStep, 4.0f * kStep, 5.0f * kStep, 6.0f * kStep, 7.0f * kStep);
  const __m256i row = _mm256_set1_epi32(nx), base = _mm256_set1_epi32(layer);
  for (; t + 7.0f * kStep <= last; t += 8.0f * kStep) {
    const __m256 tv = _mm256_add_ps(_mm256_set1_ps(t), lanes);
    const __m256i cx = _mm256_cvttps_epi32(_mm256_sub_ps(_mm256_add_ps(px, _mm256_mul_ps(dx, tv)), ox));
    const __m256i cy = _mm256_cvttps_epi32(_mm256_sub_ps(_mm256_add_ps(py, _mm256_mul_ps(dy, tv)), oy));
    const __m256i cell = _mm256_add_epi32(_mm256_mullo_epi32(_mm256_add_epi32(base, cy), row), cx);
    const __m256i entry = _mm256_i32gather_epi32(dense, cell, 4);
    const auto crowded = ~static_cast<unsigned>(_mm256_movemask_ps(_mm256_castsi256_ps(entry))) & 0xffu;  // entries >= 0
    if (crowded != 0) {
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(entries), entry);
      return crowded;
    }
  }
  return 0;
}
#endif

/// Agents per cell of kCrowdCell metres (and storey bins of kCrowdStorey on multi-level worlds) over
/// the box round every agent: what walkers see of the crowd ahead. Built serially once a tick from
/// the positions at its start, so the same for any thread or rank count.
class CrowdGrid {
 public:
  void build(const ModelInput& in, float range) {
    const AgentStore& a = in.agents;
    range_ = range;
    cells_.clear();
    const std::size_t n = a.posX.size();
    if (n == 0) return;
    float x0 = a.posX[0], x1 = x0, y0 = a.posY[0], y1 = y0, z0 = a.height(0), z1 = z0;
    for (std::size_t i = 1; i < n; ++i) {
      x0 = std::min(x0, a.posX[i]);
      x1 = std::max(x1, a.posX[i]);
      y0 = std::min(y0, a.posY[i]);
      y1 = std::max(y1, a.posY[i]);
      z0 = std::min(z0, a.height(i));
      z1 = std::max(z1, a.height(i));
    }
    x0_ = x0 - range;
    y0_ = y0 - range;
    z0_ = z0;
    nx_ = static_cast<std::int64_t>((x1 - x0 + 2.0f * range) / kCrowdCell) + 1;
    ny_ = static_cast<std::int64_t>((y1 - y0 + 2.0f * range) / kCrowdCell) + 1;
    nz_ = std::min(64, static_cast<int>((z1 - z0) / kCrowdStorey) + 1);
    // Only crowded cells are stored (cells_, 12 bytes each): at 1 agent/m² about 8 % of the cells
    // hold kCrowdedCount people or more, and the look ahead skips every other cell. They are found
    // through a dense index over the box while that stays within kDenseCellsPerAgent cells an agent,
    // else through an open-addressed table at most a quarter full: memory and the per-tick reset
    // follow the number of agents, not the world's size. An index entry is a cell's place in cells_
    // (>= 0) or, below 0, no crowd: while counting, -1 - (the people in it).
    dense_.clear();
    slots_.clear();
    cells_.clear();
    const auto boxCells = static_cast<double>(nx_) * static_cast<double>(ny_) * nz_;
    avx2_ = false;
    if (boxCells <= kDenseCellsPerAgent * static_cast<double>(n) + kDenseCellsMin) {
      dense_.assign(static_cast<std::size_t>(boxCells), -1);
      avx2_ = core::simdPath() == core::SimdPath::Avx2 && boxCells < 2147483647.0;
    } else {
      std::size_t size = 64;
      while (size < 4 * n) size *= 2;
      mask_ = size - 1;
      slots_.assign(size, Slot{});
    }
    const auto cellOf = [&](std::size_t i) {
      // fx, fy >= 0 (the box reaches `range` beyond everyone): truncation is floor.
      const float fx = (a.posX[i] - x0_) / kCrowdCell, fy = (a.posY[i] - y0_) / kCrowdCell;
      return key(static_cast<std::int64_t>(fx), static_cast<std::int64_t>(fy), storey(a.height(i)));
    };
    for (std::size_t i = 0; i < n; ++i) {  // count
      std::int32_t& v = indexOf(cellOf(i));
      if (v > -1 - 0xffff) --v;
    }
    for (std::size_t i = 0; i < n; ++i) {  // the crowded cells: their people's directions
      std::int32_t& v = indexOf(cellOf(i));
      if (v < 0) {
        if (-1 - v < kCrowdedCount) continue;
        v = static_cast<std::int32_t>(cells_.size());
        cells_.push_back(Cell{});
      }
      Cell& c = cells_[static_cast<std::size_t>(v)];
      if (c.count == 0xffff) continue;
      ++c.count;
      const core::Vec2 want{in.priorDesiredX[i], in.priorDesiredY[i]};
      const float len = core::length(want);
      if (len > 1e-6f) {
        c.sumX += fixedPoint(want.x / len);
        c.sumY += fixedPoint(want.y / len);
      }
    }
    for (Cell& c : cells_) {
      c.kind = core::length(c.heading()) < kOrderedShare * static_cast<float>(c.count) ? kKnot : kStream;
    }
  }

  /// How far along the unit vector dir from pos (at floor height z) before a cell crowded with
  /// people not going e0's way, at most `range` [m] (the walker's own cell is not looked at).
  /// It looks at the points t = 1, 1.5, 2, … m ≤ range along the ray, each in the cell it falls in.
  [[nodiscard]] float clearAhead(core::Vec2 pos, float z, core::Vec2 dir, core::Vec2 e0, float range) const {
    constexpr float kStep = 0.5f * kCrowdCell;
    range = std::min(range, range_);
    const int floor = storey(z);
    if (range < kCrowdCell) return range;
    // The last point (t is exact: a multiple of kStep). A point's cell coordinates are monotone in t
    // (each float operation is), so when the first and the last point are on the grid, all are, and
    // the dense index needs no bounds checks.
    float last = kCrowdCell + kStep * std::floor((range - kCrowdCell) / kStep);
    while (last + kStep <= range) last += kStep;
    while (last > range) last -= kStep;
    if (!dense_.empty() && onGrid(pos, dir, kCrowdCell) && onGrid(pos, dir, last)) {
      const std::int64_t layer = static_cast<std::int64_t>(floor) * ny_;
      const std::int32_t* dense = dense_.data();
      float t = kCrowdCell;
#if defined(__x86_64__)
      static_assert(kCrowdCell == 1.0f, "nextCrowdedAvx2 leaves out the division by the cell size");
      if (avx2_) {  // eight points at a time, only blocks with a crowded cell looked at point by point
        alignas(32) std::int32_t entries[8];
        const auto l32 = static_cast<std::int32_t>(layer), nx32 = static_cast<std::int32_t>(nx_);
        while (unsigned crowded = nextCrowdedAvx2(dense, l32, nx32, pos, dir, {x0_, y0_}, t, last, entries)) {
          for (; crowded != 0; crowded &= crowded - 1) {
            const int j = std::countr_zero(crowded);
            if (blocks(cells_[static_cast<std::size_t>(entries[j])], e0)) return t + kStep * static_cast<float>(j);
          }
          t += 8.0f * kStep;
        }
      }
#endif
#if defined(__SSE2__)
      // Four points at a time: the same IEEE operations on four lanes (exact as one at a time), then
      // the look-ups in order.
      static_assert(kCrowdCell == 1.0f, "the lanes leave out the division by the cell size");
      const __m128 px = _mm_set1_ps(pos.x), py = _mm_set1_ps(pos.y), dx = _mm_set1_ps(dir.x), dy = _mm_set1_ps(dir.y);
      const __m128 ox = _mm_set1_ps(x0_), oy = _mm_set1_ps(y0_), lanes = _mm_setr_ps(0.0f, kStep, 2.0f * kStep, 3.0f * kStep);
      alignas(16) std::int32_t cx[4], cy[4];
      for (; t + 3.0f * kStep <= last; t += 4.0f * kStep) {
        const __m128 tv = _mm_add_ps(_mm_set1_ps(t), lanes);
        _mm_store_si128(reinterpret_cast<__m128i*>(cx), _mm_cvttps_epi32(_mm_sub_ps(_mm_add_ps(px, _mm_mul_ps(dx, tv)), ox)));
        _mm_store_si128(reinterpret_cast<__m128i*>(cy), _mm_cvttps_epi32(_mm_sub_ps(_mm_add_ps(py, _mm_mul_ps(dy, tv)), oy)));
        for (int j = 0; j < 4; ++j) {
          const std::int32_t i = dense[(layer + cy[j]) * nx_ + cx[j]];
          if (i >= 0 && blocks(cells_[static_cast<std::size_t>(i)], e0)) return t + kStep * static_cast<float>(j);
        }
      }
#endif
      for (; t <= range; t += kStep) {
        const core::Vec2 q = pos + dir * t;
        const float fx = (q.x - x0_) / kCrowdCell, fy = (q.y - y0_) / kCrowdCell;
        const std::int64_t k = (layer + static_cast<std::int64_t>(fy)) * nx_ + static_cast<std::int64_t>(fx);
        const std::int32_t i = dense[k];
        if (i >= 0 && blocks(cells_[static_cast<std::size_t>(i)], e0)) return t;
      }
      return range;
    }
    for (float t = kCrowdCell; t <= range; t += kStep) {
      const core::Vec2 q = pos + dir * t;
      const float fx = (q.x - x0_) / kCrowdCell, fy = (q.y - y0_) / kCrowdCell;
      if (!(fx >= 0.0f && fy >= 0.0f)) return range;  // off the grid (truncation is floor from here)
      const auto cx = static_cast<std::int64_t>(fx), cy = static_cast<std::int64_t>(fy);
      if (cx >= nx_ || cy >= ny_) return range;
      const Cell* c = find(key(cx, cy, floor));
      if (c != nullptr && blocks(*c, e0)) return t;
    }
    return range;
  }

  [[nodiscard]] bool empty() const { return cells_.empty(); }

 private:
  /// A cell's crowd: fewer than kCrowdedCount people, a stream (its people go one way: blocks those
  /// it is not within kJoinCos of) or a knot (they go every which way: blocks everyone).
  enum : std::uint8_t { kClear, kStream, kKnot };

  /// A cell's directions are summed in fixed point (units of 1 / kHeadingScale; at most 65535 of
  /// them fit in 32 bits): integer sums do not depend on the order of the rows (row_order.cpp).
  static constexpr float kHeadingScale = 16384.0f;
  static std::int32_t fixedPoint(float unit) {
    return static_cast<std::int32_t>(unit * kHeadingScale + (unit >= 0.0f ? 0.5f : -0.5f));
  }
  struct Cell {
    std::int32_t sumX = 0, sumY = 0;  ///< the cell's agents' unit desired directions, summed in fixed point
    std::uint16_t count = 0;
    std::uint8_t kind = kClear;
    /// The sum of the unit desired directions of the cell's agents.
    [[nodiscard]] core::Vec2 heading() const {
      return core::Vec2{static_cast<float>(sumX), static_cast<float>(sumY)} / kHeadingScale;
    }
  };
  static_assert(sizeof(Cell) <= 12);
  struct Slot {
    std::int64_t key = -1;  ///< -1: free
    std::int32_t cell = -1;
  };
  /// The dense index is used while the box holds at most this many cells per agent (plus kDenseCellsMin).
  static constexpr double kDenseCellsPerAgent = 16.0;
  static constexpr double kDenseCellsMin = 65536.0;

  /// Whether the point pos + dir · t falls in a cell of the grid (as clearAhead computes it).
  [[nodiscard]] bool onGrid(core::Vec2 pos, core::Vec2 dir, float t) const {
    const core::Vec2 q = pos + dir * t;
    const float fx = (q.x - x0_) / kCrowdCell, fy = (q.y - y0_) / kCrowdCell;
    return fx >= 0.0f && fy >= 0.0f && static_cast<std::int64_t>(fx) < nx_ && static_cast<std::int64_t>(fy) < ny_;
  }

  /// Whether cell c stops the look of a walker whose desired direction is e0: a knot, or a stream
  /// not going e0's way.
  static bool blocks(const Cell& c, core::Vec2 e0) {
    if (c.kind == kClear) return false;
    return c.kind == kKnot || core::dot(c.heading(), e0) < kJoinCos * static_cast<float>(c.count);
  }

  /// The storey bin of height z.
  [[nodiscard]] int storey(float z) const {
    return std::min(nz_ - 1, std::max(0, static_cast<int>((z - z0_) / kCrowdStorey)));
  }

  [[nodiscard]] std::int64_t key(std::int64_t cx, std::int64_t cy, int cz) const {
    return (static_cast<std::int64_t>(cz) * ny_ + cy) * nx_ + cx;
  }

  [[nodiscard]] std::size_t home(std::int64_t k) const {
    return static_cast<std::size_t>((static_cast<std::uint64_t>(k) * 0x9e3779b97f4a7c15ull) >> 20) & mask_;
  }

  /// Where cell k's index entry is kept (-1 until someone is in it).
  std::int32_t& indexOf(std::int64_t k) {
    if (!dense_.empty()) return dense_[static_cast<std::size_t>(k)];
    for (std::size_t i = home(k);; i = (i + 1) & mask_) {
      if (slots_[i].key == k) return slots_[i].cell;
      if (slots_[i].key < 0) {
        slots_[i].key = k;
        return slots_[i].cell;
      }
    }
  }

  /// Cell k when it is crowded, else null.
  [[nodiscard]] const Cell* find(std::int64_t k) const {
    if (!dense_.empty()) {
      const std::int32_t i = dense_[static_cast<std::size_t>(k)];
      return i < 0 ? nullptr : &cells_[static_cast<std::size_t>(i)];
    }
    for (std::size_t i = home(k);; i = (i + 1) & mask_) {
      if (slots_[i].key == k) return slots_[i].cell < 0 ? nullptr : &cells_[static_cast<std::size_t>(slots_[i].cell)];
      if (slots_[i].key < 0) return nullptr;
    }
  }

  std::vector<Cell> cells_;          ///< the crowded cells, in the order they were first met
  std::vector<std::int32_t> dense_;  ///< index entry per cell of the box (see build), or empty
  std::vector<Slot> slots_;          ///< open-addressed cell → index, when the box is too large
  std::size_t mask_ = 0;
  float x0_ = 0, y0_ = 0, z0_ = 0, range_ = 0;
  std::int64_t nx_ = 0, ny_ = 0;
  int nz_ = 1;
  bool avx2_ = false;  ///< clearAhead scans with nextCrowdedAvx2 (the AVX2 path, and a dense index of 32-bit offsets)
};

/// The perpendicular of e pointing to its right.
core::Vec2 rightOf(core::Vec2 e) { return {e.y, -e.x}; }

class AnticipationVelocityModel final : public OperationalModel {
 public:
  [[nodiscard]] ModelKind kind() const override { return ModelKind::AnticipationVelocity; }

  void configure(const ScenarioDesc& desc) override {
    params_.clear();
    vision_ = 0.0f;
    dt_ = desc.dt;
    for (const PopulationDesc& pop : desc.populations) {
      AvmParams p;
      if (pop.model.kind == ModelKind::AnticipationVelocity) {
        const auto& v = pop.model.values;
        p = {v[kTimeGap],        v[kAnticipationTime], v[kReactionTime], v[kNeighbourStrength],
             v[kNeighbourRange], v[kWallStrength],     v[kWallRange],    v[kPassageRatio], v[kVisionRange],
             static_cast<int>(v[kSeparationPasses]), v[kNoPressing] != 0.0f, v[kOvertakeDensity]};
      } else {
        p.passageRatio = 1.0f;  // another model's bodies are discs (contact)
      }
      params_.push_back(p);
      vision_ = std::max(vision_, p.visionRange);
    }
    lookPeriod_ = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::floor(kLookPeriod / desc.dt + 1e-4f)));
  }

  [[nodiscard]] std::unique_ptr<ModelScratch> makeScratch() const override { return std::make_unique<AvmScratch>(); }

  [[nodiscard]] bool readsPriorDesired() const override { return true; }

  void beginStep(const ModelInput& in) override {
    avx2_ = core::simdPath() == core::SimdPath::Avx2;
    maxRadius_ = 0.0f;
    for (const float r : in.agents.radius) maxRadius_ = std::max(maxRadius_, r);
    if (vision_ > 0.0f) crowd_.build(in, vision_);
  }

  void computeVelocities(const ModelInput& in, RowRange rows, ModelScratch& scratch, VelocityOutput out) const override {
#if defined(__x86_64__)
    if (avx2_) {
      computeVelocitiesAvx2(in, rows, scratch, out);
      return;
    }
#endif
    computeRows(in, rows, scratch, out);
  }

 private:
#if defined(__x86_64__)
  /// computeVelocities on the AVX2 path (core::simdPath): the same operations in the same order, so
  /// the same bits, compiled for AVX2 with velocity and what it inlines (VEX encoding: three
  /// operands, fewer register copies). Not inlined: the target differs.
  [[gnu::target("avx2"), gnu::noinline]] void computeVelocitiesAvx2(const ModelInput& in, RowRange rows, ModelScratch& scratch,
                                                                    VelocityOutput out) const {
    computeRows(in, rows, scratch, out);
  }
#endif

  [[gnu::always_inline]] void computeRows(const ModelInput& in, RowRange rows, ModelScratch& scratch, VelocityOutput out) const {
    auto& ws = static_cast<AvmScratch&>(scratch);
    for (std::size_t i = rows.begin; i < rows.end; ++i) {
      const std::size_t row = rows.row(i);
      const AvmParams& p = params_[in.agents.population[row]];
      // The look ahead's turn: worked out anew on the row's look ticks (every row when there is no
      // column to keep it in), else the one it chose last.
      const bool kept = !out.lookTurn.empty() && !looksNow(in, row);
      int turn = kept ? in.agents.lookTurn[row] : kLookAgain;
      const core::Vec2 v = velocity(in, row, p, ws, turn);
      out.x[row] = v.x;
      out.y[row] = v.y;
      if (!out.lookTurn.empty()) out.lookTurn[row] = static_cast<std::int8_t>(turn);
      if (!out.holdHeading.empty()) out.holdHeading[row] = p.noPressing && turnDeepens(in, row, v, p) ? 1 : 0;
    }
  }

  /// The look ahead (visionRange, CrowdGrid): 0 (e0 itself) unless a crowd closer than the vision
  /// range stands between i and its target, else the turn k (e0 turned by k · kSlipStep, k within
  /// ±kSlipSteps: turned(e0, k)) that brings i nearest its destination, walls and crowded cells
  /// limiting the view.
  int seeAhead(const ModelInput& in, std::size_t row, core::Vec2 e0, float range, float onWall, AvmScratch& ws) const {
    const AgentStore& a = in.agents;
    float f0 = 0.0f;
    if (!crowdBetween(in, row, e0, range, f0)) return 0;
    const core::Vec2 pos{a.posX[row], a.posY[row]};
    const float z = a.height(row);
    // Walls matter only nearer than the crowd along a ray: those in the cells the ray crosses that far.
    f0 = std::min(f0, roomAlong(in, ws, pos, z, e0, f0, onWall));
    const float h = range;
    float best = h * h + f0 * f0 - 2.0f * h * f0;
    int out = 0;
    for (int k = 1; k <= kSlipSteps; ++k) {
      // Along α the destination gets no nearer than H·sin α (seen clear to H·cos α), which only grows
      // with α up to 90°: once that cannot beat the best, no wider direction can.
      const float widest = kSlipAngles.s(k);
      if (h * h * widest * widest >= best - 1e-4f) break;
      for (const int side : {1, -1}) {  // nearer angles first, the right before the left
        const core::Vec2 ec = turned(e0, side * k);
        const float crowd = crowd_.clearAhead(pos, z, ec, e0, range);
        const float f = std::min(crowd, roomAlong(in, ws, pos, z, ec, crowd, onWall));
        const float d2 = h * h + f * f - 2.0f * h * f * kSlipAngles.c(side * k);
        if (d2 < best - 1e-4f) {
          best = d2;
          out = side * k;
        }
      }
    }
    return out;
  }

  /// Whether a crowd closer than `range` along e0 stands between i and its target (f0: how far i
  /// sees along e0 before it), seeAhead's first question. Not when the crowd is where i is going:
  /// at its target, or at the path's corner it walks to (a door's jamb: the crowd in the doorway is
  /// passed through, not walked round — turned away by it, people at a door's mouth walked back from
  /// it along the wall, the dense room's walk-back).
  bool crowdBetween(const ModelInput& in, std::size_t row, core::Vec2 e0, float range, float& f0) const {
    const AgentStore& a = in.agents;
    if (range <= 0.0f || crowd_.empty()) return false;
    const core::Vec2 pos{a.posX[row], a.posY[row]};
    f0 = crowd_.clearAhead(pos, a.height(row), e0, e0, range);
    if (f0 >= range) return false;
    const core::Vec2 toTarget{a.targetX[row] - pos.x, a.targetY[row] - pos.y};
    if (core::length(toTarget) < f0 + kVisionBeyond) return false;
    if (const CornerPath& c = a.corners[row]; c.index < c.size() && core::length(c[c.index] - pos) < f0 + kVisionBeyond) return false;
    return true;
  }

  /// e turned by k · kSlipStep (k within ±kSlipSteps; positive: to the left).
  static core::Vec2 turned(core::Vec2 e, int k) {
    if (k == 0) return e;
    const float c = kSlipAngles.c(k), sn = kSlipAngles.s(k);
    return {e.x * c - e.y * sn, e.x * sn + e.y * c};
  }

  /// Whether row looks ahead this tick: once every lookPeriod_ ticks, the rows taking turns by id.
  [[nodiscard]] bool looksNow(const ModelInput& in, std::size_t row) const {
    return lookPeriod_ <= 1 || (static_cast<std::uint64_t>(in.agents.id[row]) + in.tick) % lookPeriod_ == 0;
  }

  /// room() against the walls in the cells along the ray (Walls::queryRay): the same as against every
  /// wall within `reach`, as a wall the ray does not cross within reach leaves room() unchanged.
  static float roomAlong(const ModelInput& in, AvmScratch& ws, core::Vec2 pos, float z, core::Vec2 dir, float reach, float onWall) {
    ws.visionWalls.clear();
    in.walls.queryRay(pos, dir, reach, ws.visionWalls);
    if (in.agents.levels) {  // another floor's edges, above or below, are no walls here
      std::erase_if(ws.visionWalls, [&](std::uint32_t w) { return !in.walls.onLevel(w, pos, z); });
    }
    return room(in, ws.visionWalls, pos, dir, reach, onWall);
  }

  /// Up to four of a pass's picked places (pick) and their neighbours' rows, as lanes
  /// (simd::Lanes<4>) built from scalars: no lane is written through memory (a vector stored, one
  /// lane overwritten and the vector loaded again stalls store forwarding: four fifths of
  /// sidePushes' time in a profile with it not inlined; inlined, the compiler had kept the lanes
  /// in registers). Lanes past places.size() repeat the first place; `valid` masks them out.
  struct Four {
    std::array<std::uint32_t, 4> n{}, o{};  ///< the places in the neighbour list and the neighbours' rows
    Lanes4::I valid{};
    Four(const std::uint32_t* nb, std::span<const std::uint32_t> places) {
      const std::size_t m = places.size();  // 1 to 4
      n = {places[0], places[m > 1 ? 1 : 0], places[m > 2 ? 2 : 0], places[m > 3 ? 3 : 0]};
      o = {nb[n[0]], nb[n[1]], nb[n[2]], nb[n[3]]};
      valid = Lanes4::I{0, 1, 2, 3} < static_cast<std::int32_t>(m);
    }
    /// The places' entries of lookAround's array v.
    [[nodiscard]] Lanes4::F around(const std::vector<float>& v) const { return {v[n[0]], v[n[1]], v[n[2]], v[n[3]]}; }
    /// The neighbours' values of a column.
    [[nodiscard]] Lanes4::F of(std::span<const float> c) const { return {c[o[0]], c[o[1]], c[o[2]], c[o[3]]}; }
    /// -1 where test(neighbour's row) holds, else 0.
    template <class Test>
    [[nodiscard]] Lanes4::I test(Test&& t) const {
      return {t(o[0]) ? -1 : 0, t(o[1]) ? -1 : 0, t(o[2]) ? -1 : 0, t(o[3]) ? -1 : 0};
    }
  };

  /// What the sideways push of a neighbour depends on besides the neighbour (pushes).
  struct SideRule {
    core::Vec2 e0, side, u;  ///< i's desired direction, its right, its desired velocity
    float roomLeft, roomRight;  ///< room to step aside, as a share of a body width
    float need;  ///< kPassWidths · 2 r_i: the room needed beside a neighbour to pass it
    const AvmParams& p;
  };
  /// Four neighbours' sideways pushes (sidePushes): bit q of a mask for the q-th.
  struct SideLanes {
    alignas(16) float push[4];      ///< the push along side, before the room to pass
    alignas(16) float passOpen[4];  ///< the room to pass where no wall is near (roomToPass in the open)
    alignas(16) float share[4];     ///< what it adds to the push along side where no wall is near (0: none)
    unsigned overlap = 0;  ///< the discs (nearly) overlap: overlapPush acts instead
    unsigned seen = 0;     ///< in front, not of i's group, not overlapping: it pushes
    unsigned felt = 0;     ///< the push is over 1e-3 (the room to pass is looked at)
    unsigned toLeft = 0;   ///< i passes it on its left
  };

  /// Up to four neighbours of pushes' lane at once (simd::Lanes<4>): the closest approach within the
  /// anticipation time and the push it gives, with the one-at-a-time rule's operations in its order
  /// (core::exp's four-lane form gives core::exp's bits), so the same values.
  /// (The kernel, inlined into each entry point below and so compiled for its target; kWide: the
  /// exponential's doubles in one 32-byte vector, core::expWide.)
  template <bool kWide>
  [[gnu::always_inline]] static void sidePushesKernel(const ModelInput& in, std::size_t row, const AvmScratch& ws, const std::uint32_t* nb,
                                                      std::span<const std::uint32_t> places, const SideRule& r, SideLanes& out) {
    using F = Lanes4::F;
    using I = Lanes4::I;
    const AgentStore& a = in.agents;
    const Four four(nb, places);
    const I valid = four.valid;  // every mask read below excludes the repeated lanes
    const F dx = four.around(ws.aroundX), dy = four.around(ws.aroundY), l = four.around(ws.aroundL);
    const F vx = four.of(a.velX), vy = four.of(a.velY), ro = four.of(a.radius);
    const I same = four.test([&a, g = a.group[row]](std::uint32_t o) { return a.group[o] == g; });
    F dist;
    simd::sqrtLanes<4>(dist, dx * dx + dy * dy);
    const I apart = valid & (dist >= 1e-6f);
    const I overlap = apart & (dist < l);
    const F cosPhi = (r.e0.x * dx + r.e0.y * dy) / dist;
    const I seen = apart & ~overlap & (cosPhi > 0.0f) & ~same;  // behind: not seen; i's group keeps its formation
    // Closest approach within the anticipation time, both walking on.
    const F wx = vx - r.u.x, wy = vy - r.u.y;
    const F ww = wx * wx + wy * wy;
    const F tq = -(dx * wx + dy * wy) / ww;
    const F clamped = tq < 0.0f ? F{} : r.p.anticipationTime < tq ? F{} + r.p.anticipationTime : tq;  // std::clamp
    const F t = ww > 1e-8f ? clamped : F{};
    const F cx = dx + wx * t, cy = dy + wy * t;
    const F lateral = cx * r.side.x + cy * r.side.y;  // > 0: j passes on i's right
    F reachC;
    simd::sqrtLanes<4>(reachC, cx * cx + cy * cy);
    const F scaled = (l - reachC) / r.p.neighbourRange;
    F e;
    if constexpr (kWide) {
      e = core::expWide(scaled);
    } else {
      e = core::exp(scaled);
    }
    const F strength = r.p.neighbourStrength * e * 0.5f * (1.0f + cosPhi);
    // Keep right: someone coming the other way is passed on one's right side (one steps right)
    // unless they are already well to the right; that is how counter-flows form lanes.
    const I oncoming = vx * r.e0.x + vy * r.e0.y < 0.0f;
    const F threshold = oncoming ? l : F{};
    const I toLeft = lateral > threshold;
    const F push = strength * (toLeft ? F{} - r.roomLeft : F{} + r.roomRight);
    const I felt = (push > 1e-3f) | (-push > 1e-3f);
    const F beside = ro + r.need + kPassRamp - ro;
    const F passQ = (beside - r.need) / kPassRamp;
    const F pass = passQ < 0.0f ? F{} : 1.0f < passQ ? F{} + 1.0f : passQ;
    const F share = seen ? (felt ? push * pass : push) : F{};
    std::memcpy(out.push, &push, sizeof push);
    std::memcpy(out.passOpen, &pass, sizeof pass);
    std::memcpy(out.share, &share, sizeof share);
    out.overlap = laneMask(overlap), out.seen = laneMask(seen), out.felt = laneMask(felt), out.toLeft = laneMask(toLeft);
  }
  static void sidePushes(const ModelInput& in, std::size_t row, const AvmScratch& ws, const std::uint32_t* nb,
                         std::span<const std::uint32_t> places, const SideRule& r, SideLanes& out) {
    sidePushesKernel<false>(in, row, ws, nb, places, r, out);
  }
#if defined(__x86_64__)
  /// sidePushes on the AVX2 path (core::simdPath): the same operations in the same order, so the
  /// same bits, in VEX encoding (three operands) with the exponential's four doubles in one vector:
  /// the block was a quarter of velocity's instructions. Not inlined: the target differs.
  [[gnu::target("avx2"), gnu::noinline]] static void sidePushesAvx2(const ModelInput& in, std::size_t row, const AvmScratch& ws,
                                                                  const std::uint32_t* nb, std::span<const std::uint32_t> places,
                                                                  const SideRule& r, SideLanes& out) {
    sidePushesKernel<true>(in, row, ws, nb, places, r, out);
  }
#endif

  /// The push of a neighbour whose disc overlaps i's (d from i to it, ℓ = r_i + r_o): apart along
  /// the line of centres, but backwards only when the bodies (ellipses, aligned with e0) really
  /// interpenetrate — standing close behind someone is what people do in a queue, not a reason to
  /// back off — or i has been wedged for half the deadlock patience.
  static core::Vec2 overlapPush(const ModelInput& in, std::size_t row, core::Vec2 d, float l, core::Vec2 e0, const AvmParams& p) {
    const float dist = core::length(d);
    core::Vec2 push = -d * (p.neighbourStrength * core::exp((l - dist) / p.neighbourRange) / dist);
    const float along = core::dot(e0, d) / dist, across = core::cross(e0, d) / dist;
    const float q = p.passageRatio;
    const float touch = l * q / std::sqrt(along * along + q * q * across * across);
    const bool stuck = in.agents.stuckTime[row] > 0.5f * in.desc.steering.stuckPatience;  // wedged: may back off
    if (const float back = core::dot(push, e0); back < 0.0f && dist >= touch && !stuck) push -= e0 * back;
    return push;
  }

  /// The desired direction turned aside by the neighbours in front and pushed off the walls.
  core::Vec2 pushes(const ModelInput& in, std::size_t row, core::Vec2 e0, float v0, const AvmParams& p,
                    AvmScratch& ws) const {
    const AgentStore& a = in.agents;
    const core::Vec2 pos{a.posX[row], a.posY[row]};
    const core::Vec2 side = rightOf(e0);
    // Walls turn a walker aside but never back: the part of their push against e0 is dropped (the
    // path already leads round walls; pushing back only stalls agents on the mesh's small notches).
    core::Vec2 wall = exponentialWallPush(in, row, 2.0f * a.radius[row] + 30.0f * p.wallRange, p.wallStrength, p.wallRange, ws.wallIds);
    if (const float back = core::dot(wall, e0); back < 0.0f) wall -= e0 * back;
    core::Vec2 dir = e0 + wall;
    // Room to step aside (to the walls on either side, up to a body width): nobody swerves into a
    // wall to pass someone, they follow.
    const float reach = 2.0f * a.radius[row];
    const float onWall = p.noPressing ? kOnWall : 0.0f;
    const float roomRight = room(in, ws.wallIds, pos, side, reach, onWall) / reach;
    const float roomLeft = room(in, ws.wallIds, pos, -side, reach, onWall) / reach;
    const core::Vec2 u = e0 * v0;
    // The neighbours that push: those in front and those whose discs (nearly) overlap i's; the rest
    // is dropped first, without a branch (half of them are behind).
    const std::uint32_t* nb = &a.neighbours[row * in.desc.steering.maxNeighbours];  // lane holds places in this list
    const std::span<const std::uint32_t> lane = pick(in, row, ws, ws.lane, [e0](const Lanes4::F& x, const Lanes4::F& y, const Lanes4::F& l) {
      return (e0.x * x + e0.y * y > 0.0f) | (x * x + y * y < 1.01f * l * l);  // dot(e0, d) > 0 or |d|² < 1.01 ℓ²
    });
    const SideRule rule{e0, side, u, roomLeft, roomRight, kPassWidths * 2.0f * a.radius[row], p};
    float sideways = 0.0f;  // the neighbours' push along side
    for (std::size_t j = 0; j < lane.size(); j += 4) {
      SideLanes s;
      const std::span<const std::uint32_t> four = lane.subspan(j, std::min<std::size_t>(4, lane.size() - j));
#if defined(__x86_64__)
      if (avx2_) {
        sidePushesAvx2(in, row, ws, nb, four, rule, s);
      } else {
        sidePushes(in, row, ws, nb, four, rule, s);
      }
#else
      sidePushes(in, row, ws, nb, four, rule, s);
#endif
      if (ws.wallIds.empty()) {
        // In the open (most walkers): the overlapping ones push `dir`, the seen ones add to
        // `sideways` in their order, each lane's share selected without a branch (0 for a lane
        // that does not push: sideways starts at +0 and so is never −0, and x + 0 is x).
        for (unsigned m = s.overlap; m != 0; m &= m - 1) {
          const std::uint32_t n = lane[j + static_cast<std::size_t>(std::countr_zero(m))];
          dir += overlapPush(in, row, {ws.aroundX[n], ws.aroundY[n]}, ws.aroundL[n], e0, p);
        }
        sideways = ((sideways + s.share[0]) + s.share[1]) + s.share[2] + s.share[3];
        continue;
      }
      for (std::size_t q = 0; q < 4 && j + q < lane.size(); ++q) {  // in the neighbours' order, as one at a time
        const std::uint32_t n = lane[j + q];
        if ((s.overlap >> q) & 1u) {
          dir += overlapPush(in, row, {ws.aroundX[n], ws.aroundY[n]}, ws.aroundL[n], e0, p);
        } else if ((s.seen >> q) & 1u) {
          // Room to pass o: in the open its wall-free figure (worked out in the lanes), by the walls
          // beside o when the push is felt.
          const bool felt = (s.felt >> q) & 1u, toLeft = (s.toLeft >> q) & 1u;
          const float pass = !felt ? 1.0f
                             : ws.wallIds.empty() ? s.passOpen[q]
                                                  : roomToPass(in, ws, nb[n], toLeft ? -side : side, a.radius[row], onWall);
          sideways += felt ? s.push[q] * pass : s.push[q];
        }
      }
    }
    return dir + side * sideways;
  }

  /// Whether there is room to pass neighbour o on its side `dir` (a unit vector across i's desired
  /// direction): 1 when the wall on that side is at least kPassWidths · 2r_i + kPassRamp beyond o's
  /// shoulder, 0 when it is within kPassWidths · 2r_i, linear between. Only the walls near i are
  /// looked at (ws.wallIds, about a metre round i): the push of a neighbour further off is negligible.
  static float roomToPass(const ModelInput& in, const AvmScratch& ws, std::uint32_t o, core::Vec2 dir, float radius, float onWall) {
    const AgentStore& a = in.agents;
    const float need = kPassWidths * 2.0f * radius;
    const float reach = a.radius[o] + need + kPassRamp;
    const float beside = (ws.wallIds.empty() ? reach : room(in, ws.wallIds, core::Vec2{a.posX[o], a.posY[o]}, dir, reach, onWall)) - a.radius[o];
    return std::clamp((beside - need) / kPassRamp, 0.0f, 1.0f);
  }

  /// Where the navmesh takes a step `move` from pos, as the displacement: the target pushed back
  /// out of every wall of wallIds whose line the step crosses (Detour's moveAlongSurface ends at the
  /// walkable point nearest the target).
  static core::Vec2 slideAlongWalls(const ModelInput& in, const std::vector<std::uint32_t>& wallIds, core::Vec2 pos,
                                    core::Vec2 move) {
    core::Vec2 target = pos + move;
    for (int k = 0; k < 3; ++k) {
      float deepest = 0.0f;
      core::Vec2 out;
      for (std::uint32_t wid : wallIds) {
        const core::Segment& seg = in.walls.segments()[wid];
        const core::Vec2 e = seg.b - seg.a;
        const float len2 = core::lengthSq(e);
        if (len2 < 1e-12f) continue;
        const core::Vec2 n = rightOf(e) / std::sqrt(len2);  // towards the walkable side
        const float behind = -core::dot(target - seg.a, n);
        if (behind <= deepest || core::dot(pos - seg.a, n) < -0.01f) continue;
        const float t = core::dot(target - seg.a, e) / len2;
        if (t < 0.0f || t > 1.0f) continue;
        deepest = behind;
        out = n * behind;
      }
      if (deepest <= 0.0f) break;
      target += out;
    }
    return target - pos;
  }

  /// How far i can step from pos along the unit vector dir before a wall of ws.wallIds [m], at most `reach`.
  static float room(const ModelInput& in, const AvmScratch& ws, core::Vec2 pos, core::Vec2 dir, float reach, float onWall) {
    return room(in, ws.wallIds, pos, dir, reach, onWall);
  }
  /// The same against the walls `wallIds`.
  /// `onWall` > 0 (noPressing): a walker that close to a wall line, or past it, or at the corner
  /// between two segments, has no room that way.
  static float room(const ModelInput& in, const std::vector<std::uint32_t>& wallIds, core::Vec2 pos, core::Vec2 dir,
                    float reach, float onWall = 0.0f) {
    float best = reach;
    for (std::uint32_t wid : wallIds) {
      const core::Segment& seg = in.walls.segments()[wid];
      const core::Vec2 e = seg.b - seg.a;
      // The walkable side is on the right of a → b (nav::NavMesh::boundary keeps the polygons'
      // winding): a step towards it is never blocked, even for someone standing on the wall line,
      // as the navmesh holds people pressed against a wall.
      if (core::dot(dir, rightOf(e)) >= 0.0f) continue;
      const float den = core::cross(dir, e);
      if (std::abs(den) < 1e-9f) continue;  // parallel
      const core::Vec2 q = seg.a - pos;
      const float t = core::cross(q, e) / den;    // along dir
      const float s = core::cross(q, dir) / den;  // along the segment
      const float slack = onWall / std::sqrt(core::lengthSq(e));
      if (t >= -onWall && s >= -slack && s <= 1.0f + slack) best = std::min(best, std::max(0.0f, t));
    }
    return best;
  }

  /// o's walking direction: its velocity, or where it faces while it stands in a queue.
  static core::Vec2 walkingDirection(const AgentStore& a, std::uint32_t o) {
    const core::Vec2 vo{a.velX[o], a.velY[o]};
    const float so = core::length(vo);
    return so > 0.05f ? vo / so : core::Vec2{a.oriX[o], a.oriY[o]};
  }

  /// Whether i's desired direction (its preferred velocity) and o's (as it was a tick ago,
  /// ModelInput::priorDesiredX/Y: the same for any thread or rank count) are further apart than acos(cosLimit); false
  /// when either stands.
  static bool opposed(const ModelInput& in, std::size_t row, std::uint32_t o, float cosLimit) {
    const core::Vec2 pi{in.agents.prefVelX[row], in.agents.prefVelY[row]}, po{in.priorDesiredX[o], in.priorDesiredY[o]};
    const float n = core::length(pi) * core::length(po);
    return n > 1e-9f && core::dot(pi, po) < cosLimit * n;
  }

  /// Whether i, walking `speed` of its v0 with o the first body ahead, overtakes o (kOvertakeShare):
  /// o walks i's way (not opposed) at nearly its own desired speed, i is held well below its own,
  /// and the crowd around i is thinner than p.overtakeDensity.
  bool overtaking(const ModelInput& in, std::size_t row, std::uint32_t o, float speed, float v0, const AvmParams& p) const {
    const AgentStore& a = in.agents;
    if (speed >= kOvertakeShare * v0 || a.mode[o] != AgentMode::Walking || opposed(in, row, o, kSlipCos)) return false;
    const float vo2 = a.velX[o] * a.velX[o] + a.velY[o] * a.velY[o];
    const float want2 = in.priorDesiredX[o] * in.priorDesiredX[o] + in.priorDesiredY[o] * in.priorDesiredY[o];
    if (vo2 < kOvertakeShare * kOvertakeShare * want2) return false;  // o is held up in turn
    // Fewer than `most` people (i included) within kOvertakeRadius; counted until that many are found.
    const float most = p.overtakeDensity * std::numbers::pi_v<float> * kOvertakeRadius * kOvertakeRadius;
    const core::Vec2 pos{a.posX[row], a.posY[row]};
    const std::uint32_t* nb = &a.neighbours[row * in.desc.steering.maxNeighbours];
    float around = 1.0f;  // i itself
    for (std::size_t n = 0; n < a.neighbourCount[row] && around < most; ++n) {
      const core::Vec2 d = core::Vec2{a.posX[nb[n]], a.posY[nb[n]]} - pos;
      around += core::dot(d, d) < kOvertakeRadius * kOvertakeRadius ? 1.0f : 0.0f;
    }
    return around < most;
  }

  /// Slip's and overtake's near neighbours (AvmScratch::near). Only neighbours nearer than limit + ℓ
  /// + s0 (with a centimetre to spare) ahead can shorten a gap below `limit` in any direction (a body
  /// further ahead leaves a gap of at least that), so the directions are tried against those alone:
  /// the same result for fewer reads.
  void collectNear(const ModelInput& in, std::size_t row, float limit, AvmScratch& ws) const {
    const AgentStore& a = in.agents;
    const core::Vec2 pos{a.posX[row], a.posY[row]};
    ws.near.clear();
    const float tx = a.targetX[row] - pos.x, ty = a.targetY[row] - pos.y;
    const bool nearTarget = tx * tx + ty * ty < kSqueezeIn * kSqueezeIn;
    const std::uint32_t* nb = &a.neighbours[row * in.desc.steering.maxNeighbours];  // lane holds places in this list
    const std::span<const std::uint32_t> lane = pick(in, row, ws, ws.lane, [limit](const Lanes4::F& x, const Lanes4::F& y, const Lanes4::F& l) {
      const Lanes4::F reach = limit + l + kStandingGap + 0.01f;
      return x * x + y * y < reach * reach + l * l;
    });
    for (const std::uint32_t n : lane) {
      const std::uint32_t o = nb[n];
      const float l = ws.aroundL[n];
      const bool walking = a.mode[o] == AgentMode::Walking;
      if (!walking && nearTarget) continue;  // squeezing in beside someone standing at one's spot
      const core::Vec2 d{ws.aroundX[n], ws.aroundY[n]};
      const core::Vec2 eo = walkingDirection(a, o);
      ws.near.push_back({d, eo, l, -core::dot(d, eo), opposed(in, row, o, kRotateCos), walking, a.id[row] < a.id[o]});
    }
  }

  /// Whether walking v along a direction at cosine c to e0 beats making `progress` along e0 at
  /// `bestSpeed`: more progress, or, when none is made, a sideways step faster than the best so far.
  static bool beats(float v, float c, float progress, float bestSpeed) {
    return v * c > progress + 1e-4f || (progress < 1e-3f && v * c > -1e-3f && v > kSidestepSpeed && v > bestSpeed + 1e-4f);
  }

  /// Held up by cross traffic: of e (making `progress` along e0) and the directions within
  /// ±kSlipSteps · kSlipStep of e0, the velocity that makes the most progress along e0.
  core::Vec2 slip(const ModelInput& in, std::size_t row, core::Vec2 e0, float v0, const AvmParams& p,
                  AvmScratch& ws, core::Vec2 e, float speed) const {
    const AgentStore& a = in.agents;
    const core::Vec2 pos{a.posX[row], a.posY[row]};
    core::Vec2 best = e * speed;
    float progress = speed * core::dot(e, e0);
    const float limit = v0 * p.timeGap;
    const SlipLanes lanes = slipLanes(in, row, e0, limit, p.passageRatio, ws);
    for (int k = -kSlipSteps; k <= kSlipSteps; ++k) {
      if (k == 0) continue;
      const float c = kSlipAngles.c(k);
      // Whether speed v along this direction beats the best so far. It only gets likelier as v
      // grows, so a direction that would not win at a bound of its speed (v0, then the gap to the
      // bodies) is passed over: the same choice, fewer reads.
      const auto wins = [&](float v) { return beats(v, c, progress, core::length(best)); };
      if (!wins(v0)) continue;
      const std::size_t j = SlipLanes::index(k);
      const core::Vec2 ec{lanes.x[j], lanes.y[j]};
      const float bodies = lanes.gap[j];
      if (!wins(std::min(v0, bodies / p.timeGap))) continue;
      const float g = std::min(bodies, room(in, ws, pos, ec, limit, p.noPressing ? kOnWall : 0.0f));
      const float v = std::min(v0, g / p.timeGap);
      if (wins(v)) {
        progress = v * c;
        best = ec * v;
      }
    }
    return best;
  }

  /// Overtaking (overtaking() said so): the lane nearest e0 — 15°, then 30° … to either side, the
  /// left first — with a free walk of v0 · T past bodies and walls, walked at v0; e · speed when no
  /// lane that makes more progress is free. (Every free lane is walked at v0, so the nearest wins.)
  core::Vec2 overtake(const ModelInput& in, std::size_t row, core::Vec2 e0, float v0, const AvmParams& p,
                      AvmScratch& ws, core::Vec2 e, float speed) const {
    const AgentStore& a = in.agents;
    const core::Vec2 pos{a.posX[row], a.posY[row]};
    const float progress = speed * core::dot(e, e0);
    const float limit = v0 * p.timeGap;
    const SlipLanes lanes = slipLanes(in, row, e0, limit, p.passageRatio, ws);
    for (int k = 1; k <= kSlipSteps; ++k) {
      if (!beats(v0, kSlipAngles.c(k), progress, speed)) break;  // this lane and every wider one make no more progress than walking on
      for (const int side : {-1, 1}) {
        const std::size_t j = SlipLanes::index(side * k);
        const core::Vec2 ec{lanes.x[j], lanes.y[j]};
        if (lanes.gap[j] < limit) continue;
        if (room(in, ws, pos, ec, limit, p.noPressing ? kOnWall : 0.0f) < limit) continue;  // a wall closes this lane
        return ec * v0;
      }
    }
    return e * speed;
  }

  /// Calls f(o, d) for each of i's neighbours o (the rows sense found; d the vector from i to o)
  /// nearer than i's radius + the largest radius + `beyond` [m]: the only ones i's body can touch
  /// within `beyond`. Only during steer: nobody has moved since sense, whose lists are nearest
  /// first (SpatialGrid::nearest, with the same arithmetic), so the first neighbour that far ends
  /// the list.
  template <class F>
  void forEachTouchable(const ModelInput& in, std::size_t row, float beyond, F&& f) const {
    const AgentStore& a = in.agents;
    const core::Vec2 pos{a.posX[row], a.posY[row]};
    const float reach = a.radius[row] + maxRadius_ + beyond;
    const std::uint32_t* nb = &a.neighbours[row * in.desc.steering.maxNeighbours];
    for (std::size_t n = 0; n < a.neighbourCount[row]; ++n) {
      const std::uint32_t o = nb[n];
      const core::Vec2 d = core::Vec2{a.posX[o], a.posY[o]} - pos;
      if (core::lengthSq(d) >= reach * reach) break;
      f(o, d);
    }
  }

  /// Calls f(o, d) for every one of i's neighbours o (d from i to o), in the list's order.
  template <class F>
  static void forEachListed(const ModelInput& in, std::size_t row, F&& f) {
    const AgentStore& a = in.agents;
    const core::Vec2 pos{a.posX[row], a.posY[row]};
    const std::uint32_t* nb = &a.neighbours[row * in.desc.steering.maxNeighbours];
    for (std::size_t n = 0; n < a.neighbourCount[row]; ++n) {
      const std::uint32_t o = nb[n];
      f(o, core::Vec2{a.posX[o], a.posY[o]} - pos);
    }
  }

  /// Whether any neighbour's disc overlaps i's (|d| < r_i + r_o, the test `overlap` starts with),
  /// without a branch on the data: in the open about one walker in a hundred touches anyone
  /// (`throng bench`'s random square), and separation is done with the rest at once. (Eight at a
  /// time with AVX2 gathers it took fewer instructions but more time: the separation passes 1.17 →
  /// 1.31–1.44 ms a tick at 10,000 agents: `integrate` in `--phase-times`.)
  static bool touchesAny(const ModelInput& in, std::size_t row) {
    const AgentStore& a = in.agents;
    const float ri = a.radius[row];
    unsigned any = 0;
    forEachListed(in, row, [&](std::uint32_t o, core::Vec2 d) {
      const float l = ri + a.radius[o];
      any |= core::lengthSq(d) < l * l ? 1u : 0u;
    });
    return any != 0;
  }

  /// Fills ws.aroundX/Y/L with i's neighbours as seen from i (pick reads them): the offsets and
  /// ℓ = r_i + r_o, with the arithmetic of every pass (so the same values); zeros up to the next
  /// multiple of four.
  static void lookAround(const ModelInput& in, std::size_t row, AvmScratch& ws) {
    const AgentStore& a = in.agents;
    const std::size_t count = a.neighbourCount[row];
    const std::size_t padded = (count + 3) & ~std::size_t{3};
    if (ws.aroundX.size() < padded) ws.aroundX.resize(padded), ws.aroundY.resize(padded), ws.aroundL.resize(padded);
    const core::Vec2 pos{a.posX[row], a.posY[row]};
    const std::uint32_t* nb = &a.neighbours[row * in.desc.steering.maxNeighbours];
    for (std::size_t n = 0; n < count; ++n) {
      const std::uint32_t o = nb[n];
      ws.aroundX[n] = a.posX[o] - pos.x;
      ws.aroundY[n] = a.posY[o] - pos.y;
      ws.aroundL[n] = a.radius[row] + a.radius[o];
    }
    for (std::size_t n = count; n < padded; ++n) ws.aroundX[n] = ws.aroundY[n] = ws.aroundL[n] = 0.0f;
  }

  /// Picks out the places n in i's neighbour list (lookAround: d = (x, y) from i to its n-th
  /// neighbour, ℓ = r_i + r_o) for which keep(x, y, ℓ) holds into `into`, in their order. keep
  /// takes four neighbours at once (simd::Lanes<4>, -1 where kept) and the places kept of each four
  /// are written together at the output's end in the order kPickOrder gives for the lanes' mask:
  /// no branch on the data (the passes drop half their neighbours or more, those behind, those out
  /// of reach, at random, and branching on that was mispredicted about as often: a tenth of avm's
  /// time at 10,000 agents), no dependency from one neighbour to the next.
  template <class Keep>
  static std::span<const std::uint32_t> pick(const ModelInput& in, std::size_t row, AvmScratch& ws, std::vector<std::uint32_t>& into,
                                             Keep&& keep) {
    using L = simd::Lanes<4>;
    const std::size_t count = in.agents.neighbourCount[row];
    const std::size_t padded = (count + 3) & ~std::size_t{3};
    if (into.size() < padded) into.resize(padded);
    std::uint32_t* out = into.data();
    std::size_t kept = 0;
    for (std::size_t j = 0; j < count; j += 4) {
      L::F x, y, l;
      std::memcpy(&x, ws.aroundX.data() + j, sizeof x);
      std::memcpy(&y, ws.aroundY.data() + j, sizeof y);
      std::memcpy(&l, ws.aroundL.data() + j, sizeof l);
      const L::I k = keep(x, y, l);
      const unsigned valid = count - j >= 4 ? 0xfu : (1u << (count - j)) - 1u;
      const unsigned mask = laneMask(k) & valid;
      Lanes4::I order;
      std::memcpy(&order, kPickOrder.lanes[mask], sizeof order);
      order += static_cast<std::int32_t>(j);
      std::memcpy(out + kept, &order, sizeof order);  // all four: those past the kept ones are overwritten or unused
      kept += kPickOrder.count[mask];
    }
    return {out, kept};
  }

  /// Bit q set where lane q of a comparison's result is true (-1).
  static unsigned laneMask(const simd::Lanes<4>::I& k) {
#if defined(__SSE2__)
    return static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(reinterpret_cast<const __m128i&>(k))));
#else
    return static_cast<unsigned>(k[0] != 0) | static_cast<unsigned>(k[1] != 0) << 1 | static_cast<unsigned>(k[2] != 0) << 2 |
           static_cast<unsigned>(k[3] != 0) << 3;
#endif
  }

  /// A standing agent (waiting, acting, arrived) is no wall: pressed by someone whose disc overlaps
  /// its own it steps away, at most kMakeRoomSpeed, so people waiting for their group at a busy
  /// spot do not block everyone else's way.
  core::Vec2 makeRoom(const ModelInput& in, std::size_t row, const AvmParams& p) const {
    const AgentStore& a = in.agents;
    core::Vec2 push;
    forEachTouchable(in, row, 0.0f, [&](std::uint32_t o, core::Vec2 d) {
      const float dist = core::length(d);
      const float l = a.radius[row] + a.radius[o];
      if (dist < 1e-6f || dist >= l) return;
      push -= d * (p.neighbourStrength * core::exp((l - dist) / p.neighbourRange) / dist);
    });
    const float len = core::length(push);
    if (len < 1e-6f) return {};
    return push * (std::min(kMakeRoomSpeed, kMakeRoomGain * len) / len);
  }

  /// Four neighbours in i's lane (gapAhead): bit q of `blocks` set where the q-th blocks e, and the
  /// gap it leaves as g / f (the stagger weight f: kStaggerExponent, kStandingGap).
  struct GapLanes {
    alignas(16) float g[4];
    alignas(16) float f[4];
    unsigned blocks = 0;
  };
  /// Up to four of gapAhead's neighbours at once (simd::Lanes<4>): which block e — not when the two
  /// turn their shoulders to pass, nor when o gives way (the merge rule, below), nor when i squeezes in beside
  /// someone standing at its spot, nor at the lane's very edge — with the one-at-a-time rule's
  /// operations in its order, so the same values; every test a mask, no branch on the data (gapAhead
  /// one neighbour at a time mispredicted a tenth of the avm's branches). Lanes past places.size()
  /// repeat the first neighbour and are masked out.
  static void gapLanes(const ModelInput& in, std::size_t row, const AvmScratch& ws, const std::uint32_t* nb,
                       std::span<const std::uint32_t> places, core::Vec2 e, float depthRatio, bool nearTarget, GapLanes& out) {
    using F = Lanes4::F;
    using I = Lanes4::I;
    const AgentStore& a = in.agents;
    const Four four(nb, places);
    const F dx = four.around(ws.aroundX), dy = four.around(ws.aroundY), l = four.around(ws.aroundL);
    const F px = four.of(in.priorDesiredX), py = four.of(in.priorDesiredY);
    const F vx = four.of(a.velX), vy = four.of(a.velY), ox = four.of(a.oriX), oy = four.of(a.oriY);
    const I walking = four.test([&a](std::uint32_t o) { return a.mode[o] == AgentMode::Walking; });
    const I lowerId = four.test([&a, id = a.id[row]](std::uint32_t o) { return id < a.id[o]; });
    const I valid = four.valid;
    const F ahead = dx * e.x + dy * e.y;        // dot(d, e)
    const F lateral = e.x * dy - e.y * dx;      // cross(e, d)
    const F absLateral = lateral < 0.0f ? F{} - lateral : lateral;
    // Shoulders turned: |lateral| ≥ depthRatio · ℓ and opposed(in, row, o, kRotateCos).
    const float pix = a.prefVelX[row], piy = a.prefVelY[row];
    const float lengthI = std::sqrt(pix * pix + piy * piy);
    F lengthO;
    simd::sqrtLanes<4>(lengthO, px * px + py * py);
    const F norms = lengthI * lengthO;
    const I opposedRot = (norms > 1e-9f) & (pix * px + piy * py < kRotateCos * norms);
    const I shoulders = (absLateral >= depthRatio * l) & opposedRot;
    // The merge rule (two people walking into the same space from the side, less than 90° apart:
    // the one nearer that space goes first): o does not block i when i is further ahead of o, along
    // o's walking direction eo (as walkingDirection has it), than o is of i along e (ties: the lower
    // id goes). Without it both see the other ahead and both stop, which clogs every door and
    // corridor mouth.
    F speedO;
    simd::sqrtLanes<4>(speedO, vx * vx + vy * vy);
    const I moving = speedO > 0.05f;
    const F eox = moving ? vx / speedO : ox, eoy = moving ? vy / speedO : oy;
    const F aheadOfO = F{} - (dx * eox + dy * eoy);  // -dot(d, eo)
    const I gives = walking & (e.x * eox + e.y * eoy > kGiveWayCos) & (aheadOfO > 0.0f) &
                    ((aheadOfO > ahead) | ((aheadOfO == ahead) & lowerId));
    const I squeezes = nearTarget ? ~walking : I{};  // beside someone standing at one's spot
    // Bodies are ellipses, shoulders across the walking direction (semi-axis r) and chest to back
    // along it (depthRatio · r): two touch at this distance along e. As a gap at the time gap of
    // someone straight ahead: (s − s0·f) / f, f the stagger weight.
    const F y = lateral / l;
    const F across = 1.0f - y * y;
    static_assert(kStaggerExponent == 2.0f, "f below is (1 - y^2)^2");
    const F f = across * across;
    F root;
    simd::sqrtLanes<4>(root, across);
    const F reach = ahead - depthRatio * l * root - kStandingGap * f;
    const F g = 0.0f < reach ? reach : F{};  // std::max(0, reach)
    const I blocks = valid & ~shoulders & ~gives & ~squeezes & (f >= 1e-6f);
    std::memcpy(out.g, &g, sizeof g);
    std::memcpy(out.f, &f, sizeof f);
    out.blocks = laneMask(blocks);
  }

  /// The gap i can walk along e before touching the first body ahead [m], as the gap to someone
  /// straight ahead that asks the same speed (kStaggerExponent, kStandingGap), at most `limit` (v0·T).
  float gapAhead(const ModelInput& in, std::size_t row, core::Vec2 e, float limit, float depthRatio, AvmScratch& ws,
                 std::int64_t* blocker) const {
    const AgentStore& a = in.agents;
    const core::Vec2 pos{a.posX[row], a.posY[row]};
    // First the neighbours in i's lane ahead: in front, less than ℓ aside.
    const std::uint32_t* nb = &a.neighbours[row * in.desc.steering.maxNeighbours];  // lane holds places in this list
    const std::span<const std::uint32_t> lane = pick(in, row, ws, ws.lane, [e](const Lanes4::F& x, const Lanes4::F& y, const Lanes4::F& l) {
      const Lanes4::F lateral = e.x * y - e.y * x;  // cross(e, d); |lateral| < ℓ as two comparisons
      return (x * e.x + y * e.y > 0.0f) & (lateral < l) & (-lateral < l);  // dot(d, e) > 0
    });
    float gap = limit;
    const float tx = a.targetX[row] - pos.x, ty = a.targetY[row] - pos.y;
    const bool nearTarget = tx * tx + ty * ty < kSqueezeIn * kSqueezeIn;
    for (std::size_t j = 0; j < lane.size(); j += 4) {
      GapLanes s;
      gapLanes(in, row, ws, nb, lane.subspan(j, std::min<std::size_t>(4, lane.size() - j)), e, depthRatio, nearTarget, s);
      for (unsigned m = s.blocks; m != 0; m &= m - 1) {  // in the neighbours' order, as one at a time
        const auto q = static_cast<std::size_t>(std::countr_zero(m));
        if (s.g[q] < gap * s.f[q]) {  // g / f < gap, without dividing for every neighbour
          gap = s.g[q] / s.f[q];
          *blocker = nb[lane[j + q]];
        }
      }
    }
    return gap;
  }

  /// Slip's twelve directions (e0 turned by k · kSlipStep, k = ±1 … ±kSlipSteps) and the gap to the
  /// bodies along each (gapAhead).
  struct SlipLanes {
    static constexpr std::size_t kCount = 2 * kSlipSteps;
    std::array<float, kCount> x{}, y{}, gap{};
    static std::size_t index(int k) { return static_cast<std::size_t>(k < 0 ? k + kSlipSteps : k + kSlipSteps - 1); }
  };

  /// Slip's and overtake's twelve directions round e0 and the gap to the near bodies (collectNear)
  /// along each, at most `limit`.
  [[gnu::always_inline]] SlipLanes slipLanes(const ModelInput& in, std::size_t row, core::Vec2 e0, float limit, float depthRatio, AvmScratch& ws) const {
    collectNear(in, row, limit, ws);
    SlipLanes lanes;
    for (int k = -kSlipSteps; k <= kSlipSteps; ++k) {
      if (k == 0) continue;
      const core::Vec2 ek = turned(e0, k);
      lanes.x[SlipLanes::index(k)] = ek.x;
      lanes.y[SlipLanes::index(k)] = ek.y;
    }
    slipGaps(ws, limit, depthRatio, lanes);
    return lanes;
  }

  /// The gap along each of slip's directions (gapAhead's rule against the near bodies), in one pass over the
  /// near bodies: each body against four directions at once (simd::Lanes<4>, three times), every
  /// test of the gap law a mask and the gap kept or replaced by a select, so no branch on the data
  /// (testing lane by lane which directions a body stands in mispredicted a tenth of the avm's
  /// branches: slip took 8 % of a 10,000-agent tick for 3 % of its instructions). Per direction
  /// the same bodies are taken in the same order with the same arithmetic, so the gaps are
  /// gapAhead's to the bit (lanes a body is not in may compute NaN; they are never selected).
  static void slipGaps(const AvmScratch& ws, float limit, float depthRatio, SlipLanes& lanes) {
    using F = Lanes4::F;
    using I = Lanes4::I;
    static_assert(SlipLanes::kCount % 4 == 0);
    constexpr std::size_t kGroups = SlipLanes::kCount / 4;
    F ex[kGroups], ey[kGroups], gap[kGroups];
    for (std::size_t k = 0; k < kGroups; ++k) {
      std::memcpy(&ex[k], lanes.x.data() + 4 * k, sizeof(F));
      std::memcpy(&ey[k], lanes.y.data() + 4 * k, sizeof(F));
      Lanes4::fill(gap[k], limit);
    }
    for (const AvmScratch::NearBlocker& b : ws.near) {
      const float reachDepth = depthRatio * b.l;
      // The body's flags as all-lane masks by arithmetic (0 − 1 = −1): written as selects, the
      // compiler tested each flag again for every four directions, a branch on the data mispredicted
      // about twenty times a slip.
      const I turned = I{} - static_cast<std::int32_t>(b.turned);
      const I mayGive = I{} - static_cast<std::int32_t>(b.walking & (b.aheadOfO > 0.0f));
      const I tie = I{} - static_cast<std::int32_t>(b.lowerId);
      for (std::size_t k = 0; k < kGroups; ++k) {
        const F ahead = b.d.x * ex[k] + b.d.y * ey[k];    // dot(d, e)
        const F lateral = ex[k] * b.d.y - ey[k] * b.d.x;  // cross(e, d)
        const F absLateral = lateral < 0.0f ? F{} - lateral : lateral;
        const I inLane = (ahead > 0.0f) & (absLateral < b.l);
        const I shoulders = (absLateral >= reachDepth) & turned;  // shoulders turned
        const I gives = mayGive & (ex[k] * b.eo.x + ey[k] * b.eo.y > kGiveWayCos) &
                        ((b.aheadOfO > ahead) | ((b.aheadOfO == ahead) & tie));  // o gives way (the merge rule)
        const F y = lateral / b.l;
        const F across = 1.0f - y * y;
        const F f = across * across;
        F root;
        simd::sqrtLanes<4>(root, across);
        const F reach = ahead - reachDepth * root - kStandingGap * f;
        const F g = 0.0f < reach ? reach : F{};  // std::max(0, reach)
        const I take = inLane & ~shoulders & ~gives & (f >= 1e-6f) & (g < gap[k] * f);
        gap[k] = take ? g / f : gap[k];
      }
    }
    for (std::size_t k = 0; k < kGroups; ++k) std::memcpy(lanes.gap.data() + 4 * k, &gap[k], sizeof(F));
  }

  /// i's new velocity. `turn`: the look ahead's turn to walk by, or kLookAgain to look now; it is
  /// left what was walked by (0 for someone standing).
  [[gnu::always_inline]] core::Vec2 velocity(const ModelInput& in, std::size_t row, const AvmParams& p, AvmScratch& ws, int& turn) const {
    const AgentStore& a = in.agents;
    const core::Vec2 pref{a.prefVelX[row], a.prefVelY[row]};
    const float v0 = core::length(pref);
    if (v0 < 1e-6f) {  // nowhere to go: stand, but let others by — unless incapacitated (it cannot)
      turn = 0;
      return a.goalState[row] == GoalState::Incapacitated ? core::Vec2{} : makeRoom(in, row, p);
    }
    if (turn == kLookAgain) turn = seeAhead(in, row, pref / v0, p.visionRange, p.noPressing ? kOnWall : 0.0f, ws);
    const core::Vec2 e0 = turned(pref / v0, turn);
    lookAround(in, row, ws);  // for pick, in pushes, gapAhead and collectNear
    core::Vec2 target = pushes(in, row, e0, v0, p, ws);
    const float len = core::length(target);
    if (len < 1e-6f) return {};
    target = target / len;
    // Turn over the reaction time from the direction walked a tick ago, or, when that ran away from
    // the desired direction, from the one i meant to walk (newVel, this row's own output of the last
    // tick): pressed into a wall, the navmesh slides a walker along it, and turning from that slide
    // made the slide its own cause (a walker beside a door slid 4 m along the wall away from it).
    core::Vec2 vel{a.velX[row], a.velY[row]};
    if (core::dot(vel, e0) < 0.0f) vel = {a.newVelX[row], a.newVelY[row]};
    const float speedNow = core::length(vel);
    core::Vec2 e = target;
    if (speedNow > 0.05f) {
      const core::Vec2 h = vel / speedNow;
      const core::Vec2 mixed = h + (target - h) * std::min(1.0f, dt_ / p.reactionTime);
      const float m = core::length(mixed);
      e = m > 1e-6f ? mixed / m : target;
    }
    // Never backwards: pushed aside hard (or turning from a step the crowd forced), a walker steps
    // sideways at most. Walking on in a direction that had turned more than 90° from the desired one
    // let a relaxing heading carry walkers deep in a queue backwards at full speed, the time-gap law
    // finding the space behind them free (the dense room's walk-back, the dense rings' backward
    // samples: docs/validation.md).
    if (const float back = core::dot(e, e0); back < 0.0f) {
      const core::Vec2 across = e - e0 * back;
      const float m = core::length(across);
      e = m > 1e-3f ? across / m : e0;
    }
    std::int64_t blocker = -1;
    const float gap = gapAhead(in, row, e, v0 * p.timeGap, p.passageRatio, ws, &blocker);
    const float speed = std::min(v0, gap / p.timeGap);
    const auto bo = static_cast<std::uint32_t>(blocker);
    const bool crossSlip = blocker >= 0 && speed < kSlipSpeed * v0 && (opposed(in, row, bo, kSlipCos) || a.mode[bo] != AgentMode::Walking);
    const bool overtakes = !crossSlip && blocker >= 0 && overtaking(in, row, bo, speed, v0, p);
    const core::Vec2 walk = crossSlip ? slip(in, row, e0, v0, p, ws, e, speed)
                            : overtakes ? overtake(in, row, e0, v0, p, ws, e, speed)
                                        : e * speed;
    const core::Vec2 v = walk + contact(in, row, p);
    return p.noPressing ? clampToBodies(in, row, v, p, ws) : v;
  }

  /// v, changed so that i's step this tick takes its body no deeper into any neighbour's (ellipses
  /// along their headings, as the overlaps are measured; docs/crowd-model.md, "No step into a
  /// body"). The time-gap law checks the walking direction only; the contact step, the slip's
  /// sideways steps, the merge rule (gapLanes) and the navmesh sliding a walker along a wall all
  /// moved people into bodies beside them, which put the dense room's deepest overlap at 0.11 m.
  core::Vec2 clampToBodies(const ModelInput& in, std::size_t row, core::Vec2 v, const AvmParams& p, AvmScratch& ws) const {
    const AgentStore& a = in.agents;
    const float step = core::length(v) * dt_;
    if (step < 1e-6f) return v;
    const core::Vec2 oi{a.oriX[row], a.oriY[row]};
    // Pressed against a wall, the navmesh slides the step along it: that is the move to check.
    core::Vec2 move = slideAlongWalls(in, ws.wallIds, {a.posX[row], a.posY[row]}, v * dt_);
    const core::Vec2 planned = move;
    // How deep the step may take i into o's body: a body not touched closes at most half the gap
    // (o, seeing the same, the other half); one already overlapping gets no deeper. Except when i
    // squeezes by o (kSqueezeDepth): of two merging walkers (less than 120° apart) the one further
    // along goes first (ties: the lower id; `leads`, also capped at kSqueezeSpeed), two crossing
    // (more than 60° apart) may both squeeze, and two coming head on (desired
    // directions and bodies more than 120° apart) pass each other when they would be offset enough
    // to pass with shoulders turned, as the gap law lets them (gapAhead).
    // First the step loses what presses (the part along the line of centres towards o; a leader is
    // slowed to kSqueezeSpeed) unless it passes o head on; then it is shortened until it presses no
    // body beyond its limit, squeezing by allowed to leaders and passers alike.
    ws.nearBodies.clear();
    forEachTouchable(in, row, step, [&](std::uint32_t o, core::Vec2 d) {
      const float l = a.radius[row] + a.radius[o];
      if (core::lengthSq(d) >= (l + step) * (l + step)) return;
      const float before = depthAt(a, row, o, d, oi, p.passageRatio);
      const float strict = before < 0.0f ? 0.5f * before : before;
      const float squeeze = std::max(strict, kSqueezeDepth);
      const core::Vec2 ei{a.prefVelX[row], a.prefVelY[row]}, eo{in.priorDesiredX[o], in.priorDesiredY[o]};
      const bool leads = core::dot(ei, eo) > kGiveWayCos * core::length(ei) * core::length(eo) &&
                         furtherAlong(d, ei, eo, a.id[row], a.id[o]);
      const core::Vec2 w = eo - ei;  // how o moves relative to i, both walking as they want
      const float ww = core::lengthSq(w);
      const float t = ww > 1e-8f ? std::max(0.0f, -core::dot(d, w) / ww) : 0.0f;
      const bool passing = opposed(in, row, o, kGiveWayCos) && core::dot(oi, core::Vec2{a.oriX[o], a.oriY[o]}) < kGiveWayCos &&
                           core::length(d + w * t) >= p.passageRatio * l;
      // Two crossing (desired directions more than 60° apart) may both squeeze by: strict, a crowd
      // crossing every way knotted (the plaza's first waves 84 % out against 92 %; docs/crowd-model.md).
      const bool crossing = opposed(in, row, o, kRotateCos);
      ws.nearBodies.push_back({o, d, passing ? squeeze : strict, leads || passing || crossing ? squeeze : strict, leads});
    });
    // First: no step towards a body it would press into (the part along the line of centres goes).
    bool pressed = false;
    for (const AvmScratch::NearBody& b : ws.nearBodies) {
      if (depthAt(a, row, b.o, b.d - move, oi, p.passageRatio) <= b.first) continue;
      pressed = true;
      const float dist = core::length(b.d);
      const core::Vec2 u = dist > 1e-6f ? b.d / dist : core::Vec2{1.0f, 0.0f};
      const float radial = core::dot(move, u);
      if (radial > 0.0f) move -= u * radial;
      if (b.leads) {
        const float tl = core::length(move), cap = kSqueezeSpeed * dt_;
        if (tl > cap) move = move * (cap / tl);
      }
    }
    if (!pressed) return v;
    // Then: the step shortened until it presses no body beyond its limit.
    float s = 1.0f;
    for (const AvmScratch::NearBody& b : ws.nearBodies) {
      if (s <= 0.0f) break;
      if (depthAt(a, row, b.o, b.d - move * s, oi, p.passageRatio) <= b.then) continue;
      float lo = 0.0f, hi = s;
      for (int it = 0; it < 6; ++it) {
        const float mid = 0.5f * (lo + hi);
        (depthAt(a, row, b.o, b.d - move * mid, oi, p.passageRatio) <= b.then ? lo : hi) = mid;
      }
      s = lo;
    }
    move = move * s;
    if (move.x == planned.x && move.y == planned.y) return v;
    return move / dt_;
  }

  /// Whether a slow walker's turn this tick (integrate's rule: below kFaceDesiredBelow a body turns
  /// toward where it wants to go, over kTurnTime) would press its body deeper into a neighbour's it
  /// touches: then it keeps its heading (VelocityOutput::holdHeading). People wedged in a crowd cannot
  /// turn their shoulders into the person beside them; the turning ellipses pressed bodies up to
  /// 6 cm into each other in the dense room (docs/crowd-model.md). Walkers going faster turn toward
  /// their motion as before: held sideways at speed, their bodies met others worse (0.28 m).
  bool turnDeepens(const ModelInput& in, std::size_t row, core::Vec2 v, const AvmParams& p) const {
    const AgentStore& a = in.agents;
    const core::Vec2 pref{a.prefVelX[row], a.prefVelY[row]};
    if (core::length(v) >= kFaceDesiredBelow || core::length(pref) <= 1e-3f) return false;
    const core::Vec2 oi{a.oriX[row], a.oriY[row]};
    const core::Vec2 next = core::normalize(oi + (core::normalize(pref) - oi) * std::min(1.0f, dt_ / kTurnTime));
    bool deepens = false;
    forEachTouchable(in, row, 0.0f, [&](std::uint32_t o, core::Vec2 d) {
      if (deepens) return;
      const float l = a.radius[row] + a.radius[o];
      if (core::lengthSq(d) >= l * l) return;
      const float now = depthAt(a, row, o, d, oi, p.passageRatio);
      const float then = depthAt(a, row, o, d, next, p.passageRatio);
      if (then > std::max(now, 0.0f) + 1e-4f) deepens = true;
    });
    return deepens;
  }

  /// Signed overlap depth of i's and o's ellipses along their line of centres (negative: the gap) [m].
  float depthAt(const AgentStore& a, std::size_t row, std::uint32_t o, core::Vec2 d, core::Vec2 oi, float qi) const {
    const float l = a.radius[row] + a.radius[o];
    const float dist = core::length(d);
    if (dist < 1e-6f) return l;
    return depthAlong(a, o, d / dist, dist, l, oi, qi);
  }

  /// The overlap of i's ellipse (heading oi, depth ratio qi) and o's along the unit vector u from i to
  /// o, their centres dist apart and their shoulders summing to l [m]; negative: the gap.
  float depthAlong(const AgentStore& a, std::uint32_t o, core::Vec2 u, float dist, float l, core::Vec2 oi, float qi) const {
    return 0.5f * (ellipseReach(oi, u, l, qi) + ellipseReach({a.oriX[o], a.oriY[o]}, u, l, params_[a.population[o]].passageRatio)) - dist;
  }

  [[nodiscard]] int separationPasses(std::uint16_t population) const override {
    return params_[population].separationPasses;
  }

  /// Position correction (separationPasses): for every neighbour whose ellipse (headings as moved)
  /// overlaps i's, half the depth along the line of centres, away from it — the neighbour, reading
  /// the same positions, takes the other half. Nobody is pushed back along its own heading: the
  /// backward part of the one behind is taken by the one in front, who steps on along the other's
  /// heading (pushing walkers back made the dense rings walk backwards and the dense room's queue
  /// walk back from the door; docs/crowd-model.md, Overlaps).
  core::Vec2 separation(const ModelInput& in, std::size_t row) const override {
    if (!touchesAny(in, row)) return {};  // most walkers
    const AgentStore& a = in.agents;
    const core::Vec2 oi{a.oriX[row], a.oriY[row]};
    const float q = params_[a.population[row]].passageRatio;
    core::Vec2 out;
    // The whole list: everyone has moved since sense sorted it, so the nearest first order no longer
    // ends it (overlap: depth 0 for the discs that do not touch).
    forEachListed(in, row, [&](std::uint32_t o, core::Vec2 d) {
      const Overlap ov = overlap(a, row, o, d, oi, q);
      if (ov.depth <= 0.0f || a.goalState[o] == GoalState::Exited) return;
      const core::Vec2 u = ov.u, oo{a.oriX[o], a.oriY[o]};
      // Merging (desired directions less than 90° apart): the one further along takes half with
      // nothing against its own way, the other the whole correction — the zipper at a narrow door,
      // where the two halves wedged two people side by side in its mouth for 5 s (docs/crowd-model.md).
      const core::Vec2 ei{a.prefVelX[row], a.prefVelY[row]}, eo{a.prefVelX[o], a.prefVelY[o]};
      if (core::dot(ei, eo) > 0.0f) {
        const bool leads = furtherAlong(d, ei, eo, a.id[row], a.id[o]);
        const core::Vec2 want = core::normalize(ei);
        if (!leads) {
          core::Vec2 mine = -u * ov.depth;
          // Its step back is dropped as far as the leader is straight ahead (cos² of the angle between
          // the line of centres and its desired direction): a queue does not walk backwards; side by
          // side in a door's mouth, it makes way.
          const float ahead = core::dot(u, want);
          if (const float back = core::dot(mine, want); back < 0.0f) mine -= want * (back * ahead * ahead);
          out += mine;
          return;
        }
        core::Vec2 mine = -u * (kSeparationShare * ov.depth);
        if (const float back = core::dot(mine, want); back < 0.0f) mine -= want * back;
        out += mine;
        return;
      }
      const float share = kSeparationShare * ov.depth;
      core::Vec2 mine = -u * share;
      if (const float back = core::dot(mine, oi); back < 0.0f) mine -= oi * back;         // i behind o: not back
      if (const float back = core::dot(u * share, oo); back < 0.0f) mine -= oo * back;    // o behind i: i steps on
      out += mine;
    });
    return out;
  }

  /// How deep i's ellipse (heading oi, depth ratio qi) and neighbour o's (d from i to o) overlap along
  /// their line of centres u (pointing from i to o; ids break the tie of two bodies on one spot) [m];
  /// depth 0 when their discs do not overlap (contact and separation share it).
  struct Overlap {
    core::Vec2 u;
    float depth = 0.0f;
  };
  Overlap overlap(const AgentStore& a, std::size_t row, std::uint32_t o, core::Vec2 d, core::Vec2 oi, float qi) const {
    const float l = a.radius[row] + a.radius[o];
    const float dist2 = core::lengthSq(d);
    if (dist2 >= l * l) return {};
    const float dist = std::sqrt(dist2);
    const core::Vec2 u = dist > 1e-6f ? d / dist : core::Vec2{a.id[row] < a.id[o] ? 1.0f : -1.0f, 0.0f};
    return {u, depthAlong(a, o, u, dist, l, oi, qi)};
  }

  /// How far along the unit vector u an ellipse of shoulder semi-axis l (across its heading `ori`)
  /// and depth semi-axis ratio · l reaches: l when ori is across u, ratio · l when along it.
  static float ellipseReach(core::Vec2 ori, core::Vec2 u, float l, float ratio) {
    const float along = core::dot(ori, u), across = core::cross(ori, u);
    const float den = std::sqrt(along * along + ratio * ratio * across * across);
    return den > 1e-6f ? l * ratio / den : l;
  }

  /// Bodies in contact give way to each other: for every neighbour whose ellipse (headings as drawn,
  /// oriX/oriY) overlaps i's deeper than kContactSlack, i steps back along the line of centres by
  /// half the excess this tick (the neighbour, seeing the same overlap, takes the other half), at
  /// most kContactSpeed. The time-gap law keeps walkers from walking into the person ahead, but
  /// pushes from behind and the side, walls and turning bodies still press people into each other;
  /// this keeps a crush's overlaps to a few centimetres (docs/crowd-model.md).
  core::Vec2 contact(const ModelInput& in, std::size_t row, const AvmParams& p) const {
    const AgentStore& a = in.agents;
    const core::Vec2 oi{a.oriX[row], a.oriY[row]};
    core::Vec2 out;
    forEachTouchable(in, row, 0.0f, [&](std::uint32_t o, core::Vec2 d) {
      const Overlap ov = overlap(a, row, o, d, oi, p.passageRatio);
      if (ov.depth > kContactSlack) out -= ov.u * (kContactShare * (ov.depth - kContactSlack) / dt_);
    });
    const float len = core::length(out);
    return len > kContactSpeed ? out * (kContactSpeed / len) : out;
  }

  std::vector<AvmParams> params_;  ///< per population
  float dt_ = 0.05f;
  CrowdGrid crowd_;  ///< what walkers see of the crowd ahead (beginStep), when a population looks ahead
  float vision_ = 0.0f;  ///< the longest visionRange of the populations [m]
  bool avx2_ = false;  ///< velocities on the AVX2 path (core::simdPath, read in beginStep)
  float maxRadius_ = 0.0f;  ///< the largest body radius this tick [m] (beginStep; forEachTouchable)
  std::uint64_t lookPeriod_ = 1;  ///< ticks between a walker's looks ahead (kLookPeriod)
};

}  // namespace

const ModelInfo& anticipationVelocityModelInfo() {
  static const ModelInfo info{ModelKind::AnticipationVelocity, "avm", "anticipation velocity model",
                              "Xu, Chraibi, Seyfried, Anticipation in a velocity-based model for pedestrian dynamics, "
                              "Transportation Research Part C 133, 2021 (on Tordeux, Chraibi, Seyfried 2016)",
                              kParameters};
  return info;
}

std::unique_ptr<OperationalModel> makeAnticipationVelocityModel() { return std::make_unique<AnticipationVelocityModel>(); }

}  // namespace throng::sim
