// Tests for the crowd-model keys of libs/io/src/scenario_parser.cpp and the guide-waypoint check
// of scenario_validator.cpp (Musse et al.: automatic goals, Bézier paths, flocking, following,
// guided crowds, the sociological model, density-dependent range and multiresolution): a scenario
// using every key loads into ScenarioDesc; each class of error gives one located diagnostic.
#include <gtest/gtest.h>

#include "scenario_test_util.hpp"

using namespace throng;
using namespace throng::io::test;

namespace {

/// The bottleneck with an action point and two populations using every crowd-model key (one
/// key per line where the tests locate diagnostics).
const char* kCrowd = R"({
  "format": "throng/1",
  "walkable":  [ [[0,0],[20,0],[20,10],[0,10]] ],
  "obstacles": [ [[9,0],[10,0],[10,4.5],[9,4.5]], [[9,5.5],[10,5.5],[10,10],[9,10]] ],
  "points": [
    {"id": "gap",    "kind": "interest", "position": [9.5, 5], "radius": 0.5},
    {"id": "exit",   "kind": "exit", "polygon": [[19,4],[20,4],[20,6],[19,6]]},
    {"id": "statue", "kind": "action", "position": [15, 8], "radius": 0.5}
  ],
  "populations": [
    {"id": "leaders", "groups": 2, "size": [2, 3], "spawn": {"polygon": [[1,1],[8,1],[8,4],[1,4]]},
     "goals": "auto",
     "autoNearDistance": 2.5,
     "paths": "bezier",
     "flocking": false,
     "waitTimeout": 12,
     "groupSpacing": 0.9,
     "guide": {"script": [{"time": 5, "position": [2, 5]},
                          {"time": 20, "position": [9.5, 5]},
                          {"time": 40, "position": [15, 5]}],
               "distance": 2,
               "release": 60},
     "sociological": {"enabled": true, "meetDistance": 1.5, "changeGroupRate": 0.05, "followAgentRate": 0.03,
                      "followDuration": 20, "leaderChangeRate": 0.02, "sociability": 1.5,
                      "domination": 0.8}},
    {"id": "followers", "groups": 3, "size": 2, "spawn": {"polygon": [[1,6],[8,6],[8,9],[1,9]]},
     "goals": ["gap", "exit"],
     "follow": {"population": "leaders",
                "group": 1,
                "mode": "temporary",
                "on": [5, 15],
                "off": [8, 12]},
     "sociological": {"domination": 0.2}},
    {"id": "plain", "spawn": {"position": [3, 7]}}
  ],
  "steering": {"neighbourDistance": 4,
               "denseNeighbourDistance": 2,
               "denseThreshold": 3,
               "lodDistance": 50}
}
)";

/// The followers' "follow" object as written in kCrowd.
const char* kFollow = R"({"population": "leaders",
                "group": 1,
                "mode": "temporary",
                "on": [5, 15],
                "off": [8, 12]})";

/// The only diagnostic of `text`, which must fail with exactly one, at `pointer`.
core::Diagnostic only(const std::string& text, const std::string& pointer, bool reachability = false) {
  const auto ds = errorsOf(text, reachability);
  EXPECT_EQ(ds.size(), 1u) << core::formatAll(ds);
  return at(ds, pointer);
}

}  // namespace

