// Tests for waypoint choices in scenarios (libs/io: scenario_crowd_parser.cpp readGoalChoice /
// readChoiceShares, and the validator's reachability of every option): a "goals" entry
// {"choose", "split", "shares"} loads into sim::PopulationDesc::goalChoices with the first option
// in its slot, and each class of bad value gives one located diagnostic (JSON pointer, what was
// expected).
#include <gtest/gtest.h>

#include <string>

#include "scenario_test_util.hpp"

using namespace throng;
using namespace throng::io::test;

namespace {

/// kBottleneck with two more interest points beyond the gap ("north", "south") and the population's
/// goals replaced by `goals`.
std::string withGoals(const std::string& goals) {
  std::string text = edit(kBottleneck, R"({"id": "exit", "kind": "exit", "polygon": [[19,4],[20,4],[20,6],[19,6]]})",
                          R"({"id": "exit", "kind": "exit", "polygon": [[19,4],[20,4],[20,6],[19,6]]},
    {"id": "north", "kind": "interest", "position": [15, 8], "radius": 1},
    {"id": "south", "kind": "action", "position": [15, 2], "radius": 1})");
  return edit(text, R"("goals": ["gap", "exit"])", "\"goals\": " + goals);
}

const std::string kGoals = "/populations/0/goals";

}  // namespace

TEST(ScenarioGoalChoice, ChoicesLoadWithTheFirstOptionInTheirSlot) {
  auto r = load(withGoals(R"(["gap", {"choose": ["south", "north"], "split": "shares", "shares": [3, 1]},
                                {"choose": ["north", "south"], "split": "leastTargeted"}, "exit"])"));
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  const sim::PopulationDesc& p = r.value().desc.populations[0];
  EXPECT_EQ(p.goals, (std::vector<std::uint32_t>{0, 3, 2, 1}));
  ASSERT_EQ(p.goalChoices.size(), 2u);
  EXPECT_EQ(p.goalChoices[0].slot, 1u);
  EXPECT_EQ(p.goalChoices[0].options, (std::vector<std::uint32_t>{3, 2}));
  EXPECT_EQ(p.goalChoices[0].split, sim::GoalSplit::Shares);
  EXPECT_EQ(p.goalChoices[0].shares, (std::vector<float>{3.0f, 1.0f}));
  EXPECT_EQ(p.goalChoices[1].slot, 2u);
  EXPECT_EQ(p.goalChoices[1].split, sim::GoalSplit::LeastTargeted);
  EXPECT_TRUE(p.goalChoices[1].shares.empty());
}

TEST(ScenarioGoalChoice, DefaultsToEqualShares) {
  auto r = load(withGoals(R"([{"choose": ["north", "south"]}, "exit"])"));
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  const sim::GoalChoiceDesc& c = r.value().desc.populations[0].goalChoices.at(0);
  EXPECT_EQ(c.split, sim::GoalSplit::Shares);
  EXPECT_TRUE(c.shares.empty());
  EXPECT_EQ(r.value().desc.populations[0].goalChoices.size(), 1u);
}

TEST(ScenarioGoalChoice, BadChoicesAreLocated) {
  const std::string exitOption = withGoals(R"([{"choose": ["north", "exit"]}])");
  const auto d = at(errorsOf(exitOption), kGoals + "/0/choose/1");
  EXPECT_EQ(d.what, "point \"exit\" is an exit");
  EXPECT_EQ(d.expected, "an array of at least 2 ids of interest or action points, each once");
  expectAt(d, exitOption, "\"exit\"]", 0);
  EXPECT_EQ(at(errorsOf(withGoals(R"([{"choose": ["north"]}, "exit"])")), kGoals + "/0/choose").what, "fewer than 2 options");
  EXPECT_EQ(at(errorsOf(withGoals(R"([{"choose": "north"}, "exit"])")), kGoals + "/0/choose").what, "wrong type: a string");
  EXPECT_EQ(at(errorsOf(withGoals(R"([{"split": "shares"}, "exit"])")), kGoals + "/0").what, "a goal choice without \"choose\"");
  EXPECT_EQ(at(errorsOf(withGoals(R"([{"choose": ["north", "north"]}, "exit"])")), kGoals + "/0/choose/1").what,
            "point \"north\" listed twice");
  EXPECT_EQ(at(errorsOf(withGoals(R"([{"choose": ["north", "sooth"]}, "exit"])")), kGoals + "/0/choose/1").hint,
            "did you mean \"south\"?");
  EXPECT_EQ(at(errorsOf(withGoals(R"([{"choose": ["north", "south"], "split": "leastTarget"}, "exit"])")), kGoals + "/0/split").hint,
            "did you mean \"leastTargeted\"?");
  EXPECT_EQ(at(errorsOf(withGoals(R"([{"choose": ["north", "south"], "split": "leastTargeted", "shares": [1, 1]}, "exit"])")),
               kGoals + "/0/shares").what,
            "\"shares\" only apply to the shares split");
  EXPECT_EQ(at(errorsOf(withGoals(R"([{"choose": ["north", "south"], "shares": [1]}, "exit"])")), kGoals + "/0/shares").what, "1 shares");
  EXPECT_EQ(at(errorsOf(withGoals(R"([{"choose": ["north", "south"], "shares": [0, 0]}, "exit"])")), kGoals + "/0/shares").what,
            "every share is 0");
  EXPECT_EQ(at(errorsOf(withGoals(R"([{"choose": ["north", "south"], "shares": [-1, 1]}, "exit"])")), kGoals + "/0/shares/0").what,
            "value -1 is out of range");
  EXPECT_EQ(at(errorsOf(withGoals(R"([{"choose": ["north", "south"], "weights": [1, 1]}, "exit"])")), kGoals + "/0/weights").what,
            "unknown key \"weights\" in goal choice");
}

TEST(ScenarioGoalChoice, AnUnreachableOptionIsNamed) {
  // "north" walled off from the spawn: the reachability check names it at its place in "choose".
  std::string text = withGoals(R"([{"choose": ["south", "north"]}, "exit"])");
  text = edit(text, R"("obstacles": [)", R"("obstacles": [ [[13,6.5],[17,6.5],[17,6.7],[13,6.7]], [[13,6.5],[13.2,6.5],[13.2,10],[13,10]], [[16.8,6.5],[17,6.5],[17,10],[16.8,10]],)");
  const auto d = at(errorsOf(text, true), kGoals + "/0/choose/1");
  EXPECT_EQ(d.what, "point \"north\" cannot be reached from the spawn area of population \"crowd\"");
}
