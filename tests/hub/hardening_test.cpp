// What the server does with hostile requests before they reach the world: text checks (UTF-8,
// printable echoes), the per-request limits of a crowd file (the JSON pointer and line:column of
// the first one crossed), the same limits on the path `throng link` shares, and the tick watch
// that counts late and stalled ticks, the running one included.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "throng/hub/crowd_requests.hpp"
#include "throng/hub/motion_library.hpp"
#include "throng/hub/world_description.hpp"
#include "throng/hub/text.hpp"
#include "throng/hub/tick_watch.hpp"
#include "throng/io/scenario_loader.hpp"

namespace throng::hub {
namespace {

TEST(Text, Utf8IsValidatedToTheByte) {
  EXPECT_FALSE(invalidUtf8At("").has_value());
  EXPECT_FALSE(invalidUtf8At("plain ascii").has_value());
  EXPECT_FALSE(invalidUtf8At("Zo\xc3\xab \xe2\x82\xac \xf0\x9f\x98\x80").has_value());  // ë € 😀
  EXPECT_EQ(invalidUtf8At("ab\xff"), 2u);
  EXPECT_EQ(invalidUtf8At("\xc3\x28"), 0u);            // lead byte without its continuation
  EXPECT_EQ(invalidUtf8At("x\xc0\xaf"), 1u);           // overlong '/'
  EXPECT_EQ(invalidUtf8At("\xed\xa0\x80"), 0u);        // a UTF-16 surrogate
  EXPECT_EQ(invalidUtf8At("ok\xf4\x90\x80\x80"), 2u);  // above U+10FFFF
  EXPECT_EQ(invalidUtf8At("cut \xe2\x82"), 4u);        // a sequence cut short
  EXPECT_EQ(describeByte("ab\xff", 2), "byte 2 (0xFF)");
}

TEST(Text, PrintableEscapesControlsAndBadBytesAndCapsTheLength) {
  EXPECT_EQ(printable("Zo\xc3\xab", 64), "Zo\xc3\xab");
  EXPECT_EQ(printable("a\x1b[2J\nb\x7f", 64), "a\\x1B[2J\\x0Ab\\x7F");
  EXPECT_EQ(printable("bad\xff", 64), "bad\\xFF");
  EXPECT_EQ(printable(std::string(100, 'x'), 10), "xxxxxxx...");
  // Cut at a character boundary: never half of "ë" or of an escape.
  EXPECT_EQ(printable("ab\xc3\xab\xc3\xab\xc3\xab", 8), "ab\xc3\xab\xc3\xab\xc3\xab");  // exactly fits
  const std::string cut = printable("ab\xc3\xab\xc3\xab\xc3\xab", 7);
  EXPECT_LE(cut.size(), 7u);
  EXPECT_FALSE(invalidUtf8At(cut).has_value()) << cut;
  EXPECT_EQ(cut, "ab\xc3\xab...");
  EXPECT_EQ(printable("\x01\x02\x03\x04", 9), "\\x01...");
  EXPECT_EQ(cutUtf8("ab\xc3\xab", 3), "ab");
  EXPECT_EQ(cutUtf8("abc", 3), "abc");
}

TEST(Text, ValidUtf8ReplacesOnlyBadBytes) {
  EXPECT_EQ(validUtf8("Zo\xc3\xab"), "Zo\xc3\xab");
  EXPECT_EQ(validUtf8("a\xff" "b\xc3"), "a\xef\xbf\xbd" "b\xef\xbf\xbd");
}

// Names from a scenario that are not UTF-8 made the server's JSON throw (HTTP 500, a serve that
// fails): the world description is always JSON, the bad bytes written as U+FFFD.
TEST(WorldDescription, NamesThatAreNotUtf8NeverBreakIt) {
  auto loaded = io::loadScenarioFile(std::string(THRONG_SOURCE_DIR) + "/scenarios/museum.json");
  ASSERT_TRUE(loaded.ok());
  io::LoadedScenario scenario = std::move(loaded).value();
  auto world = sim::World::create(scenario.desc, scenario.navmesh);
  ASSERT_TRUE(world.ok());
  std::vector<std::string> warnings;
  const MotionLibrary motions = MotionLibrary::load(scenario, std::string(THRONG_SOURCE_DIR) + "/scenarios", warnings);
  scenario.desc.name = "bad\xff name";
  const std::size_t at = scenario.text.find("\"hall\"");
  ASSERT_NE(at, std::string::npos);
  scenario.text.replace(at + 1, 4, "h\xc3\x28l");  // "hall" with a broken sequence
  std::string described;
  ASSERT_NO_THROW(described = describeWorld(scenario, motions, *world.value(), 20.0));
  const auto j = nlohmann::json::parse(described, nullptr, false);
  ASSERT_FALSE(j.is_discarded()) << described.substr(0, 200);
  EXPECT_EQ(j["name"], "bad\xef\xbf\xbd name");
  ASSERT_TRUE(j["scenario"].is_object());
  EXPECT_NE(j["scenario"].dump().find("h\xef\xbf\xbd(l"), std::string::npos);
}

TEST(CrowdLimits, AValidCrowdFileKeepsWithinEveryLimit) {
  const std::string crowd = R"({"format": "throng-crowd/1", "id": "tour",
    "points": [{"id": "meet", "kind": "interest", "polygon": [[1, 1], [2, 1], [2, 2.5], [1, 2]]}],
    "populations": [{"id": "t", "groups": 1, "size": 8, "spawn": {"polygon": [[1, 1], [8, 1], [8, 9], [1, 9]]},
                     "goals": ["meet"], "speed": 1.1, "radius": 0.22, "flocking": true}]})";
  EXPECT_TRUE(checkCrowdLimits(crowd, "c.json").empty()) << core::formatAll(checkCrowdLimits(crowd, "c.json"));
}