TEST(ScenarioCrowdKeys, EveryKeyLoadsIntoTheDescription) {
  auto r = load(kCrowd, true);  // reachability included: the bundled-scenario path
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  const sim::ScenarioDesc& d = r->desc;
  ASSERT_EQ(d.populations.size(), 3u);

  const sim::PopulationDesc& leaders = d.populations[0];
  EXPECT_TRUE(leaders.autoGoals);
  EXPECT_TRUE(leaders.goals.empty());
  EXPECT_FLOAT_EQ(leaders.autoNearDistance, 2.5f);
  EXPECT_TRUE(leaders.bezierPaths);
  EXPECT_FALSE(leaders.flocking);
  EXPECT_FLOAT_EQ(leaders.waitTimeout, 12.0f);
  EXPECT_FLOAT_EQ(leaders.groupSpacing, 0.9f);
  EXPECT_EQ(leaders.follow.mode, sim::FollowMode::None);
  ASSERT_EQ(leaders.guide.script.size(), 3u);
  EXPECT_FLOAT_EQ(leaders.guide.script[1].time, 20.0f);
  EXPECT_FLOAT_EQ(leaders.guide.script[1].position.x, 9.5f);
  EXPECT_FLOAT_EQ(leaders.guide.script[2].position.y, 5.0f);
  EXPECT_FLOAT_EQ(leaders.guide.distance, 2.0f);
  EXPECT_FLOAT_EQ(leaders.guide.release, 60.0f);
  const sim::SociologicalDesc& s = leaders.sociological;
  EXPECT_TRUE(s.enabled);
  EXPECT_FLOAT_EQ(s.meetDistance, 1.5f);
  EXPECT_FLOAT_EQ(s.changeGroupRate, 0.05f);
  EXPECT_FLOAT_EQ(s.followAgentRate, 0.03f);
  EXPECT_FLOAT_EQ(s.followDuration, 20.0f);
  EXPECT_FLOAT_EQ(s.leaderChangeRate, 0.02f);
  EXPECT_FLOAT_EQ(s.sociability, 1.5f);
  EXPECT_FLOAT_EQ(s.domination, 0.8f);

  const sim::PopulationDesc& followers = d.populations[1];
  EXPECT_FALSE(followers.autoGoals);
  EXPECT_EQ(followers.goals, (std::vector<std::uint32_t>{0, 1}));
  EXPECT_FALSE(followers.bezierPaths);
  EXPECT_EQ(followers.follow.mode, sim::FollowMode::Temporary);
  EXPECT_EQ(followers.follow.population, 0u);
  EXPECT_EQ(followers.follow.group, 1u);
  EXPECT_FLOAT_EQ(followers.follow.onMin, 5.0f);
  EXPECT_FLOAT_EQ(followers.follow.onMax, 15.0f);
  EXPECT_FLOAT_EQ(followers.follow.offMin, 8.0f);
  EXPECT_FLOAT_EQ(followers.follow.offMax, 12.0f);
  // A present "sociological" object turns the model on; unset rates keep their defaults.
  EXPECT_TRUE(followers.sociological.enabled);
  EXPECT_FLOAT_EQ(followers.sociological.domination, 0.2f);
  EXPECT_FLOAT_EQ(followers.sociological.meetDistance, sim::SociologicalDesc{}.meetDistance);
  EXPECT_TRUE(followers.guide.script.empty());

  EXPECT_FLOAT_EQ(d.steering.neighbourDistance, 4.0f);
  EXPECT_FLOAT_EQ(d.steering.denseNeighbourDistance, 2.0f);
  EXPECT_FLOAT_EQ(d.steering.denseThreshold, 3.0f);
  EXPECT_FLOAT_EQ(d.steering.lodDistance, 50.0f);
}

