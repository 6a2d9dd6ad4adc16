// Tests of the whole-group extension of the Common Ground coordination planner
// (libs/common_ground/src/coordination.cpp, docs/social-coordination.md "Whole group") on the bundled
// databases (data/social/*.json): B and every companion answer each of A's signals in parallel from
// the signal's end, A goes on when the last answer ends, a companion that cannot perceive a signal
// turns toward A, companions take B's part in the macro-plan; and, over 200 seeded random layouts
// with 0–5 companions and lost responses, every script is valid and ends within the bound.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <tuple>

#include "social_test_util.hpp"
#include "throng/core/rng.hpp"
#include "throng/common_ground/coordination.hpp"

namespace {

using namespace throng;
using namespace throng::common_ground;
using core::Vec2;
using G = GroundingStep;

using test::bundled;
using test::clipLengths;
using test::databases;

constexpr double kEps = 1e-9;

/// The worked example's layout (A3, divide-and-wait) plus `companions`.
CoordinationInput workedExample(std::vector<Companion> companions) {
  CoordinationInput in;
  in.initiator = {{0, 0}, 0.0f, 1.25f, 1};
  in.respondent = {{10, 0}, 0.0f, 1.25f, 2};
  in.companions = std::move(companions);
  in.relation = Relation::A3;
  in.viewPoint = Vec2{14, 3};
  in.goal = {{5, 8}, GoalKind::Personal, 60.0, std::nullopt};
  in.destination = {30, 0};
  in.startTime = 5.0;
  in.initiatorStyle.mode = SelectionMode::Best;
  in.respondentStyle.mode = SelectionMode::Best;
  return in;
}

/// Checks the parallel-response rules on a script; returns "" or what is wrong. For each of A's
/// signals (step 2, or step 4 part p; attempt k) every companion answers (step 3 / 5, same part and
/// attempt) starting at the signal's end, and B too unless its answer was lost; A's next entry
/// starts at the last answer's end (B answered) or A awaits from the signal's end until at least
/// the companions' last end (B's answer lost).
std::string checkParallelResponses(const ActionScript& s) {
  using Key = std::tuple<int, int, int>;  // answer step, part, attempt
  struct Span {
    double first = 1e300, last = -1e300;
  };
  std::vector<std::map<Key, Span>> answers(s.actorCount());
  for (std::size_t a = 1; a < s.actorCount(); ++a) {
    for (const ScriptEntry& e : s.actor(a)) {
      if (e.step != G::GiveAttention && e.step != G::Acknowledge) continue;
      Span& sp = answers[a][{static_cast<int>(e.step), e.part, e.attempt}];
      sp.first = std::min(sp.first, e.start);
      sp.last = std::max(sp.last, e.end());
    }
  }
  const auto& A = s.actor(0);
  std::size_t signals = 0;
  for (std::size_t i = 0; i < A.size(); ++i) {
    const ScriptEntry& e = A[i];
    if (e.step != G::RequestAttention && e.step != G::Propose) continue;
    if (e.behaviour == "await_response" || e.behaviour == "move_closer") continue;
    if (i + 1 < A.size() && A[i + 1].step == e.step && A[i + 1].attempt == e.attempt &&
        A[i + 1].behaviour == e.behaviour) {
      continue;  // the turn before the clip: the signal ends with the clip
    }
    ++signals;
    const G answerStep = e.step == G::RequestAttention ? G::GiveAttention : G::Acknowledge;
    const Key key{static_cast<int>(answerStep), e.part, e.attempt};
    const std::string where = "signal " + e.behaviour + " " + stepLabel(e) + " at " + std::to_string(e.start);
    double last = e.end();
    for (std::size_t a = 1; a < s.actorCount(); ++a) {
      const auto it = answers[a].find(key);
      if (it == answers[a].end()) {
        if (a >= 2) return where + ": companion " + actorLabel(a) + " did not answer";
        continue;
      }
      if (std::abs(it->second.first - e.end()) > kEps) {
        return where + ": " + actorLabel(a) + " answers at " + std::to_string(it->second.first) + ", not at the signal's end";
      }
      last = std::max(last, it->second.last);
    }
    const bool bAnswered = answers[1].count(key) > 0;
    if (i + 1 >= A.size()) return where + ": A's script ends with a signal";
    const ScriptEntry& next = A[i + 1];
    if (bAnswered) {
      if (std::abs(next.start - last) > kEps) {
        return where + ": A goes on at " + std::to_string(next.start) + ", the last answer ends at " + std::to_string(last);
      }
    } else {
      if (next.behaviour != "await_response") return where + ": B did not answer but A does not await";
      if (std::abs(next.start - e.end()) > kEps) return where + ": A's await does not start at the signal's end";
      if (next.end() + kEps < last) return where + ": A stops waiting before the companions have answered";
    }
  }
  if (signals == 0 && s.outcome == Outcome::Grounded) return "a grounded script without signals";
  return {};
}

const ScriptEntry* findEntry(const std::vector<ScriptEntry>& list, G step, int part, const std::string& behaviour) {
  for (const auto& e : list) {
    if (e.step == step && e.part == part && (behaviour.empty() || e.behaviour == behaviour)) return &e;
  }
  return nullptr;
}

TEST(SocialGroupCoordination, DefaultScriptHasTwoActorsAndNoCompanionsGiveTwo) {
  ActionScript empty;
  EXPECT_EQ(empty.actorCount(), 2u);
  auto r = planCoordination(workedExample({}), databases(), clipLengths());
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  EXPECT_EQ(r.value().actorCount(), 2u);
  EXPECT_EQ(checkParallelResponses(r.value()), "");
}

TEST(SocialGroupCoordination, OneCompanionAnswersWithBAndAGoesOnAfterTheLastAnswer) {
  // C1 stands beside B, facing away from A too (A3 for C1 as well): it cannot see the wave, so it
  // turns toward A with the others; from then on it sees A and acknowledges like B.
  const Vec2 xc{11, -4};
  auto in = workedExample({Companion{{xc, 1.2f, 1.0f, 3}, Relation::A3}});
  CoordinationParams params;
  params.turnRate = 2.0;
  auto r = planCoordination(in, databases(), clipLengths(), params);
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  const ActionScript& s = r.value();
  SCOPED_TRACE(formatScript(s));
  EXPECT_EQ(checkScript(s), "");
  EXPECT_EQ(checkParallelResponses(s), "");
  ASSERT_EQ(s.actorCount(), 3u);
  EXPECT_EQ(s.outcome, Outcome::Grounded);
  EXPECT_EQ(s.plan, PlanKind::DivideAndWait);
  const auto& A = s.of(Actor::Initiator);
  const auto& B = s.of(Actor::Respondent);
  const auto& C = s.actor(2);

  // Step 3: both answer the wave at its end.
  const ScriptEntry* wave = findEntry(A, G::RequestAttention, 0, "wave");
  const ScriptEntry* b3 = findEntry(B, G::GiveAttention, 0, "");
  const ScriptEntry* c3 = findEntry(C, G::GiveAttention, 0, "");
  ASSERT_TRUE(wave && b3 && c3);
  EXPECT_NEAR(b3->start, wave->end(), kEps);
  EXPECT_NEAR(c3->start, wave->end(), kEps);
  // C1 cannot perceive the wave (A3): the procedural turn toward A (at x_i), from its own heading.
  EXPECT_EQ(c3->behaviour, "turn_toward");
  EXPECT_EQ(c3->motion, "turn");
  EXPECT_EQ(c3->targetType, ScriptEntry::Target::Agent);
  EXPECT_EQ(c3->targetActor, 0u);
  EXPECT_EQ(c3->targetPoint, (Vec2{14, 3}));
  double want = std::atan2(3.0 - xc.y, 14.0 - xc.x) - 1.2;
  EXPECT_NEAR(c3->duration, std::abs(want) / 2.0, 1e-5);

  // Step 4a starts at the later of B's and C1's answer; 5a both at 4a's end; 4b, 5b, 6 likewise.
  const ScriptEntry* p4a = findEntry(A, G::Propose, 1, "");
  ASSERT_TRUE(p4a);
  EXPECT_NEAR(p4a->start, std::max(b3->end(), c3->end()), kEps);
  for (int part : {1, 2}) {
    const ScriptEntry* sig = findEntry(A, G::Propose, part, "");
    ASSERT_TRUE(sig);
    double last = 0.0;
    for (const auto* list : {&B, &C}) {
      const ScriptEntry* first = findEntry(*list, G::Acknowledge, part, "");
      ASSERT_TRUE(first) << part;
      EXPECT_NEAR(first->start, sig->end(), kEps) << part;
      for (const auto& e : *list) {
        if (e.step == G::Acknowledge && e.part == part) last = std::max(last, e.end());
      }
    }
    const ScriptEntry* next = part == 1 ? findEntry(A, G::Propose, 2, "") : findEntry(A, G::Confirm, 0, "");
    ASSERT_TRUE(next);
    EXPECT_NEAR(next->start, last, kEps) << part;
  }
  // C1 sees A after turning: it acknowledges 5a like B (turn toward the store, nod).
  const ScriptEntry* c5a = findEntry(C, G::Acknowledge, 1, "");
  ASSERT_TRUE(c5a);
  EXPECT_EQ(c5a->behaviour, "turn_toward_and_nod");
  EXPECT_EQ(c5a->targetPoint, (Vec2{5, 8}));

  // Step 7, divide-and-wait: C1 waits where it is and resumes with A and B.
  const ScriptEntry* bResume = findEntry(B, G::Execute, 0, "resume");
  const ScriptEntry* cResume = findEntry(C, G::Execute, 0, "resume");
  const ScriptEntry* aResume = findEntry(A, G::Execute, 0, "resume");
  const ScriptEntry* cWait = findEntry(C, G::Execute, 0, "wait");
  ASSERT_TRUE(bResume && cResume && aResume && cWait);
  EXPECT_EQ(cResume->start, bResume->start);
  EXPECT_EQ(aResume->start, bResume->start);
  EXPECT_NEAR(cWait->start, s.executeTime, kEps);
  EXPECT_EQ(cWait->targetPoint, xc);
  EXPECT_NEAR(cResume->duration, core::distance(xc, Vec2{30, 0}) / 1.0, 1e-4);
  EXPECT_LE(s.endTime - s.startTime, coordinationTimeBound(in, databases(), clipLengths(), params));
}

TEST(SocialGroupCoordination, ThreeCompanionsAnswerEverySignalInParallel) {
  auto in = workedExample({Companion{{{12, 2}, 3.0f, 1.4f, 3}, Relation::A2},
                           Companion{{{8, -3}, 0.0f, 0.9f, 4}, Relation::A4},
                           Companion{{{20, 5}, -1.0f, 1.1f, 5}, Relation::A6}});
  in.respondentStyle.mode = SelectionMode::Weighted;
  in.seed = 17;
  auto r = planCoordination(in, databases(), clipLengths());
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  const ActionScript& s = r.value();
  SCOPED_TRACE(formatScript(s));
  EXPECT_EQ(checkScript(s), "");
  EXPECT_EQ(checkParallelResponses(s), "");
  ASSERT_EQ(s.actorCount(), 5u);
  EXPECT_EQ(s.outcome, Outcome::Grounded);
  const auto& B = s.of(Actor::Respondent);
  for (G step : {G::GiveAttention, G::Acknowledge}) {
    for (int part : step == G::GiveAttention ? std::vector<int>{0} : std::vector<int>{1, 2}) {
      const ScriptEntry* b = findEntry(B, step, part, "");
      ASSERT_TRUE(b);
      for (std::size_t c = 2; c < 5; ++c) {
        const ScriptEntry* e = findEntry(s.actor(c), step, part, "");
        ASSERT_TRUE(e) << actorLabel(c);
        EXPECT_NEAR(e->start, b->start, kEps) << actorLabel(c);
      }
    }
  }
  // A3's neighbours: C3 (A6) cannot perceive the wave and turns toward A (contagion).
  EXPECT_EQ(findEntry(s.actor(4), G::GiveAttention, 0, "")->motion, "turn");
  EXPECT_EQ(findEntry(s.actor(4), G::GiveAttention, 0, "")->behaviour, "turn_toward");
  // Divide-and-wait: everybody resumes at B's time.
  const double resume = findEntry(B, G::Execute, 0, "resume")->start;
  for (std::size_t a = 0; a < 5; ++a) {
    const ScriptEntry* e = findEntry(s.actor(a), G::Execute, 0, "resume");
    ASSERT_TRUE(e) << actorLabel(a);
    EXPECT_EQ(e->start, resume) << actorLabel(a);
  }
  // The table names companions C1..C3.
  const std::string text = formatScript(s);
  EXPECT_NE(text.find(" C3 "), std::string::npos);
  EXPECT_EQ(text.find(" C4 "), std::string::npos);
}

TEST(SocialGroupCoordination, CompanionThatCannotPerceiveTheSignalTurnsTowardA) {
  // B and C1 face A (A2); C2 faces away, too far to hear (A3). Nobody may pick turn_toward, so
  // B and C1 answer the wave with look_at; C2's answer is the procedural turn toward A.
  CoordinationInput in;
  in.initiator = {{0, 0}, 0.0f, 1.3f, 1};
  in.respondent = {{3, 0}, std::numbers::pi_v<float>, 1.3f, 2};
  in.companions = {Companion{{{3, 2}, std::numbers::pi_v<float>, 1.3f, 3}, Relation::A2},
                   Companion{{{5, -2}, 0.0f, 1.3f, 4}, Relation::A3}};
  in.relation = Relation::A2;
  in.goal = {{5, 5}, GoalKind::Personal, 10.0, std::nullopt};
  in.destination = {20, 0};
  in.initiatorStyle.mode = SelectionMode::Best;
  in.respondentStyle.mode = SelectionMode::Best;
  in.respondentStyle.preference["turn_toward"] = 0.0;
  CoordinationParams params;
  auto r = planCoordination(in, databases(), clipLengths(), params);
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  const ActionScript& s = r.value();
  SCOPED_TRACE(formatScript(s));
  EXPECT_EQ(checkScript(s), "");
  EXPECT_EQ(checkParallelResponses(s), "");
  ASSERT_EQ(findEntry(s.actor(0), G::RequestAttention, 0, "")->behaviour, "wave");
  EXPECT_EQ(s.actor(1).front().step, G::GiveAttention);
  EXPECT_EQ(findEntry(s.actor(1), G::GiveAttention, 0, "look_at")->motion, "turn");
  EXPECT_NE(findEntry(s.actor(2), G::GiveAttention, 0, "look_at"), nullptr);
  const ScriptEntry* c2 = findEntry(s.actor(3), G::GiveAttention, 0, "");
  ASSERT_NE(c2, nullptr);
  EXPECT_EQ(c2->behaviour, "turn_toward");
  EXPECT_EQ(c2->motion, "turn");
  EXPECT_EQ(c2->targetActor, 0u);
  EXPECT_NEAR(c2->duration, std::abs(std::atan2(2.0, -5.0)) / params.turnRate, 1e-5);
  // Only one entry for the contagion turn; afterwards C2 acknowledges like the others.
  EXPECT_EQ(s.actor(3)[1].step, G::Acknowledge);
}

TEST(SocialGroupCoordination, CompanionsTakeBsPartInEveryPlan) {
  for (const PlanKind kind : {PlanKind::DivideAndWait, PlanKind::DivideAndProceed, PlanKind::DetourTogether}) {
    auto in = workedExample({Companion{{{12, 2}, 3.0f, 0.8f, 3}, Relation::A2},
                             Companion{{{9, -1}, 0.0f, 1.6f, 4}, Relation::A5}});
    in.forcedPlan = kind;
    auto r = planCoordination(in, databases(), clipLengths());
    ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
    const ActionScript& s = r.value();
    SCOPED_TRACE(formatScript(s));
    EXPECT_EQ(checkScript(s), "");
    EXPECT_EQ(s.plan, kind);
    const double t8 = s.executeTime;
    const auto& B = s.of(Actor::Respondent);
    for (std::size_t c = 1; c < s.actorCount(); ++c) {
      const auto& list = s.actor(c);
      std::vector<std::string> names;
      for (const auto& e : list) {
        if (e.step == G::Execute) names.push_back(e.behaviour);
      }
      switch (kind) {
        case PlanKind::DivideAndWait:
          EXPECT_EQ(names, (std::vector<std::string>{"wait", "resume"})) << actorLabel(c);
          EXPECT_EQ(list.back().start, B.back().start);
          break;
        case PlanKind::DivideAndProceed:
          EXPECT_EQ(names, (std::vector<std::string>{"walk_to_destination"})) << actorLabel(c);
          EXPECT_NEAR(list.back().start, t8, kEps);
          break;
        case PlanKind::DetourTogether: {
          EXPECT_EQ(names, (std::vector<std::string>{"follow", "stay", "resume"})) << actorLabel(c);
          const ScriptEntry* follow = findEntry(list, G::Execute, 0, "follow");
          EXPECT_NEAR(follow->start, t8, kEps);
          EXPECT_EQ(follow->targetActor, 0u);
          EXPECT_EQ(list.back().start, s.actor(0).back().start);  // all resume together
          break;
        }
        default: break;
      }
      EXPECT_EQ(list.back().targetPoint, (Vec2{30, 0}));
    }
    if (kind == PlanKind::DetourTogether) {
      // Stay until the last arrival (the slow C1) + the visit.
      double lastArrival = 0.0;
      for (std::size_t a = 0; a < s.actorCount(); ++a) {
        const ScriptEntry* w = findEntry(s.actor(a), G::Execute, 0, a == 0 ? "lead_to_goal" : "follow");
        lastArrival = std::max(lastArrival, w->end());
      }
      EXPECT_NEAR(s.actor(2).back().start, lastArrival + bundled().macro.plans[0].visitDuration, 1e-6);
    }
  }
}

TEST(SocialGroupCoordination, BadCompanionIsADiagnostic) {
  auto in = workedExample({Companion{{{12, 2}, 0.0f, 0.0f, 3}, Relation::A2}});
  auto r = planCoordination(in, databases(), clipLengths());
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.errors()[0].what.find("companion 1 walkSpeed"), std::string::npos);
}