TEST(CrowdLimits, TheFirstLimitCrossedIsNamedWithItsPointerAndPosition) {
  // Each limit alone, small, so that it is the one crossed.
  auto first = [](const std::string& text, auto set) {
    CrowdLimits limits;
    set(limits);
    const core::Diagnostics d = checkCrowdLimits(text, "req", limits);
    EXPECT_EQ(d.size(), 1u) << text;
    return d.empty() ? std::string() : d.front().format();
  };
  EXPECT_EQ(first(R"({"a": {"polygon": [[0,0],[1,0],[1,1],
[0,1],[0.5,2]]}})", [](CrowdLimits& l) { l.maxPolygonVertices = 4; }),
            "req:2:7 /a/polygon/4: a polygon of more than 4 vertices; expected at most 4 vertices per polygon in a "
            "crowd request (server limit) (simplify the polygon, or split it into several)");
  EXPECT_EQ(first(R"({"a": [[0,0],[1,0],[1,1]], "b": [[0,0],[1,0],[1,1],[2,2]]})", [](CrowdLimits& l) { l.maxVertices = 6; }),
            "req:1:52 /b/3: more than 6 positions; expected at most 6 positions (polygon vertices, points) per crowd "
            "request (server limit)");
  EXPECT_EQ(first(R"({"a": 1, "b": {"c": 2, "d~/": 3}, "e": 4, "f": 5})", [](CrowdLimits& l) { l.maxKeys = 3; }),
            "req:1:24 /b/d~0~1: more than 3 object keys; expected at most 3 keys per crowd request (all objects together) "
            "(server limit)");
  EXPECT_EQ(first(R"({"x": {"y": [[{"z": 1}]]}})", [](CrowdLimits& l) { l.maxDepth = 4; }),
            "req:1:15 /x/y/0/0: nesting deeper than 4 levels; expected at most 4 levels of arrays and objects per crowd "
            "request (server limit)");
  EXPECT_EQ(first(R"(["a", "b", "c", "d", "e", "f", "g", "h", "i", "j", "k", "l"])", [](CrowdLimits& l) { l.maxValues = 12; }),
            "req:1:57 /11: more than 12 values; expected at most 12 values (numbers, strings, arrays, objects) per crowd "
            "request (server limit)");
  EXPECT_EQ(first(std::string(201, ' '), [](CrowdLimits& l) { l.maxBytes = 200; }),
            "req: the crowd file is 201 bytes; expected at most 200 bytes per crowd request (server limit)");
  EXPECT_EQ(first("{\"a\": \"\xc3\xab\",\n\"b\": \"\xff\"}", [](CrowdLimits&) {}),
            "req:2:7: not UTF-8: byte 18 (0xFF); expected UTF-8 text (a crowd file is JSON)");
  CrowdLimits limits;
  limits.maxKeys = 2;
  // Escaped quotes and keys with "/" or "~" do not confuse it; malformed JSON is left to the parser.
  EXPECT_TRUE(checkCrowdLimits(R"({"a\"b": "c\\", "d": [1, 2])", "req", limits).empty());
  EXPECT_TRUE(checkCrowdLimits(R"(]]]}}}{"a": [1, 2)", "req", limits).empty());
}

