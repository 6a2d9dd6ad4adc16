// VerticalTransports — lifts and escalators (ScenarioDesc::transports; docs/crowd-model.md, "Tactical level:
// lifts and escalators"). decide puts someone who reaches a transport's boarding stop (its current
// goal) in GoalState::Riding; from then on this pass, run once a tick after integrate, queues them
// at that stop, carries them and lets them off at the other stop, where they go on with their next
// goal (GoalWriter::advanceGoal). Serial and in ascending id order, in whole ticks: the same for
// any thread or rank count. People queuing for a lift stand (AgentMode::Waiting) and step aside
// when pressed, as anyone standing does; for an escalator they creep toward where people step on
// (AgentMode::Walking; steer.cpp). People carried are AgentMode::Acting: no model or navmesh moves them
// (integrate), they are nobody's neighbours (sense), and their position, height and velocity are the
// car's or the belt's.
#pragma once
#include <cstdint>
#include <deque>
#include <functional>
#include <vector>

#include "agent_store.hpp"
#include "goals.hpp"
#include "throng/nav/navmesh.hpp"
#include "throng/sim/scenario.hpp"

namespace throng::sim {

class VerticalTransports {
 public:
  /// One state per transport of `desc` (all idle, nobody queuing).
  void configure(const ScenarioDesc& desc);
  [[nodiscard]] bool empty() const { return states_.empty(); }

  /// One tick at `tick`: queues those who started riding, runs every lift and escalator, moves the
  /// people aboard and lets off those who arrived (GoalReached at the stop, then their next goal).
  void step(const ScenarioDesc& desc, std::uint64_t tick, const nav::NavQuery& query, GoalWriter goals);

  /// The transport whose boarding stop point `point` is, or kNoIndex.
  [[nodiscard]] static std::uint32_t boardingAt(const ScenarioDesc& desc, std::uint32_t point);

  // What choosing a transport (transport_choice.hpp) asks, in seconds.
  /// How long someone who sets off for stop `stop` of transport `t` now waits there before stepping
  /// on, `heading` people queuing there or on their way (carried ones included): for an escalator one
  /// headway for each of them not carried yet; for a lift the car's way to the stop and its doors,
  /// and a round trip to `to` and back for every full car of those ahead.
  [[nodiscard]] float expectedWait(const ScenarioDesc& desc, std::size_t t, std::size_t stop, std::size_t to,
                                   std::uint32_t heading) const;
  /// From stepping on at stop `from` of t to stepping off at stop `to`: an escalator's length over
  /// its speed; for a lift its doors closing, the trip, its doors opening and one person's transfer.
  [[nodiscard]] static float rideTime(const ScenarioDesc& desc, const TransportDesc& t, std::size_t from, std::size_t to);
  /// A lift's trip between two of its stops (trapezoidal: accelerating to its speed, braking) [s].
  [[nodiscard]] static float tripTime(const ScenarioDesc& desc, const TransportDesc& t, std::size_t from, std::size_t to);

 private:
  enum class Phase : std::uint8_t { Idle, Opening, Transfer, Closing, Moving };
  /// Someone queuing or carried: its id, the stop it rides to (rideTo), when it stepped on.
  struct Rider {
    std::uint32_t id;
    std::uint32_t dest;
    std::uint64_t boarded = 0;  ///< escalator: the tick it stepped on; elevator: the tick it came to the stop
  };
  struct State {
    std::vector<std::deque<Rider>> queue;  ///< per stop: those waiting there, in the order they came
    std::vector<Rider> aboard;             ///< those carried, in boarding order
    std::uint64_t nextBoard = 0;           ///< escalator: the first tick the next may step on
    std::uint32_t at = 0;                  ///< elevator: the stop the car is at (or travels to)
    std::uint32_t from = 0;                ///< elevator: the stop it left (while Moving)
    int dir = 0;                           ///< elevator: +1 going up, -1 down (the stops by height), 0 idle
    Phase phase = Phase::Idle;             ///< elevator
    std::uint64_t until = 0;               ///< elevator: the tick the phase's current step ends
    std::uint64_t moveStart = 0;           ///< elevator: the tick the car left
    std::uint64_t moveTicks = 1;           ///< elevator: how long this trip takes
  };
  struct Place {
    core::Vec2 p;
    float z = 0.0f;
  };

  void runEscalator(const ScenarioDesc& desc, const TransportDesc& t, State& s, std::uint64_t tick);
  void runElevator(const ScenarioDesc& desc, const TransportDesc& t, State& s, std::uint64_t tick);
  /// Sends the car from its stop to stop `to`.
  void startMove(const ScenarioDesc& desc, const TransportDesc& t, State& s, std::uint64_t tick, std::uint32_t to);
  /// The stop the car goes to next, from what those aboard and those waiting elsewhere want: the
  /// nearest such stop in its direction (by height, then list order), else the nearest the other
  /// way; kNoIndex when nobody wants anything.
  [[nodiscard]] static std::uint32_t nextStop(const ScenarioDesc& desc, const TransportDesc& t, State& s);
  /// Of `queue` (those `eligible`, when given), the index of the person nearest p (ties: the first to
  /// come).
  [[nodiscard]] std::size_t nearest(const std::deque<Rider>& queue, core::Vec2 p,
                                    const std::function<bool(const Rider&)>& eligible = {}) const;
  /// The way the car goes on from its stop (+1 up, -1 down): its direction while someone aboard rides,
  /// or someone waits, further that way; else 0 (it may turn).
  [[nodiscard]] static int servingDirection(const ScenarioDesc& desc, const TransportDesc& t, const State& s);
  /// Puts `id` off at stop `stop` of t (the k-th let off there this tick).
  void alight(const ScenarioDesc& desc, const TransportDesc& t, std::uint32_t stop, std::uint32_t id, int k);
  [[nodiscard]] static Place stopPlace(const ScenarioDesc& desc, const TransportDesc& t, std::uint32_t stop);

  std::vector<State> states_;
  // Valid during step():
  std::vector<std::uint32_t> rowOfId_;  ///< riders' rows by id (kNoRow for others), this tick
  std::vector<std::uint32_t> riders_;   ///< riders' ids this tick, ascending
  std::vector<std::uint8_t> known_;     ///< by id: 1 while in a queue or a car
  struct Off {
    std::uint32_t row;
    std::uint32_t point;
    Place place;
  };
  std::vector<Off> off_;  ///< let off this tick: placed and sent on after every transport ran
  AgentStore* agents_ = nullptr;
  float dt_ = 0.05f;
};

}  // namespace throng::sim