// ~200 seeded random groups: layouts, relations, 0–5 companions, lost responses for B.
TEST(SocialGroupCoordination, RandomGroupsGiveValidBoundedScripts) {
  std::set<Outcome> outcomes;
  std::set<std::size_t> sizes;
  std::size_t lostSeen = 0;
  for (std::uint64_t i = 0; i < 200; ++i) {
    core::Rng rng(20240601, i, core::RngPurpose::Bench);
    auto pt = [&] { return Vec2{static_cast<float>(rng.uniform(-40, 40)), static_cast<float>(rng.uniform(-40, 40))}; };
    auto heading = [&] { return static_cast<float>(rng.uniform(-std::numbers::pi, std::numbers::pi)); };
    auto speed = [&] { return static_cast<float>(rng.uniform(0.5, 3.0)); };
    auto relation = [&] { return static_cast<Relation>(rng.uniformInt(1, 6)); };
    auto mode = [&] {
      const SelectionMode m[] = {SelectionMode::Uniform, SelectionMode::Weighted, SelectionMode::Best};
      return m[rng.uniformInt(0, 2)];
    };
    CoordinationInput in;
    in.initiator = {pt(), heading(), speed(), 1000 + i};
    in.respondent = {pt(), heading(), speed(), 2000 + i};
    in.relation = relation();
    const std::uint32_t n = rng.uniformInt(0, 5);
    for (std::uint32_t k = 0; k < n; ++k) in.companions.push_back({{pt(), heading(), speed(), 3000 + 10 * i + k}, relation()});
    if (rng.uniform() < 0.7) in.viewPoint = pt();
    if (rng.uniform() < 0.7) in.hearingPoint = pt();
    in.goal = {pt(), rng.uniform() < 0.5 ? GoalKind::Personal : GoalKind::Shared, rng.uniform(0, 600), std::nullopt};
    if (rng.uniform() < 0.3) in.goal.next = pt();
    in.destination = pt();
    in.startTime = rng.uniform(0, 100);
    in.seed = rng.next();
    in.initiatorStyle.mode = mode();
    in.respondentStyle.mode = mode();
    const std::uint32_t lost = rng.uniformInt(0, 8);
    for (std::uint32_t k = 0; k < lost; ++k) in.lostResponses.push_back(rng.uniform() < 0.5);
    in.respondentAbsent = rng.uniform() < 0.1;
    ClipLengths clips;
    for (const char* c : {"wave", "nod", "point_toward", "point_down", "call_out", "look_at", "talk"}) {
      clips[c] = rng.uniform(0.1, 6.0);
    }
    CoordinationParams p;
    p.turnRate = rng.uniform(0.5, 6.0);
    p.responseTimeout = rng.uniform(0.0, 5.0);
    p.maxAttempts = static_cast<int>(rng.uniformInt(1, 5));

    SCOPED_TRACE("case " + std::to_string(i));
    auto r = planCoordination(in, databases(), clips, p);
    ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
    const ActionScript& s = r.value();
    SCOPED_TRACE(formatScript(s));
    ASSERT_EQ(s.actorCount(), 2u + n);
    ASSERT_EQ(checkScript(s), "");
    ASSERT_EQ(checkParallelResponses(s), "");
    const double bound = coordinationTimeBound(in, databases(), clips, p);
    EXPECT_LE(s.executeTime - s.startTime, bound);
    EXPECT_LE(s.endTime - s.startTime, bound);
    if (in.respondentAbsent) EXPECT_EQ(s.outcome, Outcome::Failed);
    if (s.outcome == Outcome::Failed) EXPECT_EQ(s.plan, bundled().macro.failurePlan);
    // Every actor ends walking on in the executed plan: nobody waits forever.
    for (std::size_t a = 0; a < s.actorCount(); ++a) {
      ASSERT_FALSE(s.actor(a).empty()) << actorLabel(a);
      EXPECT_EQ(s.actor(a).back().step, G::Execute);
      EXPECT_EQ(s.actor(a).back().plan, s.plan);
      EXPECT_EQ(s.actor(a).back().motion, "walk");
    }
    // Companions respond only in steps 3 and 5, and do B's part from t_8.
    for (std::size_t a = 2; a < s.actorCount(); ++a) {
      for (const auto& e : s.actor(a)) {
        EXPECT_TRUE(e.step == G::GiveAttention || e.step == G::Acknowledge || e.step == G::Execute) << stepLabel(e);
        if (e.step == G::Execute) EXPECT_GE(e.start + kEps, s.executeTime);
      }
      if (s.plan == PlanKind::DivideAndWait) EXPECT_EQ(s.actor(a).back().start, s.actor(1).back().start);
    }
    // B's choices do not depend on the companions (own random stream, own relation).
    CoordinationInput alone = in;
    alone.companions.clear();
    auto r2 = planCoordination(alone, databases(), clips, p);
    ASSERT_TRUE(r2.ok());
    std::vector<std::string> withGroup, withoutGroup;
    for (const auto& e : s.actor(1)) withGroup.push_back(e.behaviour);
    for (const auto& e : r2.value().actor(1)) withoutGroup.push_back(e.behaviour);
    EXPECT_EQ(withGroup, withoutGroup);
    EXPECT_EQ(r2.value().outcome, s.outcome);
    // Deterministic: the same input gives the same script.
    auto r3 = planCoordination(in, databases(), clips, p);
    ASSERT_TRUE(r3.ok());
    EXPECT_EQ(formatScript(r3.value()), formatScript(s));

    outcomes.insert(s.outcome);
    sizes.insert(n);
    for (const bool b : in.lostResponses) lostSeen += b ? 1 : 0;
  }
  EXPECT_EQ(outcomes.size(), 2u);  // grounded and failed both occur
  EXPECT_EQ(sizes.size(), 6u);     // 0..5 companions
  EXPECT_GT(lostSeen, 0u);
}

}  // namespace
