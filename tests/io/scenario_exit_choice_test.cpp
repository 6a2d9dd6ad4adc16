// Tests for exit choice in scenarios and a point's "aim" (libs/io: scenario_crowd_parser.cpp readExits /
// readExitChoice, a point's "width", the timeline's "close" / "open", and the validator's
// reachability of exits): good keys load into sim::PopulationDesc / PointDesc / TimelineEntry, and
// each class of bad value gives one located diagnostic (JSON pointer, what was expected).
#include <gtest/gtest.h>

#include <string>

#include "scenario_test_util.hpp"

using namespace throng;
using namespace throng::io::test;

namespace {

/// kBottleneck with a second exit ("east", north of the first), the population's goals only ["gap"],
/// and its extra `keys` (and a timeline).
std::string withExits(const std::string& keys, const std::string& timeline = "") {
  std::string text = edit(kBottleneck, R"({"id": "exit", "kind": "exit", "polygon": [[19,4],[20,4],[20,6],[19,6]]})",
                          R"({"id": "exit", "kind": "exit", "polygon": [[19,4],[20,4],[20,6],[19,6]]},
    {"id": "east", "kind": "exit", "polygon": [[19,8],[20,8],[20,9.5],[19,9.5]], "width": 1.5})");
  text = edit(text, R"("goals": ["gap", "exit"])", R"("goals": ["gap"])");
  text = edit(text, "\"radius\": 0.2}", "\"radius\": 0.2, " + keys + "}");
  if (!timeline.empty()) text = edit(text, "\"duration\": 300,", "\"duration\": 300, \"timeline\": " + timeline + ",");
  return text;
}

const std::string kPop = "/populations/0";

}  // namespace

TEST(ScenarioExitChoice, ExitsAndTheirChoiceLoad) {
  auto r = load(withExits(R"("exits": ["exit", "east"], "exitChoice": {"rule": "allocation", "shares": [3, 1]})",
                          R"([{"time": 20, "close": "east"}, {"time": 40, "open": "east"}])"));
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  const sim::ScenarioDesc& d = r.value().desc;
  const sim::PopulationDesc& p = d.populations[0];
  EXPECT_EQ(p.goals, (std::vector<std::uint32_t>{0}));
  EXPECT_EQ(p.exits, (std::vector<std::uint32_t>{1, 2}));
  EXPECT_EQ(p.exitChoice.rule, sim::ExitRule::Allocation);
  EXPECT_EQ(p.exitChoice.shares, (std::vector<float>{3.0f, 1.0f}));
  EXPECT_FLOAT_EQ(d.points[2].width, 1.5f);
  EXPECT_FLOAT_EQ(d.points[1].width, 1.0f);  // the default
  ASSERT_EQ(d.timeline.size(), 2u);
  EXPECT_EQ(d.timeline[0].action, sim::TimelineAction::CloseExit);
  EXPECT_EQ(d.timeline[0].point, 2u);
  EXPECT_EQ(d.timeline[1].action, sim::TimelineAction::OpenExit);
}

TEST(ScenarioExitChoice, DefaultsAreQuickestEveryTwoSecondsWithHysteresis) {
  auto r = load(withExits(R"("exits": ["exit", "east"])"));
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  const sim::ExitChoiceDesc& c = r.value().desc.populations[0].exitChoice;
  EXPECT_EQ(c.rule, sim::ExitRule::Quickest);
  EXPECT_FLOAT_EQ(c.period, 2.0f);
  EXPECT_FLOAT_EQ(c.hysteresis, 0.2f);
}

TEST(ScenarioExitChoice, ExitsMustBeExitPointsListedOnce) {
  const std::string notExit = withExits(R"("exits": ["exit", "gap"])");
  const auto d = at(errorsOf(notExit), kPop + "/exits/1");
  EXPECT_EQ(d.what, "point \"gap\" is not an exit");
  expectAt(d, notExit, "\"gap\"]", 1);  // the first is the goal
  EXPECT_EQ(at(errorsOf(withExits(R"("exits": ["exit", "exit"])")), kPop + "/exits/1").what, "exit \"exit\" listed twice");
  EXPECT_EQ(at(errorsOf(withExits(R"("exits": ["exit", "eats"])")), kPop + "/exits/1").hint, "did you mean \"east\"?");
  EXPECT_EQ(at(errorsOf(withExits(R"("exits": [])")), kPop + "/exits").what, "no exits");
  EXPECT_EQ(at(errorsOf(withExits(R"("exits": "exit")")), kPop + "/exits").what, "wrong type: a string");
}

