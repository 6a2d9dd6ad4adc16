// Test fixture: a small Common Ground recording with known answers, written through
// throng::recording::Recorder from hand-built frames (used by tests/recording/recording_social_test.cpp and
// tests/e2e/social_commands_test.cpp). docs/social-metrics.md derives the expected metrics.
//
// Scenario: a 20 m x 10 m room; points 0 "wc" (restroom, (5, 5)), 1 "shoes" (shoes, (15, 5)),
// 2 "exit" (no category). Agents 0 and 1 form group 7, agent 2 is alone in group 8.
// Frames (10 fps, time = 0.1 f):
//   f0..f2: agent 0 at (5, 5), agent 1 at (5, 6), agent 2 at (15, 5.5)
//   f3:     agent 0 at (5, 5), agent 1 at (5, 13), agent 2 at (15, 5.5)
//   f4:     nobody (agent 2 exits; 0 and 1 are not in the frame)
// Events: spawns (f0), goal_generated x2, visit_start at wc (f0, agent 0) and at shoes (f3,
// agent 2), reunited (f3), exit (f4, agent 2).
// Coordinations: 1 grounded divide_and_wait A3 (t0 0, t8 2.5, end 10) with a Table 3/5 script for
// A = 0 and B = 1; 2 alone divide_and_proceed (3, 3, 5) of agent 2; 3 failed resume A6 (1, 4, 4.5).
#pragma once
#include <memory>
#include <string>

#include "throng/recording/recorder.hpp"

