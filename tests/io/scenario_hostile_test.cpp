// Hostile scenario input (issue 15, items 10, 13, 17): files far larger than any real scenario,
// names that are not UTF-8, points no agent can reach, and a validation stopped by a signal. Each
// must end in located diagnostics, in time and memory near-linear in the file.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>

#include "scenario_parser.hpp"
#include "scenario_test_util.hpp"
#include "throng/core/text.hpp"

namespace throng::io::test {
namespace {

/// kBottleneck with extra root keys written before "populations", one per line.
std::string withRootKeys(std::size_t n) {
  std::string keys;
  keys.reserve(n * 20);
  for (std::size_t i = 0; i < n; ++i) keys += "  \"unknown" + std::to_string(i) + "\": " + std::to_string(i) + ",\n";
  return edit(kBottleneck, "  \"populations\": [", keys + "  \"populations\": [");
}

TEST(ScenarioHostile, HundredsOfThousandsOfUnknownKeysAreEachLocated) {
  // 300,000 unknown keys (6 MB): the JSON reader scanned every key seen for each new one, the
  // check took minutes. Every key gets its diagnostic at its own line, in file order.
  const std::size_t n = 300000;
  const std::string text = withRootKeys(n);
  const auto ds = errorsOf(text);
  ASSERT_EQ(ds.size(), n);
  const int firstLine = posOf(text, "\"unknown0\"").first;
  for (std::size_t i = 0; i < n; i += 4999) {
    EXPECT_EQ(ds[i].pointer, "/unknown" + std::to_string(i));
    EXPECT_EQ(ds[i].line, firstLine + static_cast<int>(i));
    EXPECT_EQ(ds[i].column, 3);
  }
}

TEST(ScenarioHostile, ManyGoalsAndPointsResolveByHash) {
  // 20,000 points and a population naming each as a goal, plus 20,000 unknown goals: ids were
  // looked up (and "did you mean" searched) among every point for every goal.
  const std::size_t n = 20000;
  std::string points, goals, unknown;
  for (std::size_t i = 0; i < n; ++i) {
    points += ",\n    {\"id\": \"p" + std::to_string(i) + "\", \"kind\": \"interest\", \"position\": [2, 2]}";
    goals += ", \"p" + std::to_string(i) + "\"";
    unknown += ", \"q" + std::to_string(i) + "\"";
  }
  std::string text = edit(kBottleneck, "\"radius\": 0.5}", "\"radius\": 0.5}" + points);
  text = edit(text, "\"goals\": [\"gap\", \"exit\"]", "\"goals\": [\"gap\"" + goals + unknown + ", \"exit\"]");
  const auto ds = errorsOf(text);
  ASSERT_EQ(ds.size(), n);
  EXPECT_EQ(ds[0].pointer, "/populations/0/goals/" + std::to_string(n + 1));
  EXPECT_TRUE(contains(ds[0].what, "unknown point \"q0\"")) << ds[0].format();
}

TEST(ScenarioHostile, NameThatIsNotUtf8IsLocated) {
  const std::string text = edit(kBottleneck, "\"name\": \"bottleneck\"", "\"name\": \"bottle\xC3neck\"");
  const auto ds = errorsOf(text);
  ASSERT_EQ(ds.size(), 1u);
  const auto [line, col] = posOf(text, "\xC3");
  EXPECT_EQ(ds[0].line, line);
  EXPECT_EQ(ds[0].column, col);
  EXPECT_TRUE(contains(ds[0].what, "byte 0xC3 in a string is not UTF-8")) << ds[0].format();
  EXPECT_TRUE(contains(ds[0].expected, "UTF-8 text")) << ds[0].format();
  EXPECT_TRUE(core::isUtf8(ds[0].format()));
}

TEST(ScenarioHostile, EchoedIdsAreEscapedAndCapped) {
  // An unknown goal id with a newline, an escape character and 300 more characters.
  const std::string id = "ex\\nit\\u001b[2J" + std::string(300, 'x');
  const std::string text = edit(kBottleneck, "\"goals\": [\"gap\", \"exit\"]", "\"goals\": [\"gap\", \"" + id + "\"]");
  const auto ds = errorsOf(text);
  const auto d = at(ds, "/populations/0/goals/1");
  const std::string line = d.format();
  EXPECT_EQ(line.find('\n'), std::string::npos);
  EXPECT_EQ(line.find('\x1b'), std::string::npos);
  EXPECT_TRUE(contains(line, "unknown point \"ex\\nit\\u001B[2J")) << line;
  EXPECT_TRUE(contains(line, "xxx...\"")) << line;
  EXPECT_LT(line.size(), 400u) << line;
}

TEST(ScenarioHostile, InterestPointInsideAWallIsRefused) {
  // The gap's disc moved into the lower wall (obstacle 0, x 9..10, y 0..4.5): no agent can enter
  // it, and every agent stood in front of the wall until the run ended.
  const std::string text = edit(kBottleneck, "\"position\": [9.5, 5], \"radius\": 0.5", "\"position\": [9.5, 2], \"radius\": 0.3");
  const auto ds = errorsOf(text, true);
  ASSERT_EQ(ds.size(), 1u) << core::formatAll(ds);
  const auto& d = ds[0];
  EXPECT_EQ(d.pointer, "/points/0/position");
  expectAt(d, text, "[9.5, 2]");
  EXPECT_TRUE(contains(d.what, "interest point \"gap\" cannot be reached: (9.5, 2) is inside obstacle /obstacles/0")) << d.format();
  EXPECT_TRUE(contains(d.what, "the nearest walkable point is (")) << d.format();
  EXPECT_TRUE(contains(d.hint, "enlarge \"radius\" to at least")) << d.format();
}

TEST(ScenarioHostile, ExitOutsideTheWalkableAreaAndPolygonInAWallAreRefused) {
  // An exit disc just beyond the right edge, out of reach of every agent's centre.
  std::string text = edit(kBottleneck, "\"polygon\": [[19,4],[20,4],[20,6],[19,6]]", "\"position\": [20.6, 5], \"radius\": 0.5");
  auto ds = errorsOf(text, true);
  auto d = at(ds, "/points/1/position");
  EXPECT_TRUE(contains(d.what, "exit \"exit\" cannot be reached: (20.6, 5) is outside the walkable area")) << d.format();
  // An exit polygon wholly inside the upper wall (x 9..10, y 5.5..10).
  text = edit(kBottleneck, "\"polygon\": [[19,4],[20,4],[20,6],[19,6]]", "\"polygon\": [[9.2,7],[9.8,7],[9.8,8],[9.2,8]]");
  ds = errorsOf(text, true);
  d = at(ds, "/points/1/polygon");
  EXPECT_TRUE(contains(d.what, "its polygon covers no walkable ground ((9.5, 7.5) is inside obstacle /obstacles/1)")) << d.format();
  // Still accepted: a disc that reaches past the wall's face onto the floor.
  EXPECT_TRUE(load(edit(kBottleneck, "\"position\": [9.5, 5], \"radius\": 0.5", "\"position\": [9.5, 4.2], \"radius\": 1"), true).ok());
  EXPECT_TRUE(load(kBottleneck, true).ok());
}

TEST(ScenarioHostile, PointBeyondAFloorsEdgeIsRefusedOnMultiLevelWorlds) {
  // A hall (12 m x 8 m) of a multi-level world; the interest disc lies 0.6 m beyond its east edge.
  const std::string text = R"({
  "format": "throng/1",
  "terrain": {"vertices": [[0,0,0],[12,0,0],[12,8,0],[0,8,0]], "walkable": [[0,1,2],[0,2,3]]},
  "points": [{"id": "kiosk", "kind": "interest", "position": [12.6, 4, 0]}],
  "populations": [{"id": "p", "spawn": {"position": [2, 2, 0]}, "goals": ["kiosk"]}]
})";
  const auto ds = errorsOf(text, true);
  const auto d = at(ds, "/points/0/position");
  expectAt(d, text, "[12.6, 4, 0]");
  EXPECT_TRUE(contains(d.what, "interest point \"kiosk\" cannot be reached: (12.6, 4, 0) is off the walkable surface and its "
                               "radius 0.5 m reaches no ground where agents can stand (their centres keep 0.13 m from walls); the "
                               "nearest walkable "
                               "point is (11.")) << d.format();
  EXPECT_TRUE(load(edit(text, "[12.6, 4, 0]", "[11.9, 4, 0]"), true).ok());
}

