// throng::common_ground behaviour databases — the micro-behaviour database (communication intents →
// bodily behaviours, Park, Peng, Quek, Cao Table 2) and the macro-plan database (Table 4:
// divide-and-proceed, divide-and-wait, detour-together), as plain data. Both are read from JSON by
// throng::io (data/social/micro_behaviours.json, data/social/macro_plans.json; format in
// docs/social-coordination.md); the coordination planner only reads them. Adding a micro-behaviour
// is adding a JSON entry and, if it plays a new clip, the clip.
#pragma once
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "throng/common_ground/relation.hpp"

namespace throng::common_ground {

/// Communication intents (Table 2), one per grounding step of Table 1 that has an actor.
enum class Intent : std::uint8_t {
  Initiate,          ///< step 1: A acts to satisfy the conditions for communication
  RequestAttention,  ///< step 2: A signals (wave, call out, tap)
  GiveAttention,     ///< step 3: B turns toward / looks at A
  Propose,           ///< step 4: A suggests the macro-plan (point toward, point down)
  Acknowledge,       ///< step 5: B signals acknowledgement (look where pointed, nod)
  Confirm,           ///< step 6: A confirms B's acknowledgement (nod)
};

/// What a behaviour is directed at.
enum class TargetKind : std::uint8_t {
  None,          ///< no target (nod)
  Partner,       ///< the other actor (wave at x_b, turn toward x_a)
  Goal,          ///< the goal x_s (point toward the store)
  Here,          ///< the actor's own position, i.e. the meeting point (point down)
  ViewPoint,     ///< x_i, a point in B's field of view (an input of the planner)
  HearingPoint,  ///< x_j, a point within B's hearing range (an input of the planner)
  Indicated,     ///< whatever the partner's behaviour being answered pointed at (turn toward x'_s)
};

/// Procedural motions, played without a clip: their length comes from distance or angle.
inline constexpr std::string_view kWalkMotion = "walk";  ///< length = distance / walking speed
inline constexpr std::string_view kTurnMotion = "turn";  ///< length = angle / turning rate
inline constexpr std::string_view kIdleMotion = "idle";  ///< length = a wait, a stay or a timeout

struct MicroBehaviour {
  std::string name;                        ///< unique ("wave", "call_out")
  std::vector<Intent> intents;             ///< the intents it can express (>= 1)
  std::vector<Relation> allowedIn;         ///< precondition: relations in which it can be used (>= 1)
  std::string clip;                        ///< clip played ("wave"), or "walk" / "turn" (procedural)
  TargetKind target = TargetKind::None;    ///< what it is directed at
  bool turnFirst = false;                  ///< turn toward the target (procedurally) before the clip
  std::optional<Relation> resultRelation;  ///< the relation once done (initiation moves); none: unchanged
  std::vector<std::string> responses;      ///< names of the partner's behaviours that answer it
  double weight = 1.0;                     ///< preference weight, (0, 1000]
  std::string description;                 ///< free text
};

/// The behaviour's precondition holds in relation r.
[[nodiscard]] inline bool allows(const MicroBehaviour& b, Relation r) {
  for (const Relation x : b.allowedIn) if (x == r) return true;
  return false;
}

/// The behaviour can express intent i.
[[nodiscard]] inline bool hasIntent(const MicroBehaviour& b, Intent i) {
  for (const Intent x : b.intents) if (x == i) return true;
  return false;
}

struct MicroBehaviourDb {
  std::vector<MicroBehaviour> behaviours;  ///< in file order (the order breaks ties)

