// Tests of the social databases loader (libs/io/src/social_db_loader.cpp): the bundled
// data/social files load and hold the paper's behaviours and plans; each kind of bad input is one
// located diagnostic (line:column, JSON pointer, what, expected, a "did you mean" where useful).
#include <gtest/gtest.h>

#include "throng/io/social_db.hpp"

namespace {

using namespace throng;

const char* kMicro = R"({
  "version": 1,
  "behaviours": [
    {"name": "wave", "intents": ["request_attention"], "allowedIn": ["A2", "A5"], "clip": "wave",
     "target": "partner", "responses": ["turn_toward"]},
    {"name": "turn_toward", "intents": ["give_attention"], "allowedIn": ["A2", "A5"], "clip": "turn",
     "target": "partner"},
    {"name": "point_toward", "intents": ["propose"], "allowedIn": ["A2"], "clip": "point", "target": "goal"}
  ]
})";

common_ground::MicroBehaviourDb micro() {
  auto r = io::parseMicroBehaviours(kMicro, "micro.json");
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : core::formatAll(r.errors()));
  return r.ok() ? r.value() : common_ground::MicroBehaviourDb{};
}

TEST(SocialDb, BundledDatabasesLoad) {
  auto m = io::loadMicroBehaviours(THRONG_SOURCE_DIR "/data/social/micro_behaviours.json");
  ASSERT_TRUE(m.ok()) << core::formatAll(m.errors());
  for (const char* name : {"wave", "call_out", "turn_toward", "point_toward", "point_down", "nod"}) {
    EXPECT_TRUE(m.value().find(name).has_value()) << name;
  }
  const auto& wave = m.value().behaviours[*m.value().find("wave")];
  EXPECT_EQ(wave.clip, "wave");
  EXPECT_EQ(wave.allowedIn, (std::vector<common_ground::Relation>{common_ground::Relation::A2, common_ground::Relation::A5}));
  auto p = io::loadMacroPlans(THRONG_SOURCE_DIR "/data/social/macro_plans.json", m.value());
  ASSERT_TRUE(p.ok()) << core::formatAll(p.errors());
  ASSERT_EQ(p.value().plans.size(), 3u);
  EXPECT_EQ(p.value().failurePlan, common_ground::PlanKind::Resume);
  bool wait = false;
  for (const auto& plan : p.value().plans) {
    if (plan.kind != common_ground::PlanKind::DivideAndWait) continue;
    wait = true;
    EXPECT_EQ(plan.proposal, (std::vector<std::string>{"point_toward", "point_down"}));
    EXPECT_GT(plan.visitDuration, 0.0);
  }
  EXPECT_TRUE(wait);
}

TEST(SocialDb, UnknownIntentIsLocatedWithAHint) {
  const std::string text = "{\"version\": 1, \"behaviours\": [\n"
                           "  {\"name\": \"wave\", \"intents\": [\"request_atention\"], \"allowedIn\": [\"A2\"],\n"
                           "   \"clip\": \"wave\"}]}";
  auto r = io::parseMicroBehaviours(text, "m.json");
  ASSERT_FALSE(r.ok());
  ASSERT_EQ(r.errors().size(), 1u) << core::formatAll(r.errors());
  const auto& d = r.errors()[0];
  EXPECT_EQ(d.source, "m.json");
  EXPECT_EQ(d.pointer, "/behaviours/0/intents/0");
  EXPECT_EQ(d.line, 2);
  EXPECT_EQ(d.column, 32);
  EXPECT_NE(d.what.find("unknown intent"), std::string::npos);
  EXPECT_NE(d.expected.find("request_attention"), std::string::npos);
  EXPECT_NE(d.hint.find("did you mean \"request_attention\""), std::string::npos);
}

TEST(SocialDb, EveryProblemIsReported) {
  const std::string text = R"({"version": 1, "behaviours": [
    {"name": "a", "intents": [], "allowedIn": ["A7"], "clip": "walk", "weight": -1, "colour": 1,
     "responses": ["b"]},
    {"name": "a", "intents": ["confirm"], "allowedIn": ["A1"], "clip": "nod"}]})";
  auto r = io::parseMicroBehaviours(text, "m.json");
  ASSERT_FALSE(r.ok());
  std::vector<std::string> pointers;
  for (const auto& d : r.errors()) {
    pointers.push_back(d.pointer);
    EXPECT_GE(d.line, 1);
    EXPECT_FALSE(d.expected.empty()) << d.format();
  }
  for (const char* p : {"/behaviours/0/colour", "/behaviours/0/intents", "/behaviours/0/allowedIn/0",
                        "/behaviours/0/weight", "/behaviours/0/clip", "/behaviours/1/name",
                        "/behaviours/0/responses/0"}) {
    EXPECT_NE(std::find(pointers.begin(), pointers.end(), p), pointers.end()) << p << "\n" << core::formatAll(r.errors());
  }
}

TEST(SocialDb, PlanProposalsMustNameProposingBehaviours) {
  const std::string text = R"({"version": 1, "failurePlan": "resum", "plans": [
    {"name": "w", "kind": "divide_and_wait", "proposal": ["wave", "point_towrd"], "visitDuration": 30,
     "when": {"goalKinds": ["personal"], "maxGoalDistance": 0}}]})";
  auto r = io::parseMacroPlans(text, "p.json", micro());
  ASSERT_FALSE(r.ok());
  std::string all = core::formatAll(r.errors());
  EXPECT_NE(all.find("p.json:1:"), std::string::npos) << all;
  EXPECT_NE(all.find("/failurePlan: unknown plan kind \"resum\""), std::string::npos) << all;
  EXPECT_NE(all.find("/plans/0/proposal/0: micro-behaviour \"wave\" cannot propose"), std::string::npos) << all;
  EXPECT_NE(all.find("did you mean \"point_toward\""), std::string::npos) << all;
  EXPECT_NE(all.find("/plans/0/when/maxGoalDistance: value 0 m is out of range"), std::string::npos) << all;
}

TEST(SocialDb, SyntaxErrorsAndMissingFiles) {
  auto r = io::parseMicroBehaviours("{\"version\": 1,\n \"behaviours\": [,]}", "m.json");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.errors()[0].line, 2);
  EXPECT_NE(r.errors()[0].what.find("JSON syntax error"), std::string::npos);
  auto f = io::loadMicroBehaviours("/nonexistent/micro.json");
  ASSERT_FALSE(f.ok());
  EXPECT_EQ(f.errors()[0].source, "/nonexistent/micro.json");
  auto v = io::parseMicroBehaviours(R"({"version": 2, "behaviours": []})", "m.json");
  ASSERT_FALSE(v.ok());
  EXPECT_EQ(v.errors()[0].pointer, "/version");
}

}  // namespace
