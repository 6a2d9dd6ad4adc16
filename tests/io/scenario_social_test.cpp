// The scenario's Common Ground keys (scenario_social_parser.cpp, scenario_social.cpp): what a valid
// "social" section becomes, and one located, explained diagnostic per mistake.
#include <gtest/gtest.h>

#include <string>

#include "scenario_test_util.hpp"

namespace throng::io {
namespace {

using test::contains;

const std::string kSource = std::string(THRONG_SOURCE_DIR) + "/scenarios/t.json";  // motions/ is scenarios/motions

std::string scenario(const std::string& social, const std::string& interests = R"(["shoes"])",
                     const std::string& category = "shoes", const std::string& preferences = "{}") {
  return R"({"format": "throng/1",
 "walkable": [[[0,0],[30,0],[30,8],[0,8]]],
 "points": [{"id": "shop", "kind": "interest", "position": [13, 4], "radius": 1.5, "category": ")" + category + R"("},
            {"id": "wc", "kind": "interest", "position": [25, 4], "radius": 1, "category": "restroom"}],
 "populations": [{"id": "g", "spawn": {"polygon": [[1,1],[5,1],[5,7],[1,7]]}, "interests": )" + interests + R"(, "preferences": )" + preferences + R"(}],
 "social": )" + social + "}";
}

core::Result<LoadedScenario> load(const std::string& text) {
  LoadOptions options;
  options.checkReachability = false;
  return parseScenario(text, kSource, options);
}

TEST(ScenarioSocial, ValidSectionFillsTheDescription) {
  const auto r = load(scenario(R"({"commonGround": false, "cooldown": 30,
     "senses": {"hearing": 8, "vision": 20, "fieldOfView": 90},
     "needs": [{"category": "restroom", "rate": 0.001, "expectedVisit": 90, "kind": "shared"}],
     "attraction": {"probability": 0.2, "expectedVisit": 45, "checkPeriod": 1},
     "coordination": {"turnRate": 2, "responseTimeout": 3, "maxAttempts": 4, "touchDistance": 0.8}})"));
  ASSERT_TRUE(r.ok()) << r.errors().front().format();
  const sim::CommonGroundDesc& s = r.value().desc.social;
  EXPECT_TRUE(s.enabled);
  EXPECT_FALSE(s.commonGround);
  EXPECT_FLOAT_EQ(s.cooldown, 30.0f);
  EXPECT_FLOAT_EQ(s.senses.hearingRange, 8.0f);
  EXPECT_FLOAT_EQ(s.senses.visionRange, 20.0f);
  EXPECT_NEAR(s.senses.fieldOfView, 3.14159265 / 2, 1e-5);
  ASSERT_EQ(s.needs.size(), 1u);
  EXPECT_EQ(s.needs[0].category, "restroom");
  EXPECT_EQ(s.needs[0].kind, common_ground::GoalKind::Shared);
  EXPECT_FLOAT_EQ(s.attraction.probability, 0.2f);
  EXPECT_EQ(s.coordination.maxAttempts, 4);
  // The built-in databases and the clip lengths from scenarios/motions.
  EXPECT_TRUE(s.micro.find("wave"));
  EXPECT_FALSE(s.macro.plans.empty());
  ASSERT_TRUE(s.clipLengths.count("wave"));
  EXPECT_GT(s.clipLengths.at("wave"), 0.0);
  EXPECT_EQ(r.value().desc.points[0].category, "shoes");
  EXPECT_EQ(r.value().desc.populations[0].interests, std::vector<std::string>{"shoes"});
  const auto withPreferences = load(scenario("{}", R"(["shoes"])", "shoes", R"({"wave": 2.5, "call_out": 0})"));
  ASSERT_TRUE(withPreferences.ok()) << withPreferences.errors().front().format();
  EXPECT_EQ(withPreferences.value().desc.populations[0].preferences.at("wave"), 2.5);
  EXPECT_EQ(withPreferences.value().desc.populations[0].preferences.at("call_out"), 0.0);
}

TEST(ScenarioSocial, MistakesAreLocatedAndExplained) {
  struct Case {
    std::string text;
    std::string pointer;
    std::string what;
  };
  const Case cases[] = {
      {scenario(R"({"need": []})"), "/social/need", "did you mean \"needs\""},
      {scenario(R"({"needs": [{"category": "restrom"}]})"), "/social/needs/0/category", "did you mean \"restroom\""},
      {scenario(R"({"senses": {"fieldOfView": 400}})"), "/social/senses/fieldOfView", "degrees"},
      {scenario(R"({"attraction": {"probability": 2}})"), "/social/attraction/probability", "out of range"},
      {scenario(R"({"coordination": {"maxAttempts": 0}})"), "/social/coordination/maxAttempts", "out of range"},
      {scenario(R"({"needs": [{"category": "restroom", "kind": "persnal"}]})"), "/social/needs/0/kind", "did you mean \"personal\""},
      {scenario("{}", R"(["shose"])"), "/populations/0/interests/0", "did you mean \"shoes\""},
      {scenario("{}", R"(["shoes", "shoes"])"), "/populations/0/interests/1", "duplicate interest"},
      {scenario("{}", R"(["shoes"])", "sho es"), "/points/0/category", "bad category"},
      {scenario(R"({"motions": "no-such-dir"})"), "/social/motions", "no such file"},
      {scenario(R"({"microBehaviours": "nothing.json"})"), "/social/microBehaviours", "no such file"},
      {scenario(R"({"macroPlans": "/etc/plans.json"})"), "/social/macroPlans", "absolute path"},
      {scenario(R"([1])"), "/social", "wrong type"},
      {scenario("{}", R"(["shoes"])", "shoes", R"({"wav": 2})"), "/populations/0/preferences/wav", "did you mean \"wave\""},
      {scenario("{}", R"(["shoes"])", "shoes", R"({"wave": -1})"), "/populations/0/preferences/wave", "out of range"},
  };
  for (const Case& c : cases) {
    const auto r = load(c.text);
    ASSERT_FALSE(r.ok()) << c.pointer;
    bool found = false;
    for (const core::Diagnostic& d : r.errors()) {
      if (d.pointer == c.pointer) {
        found = true;
        EXPECT_GT(d.line, 0) << d.format();
        EXPECT_TRUE(contains(d.format(), c.what)) << "want \"" << c.what << "\" in: " << d.format();
      }
    }
    EXPECT_TRUE(found) << c.pointer << ": " << r.errors().front().format();
  }
}

}  // namespace
}  // namespace throng::io
