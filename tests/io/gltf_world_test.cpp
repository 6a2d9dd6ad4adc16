// Tests for glTF world files (libs/io world_file, gltf_scene, world_footprint): the example world
// scenarios/gallery.gltf loads into the expected walkable area, obstacles, points and crowds;
// naming and property errors name the node and what was expected; a .glb loads the same; and
// `throng run scenarios/gallery.gltf` works end to end.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "throng/io/scenario_loader.hpp"
#include "throng/io/world_file.hpp"
#include "throng/core/parallel.hpp"
#include "throng/sim/world.hpp"

namespace {

using nlohmann::json;
namespace io = throng::io;

const std::string kGallery = std::string(THRONG_SOURCE_DIR) + "/scenarios/gallery.gltf";

json gallery() {
  std::ifstream in(kGallery);
  return json::parse(in);
}

json& node(json& g, const std::string& name) {
  for (auto& n : g["nodes"]) {
    if (n.value("name", "") == name) return n;
  }
  throw std::runtime_error("no node " + name);
}

/// Loads a (modified) gallery and returns every diagnostic, formatted, one per line.
std::string errorsOf(const json& g) {
  const auto r = io::parseWorld(g.dump(), "world.gltf", {.checkReachability = true});
  if (r.ok()) return "";
  return throng::core::formatAll(r.errors());
}

double area(const throng::core::Polygon& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto& u = p[i];
    const auto& v = p[(i + 1) % p.size()];
    a += static_cast<double>(u.x) * v.y - static_cast<double>(v.x) * u.y;
  }
  return std::abs(a) / 2;
}

TEST(GltfWorld, GalleryLoadsIntoTheExpectedScenario) {
  const auto r = io::loadScenarioFile(kGallery);  // routed by extension
  ASSERT_TRUE(r.ok()) << throng::core::formatAll(r.errors());
  const auto& d = r.value().desc;
  EXPECT_EQ(d.name, "gallery");
  EXPECT_EQ(d.seed, 3u);
  EXPECT_FLOAT_EQ(d.duration, 120.0f);
  // Two overlapping slabs (30×12 and 10×15, overlap 10×2) become one L-shaped polygon.
  ASSERT_EQ(d.walkable.size(), 1u);
  EXPECT_NEAR(area(d.walkable[0]), 30 * 12 + 10 * 15 - 10 * 2, 0.01);
  EXPECT_EQ(d.walkable[0].size(), 6u);  // collinear vertices removed
  // Three boxes: two 1.2×1.2 plinths and a rotated 0.4×6 wall.
  ASSERT_EQ(d.obstacles.size(), 3u);
  EXPECT_NEAR(area(d.obstacles[0]), 1.44, 0.01);
  EXPECT_NEAR(area(d.obstacles[2]), 2.4, 0.01);
  ASSERT_EQ(d.points.size(), 5u);
  EXPECT_EQ(d.points[0].id, "painting_a");
  EXPECT_NEAR(d.points[0].position.x, 5, 1e-4);
  EXPECT_NEAR(d.points[0].position.y, 11, 1e-4);  // glTF z = -11 → ground y = 11
  EXPECT_EQ(d.points[3].id, "bench");
  EXPECT_EQ(d.points[3].kind, throng::sim::PointKind::Action);
  EXPECT_EQ(d.points[3].action, "sit");
  EXPECT_FLOAT_EQ(d.points[3].actionDuration, 8.0f);
  EXPECT_EQ(d.points[3].category, "rest");
  EXPECT_NEAR(d.points[3].orientation.x, 0, 1e-5);  // faces ground -y (the rotation's yaw)
  EXPECT_NEAR(d.points[3].orientation.y, -1, 1e-5);
  EXPECT_EQ(d.points[4].kind, throng::sim::PointKind::Exit);
  ASSERT_EQ(d.populations.size(), 2u);
  const auto& visitors = d.populations[0];
  EXPECT_EQ(visitors.id, "visitors");
  EXPECT_EQ(visitors.groups, 8u);
  EXPECT_EQ(visitors.sizeMin, 1u);
  EXPECT_EQ(visitors.sizeMax, 3u);
  EXPECT_EQ(visitors.goals.size(), 5u);
  ASSERT_EQ(visitors.spawn.kind, throng::sim::SpawnKind::Polygon);
  EXPECT_NEAR(area(visitors.spawn.polygon), 4 * 8, 0.01);  // the node's unit square scaled 2 × 4
  const auto& tour = d.populations[1];
  EXPECT_EQ(tour.guide.script.size(), 3u);
  EXPECT_TRUE(r.value().navmesh != nullptr);
  // The text is a scenario JSON: it loads by itself (how recordings replay a world).
  const auto again = io::parseScenario(r.value().text, kGallery);
  ASSERT_TRUE(again.ok()) << throng::core::formatAll(again.errors());
  EXPECT_EQ(again.value().desc.points.size(), 5u);
}