  /// Index of the behaviour named `name`, if any.
  [[nodiscard]] std::optional<std::size_t> find(std::string_view name) const {
    for (std::size_t i = 0; i < behaviours.size(); ++i) {
      if (behaviours[i].name == name) return i;
    }
    return std::nullopt;
  }
};

/// Macro-plans (Table 4) plus the failure fallback.
enum class PlanKind : std::uint8_t {
  DivideAndProceed,  ///< M1: A goes to x_p (then x_q), B goes on to x_r
  DivideAndWait,     ///< M2: A goes to x_p, stays, returns to B; B waits; then both go on to x_r
  DetourTogether,    ///< M3: A leads the group to x_p (follow-the-leader), then all go on to x_r
  Resume,            ///< failure fallback: A gives up the goal, both go on to x_r
};

/// What the goal means for the group.
enum class GoalKind : std::uint8_t {
  Personal,  ///< only the initiator wants it (a bag in a store, the restroom)
  Shared,    ///< the whole group wants it
};

inline constexpr double kUnlimited = std::numeric_limits<double>::infinity();

struct MacroPlan {
  std::string name;                      ///< unique ("divide_and_wait")
  PlanKind kind = PlanKind::DivideAndWait;
  std::string paperId;                   ///< "M1".."M3", may be empty
  std::vector<std::string> proposal;     ///< micro-behaviours A performs in step 4 (4a, 4b, ...), >= 1
  double visitDuration = 0.0;            ///< [s] constant stay at the goal, [0, 86400]
  // Selection rules: the first plan in file order whose rules all hold is chosen.
  std::vector<GoalKind> goalKinds;       ///< goal kinds it serves (>= 1)
  double maxGoalDistance = kUnlimited;   ///< [m] |x_s - x_b| at most this (> 0, or unlimited)
  double maxExpectedVisit = kUnlimited;  ///< [s] the goal's expected visit at most this (> 0, or unlimited)
  std::string description;               ///< free text
};

struct MacroPlanDb {
  std::vector<MacroPlan> plans;              ///< in priority order
  PlanKind failurePlan = PlanKind::Resume;   ///< what the actors do when grounding fails
};

namespace detail {
template <class E, std::size_t N>
struct NameTable {
  E values[N];
  std::string_view names[N];
  [[nodiscard]] constexpr std::string_view name(E e) const {
    for (std::size_t i = 0; i < N; ++i) if (values[i] == e) return names[i];
    return "?";
  }
  [[nodiscard]] constexpr std::optional<E> parse(std::string_view s) const {
    for (std::size_t i = 0; i < N; ++i) if (names[i] == s) return values[i];
    return std::nullopt;
  }
};
inline constexpr NameTable<Intent, 6> kIntentNames{
    {Intent::Initiate, Intent::RequestAttention, Intent::GiveAttention, Intent::Propose, Intent::Acknowledge,
     Intent::Confirm},
    {"initiate", "request_attention", "give_attention", "propose", "acknowledge", "confirm"}};
inline constexpr NameTable<TargetKind, 7> kTargetNames{
    {TargetKind::None, TargetKind::Partner, TargetKind::Goal, TargetKind::Here, TargetKind::ViewPoint,
     TargetKind::HearingPoint, TargetKind::Indicated},
    {"none", "partner", "goal", "here", "view_point", "hearing_point", "indicated"}};
inline constexpr NameTable<PlanKind, 4> kPlanNames{
    {PlanKind::DivideAndProceed, PlanKind::DivideAndWait, PlanKind::DetourTogether, PlanKind::Resume},
    {"divide_and_proceed", "divide_and_wait", "detour_together", "resume"}};
inline constexpr NameTable<GoalKind, 2> kGoalNames{{GoalKind::Personal, GoalKind::Shared}, {"personal", "shared"}};
inline constexpr NameTable<Relation, 6> kRelationNames{
    {Relation::A1, Relation::A2, Relation::A3, Relation::A4, Relation::A5, Relation::A6},
    {"A1", "A2", "A3", "A4", "A5", "A6"}};
}  // namespace detail

/// Names as written in the JSON databases ("request_attention", "view_point", "divide_and_wait").
[[nodiscard]] constexpr std::string_view intentName(Intent v) { return detail::kIntentNames.name(v); }
[[nodiscard]] constexpr std::optional<Intent> intentFromName(std::string_view s) { return detail::kIntentNames.parse(s); }
[[nodiscard]] constexpr std::string_view targetKindName(TargetKind v) { return detail::kTargetNames.name(v); }
[[nodiscard]] constexpr std::optional<TargetKind> targetKindFromName(std::string_view s) { return detail::kTargetNames.parse(s); }
[[nodiscard]] constexpr std::string_view planKindName(PlanKind v) { return detail::kPlanNames.name(v); }
[[nodiscard]] constexpr std::optional<PlanKind> planKindFromName(std::string_view s) { return detail::kPlanNames.parse(s); }
[[nodiscard]] constexpr std::string_view goalKindName(GoalKind v) { return detail::kGoalNames.name(v); }
[[nodiscard]] constexpr std::optional<GoalKind> goalKindFromName(std::string_view s) { return detail::kGoalNames.parse(s); }
[[nodiscard]] constexpr std::optional<Relation> relationFromName(std::string_view s) { return detail::kRelationNames.parse(s); }

}  // namespace throng::common_ground
