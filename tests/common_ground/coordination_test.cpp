// Tests of the Common Ground coordination planner (libs/common_ground/src/coordination.cpp) on the
// bundled databases (data/social/*.json): the paper's worked example (Park, Peng, Quek, Cao,
// Tables 3 and 5, relation A3, divide-and-wait) with every time chained from the inputs as the
// paper writes it; properties over random relations, positions, clip lengths and lost responses
// (every coordination ends, within the bound, in success or the fallback); preconditions per relation.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <numbers>

#include "social_test_util.hpp"
#include "throng/common_ground/coordination.hpp"

namespace {

using namespace throng;
using namespace throng::common_ground;
using core::Vec2;

using test::bundled;
using test::clipLengths;
using test::databases;

double turnTime(double from, Vec2 a, Vec2 b, double rate) {
  double d = std::atan2(b.y - a.y, b.x - a.x) - from;
  while (d > std::numbers::pi) d -= 2 * std::numbers::pi;
  while (d < -std::numbers::pi) d += 2 * std::numbers::pi;
  return std::abs(d) / rate;
}

// The worked example: A is behind B (A3), wants to look at a bag in a store near the path.
TEST(Coordination, WorkedExampleA3DivideAndWaitChainsTimesAsTables3And5) {
  CoordinationInput in;
  const Vec2 xa{0, 0}, xb{10, 0}, xi{14, 3}, xs{5, 8}, xr{30, 0};
  in.initiator = {xa, 0.0f, 1.25f, 1};
  in.respondent = {xb, 0.0f, 1.25f, 2};  // B walks on, facing +x, away from A
  in.relation = Relation::A3;
  in.viewPoint = xi;
  in.goal = {xs, GoalKind::Personal, 60.0, std::nullopt};
  in.destination = xr;
  in.startTime = 5.0;
  in.initiatorStyle.mode = SelectionMode::Best;
  in.respondentStyle.mode = SelectionMode::Best;
  CoordinationParams params;
  params.turnRate = 2.0;
  const ClipLengths f = clipLengths();

  auto r = planCoordination(in, databases(), f, params);
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  const ActionScript& s = r.value();
  SCOPED_TRACE(formatScript(s));
  EXPECT_EQ(checkScript(s), "");
  EXPECT_EQ(s.outcome, Outcome::Grounded);
  EXPECT_EQ(s.plan, PlanKind::DivideAndWait);

  // Table 3, computed the way the paper writes it.
  const double v = 1.25, rate = 2.0, stay = bundled().macro.plans[1].visitDuration;
  const double t0 = 5.0;
  const double t1 = t0 + core::distance(xi, xa) / v;                    // f^A_walk.to.x_i
  const double t2 = t1 + f.at("wave");                                  // f^A_wave
  const double fTurnB = turnTime(0.0, xb, xi, rate);                    // B turns toward x_a (A is at x_i)
  const double t3 = t2 + fTurnB;                                        // f^B_turn
  const double t4 = t3 + f.at("point_toward");                                 // f^A_point
  const double headingB = std::atan2(xi.y - xb.y, xi.x - xb.x);
  const double fTurnB2 = turnTime(headingB, xb, xs, rate);              // f^B_turn'
  const double t5 = t4 + fTurnB2 + f.at("nod");                         // + f^B_nod
  const double t6 = t5 + f.at("point_down");                                 // f^A_point'
  const double t7 = t6 + f.at("nod");                                   // f^B_nod'
  // Table 5.
  const double t8 = t7 + f.at("nod");                                   // f^A_nod
  const double t9 = t8 + core::distance(xs, xi) / v;                    // f^A_walk_to_x_s
  const double t10 = t9 + stay;                                         // f^A_stay
  const double t11 = t10 + core::distance(xb, xs) / v;                  // f^A_walk_to_x_b

  struct Want {
    const char* motion;
    const char* behaviour;
    GroundingStep step;
    int part;
    double start;
  };
  using G = GroundingStep;
  const std::vector<Want> wantA = {
      {"walk", "move_into_view", G::Initiate, 0, t0},     {"wave", "wave", G::RequestAttention, 0, t1},
      {"point_toward", "point_toward", G::Propose, 1, t3}, {"point_down", "point_down", G::Propose, 2, t5},
      {"nod", "nod", G::Confirm, 0, t7},                  {"walk", "walk_to_goal", G::Execute, 0, t8},
      {"idle", "stay", G::Execute, 0, t9},                {"walk", "walk_to_partner", G::Execute, 0, t10},
      {"walk", "resume", G::Execute, 0, t11}};
  const std::vector<Want> wantB = {
      {"turn", "turn_toward", G::GiveAttention, 0, t2},   {"turn", "turn_toward_and_nod", G::Acknowledge, 1, t4},
      {"nod", "turn_toward_and_nod", G::Acknowledge, 1, t4 + fTurnB2},
      {"nod", "nod", G::Acknowledge, 2, t6},              {"idle", "wait", G::Execute, 0, t8},
      {"walk", "resume", G::Execute, 0, t11}};
  for (int a = 0; a < 2; ++a) {
    const auto& got = s.actors[static_cast<std::size_t>(a)];
    const auto& want = a == 0 ? wantA : wantB;
    ASSERT_EQ(got.size(), want.size()) << (a == 0 ? "A" : "B");
    for (std::size_t i = 0; i < want.size(); ++i) {
      SCOPED_TRACE(std::string(a == 0 ? "A" : "B") + " entry " + std::to_string(i));
      EXPECT_EQ(got[i].motion, want[i].motion);
      EXPECT_EQ(got[i].behaviour, want[i].behaviour);
      EXPECT_EQ(got[i].step, want[i].step);
      EXPECT_EQ(got[i].part, want[i].part);
      EXPECT_NEAR(got[i].start, want[i].start, 1e-5);
    }
  }
  // Targets: wave at x_b, point toward x_s, B turns toward x_a (= x_i) then toward x'_s = x_s.
  EXPECT_EQ(s.of(Actor::Initiator)[1].targetType, ScriptEntry::Target::Agent);
  EXPECT_EQ(s.of(Actor::Initiator)[1].targetPoint, xb);
  EXPECT_EQ(s.of(Actor::Initiator)[2].targetPoint, xs);
  EXPECT_EQ(s.of(Actor::Initiator)[3].targetPoint, xi);  // point down: here
  EXPECT_EQ(s.of(Actor::Respondent)[0].targetPoint, xi);
  EXPECT_EQ(s.of(Actor::Respondent)[1].targetPoint, xs);
  EXPECT_EQ(s.of(Actor::Respondent)[4].duration, t11 - t8);  // B waits until A is back
  EXPECT_NEAR(s.executeTime, t8, 1e-5);
  EXPECT_EQ(s.of(Actor::Initiator).back().targetPoint, xr);
}

TEST(Coordination, SelectionRulesPickPlansFromGoalAndSituation) {
  const MacroPlanDb& db = bundled().macro;
  auto kind = [&](GoalKind k, double dist, double visit) {
    const auto i = selectPlan(db, Goal{{}, k, visit, std::nullopt}, dist);
    return i ? db.plans[*i].kind : PlanKind::Resume;
  };
  EXPECT_EQ(kind(GoalKind::Personal, 10.0, 60.0), PlanKind::DivideAndWait);      // short visit near the path
  EXPECT_EQ(kind(GoalKind::Personal, 200.0, 60.0), PlanKind::DivideAndProceed);  // far
  EXPECT_EQ(kind(GoalKind::Personal, 10.0, 3600.0), PlanKind::DivideAndProceed); // long
  EXPECT_EQ(kind(GoalKind::Shared, 10.0, 60.0), PlanKind::DetourTogether);       // everyone wants it
}

TEST(Coordination, LostResponsesLeadToAnotherBehaviourThenMovingCloser) {
  CoordinationInput in;
  in.initiator = {{0, 0}, 0.0f, 1.3f, 7};
  in.respondent = {{-20, 0}, 0.0f, 1.3f, 8};
  in.relation = Relation::A5;  // B sees A only: wave is the one request, then A must come closer
  in.goal = {{5, 5}, GoalKind::Personal, 10.0, std::nullopt};
  in.destination = {-40, 0};
  in.lostResponses = {true};
  auto r = planCoordination(in, databases(), clipLengths());
  ASSERT_TRUE(r.ok());
  const auto& a = r.value().of(Actor::Initiator);
  SCOPED_TRACE(formatScript(r.value()));
  EXPECT_EQ(r.value().outcome, Outcome::Grounded);
  ASSERT_GE(a.size(), 5u);
  EXPECT_EQ(a[0].behaviour, "wave");
  EXPECT_EQ(a[1].behaviour, "await_response");
  EXPECT_EQ(a[2].behaviour, "move_closer");
  EXPECT_EQ(a[2].attempt, 1);
  EXPECT_EQ(a[3].behaviour, "call_out");  // turning toward B first, then the clip
  EXPECT_EQ(a[3].motion, "turn");
  EXPECT_EQ(a[4].motion, "call_out");
}

TEST(Coordination, AbsentRespondentFailsIntoTheFallbackPlan) {
  CoordinationInput in;
  in.initiator = {{0, 0}, 0.0f, 1.3f, 1};
  in.respondent = {{3, 0}, 3.14f, 1.3f, 2};
  in.relation = Relation::A2;
  in.goal = {{5, 5}, GoalKind::Personal, 10.0, std::nullopt};
  in.destination = {10, 0};
  in.respondentAbsent = true;
  CoordinationParams p;
  auto r = planCoordination(in, databases(), clipLengths(), p);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.value().outcome, Outcome::Failed);
  EXPECT_EQ(r.value().plan, bundled().macro.failurePlan);
  EXPECT_EQ(r.value().of(Actor::Respondent).back().behaviour, "resume");
  EXPECT_EQ(checkScript(r.value()), "");
}