TEST(ScenarioCrowdKeys, OmittedKeysKeepTheSimulationDefaults) {
  auto r = load(kCrowd);
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  const sim::PopulationDesc& plain = r->desc.populations[2];
  const sim::PopulationDesc defaults;
  EXPECT_FALSE(plain.autoGoals);
  EXPECT_FALSE(plain.bezierPaths);
  EXPECT_TRUE(plain.flocking);
  EXPECT_FLOAT_EQ(plain.waitTimeout, defaults.waitTimeout);
  EXPECT_FLOAT_EQ(plain.groupSpacing, defaults.groupSpacing);
  EXPECT_FLOAT_EQ(plain.autoNearDistance, defaults.autoNearDistance);
  EXPECT_EQ(plain.follow.mode, sim::FollowMode::None);
  EXPECT_TRUE(plain.guide.script.empty());
  EXPECT_LT(plain.guide.release, 0.0f);
  EXPECT_FALSE(plain.sociological.enabled);

  // A permanent follow takes group 0 by default; "enabled": false keeps the model off.
  std::string text = edit(kCrowd, kFollow, R"({"population": "leaders"})");
  text = edit(text, R"({"domination": 0.2})", R"({"enabled": false})");
  auto p = load(text);
  ASSERT_TRUE(p.ok()) << core::formatAll(p.errors());
  EXPECT_EQ(p->desc.populations[1].follow.mode, sim::FollowMode::Permanent);
  EXPECT_EQ(p->desc.populations[1].follow.group, 0u);
  EXPECT_FALSE(p->desc.populations[1].sociological.enabled);
  const sim::SteeringDesc steering = load(kBottleneck)->desc.steering;
  EXPECT_FLOAT_EQ(steering.denseNeighbourDistance, sim::SteeringDesc{}.denseNeighbourDistance);
  EXPECT_FLOAT_EQ(steering.lodDistance, 0.0f);
}

TEST(ScenarioCrowdKeys, WrongTypes) {
  const std::string flocking = edit(kCrowd, "\"flocking\": false", "\"flocking\": \"no\"");
  const auto f = only(flocking, "/populations/0/flocking");
  expectAt(f, flocking, "\"no\"");
  EXPECT_EQ(f.what, "wrong type: a string");
  EXPECT_EQ(f.expected, "true or false");

  const auto w = only(edit(kCrowd, "\"waitTimeout\": 12", "\"waitTimeout\": [12]"), "/populations/0/waitTimeout");
  EXPECT_EQ(w.what, "wrong type: an array");
  EXPECT_EQ(w.expected, "a number > 0 and <= 1e+06 s");

  const auto p = only(edit(kCrowd, "\"paths\": \"bezier\"", "\"paths\": true"), "/populations/0/paths");
  EXPECT_EQ(p.what, "wrong type: a boolean");
  EXPECT_EQ(p.expected, "\"navmesh\" or \"bezier\"");

  const auto fo = only(edit(kCrowd, kFollow, "\"leaders\""), "/populations/1/follow");
  EXPECT_EQ(fo.what, "wrong type: a string");
  EXPECT_TRUE(contains(fo.expected, "a follow object")) << fo.format();

  const auto g = only(edit(kCrowd, "\"group\": 1", "\"group\": 1.5"), "/populations/1/follow/group");
  EXPECT_EQ(g.what, "value 1.5 is not a whole number");

  const auto s = only(edit(kCrowd, "\"enabled\": true", "\"enabled\": 1"), "/populations/0/sociological/enabled");
  EXPECT_EQ(s.what, "wrong type: an integer");

  const auto script = only(edit(kCrowd, "{\"time\": 20, \"position\": [9.5, 5]}", "[20, 9.5, 5]"),
                           "/populations/0/guide/script/1");
  EXPECT_TRUE(contains(script.expected, "a waypoint {\"time\"")) << script.format();

  const auto lod = only(edit(kCrowd, "\"lodDistance\": 50", "\"lodDistance\": \"far\""), "/steering/lodDistance");
  EXPECT_EQ(lod.expected, "a number from 0 to 1e+06 m");
}

