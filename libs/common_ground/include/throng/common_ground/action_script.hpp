// throng::common_ground action script — the timed output of the coordination planner (Park, Peng, Quek,
// Cao §3.1–3.2, Tables 3 and 5): per actor of the group (A, B, then the companions) a list of
// motions with activation times, targets, the grounding step (Table 1) and the macro-plan. A
// rendering engine or the simulation's decide phase reads it; nothing writes it but planCoordination.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "throng/core/vec2.hpp"
#include "throng/common_ground/behaviour_db.hpp"

namespace throng::common_ground {

/// The seven grounding steps of Table 1 (7 = executing the agreed macro-plan, or the fallback).
enum class GroundingStep : std::uint8_t {
  Initiate = 1,
  RequestAttention = 2,
  GiveAttention = 3,
  Propose = 4,
  Acknowledge = 5,
  Confirm = 6,
  Execute = 7,
};

/// The two principal actors of an interaction: A (index 0) initiates, B (index 1) responds. The
/// companions (the other group mates) follow at indices 2, 3, ... of ActionScript::actors.
enum class Actor : std::uint8_t { Initiator = 0, Respondent = 1 };

struct ScriptEntry {
  double start = 0.0;         ///< activation time [s], simulation time
  double duration = 0.0;      ///< [s] >= 0: clip length, distance / speed, angle / turning rate, or a wait
  std::string motion;         ///< clip name, or "walk" / "turn" / "idle" (procedural)
  std::string behaviour;      ///< micro-behaviour name, or macro step ("walk_to_goal", "stay", "wait", ...)
  enum class Target : std::uint8_t { None, Point, Agent } targetType = Target::None;
  core::Vec2 targetPoint{};   ///< [m] when targetType == Point (also set to the agent's position for Agent)
  std::uint32_t targetActor = 0;  ///< index into ActionScript::actors when targetType == Agent
  GroundingStep step = GroundingStep::Initiate;
  int part = 0;               ///< proposal part for steps 4 and 5: 1 = "a", 2 = "b", ...; 0 otherwise
  int attempt = 0;            ///< 0 for the first try of a step, then 1, 2, ... (retries)
  PlanKind plan = PlanKind::DivideAndWait;  ///< the macro-plan proposed or executed

  [[nodiscard]] double end() const { return start + duration; }
};

enum class Outcome : std::uint8_t {
  Grounded,  ///< common ground reached: the chosen macro-plan is executed (Table 1 step 7, TRUE)
  Failed,    ///< a step ran out of attempts: the fallback plan is executed (step 7, FALSE)
};

struct ActionScript {
  /// One list per actor, each in time order: [0] = A (initiator), [1] = B (respondent), [2 + k] =
  /// companion k of CoordinationInput::companions. Size 2 + number of companions (always >= 2).
  std::vector<std::vector<ScriptEntry>> actors = std::vector<std::vector<ScriptEntry>>(2);
  Outcome outcome = Outcome::Failed;
  PlanKind plan = PlanKind::Resume;   ///< executed plan: the chosen one, or the fallback on failure
  double startTime = 0.0;             ///< t_0 [s]
  double executeTime = 0.0;           ///< t_8 [s]: when the macro-plan (or fallback) starts
  double endTime = 0.0;               ///< [s] end of the last entry of any actor

  [[nodiscard]] const std::vector<ScriptEntry>& of(Actor a) const { return actors[static_cast<std::size_t>(a)]; }
  [[nodiscard]] std::size_t actorCount() const { return actors.size(); }
  /// Actor i's entries: 0 = A, 1 = B, 2 + k = companion k. Precondition: i < actorCount().
  [[nodiscard]] const std::vector<ScriptEntry>& actor(std::size_t i) const { return actors[i]; }
};

[[nodiscard]] std::string_view outcomeName(Outcome outcome);

/// "4a", "5b", "2" (attempt > 0 appends "/retry N").
[[nodiscard]] std::string stepLabel(const ScriptEntry& entry);

/// "A", "B", "C1", "C2", ...: the name of actor index i in formatScript.
[[nodiscard]] std::string actorLabel(std::size_t i);

/// The script as a text table in the shape of Tables 3 and 5: one row per entry, ordered by start
/// time (then step, then actor), with columns step, actor (A, B, C1, C2, ...), motion, behaviour,
/// target, start, duration, plan.
[[nodiscard]] std::string formatScript(const ActionScript& script);

/// Checks a script's invariants (for any number of actor lists): each actor's entries start in order, never
/// before t0, and never overlap; every duration is finite and >= 0; agent targets name an actor of
/// the script; startTime <= executeTime <= endTime, endTime is the last end.
/// Returns an empty string when they hold, else what is wrong.
[[nodiscard]] std::string checkScript(const ActionScript& script);

}  // namespace throng::common_ground