TEST(CrowdLimits, TheLinksPathHasTheSameLimits) {
  auto loaded = io::loadScenarioFile(std::string(THRONG_SOURCE_DIR) + "/scenarios/museum.json");
  ASSERT_TRUE(loaded.ok());
  auto world = sim::World::create(loaded->desc, loaded->navmesh);
  ASSERT_TRUE(world.ok());
  std::string polygon;
  for (int i = 0; i < 5000; ++i) polygon += std::string(i ? "," : "") + "[1,2]";
  const std::string crowd = R"({"format": "throng-crowd/1", "id": "big", "populations": [{"id": "p", "groups": 1,
    "size": 1, "spawn": {"polygon": [)" + polygon + R"(]}, "goals": ["exit"]}]})";
  const CrowdOutcome outcome = insertCrowdJson(*world.value(), crowd, "host request 1");
  EXPECT_FALSE(outcome.ok);
  EXPECT_NE(outcome.text.find("host request 1:2:"), std::string::npos) << outcome.text;
  EXPECT_NE(outcome.text.find("/populations/0/spawn/polygon/1000: a polygon of more than 1000 vertices"), std::string::npos)
      << outcome.text;
  EXPECT_TRUE(world.value()->crowds().empty());
}

TEST(TickWatch, ATickStuckNowCountsAsLateAndAsAStallBeforeItEnds) {
  TickWatch watch(0.05);  // 20 Hz; a stall is 10 periods, 0.5 s
  for (int i = 0; i < 10; ++i) {
    watch.started(i * 0.05);
    watch.finished(i * 0.05 + 0.01, false);
  }
  TickReport r = watch.report(0.5);
  EXPECT_EQ(r.ticks, 10u);
  EXPECT_EQ(r.late, 0u);
  EXPECT_EQ(r.stalls, 0u);
  EXPECT_NEAR(r.longestMs, 10.0, 1e-9);
  // A tick that has been running for 14 s (a crowd validated on the simulation thread did this).
  watch.started(0.5);
  r = watch.report(14.5);
  EXPECT_EQ(r.late, 1u);
  EXPECT_EQ(r.stalls, 1u);
  EXPECT_NEAR(r.runningMs, 14000.0, 1e-6);
  EXPECT_NEAR(r.longestMs, 14000.0, 1e-6);
  watch.finished(14.6, true);
  r = watch.report(14.6);
  EXPECT_EQ(r.ticks, 11u);
  EXPECT_EQ(r.late, 1u);
  EXPECT_EQ(r.stalls, 1u);
  EXPECT_EQ(r.runningMs, 0.0);
  // Late by the schedule (a slow tick before pushed its deadline) but no stall.
  watch.started(14.6);
  watch.finished(14.62, true);
  r = watch.report(14.7);
  EXPECT_EQ(r.late, 2u);
  EXPECT_EQ(r.stalls, 1u);
  // Over its period but under a stall: late only, while it runs.
  watch.started(15.0);
  r = watch.report(15.2);
  EXPECT_EQ(r.late, 3u);
  EXPECT_EQ(r.stalls, 1u);
}

}  // namespace
}  // namespace throng::hub
