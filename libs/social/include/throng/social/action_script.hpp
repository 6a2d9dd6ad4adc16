// throng::social action script — the timed output of the coordination planner (Park, Peng, Quek,
// Cao §3.1–3.2, Tables 3 and 5): per actor a list of motions with activation times, targets, the
// grounding step (Table 1) and the macro-plan. A rendering engine or the simulation's decide phase
// reads it; nothing writes it but planCoordination.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "throng/core/vec2.hpp"
#include "throng/social/behaviour_db.hpp"

namespace throng::social {

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

/// The two actors of an interaction: A (index 0) initiates, B (index 1) responds.
enum class Actor : std::uint8_t { Initiator = 0, Respondent = 1 };

struct ScriptEntry {
  double start = 0.0;         ///< activation time [s], simulation time
  double duration = 0.0;      ///< [s] >= 0: clip length, distance / speed, angle / turning rate, or a wait
  std::string motion;         ///< clip name, or "walk" / "turn" / "idle" (procedural)
  std::string behaviour;      ///< micro-behaviour name, or macro step ("walk_to_goal", "stay", "wait", ...)
  enum class Target : std::uint8_t { None, Point, Agent } targetType = Target::None;
  core::Vec2 targetPoint{};   ///< [m] when targetType == Point (also set to the agent's position for Agent)
  Actor targetAgent = Actor::Initiator;  ///< when targetType == Agent
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
  std::array<std::vector<ScriptEntry>, 2> actors;  ///< [Initiator], [Respondent], each in time order
  Outcome outcome = Outcome::Failed;
  PlanKind plan = PlanKind::Resume;   ///< executed plan: the chosen one, or the fallback on failure
  double startTime = 0.0;             ///< t_0 [s]
  double executeTime = 0.0;           ///< t_8 [s]: when the macro-plan (or fallback) starts
  double endTime = 0.0;               ///< [s] end of the last entry of either actor

  [[nodiscard]] const std::vector<ScriptEntry>& of(Actor a) const { return actors[static_cast<int>(a)]; }
};

[[nodiscard]] std::string_view outcomeName(Outcome outcome);

/// "4a", "5b", "2" (attempt > 0 appends "/retry N").
[[nodiscard]] std::string stepLabel(const ScriptEntry& entry);

/// The script as a text table in the shape of Tables 3 and 5: one row per entry, ordered by start
/// time, with columns step, actor, motion, behaviour, target, start, duration.
[[nodiscard]] std::string formatScript(const ActionScript& script);

/// Checks a script's invariants: each actor's entries start in order and never overlap, every
/// duration is finite and >= 0, startTime <= executeTime <= endTime, endTime is the last end.
/// Returns an empty string when they hold, else what is wrong.
[[nodiscard]] std::string checkScript(const ActionScript& script);

}  // namespace throng::social