TEST(ScenarioCrowdKeys, ValuesOutOfRangeNameUnits) {
  const std::string spacing = edit(kCrowd, "\"groupSpacing\": 0.9", "\"groupSpacing\": 5");
  const auto sp = only(spacing, "/populations/0/groupSpacing");
  expectAt(sp, spacing, "5,\n     \"guide\"");
  EXPECT_EQ(sp.format(), "t.json:17:22 /populations/0/groupSpacing: value 5 m is out of range; expected a number from "
                         "0.3 to 3 m");

  EXPECT_EQ(only(edit(kCrowd, "\"waitTimeout\": 12", "\"waitTimeout\": 0"), "/populations/0/waitTimeout").what,
            "value 0 s is out of range");
  EXPECT_EQ(only(edit(kCrowd, "\"autoNearDistance\": 2.5", "\"autoNearDistance\": -1"), "/populations/0/autoNearDistance")
                .expected,
            "a number > 0 and <= 1000 m");
  const auto rate = only(edit(kCrowd, "\"changeGroupRate\": 0.05", "\"changeGroupRate\": -0.1"),
                         "/populations/0/sociological/changeGroupRate");
  EXPECT_EQ(rate.what, "value -0.1 1/s is out of range");
  EXPECT_EQ(rate.expected, "a number from 0 to 100 1/s");
  EXPECT_EQ(only(edit(kCrowd, "\"domination\": 0.8", "\"domination\": 1.5"), "/populations/0/sociological/domination")
                .expected,
            "a number from 0 to 1");
  EXPECT_EQ(only(edit(kCrowd, "\"followDuration\": 20", "\"followDuration\": 0"), "/populations/0/sociological/followDuration")
                .expected,
            "a number > 0 and <= 1e+06 s");
  EXPECT_EQ(only(edit(kCrowd, "\"distance\": 2", "\"distance\": -2"), "/populations/0/guide/distance").expected,
            "a number from 0 to 100 m");
  EXPECT_EQ(only(edit(kCrowd, "{\"time\": 5,", "{\"time\": -5,"), "/populations/0/guide/script/0/time").what,
            "value -5 s is out of range");
  EXPECT_EQ(only(edit(kCrowd, "\"group\": 1", "\"group\": -1"), "/populations/1/follow/group").what,
            "value -1 is out of range");

  // Following periods: 0 < min <= max seconds.
  EXPECT_EQ(only(edit(kCrowd, "\"on\": [5, 15]", "\"on\": [0, 15]"), "/populations/1/follow/on/0").what,
            "value 0 s is out of range");
  const auto empty = only(edit(kCrowd, "\"off\": [8, 12]", "\"off\": [12, 8]"), "/populations/1/follow/off");
  EXPECT_EQ(empty.what, "interval [12, 8] s is empty");
  EXPECT_EQ(empty.expected, "[min, max] with min <= max, each a number > 0 and <= 1e+06 s");
  EXPECT_EQ(only(edit(kCrowd, "\"off\": [8, 12]", "\"off\": [8]"), "/populations/1/follow/off").what,
            "interval has 1 entries");
  // "on"/"off" belong to temporary following only.
  const std::string permanent = edit(kCrowd, "\"mode\": \"temporary\"", "\"mode\": \"permanent\"");
  const auto ds = errorsOf(permanent);
  EXPECT_EQ(ds.size(), 2u) << core::formatAll(ds);
  EXPECT_EQ(at(ds, "/populations/1/follow/on").what, "\"on\" only applies to temporary following");
  expectAt(at(ds, "/populations/1/follow/off"), permanent, "\"off\"");
  EXPECT_EQ(at(errorsOf(edit(kCrowd, "\"temporary\"", "\"temporray\"")), "/populations/1/follow/mode").hint,
            "did you mean \"temporary\"?");

  // Steering: densities in agents/m², the dense range within the normal one.
  EXPECT_EQ(only(edit(kCrowd, "\"denseThreshold\": 3", "\"denseThreshold\": 0"), "/steering/denseThreshold").expected,
            "a number > 0 and <= 100 agents/m²");
  const auto dense = only(edit(kCrowd, "\"denseNeighbourDistance\": 2", "\"denseNeighbourDistance\": 5"),
                          "/steering/denseNeighbourDistance");
  EXPECT_EQ(dense.what, "dense neighbour distance 5 m exceeds neighbourDistance 4 m");
  EXPECT_EQ(dense.expected, "a number from 0 (off) to neighbourDistance (4 m)");
  EXPECT_EQ(only(edit(kCrowd, "\"lodDistance\": 50", "\"lodDistance\": -1"), "/steering/lodDistance").what,
            "value -1 m is out of range");
}