TEST(Coordination, MissingClipLengthIsADiagnostic) {
  CoordinationInput in;
  in.relation = Relation::A2;
  in.respondent.position = {2, 0};
  auto r = planCoordination(in, databases(), ClipLengths{{"nod", 1.0}});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.errors()[0].what.find("no clip length"), std::string::npos);
}

// For each relation, the first request-attention behaviour is one its relation allows: the
// input relation, or the one the initiation move leads to (A3, A6).
TEST(Coordination, FirstRequestAttentionIsAllowedByTheRelation) {
  const MicroBehaviourDb& db = bundled().micro;
  for (const Relation rel : {Relation::A1, Relation::A2, Relation::A3, Relation::A4, Relation::A5, Relation::A6}) {
    for (std::uint64_t seed = 0; seed < 20; ++seed) {
      CoordinationInput in;
      in.initiator = {{0, 0}, 0.0f, 1.3f, 11};
      in.respondent = {{8, 0}, 0.0f, 1.3f, 12};
      in.relation = rel;
      in.viewPoint = Vec2{12, 2};
      in.hearingPoint = Vec2{6, 0};
      in.goal = {{5, 5}, GoalKind::Personal, 10.0, std::nullopt};
      in.seed = seed;
      in.initiatorStyle.mode = SelectionMode::Uniform;
      auto r = planCoordination(in, databases(), clipLengths());
      ASSERT_TRUE(r.ok());
      Relation now = rel;
      bool found = false;
      for (const auto& e : r.value().of(Actor::Initiator)) {
        if (e.step == GroundingStep::Initiate) {
          const auto b = db.find(e.behaviour);
          ASSERT_TRUE(b.has_value()) << e.behaviour;
          const auto& allowed = db.behaviours[*b].allowedIn;
          EXPECT_NE(std::find(allowed.begin(), allowed.end(), rel), allowed.end()) << e.behaviour;
          if (db.behaviours[*b].resultRelation) now = *db.behaviours[*b].resultRelation;
          continue;
        }
        if (e.step != GroundingStep::RequestAttention) continue;
        const auto b = db.find(e.behaviour);
        ASSERT_TRUE(b.has_value()) << e.behaviour;
        const auto& allowed = db.behaviours[*b].allowedIn;
        EXPECT_NE(std::find(allowed.begin(), allowed.end(), now), allowed.end())
            << e.behaviour << " in " << relationName(now) << " (from " << relationName(rel) << ")";
        found = true;
        break;
      }
      EXPECT_TRUE(found) << relationName(rel);
    }
  }
}