TEST(GltfWorld, PopulationErrorsNameTheNodeAndExtrasKey) {
  json g = gallery();
  node(g, "crowd:visitors")["extras"]["throng"]["groups"] = 0;
  const std::string e = errorsOf(g);
  EXPECT_NE(e.find("world.gltf node 10 \"crowd:visitors\" /extras/throng/groups: value 0"), std::string::npos) << e;
  EXPECT_NE(e.find("expected an integer"), std::string::npos) << e;
  std::printf("%s\n", e.c_str());
}

TEST(GltfWorld, UnknownGoalGetsDidYouMean) {
  json g = gallery();
  node(g, "crowd:tour")["extras"]["throng"]["goals"] = {"dor"};
  const std::string e = errorsOf(g);
  EXPECT_NE(e.find("node 11 \"crowd:tour\" /extras/throng/goals/0: unknown point \"dor\""), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean \"door\"?"), std::string::npos) << e;
}

TEST(GltfWorld, UnknownPopulationKeyGetsDidYouMean) {
  json g = gallery();
  node(g, "crowd:tour")["extras"]["throng"]["wandr"] = true;
  const std::string e = errorsOf(g);
  EXPECT_NE(e.find("node 11 \"crowd:tour\" /extras/throng/wandr: unknown key \"wandr\""), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean \"wander\"?"), std::string::npos) << e;
}

TEST(GltfWorld, MisspeltNodeKindsGetDidYouMean) {
  json g = gallery();
  node(g, "interest:painting_b")["name"] = "intrest:painting_b";
  node(g, "obstacle_wall")["name"] = "obstalce_wall";
  const std::string e = errorsOf(g);
  EXPECT_NE(e.find("node 6 \"intrest:painting_b\": unknown node kind \"intrest\""), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean \"interest:\"?"), std::string::npos) << e;
  EXPECT_NE(e.find("node 4 \"obstalce_wall\": name \"obstalce_wall\" looks like a misspelt"), std::string::npos) << e;
}

TEST(GltfWorld, ContradictoryPropertiesAreErrors) {
  json g = gallery();
  node(g, "walkable_hall")["extras"] = {{"throng", {{"obstacle", true}}}};
  node(g, "obstacle_plinth_1")["extras"] = {{"throng", {{"obstacle", false}}}};
  node(g, "Lamp")["extras"] = {{"throng", {{"walkable", true}, {"obstacle", true}}}};
  const std::string e = errorsOf(g);
  EXPECT_NE(e.find("node 0 \"walkable_hall\" /extras/throng/obstacle: contradictory properties"), std::string::npos) << e;
  EXPECT_NE(e.find("node 2 \"obstacle_plinth_1\" /extras/throng/obstacle: contradictory properties"), std::string::npos) << e;
  EXPECT_NE(e.find("node 12 \"Lamp\" /extras/throng: contradictory properties: both walkable and obstacle"), std::string::npos)
      << e;
}