TEST(ScenarioCrowdKeys, UnknownFollowPopulationWithDidYouMean) {
  const std::string text = edit(kCrowd, "\"population\": \"leaders\"", "\"population\": \"leaderz\"");
  const auto d = only(text, "/populations/1/follow/population");
  expectAt(d, text, "\"leaderz\"");
  EXPECT_EQ(d.what, "unknown population \"leaderz\"");
  EXPECT_EQ(d.expected, "an id from /populations");
  EXPECT_EQ(d.hint, "did you mean \"leaders\"?");
  // Populations are resolved after all are read: following a later one is fine.
  std::string later = edit(kCrowd, "\"population\": \"leaders\"", "\"population\": \"plain\"");
  later = edit(later, "\"group\": 1", "\"group\": 0");
  auto r = load(later);
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  EXPECT_EQ(r->desc.populations[1].follow.population, 2u);
  // A missing population is a missing required key.
  const auto missing = only(edit(kCrowd, "\"population\": \"leaders\",", ""), "/populations/1/follow");
  EXPECT_EQ(missing.what, "missing required key \"population\"");
}

TEST(ScenarioCrowdKeys, PopulationCannotFollowItself) {
  const std::string text = edit(kCrowd, "\"population\": \"leaders\"", "\"population\": \"followers\"");
  const auto d = only(text, "/populations/1/follow/population");
  expectAt(d, text, "\"followers\"", 1);
  EXPECT_EQ(d.what, "a population cannot follow itself");
  EXPECT_EQ(d.expected, "the id of another population in /populations");
}

TEST(ScenarioCrowdKeys, FollowGroupIndexOutOfRange) {
  const std::string text = edit(kCrowd, "\"group\": 1", "\"group\": 2");
  const auto d = only(text, "/populations/1/follow/group");
  expectAt(d, text, "2,\n                \"mode\"");
  EXPECT_EQ(d.what, "group 2 is out of range: population \"leaders\" has 2 groups");
  EXPECT_EQ(d.expected, "a group index from 0 to 1 (0-based)");
}

TEST(ScenarioCrowdKeys, GuideWaypointOutsideTheWalkableArea) {
  const std::string outside = edit(kCrowd, "\"position\": [9.5, 5]}", "\"position\": [25, 5]}");
  const auto o = only(outside, "/populations/0/guide/script/1/position");
  expectAt(o, outside, "[25, 5]");
  EXPECT_EQ(o.what, "guide waypoint (25, 5) is outside the walkable area");
  EXPECT_EQ(o.expected, "a waypoint inside /walkable and clear of /obstacles");

  const auto wall = only(edit(kCrowd, "\"position\": [9.5, 5]}", "\"position\": [9.5, 2]}"),
                         "/populations/0/guide/script/1/position");
  EXPECT_EQ(wall.what, "guide waypoint (9.5, 2) is inside obstacle /obstacles/0");

  const auto empty = only(edit(kCrowd, R"([{"time": 5, "position": [2, 5]},
                          {"time": 20, "position": [9.5, 5]},
                          {"time": 40, "position": [15, 5]}])", "[]"), "/populations/0/guide/script");
  EXPECT_EQ(empty.what, "empty guide script");
}

TEST(ScenarioCrowdKeys, GuideTimesStrictlyAscending) {
  const std::string text = edit(kCrowd, "{\"time\": 40,", "{\"time\": 20,");
  const auto d = only(text, "/populations/0/guide/script/2/time");
  expectAt(d, text, "20, \"position\": [15");
  EXPECT_EQ(d.what, "waypoint time 20 s is not after the previous waypoint's 20 s");
  EXPECT_EQ(d.expected, "times strictly ascending along the script");
}