RC_GTEST_PROP(CoordinationProperty, EveryCoordinationEndsWithinTheBound, ()) {
  CoordinationInput in;
  auto pt = [] {
    return Vec2{static_cast<float>(*rc::gen::inRange(-400, 401)) / 10.0f,
                static_cast<float>(*rc::gen::inRange(-400, 401)) / 10.0f};
  };
  in.initiator = {pt(), static_cast<float>(*rc::gen::inRange(-314, 315)) / 100.0f,
                  static_cast<float>(*rc::gen::inRange(5, 30)) / 10.0f, 1};
  in.respondent = {pt(), static_cast<float>(*rc::gen::inRange(-314, 315)) / 100.0f,
                   static_cast<float>(*rc::gen::inRange(5, 30)) / 10.0f, 2};
  in.relation = static_cast<Relation>(*rc::gen::inRange(1, 7));
  if (*rc::gen::arbitrary<bool>()) in.viewPoint = pt();
  if (*rc::gen::arbitrary<bool>()) in.hearingPoint = pt();
  in.goal = {pt(), *rc::gen::element(GoalKind::Personal, GoalKind::Shared),
             static_cast<double>(*rc::gen::inRange(0, 600)), std::nullopt};
  in.destination = pt();
  in.startTime = *rc::gen::inRange(0, 1000) / 10.0;
  in.seed = *rc::gen::arbitrary<std::uint32_t>();
  in.initiatorStyle.mode = *rc::gen::element(SelectionMode::Uniform, SelectionMode::Weighted, SelectionMode::Best);
  in.respondentStyle.mode = *rc::gen::element(SelectionMode::Uniform, SelectionMode::Weighted, SelectionMode::Best);
  in.lostResponses = *rc::gen::container<std::vector<bool>>(rc::gen::arbitrary<bool>());
  in.respondentAbsent = *rc::gen::weightedElement<bool>({{1, true}, {4, false}});
  ClipLengths clips;
  for (const char* c : {"wave", "nod", "point_toward", "point_down", "call_out", "look_at", "talk"}) {
    clips[c] = *rc::gen::inRange(1, 60) / 10.0;
  }
  CoordinationParams p;
  p.turnRate = *rc::gen::inRange(5, 60) / 10.0;
  p.responseTimeout = *rc::gen::inRange(0, 50) / 10.0;
  p.maxAttempts = *rc::gen::inRange(1, 6);

  auto r = planCoordination(in, databases(), clips, p);
  RC_ASSERT(r.ok());
  const ActionScript& s = r.value();
  RC_ASSERT(checkScript(s).empty());
  const double bound = coordinationTimeBound(in, databases(), clips, p);
  RC_ASSERT(s.executeTime - s.startTime <= bound + 1e-6);
  RC_ASSERT(s.endTime - s.startTime <= bound + 1e-6);  // the bound covers the macro-plan too
  bool anyLost = in.respondentAbsent;
  for (const bool b : in.lostResponses) anyLost = anyLost || b;
  if (in.respondentAbsent) RC_ASSERT(s.outcome == Outcome::Failed);
  if (!anyLost) RC_ASSERT(s.outcome == Outcome::Grounded);
  if (s.outcome == Outcome::Failed) RC_ASSERT(s.plan == bundled().macro.failurePlan);
  // Both actors end executing the plan (or the fallback), so nobody waits forever.
  for (const auto& list : s.actors) {
    RC_ASSERT(!list.empty());
    RC_ASSERT(list.back().step == GroundingStep::Execute);
    RC_ASSERT(list.back().plan == s.plan);
    RC_ASSERT(list.back().motion == "walk");
  }
}

}  // namespace