TEST(ScenarioExitChoice, BadChoicesAreLocated) {
  EXPECT_EQ(at(errorsOf(withExits(R"("exitChoice": {"rule": "nearest"})")), kPop + "/exitChoice").what,
            "\"exitChoice\" without \"exits\"");
  const auto rule = at(errorsOf(withExits(R"("exits": ["exit", "east"], "exitChoice": {"rule": "quickst"})")), kPop + "/exitChoice/rule");
  EXPECT_EQ(rule.hint, "did you mean \"quickest\"?");
  EXPECT_EQ(at(errorsOf(withExits(R"("exits": ["exit", "east"], "exitChoice": {"period": 0})")), kPop + "/exitChoice/period").what,
            "value 0 s is out of range");
  EXPECT_EQ(at(errorsOf(withExits(R"("exits": ["exit", "east"], "exitChoice": {"hysteresis": 1.5})")), kPop + "/exitChoice/hysteresis").what,
            "value 1.5 is out of range");
  EXPECT_EQ(at(errorsOf(withExits(R"("exits": ["exit", "east"], "exitChoice": {"shares": [1, 1]})")), kPop + "/exitChoice/shares").what,
            "\"shares\" only apply to the allocation rule");
  EXPECT_EQ(at(errorsOf(withExits(R"("exits": ["exit", "east"], "exitChoice": {"rule": "allocation", "shares": [1]})")),
               kPop + "/exitChoice/shares").what,
            "1 shares");
  EXPECT_EQ(at(errorsOf(withExits(R"("exits": ["exit", "east"], "exitChoice": {"rule": "allocation", "shares": [0, 0]})")),
               kPop + "/exitChoice/shares").what,
            "every share is 0");
}

TEST(ScenarioExitChoice, FamiliarExitsAndHerdingLoadAndAreChecked) {
  auto r = load(withExits(R"("exits": ["exit", "east"], "exitChoice": {"rule": "nearest", "familiar": ["east"], "familiarity": 2})"));
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  const sim::ExitChoiceDesc& c = r.value().desc.populations[0].exitChoice;
  EXPECT_EQ(c.familiar, (std::vector<std::uint32_t>{2}));
  EXPECT_FLOAT_EQ(c.familiarity, 2.0f);
  auto plain = load(withExits(R"("exits": ["exit", "east"])"));
  ASSERT_TRUE(plain.ok());
  EXPECT_TRUE(plain.value().desc.populations[0].exitChoice.familiar.empty());
  EXPECT_FLOAT_EQ(plain.value().desc.populations[0].exitChoice.familiarity, 2.0f);

  const std::string gap = withExits(R"("exits": ["exit", "east"], "exitChoice": {"familiar": ["gap"]})");
  const auto d = at(errorsOf(gap), kPop + "/exitChoice/familiar/0");
  EXPECT_EQ(d.what, "point \"gap\" is not one of the population's exits");
  EXPECT_EQ(d.hint, "add it to \"exits\"");
  EXPECT_EQ(at(errorsOf(withExits(R"("exits": ["exit", "east"], "exitChoice": {"familiar": ["east", "east"]})")),
               kPop + "/exitChoice/familiar/1").what,
            "exit \"east\" listed twice");
  EXPECT_EQ(at(errorsOf(withExits(R"("exits": ["exit", "east"], "exitChoice": {"familiar": "east"})")), kPop + "/exitChoice/familiar").what,
            "wrong type: a string");
  EXPECT_EQ(at(errorsOf(withExits(R"("exits": ["exit", "east"], "exitChoice": {"familiarity": 0.5})")),
               kPop + "/exitChoice/familiarity").what,
            "value 0.5 is out of range");
  EXPECT_EQ(at(errorsOf(withExits(R"("exits": ["exit", "east"], "exitChoice": {"rule": "allocation", "familiar": ["east"]})")),
               kPop + "/exitChoice/familiar").what,
            "\"familiar\" only applies to the nearest and quickest rules");
  auto herd = load(withExits(R"("exits": ["exit", "east"], "exitChoice": {"herding": 0.5, "herdingRadius": 8})"));
  ASSERT_TRUE(herd.ok()) << core::formatAll(herd.errors());
  EXPECT_FLOAT_EQ(herd.value().desc.populations[0].exitChoice.herding, 0.5f);
  EXPECT_FLOAT_EQ(herd.value().desc.populations[0].exitChoice.herdingRadius, 8.0f);
  EXPECT_FLOAT_EQ(plain.value().desc.populations[0].exitChoice.herding, 0.0f);
  EXPECT_EQ(at(errorsOf(withExits(R"("exits": ["exit", "east"], "exitChoice": {"herding": 1.5})")), kPop + "/exitChoice/herding").what,
            "value 1.5 is out of range");
  EXPECT_EQ(at(errorsOf(withExits(R"("exits": ["exit", "east"], "exitChoice": {"herdingRadius": 0})")),
               kPop + "/exitChoice/herdingRadius").what,
            "value 0 m is out of range");
  EXPECT_EQ(at(errorsOf(withExits(R"("exits": ["exit", "east"], "exitChoice": {"rule": "allocation", "herding": 0.5})")),
               kPop + "/exitChoice/herding").what,
            "\"herding\" only applies to the nearest and quickest rules");
  // A wrong "exits" is said once, not again for each familiar exit.
  const auto errors = errorsOf(withExits(R"("exits": ["exit", "gap"], "exitChoice": {"familiar": ["exit"]})"));
  for (const auto& e : errors) EXPECT_NE(e.pointer, kPop + "/exitChoice/familiar/0") << e.what;
}