TEST(GltfWorld, NodeGivenKeysAndStrayPropertiesAreErrors) {
  json g = gallery();
  node(g, "interest:sculpture")["extras"]["throng"]["position"] = {1, 2};
  node(g, "Lamp")["extras"] = {{"throng", {{"radius", 2}}}};
  g["scenes"][0]["extras"]["throng"]["populations"] = json::array();
  const std::string e = errorsOf(g);
  EXPECT_NE(e.find("node 7 \"interest:sculpture\" /extras/throng/position: key \"position\" comes from the node itself"),
            std::string::npos) << e;
  EXPECT_NE(e.find("node 12 \"Lamp\" /extras/throng: throng properties on a node with no throng role"), std::string::npos) << e;
  EXPECT_NE(e.find("scene 0 /extras/throng/populations: key \"populations\" is not set"), std::string::npos) << e;
}

TEST(GltfWorld, PointPropertyErrorsMapBackToTheNode) {
  json g = gallery();
  node(g, "action:bench")["extras"]["throng"]["duration"] = -1;
  node(g, "interest:painting_a")["extras"]["throng"]["action"] = "look";
  const std::string e = errorsOf(g);
  EXPECT_NE(e.find("node 8 \"action:bench\" /extras/throng/duration: value -1"), std::string::npos) << e;
  EXPECT_NE(e.find("node 5 \"interest:painting_a\" /extras/throng/action: \"action\" only applies to action points"),
            std::string::npos) << e;
  std::printf("%s\n", e.c_str());
}

TEST(GltfWorld, ScenarioKeyTypoInSceneExtras) {
  json g = gallery();
  g["scenes"][0]["extras"]["throng"]["sed"] = 4;
  const std::string e = errorsOf(g);
  EXPECT_NE(e.find("scene 0 /extras/throng/sed: unknown key \"sed\""), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean \"seed\"?"), std::string::npos) << e;
}

TEST(GltfWorld, MissingFloorAndBadFileAreReported) {
  json g = gallery();
  node(g, "walkable_hall")["name"] = "hall";
  node(g, "walkable_wing")["name"] = "wing";
  EXPECT_NE(errorsOf(g).find("world.gltf: the world has no walkable surface"), std::string::npos) << errorsOf(g);
  const auto bad = io::parseWorld("{\"asset\": 1}", "bad.gltf");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.errors()[0].what.find("not a valid glTF 2.0 file"), std::string::npos);
  const auto missing = io::loadScenarioFile("/nonexistent/world.glb");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.errors()[0].what.find("cannot open file"), std::string::npos);
}

TEST(GltfWorld, WalkableMeshWithoutMeshIsAnError) {
  json g = gallery();
  node(g, "walkable_wing").erase("mesh");
  EXPECT_NE(errorsOf(g).find("node 1 \"walkable_wing\": a walkable node without a mesh"), std::string::npos) << errorsOf(g);
}

/// Packs the gallery as a .glb: JSON chunk plus the buffer as the BIN chunk.
std::string toGlb(json g) {
  const std::string uri = g["buffers"][0]["uri"];
  const std::string b64 = uri.substr(uri.find(',') + 1);
  static const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string bin;
  unsigned acc = 0;
  int bits = 0;
  for (const char c : b64) {
    const auto pos = alphabet.find(c);
    if (pos == std::string::npos) continue;
    acc = (acc << 6) | static_cast<unsigned>(pos);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      bin.push_back(static_cast<char>((acc >> bits) & 0xff));
    }
  }
  g["buffers"][0].erase("uri");
  std::string js = g.dump();
  while (js.size() % 4) js.push_back(' ');
  while (bin.size() % 4) bin.push_back('\0');
  auto u32 = [](std::string& s, std::uint32_t v) {
    char b[4];
    std::memcpy(b, &v, 4);
    s.append(b, 4);
  };
  std::string out = "glTF";
  u32(out, 2);
  u32(out, static_cast<std::uint32_t>(12 + 8 + js.size() + 8 + bin.size()));
  u32(out, static_cast<std::uint32_t>(js.size()));
  u32(out, 0x4E4F534A);  // JSON
  out += js;
  u32(out, static_cast<std::uint32_t>(bin.size()));
  u32(out, 0x004E4942);  // BIN
  out += bin;
  return out;
}

