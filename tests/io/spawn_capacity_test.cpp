// Spawn capacity (scenario_validator: checkSpawnCapacity, checkTerrainCapacity): the agents of
// populations that spawn at the same time in overlapping areas are summed against the walkable part
// of those areas, on flat and on multi-level worlds, and the diagnostic names file:line:column.
#include <gtest/gtest.h>

#include <string>

#include "scenario_test_util.hpp"

namespace throng::io::test {
namespace {

const std::string kRoom = R"([[1,1],[8,1],[8,9],[1,9]])";

/// The bottleneck with a second population spawning in the same 56 m² room.
std::string twoCrowds(const std::string& secondSpawn, const std::string& secondStart = "0") {
  std::string text = edit(kBottleneck, "\"groups\": 100", "\"groups\": 150");
  return edit(text, R"("radius": 0.2}
  ])",
              R"("radius": 0.2},
    {"id": "second", "groups": 150, "start": )" + secondStart + R"(, "spawn": {"polygon": )" + secondSpawn +
                  R"(}, "goals": ["gap", "exit"], "radius": 0.2}
  ])");
}

TEST(SpawnCapacity, PopulationsSharingAnAreaAreSummed) {
  // 150 agents of radius 0.2 m need 37.7 m² each: either fits the room alone, not both at once.
  const std::string text = twoCrowds(kRoom);
  const auto ds = errorsOf(text);
  ASSERT_EQ(ds.size(), 1u) << core::formatAll(ds);
  const auto d = at(ds, "/populations/1/spawn/polygon");
  expectAt(d, text, kRoom, 1);
  EXPECT_EQ(d.what,
            "spawn areas of populations \"crowd\" (150 at /populations/0/spawn/polygon) and \"second\" (150 at "
            "/populations/1/spawn/polygon) overlap and start at 0 s: 56 m² of walkable ground is too small for their 300 "
            "agents");
  EXPECT_EQ(d.expected,
            "at least 75.4 m² (agents × π r² / packing factor 0.5, summed over the populations spawning there together)");
}

TEST(SpawnCapacity, OverlappingAreasCountTheirUnion) {
  // The second area reaches 0.9 m further, up to the wall: together 7.9 m x 8 m = 63.2 m².
  const std::string text = twoCrowds(R"([[5,1],[8.9,1],[8.9,9],[5,9]])");
  const auto d = at(errorsOf(text), "/populations/1/spawn/polygon");
  EXPECT_TRUE(contains(d.what, ": 63.2 m² of walkable ground is too small for their 300 agents")) << d.format();
}

TEST(SpawnCapacity, LaterStartsOrSeparateAreasAreNotSummed) {
  EXPECT_TRUE(load(twoCrowds(kRoom, "60")).ok());
  EXPECT_TRUE(load(twoCrowds(R"([[11,1],[18,1],[18,9],[11,9]])")).ok());
}

/// A hall at height 0, a ramp, an upper floor at 3 m (tests/io/scenario_terrain_test.cpp's world).
const std::string kLevels = R"({
  "format": "throng/1",
  "terrain": {
    "vertices": [[0,0,0],[12,0,0],[12,8,0],[0,8,0],[12,14,3],[0,14,3],[12,20,3],[0,20,3]],
    "walkable": [[0,1,2],[0,2,3],[3,2,4],[3,4,5],[5,4,6],[5,6,7]]
  },
  "points": [{"id": "hall", "kind": "interest", "position": [6, 4]}],
  "populations": [
    {"id": "down", "groups": GROUPS, "spawn": {"polygon": [[8,16],[10,16],[10,18],[8,18]], "height": 3}, "goals": ["hall"]},
    {"id": "also", "groups": 10, "spawn": {"polygon": [[7,15],[9,15],[9,17],[7,17]], "height": 3}, "goals": ["hall"]}
  ]
}
)";

TEST(SpawnCapacity, MultiLevelWorldsAreCheckedOnTheirFloor) {
  // 4 m² on the upper floor: 10 agents fit (2.5 m² needed), 60 do not.
  const std::string fits = edit(kLevels, "GROUPS", "5");
  EXPECT_TRUE(load(fits, true).ok()) << core::formatAll(load(fits, true).errors());
  const std::string text = edit(kLevels, "GROUPS", "60");
  const auto ds = errorsOf(text, true);
  const auto d = at(ds, "/populations/1/spawn/polygon");
  expectAt(d, text, "[[7,15]");
  EXPECT_TRUE(contains(d.what, "spawn areas of populations \"down\" (60 at /populations/0/spawn/polygon) and \"also\" (10 at "
                               "/populations/1/spawn/polygon) overlap and start at 0 s"))
      << d.format();
  EXPECT_TRUE(contains(d.what, "too small for their 70 agents")) << d.format();
}

}  // namespace
}  // namespace throng::io::test