TEST(ScenarioExitChoice, WidthOnlyOnExitsAndTimelineClosesOnlyExits) {
  const std::string width = edit(kBottleneck, R"("radius": 0.5})", R"("radius": 0.5, "width": 2})");
  EXPECT_EQ(at(errorsOf(width), "/points/0/width").what, "\"width\" only applies to exit points");
  const std::string close = withExits(R"("exits": ["exit", "east"])", R"([{"time": 5, "close": "gap"}])");
  const auto d = at(errorsOf(close), "/timeline/0/close");
  EXPECT_EQ(d.what, "point \"gap\" is not an exit");
  EXPECT_EQ(at(errorsOf(withExits(R"("exits": ["exit", "east"])", R"([{"time": 5, "close": "east", "open": "east"}])")), "/timeline/0").what,
            "entry has both \"close\" and \"open\"");
}

TEST(ScenarioExitChoice, AnUnreachableExitIsNamed) {
  // An exit walled off from the spawn: the reachability check names it at its place in "exits".
  std::string text = withExits(R"("exits": ["exit", "east"])");
  text = edit(text, R"("obstacles": [)", R"("obstacles": [ [[18,7.5],[20,7.5],[20,7.7],[18,7.7]], [[18,7.5],[18.2,7.5],[18.2,10],[18,10]],)");
  const auto d = at(errorsOf(text, true), kPop + "/exits/1");
  EXPECT_EQ(d.what, "point \"east\" cannot be reached from the spawn area of population \"crowd\"");
}

TEST(ScenarioExitChoice, APointsAimLoadsOnInterestAndExitPointsOnly) {
  // "aim": "lane" on an interest and an exit point loads; the default is spread.
  auto r = load(edit(edit(kBottleneck, R"("radius": 0.5})", R"("radius": 0.5, "aim": "lane"})"),
                     R"([[19,4],[20,4],[20,6],[19,6]]})", R"([[19,4],[20,4],[20,6],[19,6]], "aim": "spread"})"));
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  EXPECT_EQ(r.value().desc.points[0].aim, sim::PointAim::Lane);
  EXPECT_EQ(r.value().desc.points[1].aim, sim::PointAim::Spread);
  EXPECT_EQ(load(kBottleneck).value().desc.points[0].aim, sim::PointAim::Spread);
  // A misspelt aim is named with the expected values and a suggestion; an action point has none.
  const auto d = at(errorsOf(edit(kBottleneck, R"("radius": 0.5})", R"("radius": 0.5, "aim": "lanes"})")), "/points/0/aim");
  EXPECT_EQ(d.what, "unknown aim \"lanes\"");
  EXPECT_NE(d.expected.find("\"spread\""), std::string::npos) << d.expected;
  EXPECT_NE(d.hint.find("did you mean \"lane\"?"), std::string::npos) << d.hint;
  const std::string action = edit(kBottleneck, R"("kind": "interest", "position": [9.5, 5], "radius": 0.5})",
                                  R"("kind": "action", "position": [9.5, 5], "radius": 0.5, "aim": "lane"})");
  EXPECT_EQ(at(errorsOf(action), "/points/0/aim").what, "\"aim\" only applies to interest and exit points");
  EXPECT_FALSE(at(errorsOf(edit(kBottleneck, R"("radius": 0.5})", R"("radius": 0.5, "aim": 3})")), "/points/0/aim").what.empty());
}