TEST(GltfWorld, NodeCyclesAreErrorsNamingTheNode) {
  // A node that is its own child (the gallery's lamp).
  json g = gallery();
  node(g, "Lamp")["children"] = {12};
  std::string e = errorsOf(g);
  EXPECT_NE(e.find("world.gltf /nodes/12/children/0: node 12 \"Lamp\" is its own ancestor (children cycle 12 → 12); "
                   "expected a node hierarchy without cycles (a tree)"),
            std::string::npos)
      << e;
  // Two nodes that are each other's child, neither in the scene (a cycle is found wherever it is).
  g = gallery();
  g["scenes"][0]["nodes"] = json::array({0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10});
  node(g, "crowd:tour")["children"] = {12};
  node(g, "Lamp")["children"] = {11};
  e = errorsOf(g);
  EXPECT_NE(e.find("node 11 \"crowd:tour\" is its own ancestor (children cycle 11 → 12 → 11)"), std::string::npos) << e;
  EXPECT_NE(e.find("world.gltf /nodes/12/children/0: "), std::string::npos) << e;
  // A node with two parents, a scene root that is someone's child, a child that does not exist.
  g = gallery();
  node(g, "walkable_hall")["children"] = {12};
  node(g, "walkable_wing")["children"] = {12, 40};
  e = errorsOf(g);
  EXPECT_NE(e.find("/nodes/1/children/0: node 12 \"Lamp\" is a child of node 0 \"walkable_hall\" already, and of node 1 "
                   "\"walkable_wing\"; expected each node a child of at most one node (a tree)"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("/nodes/1/children/1: node 1 \"walkable_wing\" names child 40, which does not exist; expected a node index 0 … 12"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("/scenes/0/nodes/12: scene 0 names node 12 \"Lamp\" as a root, but it is a child of node 0"), std::string::npos) << e;
}

TEST(GltfWorld, ABadSceneIndexIsAnError) {
  json g = gallery();
  g["scene"] = 3;
  std::string e = errorsOf(g);
  EXPECT_NE(e.find("world.gltf /scene: scene 3 does not exist (the file has 1 scene); expected a scene index 0 … 0"),
            std::string::npos)
      << e;
  g["scene"] = -2;
  EXPECT_NE(errorsOf(g).find("/scene: scene -2 does not exist"), std::string::npos) << errorsOf(g);
  g = gallery();
  g["scenes"][0]["nodes"].push_back(99);
  e = errorsOf(g);
  EXPECT_NE(e.find("world.gltf /scenes/0/nodes/13: scene 0 names node 99, which does not exist; expected a node index 0 … 12"),
            std::string::npos)
      << e;
}

TEST(GltfWorld, NestingDeeperThan64LevelsIsAnError) {
  json g = gallery();
  const std::size_t first = g["nodes"].size();
  for (std::size_t i = 0; i < 70; ++i) {
    json n = {{"name", "level" + std::to_string(i)}};
    if (i + 1 < 70) n["children"] = {first + i + 1};
    g["nodes"].push_back(n);
  }
  g["scenes"][0]["nodes"].push_back(first);
  const std::string e = errorsOf(g);
  EXPECT_NE(e.find("is nested more than 64 levels deep; expected at most 64 levels of child nodes"), std::string::npos) << e;
}

TEST(GltfWorld, GlbLoadsLikeGltf) {
  const auto r = io::parseWorld(toGlb(gallery()), "gallery.glb");
  ASSERT_TRUE(r.ok()) << throng::core::formatAll(r.errors());
  EXPECT_EQ(r.value().desc.walkable.size(), 1u);
  EXPECT_EQ(r.value().desc.obstacles.size(), 3u);
  EXPECT_EQ(r.value().desc.populations.size(), 2u);
}

TEST(GltfWorld, GalleryRunsInTheSimulation) {
  auto r = io::loadWorldFile(kGallery);
  ASSERT_TRUE(r.ok()) << throng::core::formatAll(r.errors());
  auto world = throng::sim::World::create(r.value().desc, r.value().navmesh);
  ASSERT_TRUE(world.ok()) << throng::core::formatAll(world.errors());
  const throng::core::TaskSystem tasks(1);
  for (int i = 0; i < 100; ++i) world.value()->step(tasks);  // 5 s at dt = 0.05 s
  EXPECT_EQ(world.value()->groupCount(), 9u);  // 8 visitor groups + the tour
}

TEST(GltfWorld, BufferFilesAreConfinedToTheWorldsDirectory) {
  // The gallery's buffer as a file: next to the world it loads; one directory up it is refused.
  const std::filesystem::path dir = std::filesystem::path(THRONG_BINARY_DIR) / "gltf_confinement";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "world");
  json g = gallery();
  const std::string uri = g["buffers"][0]["uri"];
  const std::string prefix = "base64,";
  const auto comma = uri.find(prefix);
  ASSERT_NE(comma, std::string::npos);
  // Decode the data: URI (standard base64) into bytes.
  std::string bytes;
  int bits = 0, value = 0;
  for (char c : uri.substr(comma + prefix.size())) {
    const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const char* at = std::strchr(table, c);
    if (c == '=' || at == nullptr) break;
    value = (value << 6) | static_cast<int>(at - table);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      bytes.push_back(static_cast<char>((value >> bits) & 0xff));
    }
  }
  for (const auto& file : {dir / "world" / "gallery.bin", dir / "outside.bin"}) {
    std::ofstream(file, std::ios::binary) << bytes;
  }
  g["buffers"][0]["uri"] = "gallery.bin";
  std::ofstream(dir / "world" / "inside.gltf") << g.dump();
  const auto inside = io::loadWorldFile((dir / "world" / "inside.gltf").string());
  EXPECT_TRUE(inside.ok()) << (inside.ok() ? "" : throng::core::formatAll(inside.errors()));
  for (const std::string& bad : std::vector<std::string>{"../outside.bin", (dir / "outside.bin").string()}) {
    g["buffers"][0]["uri"] = bad;
    std::ofstream(dir / "world" / "escape.gltf") << g.dump();
    const auto r = io::loadWorldFile((dir / "world" / "escape.gltf").string());
    ASSERT_FALSE(r.ok()) << bad;
    const std::string text = throng::core::formatAll(r.errors());
    EXPECT_NE(text.find("outside the world file's directory"), std::string::npos) << text;
    EXPECT_NE(text.find("escape.gltf"), std::string::npos) << text;
  }
}

#ifdef THRONG_EXE
TEST(GltfWorld, ThrongRunsTheGallery) {
  // A fresh directory each run: `throng run` refuses to overwrite a recording without --force.
  const std::filesystem::path dir = std::filesystem::path(THRONG_BINARY_DIR) / "gltf_world_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string cmd = std::string("cd '") + dir.string() + "' && '" + THRONG_EXE + "' run '" + kGallery +
                          "' --duration 5 > run.log 2>&1";
  const int rc = std::system(cmd.c_str());
  std::ifstream log(dir / "run.log");
  std::stringstream text;
  text << log.rdbuf();
  EXPECT_EQ(rc, 0) << text.str();
  const std::string check = std::string("'") + THRONG_EXE + "' check '" + kGallery + "' > /dev/null 2>&1";
  EXPECT_EQ(std::system(check.c_str()), 0);
}
#endif

}  // namespace
