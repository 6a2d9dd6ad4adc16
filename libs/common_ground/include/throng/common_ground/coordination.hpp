// throng::common_ground coordination planner — the Common Ground grounding process of Park, Peng, Quek,
// Cao (Table 1) as a state machine per interaction: initiate → request attention → give attention
// → propose a macro-plan → acknowledge → confirm → execute (or fail and fall back). Pure: reads
// the group's bodies (initiator A, respondent B, companions), their Relations, target points, clip
// lengths and the two behaviour databases; writes a timed ActionScript (Tables 3 and 5) with one
// list per actor. Times are chained as in the paper: each response starts when the previous motion
// ends; clip motions last their clip length, walking distance / speed, turning angle / turning rate.
// B and every companion answer each of A's signals in parallel; A goes on when the last answer
// ends. Every step has a response timeout and a bounded number of attempts (another
// micro-behaviour, or moving closer), so every coordination ends.
#pragma once
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "throng/core/result.hpp"
#include "throng/core/rng.hpp"
#include "throng/core/vec2.hpp"
#include "throng/common_ground/action_script.hpp"
#include "throng/common_ground/behaviour_db.hpp"
#include "throng/common_ground/relation.hpp"

namespace throng::common_ground {

/// Clip name → clip length [s] (> 0, finite). Must hold every clip a chosen behaviour plays.
using ClipLengths = std::map<std::string, double, std::less<>>;

struct ActorBody {
  core::Vec2 position{};      ///< [m]
  float heading = 0.0f;       ///< body (= gaze) direction [rad], counter-clockwise from +x
  float walkSpeed = 1.3f;     ///< walking speed v [m/s], (0, 10]
  std::uint64_t id = 0;       ///< stable entity id (seeds this actor's behaviour stream)
};

/// How an actor picks among the behaviours allowed for an intent.
enum class SelectionMode : std::uint8_t {
  Uniform,   ///< uniformly at random (seeded)
  Weighted,  ///< at random, proportional to weight × the actor's preference (seeded)
  Best,      ///< the highest weight × preference; ties go to file order (no draw)
};

struct ActorStyle {
  SelectionMode mode = SelectionMode::Weighted;
  std::map<std::string, double, std::less<>> preference;  ///< behaviour name → multiplier >= 0 (default 1)
};

struct CoordinationParams {
  double turnRate = 3.0;          ///< turning rate [rad/s], (0, 100]
  double responseTimeout = 2.0;   ///< [s] >= 0: how long A waits for a response before retrying
  int maxAttempts = 3;            ///< tries per step, [1, 10]; moving closer is one of them
  double touchDistance = 0.6;     ///< [m] > 0: where "move toward" / "move closer" stops from B
};

struct Goal {
  core::Vec2 position{};          ///< x_s / x_p [m]
  GoalKind kind = GoalKind::Personal;
  double expectedVisit = 0.0;     ///< [s] >= 0, what the selection rules compare (not the stay time)
  std::optional<core::Vec2> next; ///< x_q for divide-and-proceed; none: x_r
};

/// A group mate other than A and B. Companions answer every signal of A in parallel with B (or
/// turn toward A when they cannot perceive it) and take B's part in the macro-plan.
struct Companion {
  ActorBody body;
  Relation relation = Relation::A2;  ///< of A with respect to this companion, at t0 (assess())
};

struct CoordinationInput {
  ActorBody initiator;                      ///< A
  ActorBody respondent;                     ///< B
  std::vector<Companion> companions;        ///< C1, C2, ...: script actors 2, 3, ... (may be empty)
  Relation relation = Relation::A2;         ///< of A with respect to B (assess(), relations.cpp)
  std::optional<core::Vec2> viewPoint;      ///< x_i: a point in B's field of view (pointInView)
  std::optional<core::Vec2> hearingPoint;   ///< x_j: a point within B's hearing range
  Goal goal;                                ///< what A wants
  core::Vec2 destination{};                 ///< x_r: the group's destination [m]
  std::optional<PlanKind> forcedPlan;       ///< skip the selection rules (must be in the plan DB)
  double startTime = 0.0;                   ///< t_0 [s]
  std::uint64_t seed = 0;                   ///< scenario seed
  ActorStyle initiatorStyle;
  ActorStyle respondentStyle;               ///< B's, also used by every companion (own random stream)
  /// Responses B fails to give, consumed in order, one per expected response (true = lost: B does
  /// not react and A times out); past the end every response arrives. For tests and disturbances.
  /// Companions never lose responses.
  std::vector<bool> lostResponses;
  bool respondentAbsent = false;            ///< B never responds (all responses lost)
};

struct Databases {
  const MicroBehaviourDb* micro = nullptr;  ///< required
  const MacroPlanDb* macro = nullptr;       ///< required
};

/// The first plan of `db` (priority order) whose rules hold for this goal, |x_s - x_b| = goalDistance [m].
[[nodiscard]] std::optional<std::size_t> selectPlan(const MacroPlanDb& db, const Goal& goal, double goalDistance);

/// Candidates of `db` for `intent` usable in `relation` (preconditions), in file order, minus `exclude`.
[[nodiscard]] std::vector<std::size_t> allowedBehaviours(const MicroBehaviourDb& db, Intent intent,
                                                         Relation relation,
                                                         const std::vector<std::size_t>& exclude = {});

/// Picks one of `candidates` (indices into db) as `style` says; none when candidates is empty or
/// every weight × preference is 0.
[[nodiscard]] std::optional<std::size_t> chooseBehaviour(const MicroBehaviourDb& db,
                                                         const std::vector<std::size_t>& candidates,
                                                         const ActorStyle& style, core::Rng& rng);

/// An upper bound [s] on endTime - startTime (hence also on executeTime - startTime) for this
/// input, companions included: the initiation walk and moving closer, per step maxAttempts ×
/// (signal + slowest answer + timeout), the confirmation, then the longest macro-plan (or
/// fallback) with the farthest actor walking at the slowest speed and the longest visit.
[[nodiscard]] double coordinationTimeBound(const CoordinationInput& in, const Databases& dbs,
                                           const ClipLengths& clips, const CoordinationParams& params);

/// Runs the grounding state machine and the macro-plan (or fallback) into an action script.
/// Errors (diagnostics without a file): missing databases, a clip with no length, bad parameters.
[[nodiscard]] core::Result<ActionScript> planCoordination(const CoordinationInput& in, const Databases& dbs,
                                                          const ClipLengths& clips,
                                                          const CoordinationParams& params = {});

}  // namespace throng::common_ground