namespace throng::testing {

inline sim::ScenarioDesc socialScenario() {
  sim::ScenarioDesc s;
  s.name = "cg-fixture";
  s.seed = 1;
  s.dt = 0.05f;
  s.walkable = {{{0, 0}, {20, 0}, {20, 20}, {0, 20}}};
  const struct { const char* id; const char* category; float x, y; sim::PointKind kind; } points[] = {
      {"wc", "restroom", 5, 5, sim::PointKind::Interest},
      {"shoes", "shoes", 15, 5, sim::PointKind::Interest},
      {"exit", "", 19, 19, sim::PointKind::Exit}};
  for (const auto& p : points) {
    sim::PointDesc d;
    d.id = p.id;
    d.kind = p.kind;
    d.position = {p.x, p.y};
    d.radius = 0.5f;
    d.category = p.category;
    s.points.push_back(d);
  }
  sim::PopulationDesc pop;
  pop.id = "shoppers";
  pop.spawn.polygon = {{1, 1}, {8, 1}, {8, 9}, {1, 9}};
  pop.goals = {2};
  s.populations.push_back(pop);
  s.social.enabled = true;
  s.social.commonGround = true;
  return s;
}

inline sim::ScriptRecord scriptEntry(std::uint32_t coordination, std::uint32_t agent, std::uint32_t seq,
                                     std::uint8_t role, std::uint8_t step, std::uint8_t part, const char* motion,
                                     const char* behaviour, double start, double duration, std::uint8_t targetType = 0,
                                     std::uint32_t targetAgent = 0xffffffffu, float tx = 0, float ty = 0) {
  sim::ScriptRecord r;
  r.coordination = coordination;
  r.agent = agent;
  r.seq = seq;
  r.role = role;
  r.step = step;
  r.part = part;
  r.plan = 1;  // divide_and_wait
  r.motion = motion;
  r.behaviour = behaviour;
  r.targetType = targetType;
  r.targetAgent = targetAgent;
  r.targetX = tx;
  r.targetY = ty;
  r.plannedStart = start;
  r.plannedDuration = duration;
  r.start = start + 0.1;
  r.duration = duration;
  return r;
}

/// Writes the fixture recording to `path`; returns "" or the recorder's error.
inline std::string writeSocialRecording(const std::string& path) {
  recording::RecordingOptions o;
  o.path = path;
  o.fps = 10.0;
  o.seed = 1;
  o.scenarioText = R"({"format":"throng/1","name":"cg-fixture"})";
  o.framesPerBatch = 2;
  auto rec = recording::Recorder::open(socialScenario(), o);
  if (!rec.ok()) return core::formatAll(rec.errors());
  using K = sim::EventKind;
  for (std::uint64_t f = 0; f < 5; ++f) {
    auto fr = std::make_shared<sim::Frame>();
    fr->tick = f * 2;
    fr->time = 0.1 * static_cast<double>(f);
    if (f < 4) {
      const float y1 = f == 3 ? 13.0f : 6.0f;
      const float xs[] = {5, 5, 15}, ys[] = {5, y1, 5.5f};
      for (std::uint32_t id = 0; id < 3; ++id) {
        fr->ids.push_back(id);
        fr->posX.push_back(xs[id]);
        fr->posY.push_back(ys[id]);
        fr->velX.push_back(0);
        fr->velY.push_back(0);
        fr->oriX.push_back(0);
        fr->oriY.push_back(1);
        fr->mode.push_back(sim::AgentMode::Walking);
      }
    }
    if (f == 0) {
      fr->events = {{0, 0, K::Spawn, 0, 7}, {0, 1, K::Spawn, 0, 7}, {0, 2, K::Spawn, 0, 8},
                    {0, 0, K::GoalGenerated, 0, 0}, {0, 2, K::GoalGenerated, 1, 1}, {0, 0, K::VisitStart, 0, 1}};
    } else if (f == 3) {
      fr->events = {{6, 2, K::VisitStart, 1, 2}, {6, 0, K::Reunited, 7, 1}};
    } else if (f == 4) {
      fr->events = {{8, 2, K::Exit, 2, 0}};
      // Table 3 (A3: A walks into B's view, waves, B turns, 4a/5a/4b/5b, A nods), then Table 5 (M2).
      fr->script = {
          scriptEntry(1, 0, 0, 0, 1, 0, "walk", "move_into_view", 0.0, 1.0, 1, 0xffffffffu, 4, 4),
          scriptEntry(1, 0, 1, 0, 2, 0, "wave", "wave", 1.0, 0.5, 2, 1, 5, 6),
          scriptEntry(1, 1, 0, 1, 3, 0, "turn", "turn_toward", 1.5, 0.2, 2, 0, 5, 5),
          scriptEntry(1, 0, 2, 0, 4, 1, "point", "point_toward", 1.7, 0.3, 1, 0xffffffffu, 5, 5),
          scriptEntry(1, 1, 1, 1, 5, 1, "nod", "look_and_nod", 2.0, 0.2),
          scriptEntry(1, 0, 3, 0, 4, 2, "point_down", "point_down", 2.2, 0.1, 1, 0xffffffffu, 5, 6),
          scriptEntry(1, 1, 2, 1, 5, 2, "nod", "nod", 2.3, 0.1),
          scriptEntry(1, 0, 4, 0, 6, 0, "nod", "nod", 2.4, 0.1),
          scriptEntry(1, 0, 5, 0, 7, 0, "walk", "walk_to_goal", 2.5, 2.0, 1, 0xffffffffu, 5, 5),
          scriptEntry(1, 1, 3, 1, 7, 0, "idle", "wait", 2.5, 7.5),
      };
      sim::CoordinationRecord c1;
      c1.id = 1;
      c1.group = 7;
      c1.initiator = 0;
      c1.respondents = {1};
      c1.goalPoint = 0;
      c1.trigger = sim::GoalTrigger::Need;
      c1.relation = 3;
      c1.plan = 1;
      c1.outcome = sim::CoordinationOutcome::Grounded;
      c1.retries = 1;
      c1.start = 0.0;
      c1.executeTime = 2.5;
      c1.end = 10.0;
      sim::CoordinationRecord c2;
      c2.id = 2;
      c2.group = 8;
      c2.initiator = 2;
      c2.goalPoint = 1;
      c2.trigger = sim::GoalTrigger::Attraction;
      c2.plan = 0;
      c2.outcome = sim::CoordinationOutcome::Alone;
      c2.start = c2.executeTime = 3.0;
      c2.end = 5.0;
      sim::CoordinationRecord c3;
      c3.id = 3;
      c3.group = 7;
      c3.initiator = 1;
      c3.respondents = {0};
      c3.goalPoint = 1;
      c3.goalKind = 1;
      c3.trigger = sim::GoalTrigger::Attraction;
      c3.relation = 6;
      c3.plan = 3;
      c3.outcome = sim::CoordinationOutcome::Failed;
      c3.retries = 3;
      c3.start = 1.0;
      c3.executeTime = 4.0;
      c3.end = 4.5;
      fr->coordinations = {c1, c2, c3};
    }
    rec.value()->push(fr);
  }
  const auto st = rec.value()->close(true);
  return st.ok() ? std::string() : core::formatAll(st.errors());
}

}  // namespace throng::testing
