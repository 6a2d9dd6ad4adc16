// Tests for multi-level glTF world files (libs/io world_file): scenarios/two_floors.gltf becomes a
// "terrain" scenario (ground x, y = glTF x, -z; height = glTF y) with points, spawns and heights
// from the nodes, validated on the 3D navmesh; floors at different heights with no stair or ramp
// are valid geometry whose goals are reported unreachable, naming the crowd node; a world whose
// floors are all at one height (scenarios/gallery.gltf) keeps the flat 2D scenario.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>

#include <sqlite3.h>

#include <nlohmann/json.hpp>

#include "throng/io/scenario_loader.hpp"
#include "throng/io/world_file.hpp"
#include "throng/sim/world.hpp"

namespace {

using nlohmann::json;
namespace io = throng::io;

const std::string kTwoFloors = std::string(THRONG_SOURCE_DIR) + "/scenarios/two_floors.gltf";
const std::string kGallery = std::string(THRONG_SOURCE_DIR) + "/scenarios/gallery.gltf";

json readJson(const std::string& path) {
  std::ifstream in(path);
  return json::parse(in);
}

const throng::sim::PointDesc& point(const throng::sim::ScenarioDesc& d, const std::string& id) {
  for (const auto& p : d.points) {
    if (p.id == id) return p;
  }
  throw std::runtime_error("no point " + id);
}

TEST(GltfLevels, TwoFloorsBecomesATerrainScenario) {
  const auto r = io::loadScenarioFile(kTwoFloors);
  ASSERT_TRUE(r.ok()) << throng::core::formatAll(r.errors());
  const auto& d = r.value().desc;
  EXPECT_EQ(d.name, "two floors");
  EXPECT_EQ(d.seed, 5u);
  EXPECT_FLOAT_EQ(d.duration, 120.0f);
  EXPECT_TRUE(d.walkable.empty());
  EXPECT_TRUE(d.obstacles.empty());
  // Hall, gallery, landing (2 triangles each), 17 steps (2 each), the ramp (2); two boxes (12 each).
  EXPECT_EQ(d.terrain.walkable.size(), 3u * (2 + 2 + 2 + 17 * 2 + 2));
  EXPECT_EQ(d.terrain.obstacles.size(), 3u * 24);
  float lo = 1e9f, hi = -1e9f;  // walkable heights: the hall at 0 m, the gallery at 3 m
  for (const std::uint32_t v : d.terrain.walkable) {
    lo = std::min(lo, d.terrain.vertices[3 * v + 2]);
    hi = std::max(hi, d.terrain.vertices[3 * v + 2]);
  }
  EXPECT_FLOAT_EQ(lo, 0.0f);
  EXPECT_FLOAT_EQ(hi, 3.0f);
  EXPECT_FLOAT_EQ(point(d, "mosaic").height, 0.0f);
  EXPECT_FLOAT_EQ(point(d, "painting_west").height, 3.0f);
  EXPECT_FLOAT_EQ(point(d, "painting_west").position.y, 15.0f);  // glTF z = -15 → ground y = 15
  EXPECT_FLOAT_EQ(point(d, "balcony").height, 3.0f);
  EXPECT_EQ(point(d, "balcony").kind, throng::sim::PointKind::Action);
  EXPECT_FLOAT_EQ(point(d, "door").height, 0.0f);
  ASSERT_EQ(d.populations.size(), 2u);
  EXPECT_EQ(d.populations[0].id, "visitors");
  EXPECT_FLOAT_EQ(d.populations[0].spawn.height, 0.0f);
  EXPECT_EQ(d.populations[1].id, "gallery_guests");
  EXPECT_EQ(d.populations[1].spawn.kind, throng::sim::SpawnKind::Polygon);
  EXPECT_FLOAT_EQ(d.populations[1].spawn.height, 3.0f);
  ASSERT_NE(r.value().navmesh, nullptr);
  EXPECT_TRUE(r.value().navmesh->layered());
  // The text is a terrain scenario: it loads by itself (how recordings replay a world).
  const json text = json::parse(r.value().text);
  EXPECT_TRUE(text.contains("terrain"));
  EXPECT_FALSE(text.contains("walkable"));
  EXPECT_EQ(text["points"][1]["position"], json::array({5.0, 15.0, 3.0}));
  EXPECT_EQ(text["populations"][1]["spawn"]["height"], 3.0);
  const auto again = io::parseScenario(r.value().text, kTwoFloors);
  ASSERT_TRUE(again.ok()) << throng::core::formatAll(again.errors());
  EXPECT_EQ(again.value().desc.terrain.vertices, d.terrain.vertices);
}

TEST(GltfLevels, EitherWayUpIsEnough) {
  for (const std::string drop : {"walkable_stairs", "walkable_ramp"}) {
    json g = readJson(kTwoFloors);
    json kept = json::array();
    for (std::size_t i = 0; i < g["nodes"].size(); ++i) {
      if (g["nodes"][i]["name"] != drop) kept.push_back(i);
    }
    g["scenes"][0]["nodes"] = kept;
    const auto r = io::parseWorld(g.dump(), "world.gltf");
    EXPECT_TRUE(r.ok()) << drop << ": " << throng::core::formatAll(r.errors());
  }
}

TEST(GltfLevels, FloorsWithoutAWayUpAreUnreachable) {
  json g = readJson(kTwoFloors);
  json kept = json::array();
  for (std::size_t i = 0; i < g["nodes"].size(); ++i) {
    const std::string name = g["nodes"][i]["name"];
    if (name != "walkable_stairs" && name != "walkable_ramp" && name != "walkable_landing") kept.push_back(i);
  }
  g["scenes"][0]["nodes"] = kept;
  const auto r = io::parseWorld(g.dump(), "world.gltf");
  ASSERT_FALSE(r.ok());
  const std::string e = throng::core::formatAll(r.errors());
  EXPECT_NE(e.find("world.gltf node 12 \"crowd:visitors\" /extras/throng/goals/1: point \"painting_west\" cannot be reached "
                   "from the spawn area of population \"visitors\""),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("node 13 \"crowd:gallery_guests\" /extras/throng/goals/0: point \"mosaic\" cannot be reached"),
            std::string::npos)
      << e;
  // Without the reachability check the geometry itself is fine.
  EXPECT_TRUE(io::parseWorld(g.dump(), "world.gltf", {.checkReachability = false}).ok());
}

TEST(GltfLevels, TerrainErrorsNameTheNode) {
  json g = readJson(kTwoFloors);
  // A point above the gallery, out of the height band: named by its node.
  for (auto& n : g["nodes"]) {
    if (n["name"] == "interest:painting_east") n["translation"][1] = 7.0;
  }
  const auto r = io::parseWorld(g.dump(), "world.gltf");
  ASSERT_FALSE(r.ok());
  const std::string e = throng::core::formatAll(r.errors());
  EXPECT_NE(e.find("world.gltf node 9 \"interest:painting_east\": point \"painting_east\" at (19, 15, 7) lies off the walkable "
                   "surface"),
            std::string::npos)
      << e;
  // The scene may not set the terrain itself.
  g = readJson(kTwoFloors);
  g["scenes"][0]["extras"]["throng"]["terrain"] = json::object();
  const auto s = io::parseWorld(g.dump(), "world.gltf");
  ASSERT_FALSE(s.ok());
  EXPECT_NE(throng::core::formatAll(s.errors()).find("key \"terrain\" is not set in a world's scene extras"), std::string::npos);
}

TEST(GltfLevels, FlatWorldsStayFlat) {
  const auto r = io::loadScenarioFile(kGallery, {.checkReachability = false});
  ASSERT_TRUE(r.ok()) << throng::core::formatAll(r.errors());
  EXPECT_TRUE(r.value().desc.terrain.empty());
  EXPECT_EQ(r.value().desc.walkable.size(), 1u);
  const json text = json::parse(r.value().text);
  EXPECT_FALSE(text.contains("terrain"));
  EXPECT_EQ(text["points"][0]["position"].size(), 2u);  // [x, y]: no height on a flat world
  EXPECT_FALSE(text["populations"][0]["spawn"].contains("height"));
  // A flat floor raised 2 m is still one level: the same scenario, heights dropped.
  json g = readJson(kGallery);
  for (auto& n : g["nodes"]) n["translation"] = n.contains("translation") ? n["translation"] : json::array({0, 0, 0});
  for (auto& n : g["nodes"]) n["translation"][1] = n["translation"][1].get<double>() + 2.0;
  const auto raised = io::parseWorld(g.dump(), kGallery, {.checkReachability = false});
  ASSERT_TRUE(raised.ok()) << throng::core::formatAll(raised.errors());
  EXPECT_EQ(raised.value().text, r.value().text);
}

TEST(GltfLevels, TwoFloorsRunsToTheEnd) {
  // Visitors climb to the gallery (3 m) and come down to the door; the gallery's guests go down.
  const auto r = io::loadScenarioFile(kTwoFloors);
  ASSERT_TRUE(r.ok()) << throng::core::formatAll(r.errors());
  auto created = throng::sim::World::create(r.value().desc, r.value().navmesh);
  ASSERT_TRUE(created.ok()) << throng::core::formatAll(created.errors());
  throng::sim::World& world = *created.value();
  const throng::core::TaskSystem tasks(2);
  std::map<std::uint32_t, std::pair<float, float>> range;  // id → lowest, highest height
  std::map<std::uint32_t, std::uint32_t> populationOf;
  while (!world.finished() && world.stats().time < 150.0) {
    world.step(tasks);
    const auto f = world.takeFrame();
    for (std::size_t i = 0; i < f->size(); ++i) {
      auto [it, fresh] = range.try_emplace(f->ids[i], f->height(i), f->height(i));
      it->second.first = std::min(it->second.first, f->height(i));
      it->second.second = std::max(it->second.second, f->height(i));
    }
    for (const auto& e : f->events) {
      if (e.kind == throng::sim::EventKind::Spawn) populationOf[e.agent] = e.a;
    }
  }
  EXPECT_TRUE(world.finished()) << "everyone leaves by the door within 150 s";
  ASSERT_GE(range.size(), 10u);
  for (const auto& [id, r2] : range) {
    SCOPED_TRACE("agent " + std::to_string(id));
    EXPECT_LT(r2.first, 0.1f);   // on the hall floor at some time (the door is there)
    EXPECT_GT(r2.second, 2.9f);  // and on the gallery at some time
  }
}

#ifdef THRONG_EXE
TEST(GltfLevels, RecordingKeepsTheHeights) {
  const std::filesystem::path dir = std::filesystem::path(THRONG_BINARY_DIR) / "gltf_levels_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string db = (dir / "two_floors.sqlite").string();
  const std::string cmd = std::string("'") + THRONG_EXE + "' run '" + kTwoFloors + "' --out '" + db + "' --quiet > '" +
                          (dir / "run.log").string() + "' 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  sqlite3* h = nullptr;
  ASSERT_EQ(sqlite3_open_v2(db.c_str(), &h, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
  auto one = [&](const char* sql) {
    sqlite3_stmt* s = nullptr;
    double v = -1;
    if (sqlite3_prepare_v2(h, sql, -1, &s, nullptr) == SQLITE_OK && sqlite3_step(s) == SQLITE_ROW) v = sqlite3_column_double(s, 0);
    sqlite3_finalize(s);
    return v;
  };
  const double rows = one("SELECT count(*) FROM trajectory_data");
  EXPECT_GT(rows, 1000);
  EXPECT_EQ(one("SELECT count(*) FROM throng_heights"), rows) << "one height per trajectory row";
  EXPECT_EQ(one("SELECT count(*) FROM throng_heights h JOIN trajectory_data t ON t.frame = h.frame AND t.id = h.id"), rows);
  EXPECT_NEAR(one("SELECT max(z) FROM throng_heights"), 3.0, 0.15);
  EXPECT_NEAR(one("SELECT min(z) FROM throng_heights"), 0.0, 0.15);
  EXPECT_GT(one("SELECT count(*) FROM geometry WHERE wkt LIKE 'GEOMETRYCOLLECTION%' OR wkt LIKE 'POLYGON%' OR wkt LIKE 'MULTIPOLYGON%'"), 0);
  sqlite3_close(h);
  // `throng info` reports the height range.
  const std::string info = (dir / "info.json").string();
  ASSERT_EQ(std::system((std::string("'") + THRONG_EXE + "' info '" + db + "' --json > '" + info + "'").c_str()), 0);
  const json summary = readJson(info);
  ASSERT_TRUE(summary.at("heights_m").is_array()) << summary.dump();
  EXPECT_NEAR(summary.at("heights_m").at(0).get<double>(), 0.0, 0.15);
  EXPECT_NEAR(summary.at("heights_m").at(1).get<double>(), 3.0, 0.15);
}
#endif

}  // namespace