TEST(ScenarioHostile, PolygonsTooBigOrTooTangledAreRefusedWhereTheyStand) {
  // A star of 40,000 spikes as an obstacle: all its edges pass near the centre (1.6·10⁹ pairs).
  std::string star = "[";
  for (int i = 0; i < 40000; ++i) {
    const double a = 2.0 * 3.14159265358979323846 * i / 40000.0, r = i % 2 == 0 ? 4.0 : 0.1;
    star += (i ? ",[" : "[") + std::to_string(10 + r * std::cos(a)) + "," + std::to_string(5 + r * std::sin(a)) + "]";
  }
  star += "]";
  std::string text = edit(kBottleneck, "[[9,5.5],[10,5.5],[10,10],[9,10]] ]", "[[9,5.5],[10,5.5],[10,10],[9,10]], " + star + " ]");
  auto ds = errorsOf(text);
  ASSERT_EQ(ds.size(), 1u) << core::formatAll(ds);
  EXPECT_EQ(ds[0].pointer, "/obstacles/2");
  EXPECT_TRUE(contains(ds[0].what, "polygon of 40000 points is too complex to check for self-intersections")) << ds[0].format();
  // Over the vertex cap: refused before any check.
  std::string big = "[";
  for (std::size_t i = 0; i <= kMaxPolygonVertices; ++i) big += i ? ",[0,0]" : "[0,0]";
  big += "]";
  text = edit(kBottleneck, "[[9,5.5],[10,5.5],[10,10],[9,10]] ]", "[[9,5.5],[10,5.5],[10,10],[9,10]], " + big + " ]");
  ds = errorsOf(text);
  ASSERT_EQ(ds.size(), 1u) << core::formatAll(ds);
  EXPECT_EQ(ds[0].pointer, "/obstacles/2");
  EXPECT_EQ(ds[0].what, "polygon of 250001 points");
  EXPECT_EQ(ds[0].expected, "at most 250000 points per polygon");
}

TEST(ScenarioHostile, AValidationStoppedBySignalSaysSo) {
  std::atomic<int> cancel{2};  // SIGINT already arrived
  LoadOptions options;
  options.cancel = &cancel;
  auto r = parseScenario(kBottleneck, "t.json", options);
  ASSERT_FALSE(r.ok());
  ASSERT_EQ(r.errors().size(), 1u);
  EXPECT_TRUE(contains(r.errors()[0].what, "interrupted")) << r.errors()[0].format();
  cancel = 0;
  EXPECT_TRUE(parseScenario(kBottleneck, "t.json", options).ok());
}

}  // namespace
}  // namespace throng::io::test