TEST(ScenarioCrowdKeys, ReleaseBeforeTheFirstWaypoint) {
  const std::string text = edit(kCrowd, "\"release\": 60", "\"release\": 3");
  const auto d = only(text, "/populations/0/guide/release");
  expectAt(d, text, "3}");
  EXPECT_EQ(d.what, "release at 3 s is before the first waypoint at 5 s");
  EXPECT_EQ(d.expected, "a time >= 5 s (the first waypoint's time)");
  // A release at the first waypoint's time is allowed; one without a script is not.
  EXPECT_TRUE(load(edit(kCrowd, "\"release\": 60", "\"release\": 5")).ok());
  const auto noScript = only(edit(kCrowd, "\"sociological\": {\"domination\": 0.2}",
                                  "\"sociological\": {\"domination\": 0.2}, \"guide\": {\"release\": 4}"),
                             "/populations/1/guide/release");
  EXPECT_EQ(noScript.what, "\"release\" without a \"script\"");
}

TEST(ScenarioCrowdKeys, AutoGoalsNeedAnActionPoint) {
  const std::string text = edit(kCrowd, "\"kind\": \"action\"", "\"kind\": \"interest\"");
  const auto d = only(text, "/populations/0/goals");
  expectAt(d, text, "\"auto\"");
  EXPECT_EQ(d.what, "\"goals\": \"auto\" needs at least one point of kind \"action\"");
  EXPECT_TRUE(contains(d.expected, "an action point in /points")) << d.format();
}

TEST(ScenarioCrowdKeys, GoalsStringOtherThanAuto) {
  const std::string text = edit(kCrowd, "\"goals\": \"auto\"", "\"goals\": \"autox\"");
  const auto d = only(text, "/populations/0/goals");
  expectAt(d, text, "\"autox\"");
  EXPECT_EQ(d.what, "unknown goals mode \"autox\"");
  EXPECT_EQ(d.expected, "an array of point ids from /points, or \"auto\"");
  EXPECT_EQ(d.hint, "did you mean \"auto\"?");
  // A single point id written as a string gets the array form as hint.
  EXPECT_EQ(only(edit(kCrowd, "\"goals\": \"auto\"", "\"goals\": \"exit\""), "/populations/0/goals").hint,
            "for one goal write [\"exit\"]");
  EXPECT_EQ(only(edit(kCrowd, "\"goals\": \"auto\"", "\"goals\": 3"), "/populations/0/goals").expected,
            "an array of point ids from /points, or \"auto\"");
}

TEST(ScenarioCrowdKeys, UnknownKeysWithDidYouMean) {
  const std::string text = edit(kCrowd, "\"meetDistance\"", "\"meetDistanse\"");
  const auto d = only(text, "/populations/0/sociological/meetDistanse");
  expectAt(d, text, "\"meetDistanse\"");
  EXPECT_EQ(d.what, "unknown key \"meetDistanse\" in sociological");
  EXPECT_TRUE(contains(d.expected, "one of: enabled, meetDistance, changeGroupRate")) << d.format();
  EXPECT_EQ(d.hint, "did you mean \"meetDistance\"?");

  EXPECT_EQ(only(edit(kCrowd, "\"flocking\"", "\"flockng\""), "/populations/0/flockng").hint, "did you mean \"flocking\"?");
  EXPECT_EQ(only(edit(kCrowd, "\"group\":", "\"grup\":"), "/populations/1/follow/grup").hint, "did you mean \"group\"?");
  EXPECT_EQ(only(edit(kCrowd, "\"release\"", "\"relase\""), "/populations/0/guide/relase").hint, "did you mean \"release\"?");
  EXPECT_EQ(only(edit(kCrowd, "\"lodDistance\"", "\"lodDistanc\""), "/steering/lodDistanc").hint,
            "did you mean \"lodDistance\"?");
  EXPECT_EQ(only(edit(kCrowd, "\"bezier\"", "\"bezeir\""), "/populations/0/paths").hint, "did you mean \"bezier\"?");
}
