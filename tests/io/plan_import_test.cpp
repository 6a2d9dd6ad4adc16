// Floor plan import (plan_import.cpp, dxf_reader.cpp, wkt_reader.cpp): every DXF entity kind and
// WKT geometry, units and scale, layer roles, the bounding rectangle when nothing is walkable, and
// bad files with located errors (DXF file:line, WKT file:line:column); every fragment loads as a
// scenario.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "throng/io/plan_import.hpp"
#include "throng/io/scenario_loader.hpp"

namespace throng::io {
namespace {

using Groups = std::vector<std::pair<int, std::string>>;

/// A DXF text from (code, value) pairs: pair k's code is on line 2k + 1.
std::string dxf(const Groups& groups) {
  std::string out;
  for (const auto& [code, value] : groups) out += std::to_string(code) + "\n" + value + "\n";
  return out;
}

/// A whole DXF file: $INSUNITS `units` (none when < 0) and these entities.
std::string drawing(const Groups& entities, int units = -1) {
  Groups g = {{0, "SECTION"}, {2, "HEADER"}};
  if (units >= 0) g.insert(g.end(), {{9, "$INSUNITS"}, {70, std::to_string(units)}});
  g.insert(g.end(), {{0, "ENDSEC"}, {0, "SECTION"}, {2, "ENTITIES"}});
  g.insert(g.end(), entities.begin(), entities.end());
  g.insert(g.end(), {{0, "ENDSEC"}, {0, "EOF"}});
  return dxf(g);
}

Groups line(const std::string& layer, double x0, double y0, double x1, double y1) {
  return {{0, "LINE"}, {8, layer}, {10, std::to_string(x0)}, {20, std::to_string(y0)}, {11, std::to_string(x1)}, {21, std::to_string(y1)}};
}

Groups lwpolyline(const std::string& layer, const std::vector<std::pair<double, double>>& points, bool closed) {
  Groups g = {{0, "LWPOLYLINE"}, {8, layer}, {90, std::to_string(points.size())}, {70, closed ? "1" : "0"}};
  for (const auto& [x, y] : points) g.insert(g.end(), {{10, std::to_string(x)}, {20, std::to_string(y)}});
  return g;
}

Groups operator+(Groups a, const Groups& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

const std::vector<std::pair<double, double>> kRoom = {{0, 0}, {10, 0}, {10, 8}, {0, 8}};

nlohmann::json importOk(const std::string& text, PlanFormat format, const PlanImportOptions& options = {}) {
  auto r = importPlan(text, format, "plan", options);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : core::formatAll(r.errors())) << "\n" << text.substr(0, 2000);
  if (!r.ok()) return {};
  // Every fragment is a valid scenario once the format and populations are added.
  nlohmann::json scenario = r.value();
  scenario["format"] = "throng/1";
  scenario["populations"] = nlohmann::json::array();
  auto loaded = parseScenario(scenario.dump(), "fragment.json", LoadOptions{false});
  EXPECT_TRUE(loaded.ok()) << (loaded.ok() ? "" : core::formatAll(loaded.errors()));
  return r.value();
}

core::Diagnostic importError(const std::string& text, PlanFormat format, const PlanImportOptions& options = {}) {
  auto r = importPlan(text, format, "plan", options);
  EXPECT_FALSE(r.ok()) << "expected an error for:\n" << text.substr(0, 2000);
  return r.ok() ? core::Diagnostic{} : r.errors().front();
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

double radiusOf(const nlohmann::json& p, double cx, double cy) { return std::hypot(p[0].get<double>() - cx, p[1].get<double>() - cy); }

TEST(PlanImportDxf, LayersDecideWalkableObstaclesAndWalls) {
  const auto f = importOk(drawing(lwpolyline("Floor", kRoom, true) + line("A-WALL", 5, 0, 5, 6) +
                                  lwpolyline("FURNITURE", {{1, 1}, {2, 1}, {2, 2}, {1, 2}}, true) +
                                  lwpolyline("0", {{7, 1}, {8, 2}, {9, 1}}, false)),
                          PlanFormat::Dxf);
  ASSERT_EQ(f["walkable"].size(), 1u);
  EXPECT_EQ(f["walkable"][0], nlohmann::json::parse("[[0,0],[10,0],[10,8],[0,8]]"));
  ASSERT_EQ(f["obstacles"].size(), 1u);
  EXPECT_EQ(f["obstacles"][0][2], nlohmann::json::parse("[2,2]"));
  ASSERT_EQ(f["walls"].size(), 2u);  // the LINE on the wall layer and the open polyline
  EXPECT_EQ(f["walls"][0]["line"], nlohmann::json::parse("[[5,0],[5,6]]"));
  EXPECT_EQ(f["walls"][0]["thickness"], 0.2);
  EXPECT_EQ(f["walls"][1]["line"].size(), 3u);
}

TEST(PlanImportDxf, LayerMapOverridesTheNameRule) {
  PlanImportOptions options;
  options.layers = {{"zone", PlanRole::Walkable}, {"FURNITURE", PlanRole::Ignore}, {"A-WALL", PlanRole::Obstacle}};
  options.wallThickness = 0.3;
  const auto f = importOk(drawing(lwpolyline("ZONE", kRoom, true) + lwpolyline("furniture", {{1, 1}, {2, 1}, {2, 2}}, true) +
                                  lwpolyline("A-WALL", {{3, 3}, {4, 3}, {4, 4}}, true) + line("A-WALL", 5, 0, 5, 6)),
                          PlanFormat::Dxf, options);
  EXPECT_EQ(f["walkable"].size(), 1u);
  EXPECT_EQ(f["obstacles"].size(), 1u);  // the closed shape on A-WALL; the furniture is ignored
  ASSERT_EQ(f["walls"].size(), 1u);      // open lines stay walls on any layer but an ignored one
  EXPECT_EQ(f["walls"][0]["thickness"], 0.3);
}

TEST(PlanImportDxf, ClosedShapesOnWallLayersAreClosedWalls) {
  const auto f = importOk(drawing(lwpolyline("Walls", kRoom, true)), PlanFormat::Dxf);
  ASSERT_EQ(f["walls"].size(), 1u);
  EXPECT_EQ(f["walls"][0]["line"], nlohmann::json::parse("[[0,0],[10,0],[10,8],[0,8],[0,0]]"));
  // Nothing walkable: the bounding rectangle of everything is.
  EXPECT_EQ(f["walkable"][0], nlohmann::json::parse("[[0,0],[10,0],[10,8],[0,8]]"));
}

TEST(PlanImportDxf, AnOpenPolylineBackAtItsStartIsClosed) {
  auto room = kRoom;
  room.push_back(room.front());
  const auto f = importOk(drawing(lwpolyline("room", room, false)), PlanFormat::Dxf);
  ASSERT_EQ(f["walkable"].size(), 1u);
  EXPECT_EQ(f["walkable"][0].size(), 4u);
  EXPECT_TRUE(f["walls"].empty());
}

TEST(PlanImportDxf, UnitsAndScale) {
  const Groups room = lwpolyline("floor", {{0, 0}, {1000, 0}, {1000, 500}, {0, 500}}, true);
  const std::pair<int, double> units[] = {{4, 1.0}, {5, 10.0}, {6, 1000.0}, {1, 25.4}, {2, 304.8}, {0, 1000.0}};
  for (const auto& [code, metres] : units) {
    const auto f = importOk(drawing(room, code), PlanFormat::Dxf);
    EXPECT_NEAR(f["walkable"][0][2][0].get<double>(), metres, metres * 1e-6) << "$INSUNITS " << code;
  }
  PlanImportOptions half;
  half.scale = 0.5;
  EXPECT_NEAR(importOk(drawing(room, 4), PlanFormat::Dxf, half)["walkable"][0][2][1].get<double>(), 0.25, 1e-9);
  const auto d = importError(drawing(room, 11), PlanFormat::Dxf);
  EXPECT_TRUE(contains(d.what, "$INSUNITS \"11\"")) << d.format();
  EXPECT_EQ(d.line, 8);  // the value line of group 70
}

TEST(PlanImportDxf, BulgesBecomeArcs) {
  // A half disc: from (0, 0) to (2, 0) with bulge 1 (180° counter-clockwise: below the chord), back straight.
  const Groups half = {{0, "LWPOLYLINE"}, {8, "floor"}, {90, "2"}, {70, "1"}, {10, "0"}, {20, "0"}, {42, "1"}, {10, "2"}, {20, "0"}};
  const auto f = importOk(drawing(half), PlanFormat::Dxf);
  const auto& ring = f["walkable"][0];
  ASSERT_EQ(ring.size(), 17u);  // 16 segments for half of 32 per turn
  double lowest = 0;
  for (const auto& p : ring) {
    EXPECT_NEAR(radiusOf(p, 1, 0), 1.0, 1e-5);
    lowest = std::min(lowest, p[1].get<double>());
  }
  EXPECT_NEAR(lowest, -1.0, 1e-6);
}

TEST(PlanImportDxf, PolylineVertexSeqend) {
  const Groups poly = {{0, "POLYLINE"}, {8, "COLUMNS"}, {66, "1"}, {70, "1"},
                       {0, "VERTEX"}, {8, "COLUMNS"}, {10, "1"}, {20, "1"},
                       {0, "VERTEX"}, {10, "3"}, {20, "1"},
                       {0, "VERTEX"}, {10, "3"}, {20, "2"},
                       {0, "SEQEND"}};
  const auto f = importOk(drawing(lwpolyline("floor", kRoom, true) + poly), PlanFormat::Dxf);
  EXPECT_EQ(f["obstacles"][0], nlohmann::json::parse("[[1,1],[3,1],[3,2]]"));
}

TEST(PlanImportDxf, CirclesAndArcs) {
  const Groups circle = {{0, "CIRCLE"}, {8, "columns"}, {10, "5"}, {20, "4"}, {40, "0.5"}};
  const Groups arc = {{0, "ARC"}, {8, "0"}, {10, "0"}, {20, "0"}, {40, "2"}, {50, "0"}, {51, "90"}};
  PlanImportOptions options;
  options.arcSegments = 16;
  const auto f = importOk(drawing(lwpolyline("floor", kRoom, true) + circle + arc), PlanFormat::Dxf, options);
  ASSERT_EQ(f["obstacles"].size(), 1u);
  EXPECT_EQ(f["obstacles"][0].size(), 16u);
  for (const auto& p : f["obstacles"][0]) EXPECT_NEAR(radiusOf(p, 5, 4), 0.5, 1e-5);
  const auto& wall = f["walls"][0]["line"];
  ASSERT_EQ(wall.size(), 5u);  // a quarter turn: 4 segments
  EXPECT_EQ(wall[0], nlohmann::json::parse("[2,0]"));
  EXPECT_EQ(wall[4], nlohmann::json::parse("[0,2]"));
}

TEST(PlanImportDxf, NegativeExtrusionMirrorsX) {
  Groups poly = lwpolyline("obstacle", {{1, 1}, {2, 1}, {2, 2}}, true);
  poly.insert(poly.end(), {{210, "0"}, {220, "0"}, {230, "-1"}});
  const auto f = importOk(drawing(lwpolyline("floor", {{-10, 0}, {0, 0}, {0, 5}, {-10, 5}}, true) + poly), PlanFormat::Dxf);
  EXPECT_EQ(f["obstacles"][0][0], nlohmann::json::parse("[-1,1]"));
}

TEST(PlanImportDxf, OtherEntitiesAndSectionsAreSkipped) {
  const Groups text = {{0, "TEXT"}, {8, "0"}, {10, "1"}, {20, "1"}, {1, "Lobby"}};
  std::string file = dxf({{999, "a comment"}, {0, "SECTION"}, {2, "TABLES"}, {0, "TABLE"}, {2, "LAYER"}, {0, "ENDTAB"}, {0, "ENDSEC"}});
  file += drawing(text + lwpolyline("floor", kRoom, true));
  EXPECT_EQ(importOk(file, PlanFormat::Dxf)["walkable"].size(), 1u);
  // CRLF line ends and indented group codes, as some exporters write them.
  std::string crlf;
  for (const char c : drawing(lwpolyline("floor", kRoom, true))) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  EXPECT_EQ(importOk("  " + crlf, PlanFormat::Dxf)["walkable"].size(), 1u);
}

TEST(PlanImportDxf, BadFilesGetLocatedErrors) {
  auto d = importError("AutoCAD Binary DXF\r\n\x1a", PlanFormat::Dxf);
  EXPECT_TRUE(contains(d.what, "binary DXF")) << d.format();
  EXPECT_TRUE(contains(d.hint, "ASCII")) << d.format();

  d = importError(dxf({{0, "SECTION"}, {2, "ENTITIES"}}) + "ten\nLINE\n", PlanFormat::Dxf);
  EXPECT_EQ(d.line, 5);
  EXPECT_TRUE(contains(d.what, "\"ten\" is not a DXF group code")) << d.format();
  EXPECT_EQ(d.source, "plan");

  d = importError(drawing(line("0", 0, 0, 1, 1) + Groups{{0, "LINE"}, {10, "1,5"}, {20, "0"}, {11, "2"}, {21, "2"}}),
                  PlanFormat::Dxf);
  EXPECT_TRUE(contains(d.what, "\"1,5\" of group code 10 is not a number")) << d.format();
  EXPECT_EQ(d.line, 26);  // pair 12 (0-based): the value line of its code 10

  d = importError(drawing(Groups{{0, "LINE"}, {10, "0"}, {20, "0"}}), PlanFormat::Dxf);
  EXPECT_TRUE(contains(d.what, "LINE without both end points")) << d.format();
  EXPECT_EQ(d.line, 11);  // the first entity is pair 5

  d = importError(dxf({{0, "SECTION"}, {2, "ENTITIES"}}) + dxf(line("0", 0, 0, 1, 1)), PlanFormat::Dxf);
  EXPECT_TRUE(contains(d.what, "has no end")) << d.format();
  EXPECT_EQ(d.line, 1);

  d = importError(drawing(Groups{{0, "POLYLINE"}, {70, "0"}, {0, "VERTEX"}, {10, "0"}, {20, "0"}, {0, "LINE"}}), PlanFormat::Dxf);
  EXPECT_TRUE(contains(d.what, "inside the POLYLINE at line 11")) << d.format();
  d = importError(drawing(Groups{{0, "VERTEX"}, {10, "0"}, {20, "0"}}), PlanFormat::Dxf);
  EXPECT_TRUE(contains(d.what, "VERTEX outside a POLYLINE")) << d.format();
  d = importError(drawing(Groups{{0, "POLYLINE"}, {70, "64"}}), PlanFormat::Dxf);
  EXPECT_TRUE(contains(d.what, "polyface mesh")) << d.format();

  d = importError(drawing(lwpolyline("floor", {{0, 0}, {4, 4}, {4, 0}, {0, 4}}, true)), PlanFormat::Dxf);
  EXPECT_TRUE(contains(d.what, "LWPOLYLINE on layer \"floor\" crosses itself")) << d.format();
  EXPECT_EQ(d.line, 11);

  d = importError(drawing(lwpolyline("floor", {{0, 0}, {200, 0}, {200, 1}}, true), 7), PlanFormat::Dxf);
  EXPECT_TRUE(contains(d.what, "beyond ±100000 m")) << d.format();

  d = importError(dxf({{0, "SECTION"}, {2, "HEADER"}, {0, "ENDSEC"}, {0, "EOF"}}), PlanFormat::Dxf);
  EXPECT_TRUE(contains(d.what, "no ENTITIES section")) << d.format();
  d = importError(drawing({}), PlanFormat::Dxf);
  EXPECT_TRUE(contains(d.what, "no geometry")) << d.format();
  d = importError(drawing(line("0", 0, 0, 5, 0)), PlanFormat::Dxf);
  EXPECT_TRUE(contains(d.what, "bounding rectangle has no area")) << d.format();
}

TEST(PlanImportDxf, HostileSizesAreRefused) {
  PlanImportOptions fine;
  fine.arcSegments = 1024;
  Groups circles;
  for (int i = 0; i < 2000; ++i) circles.insert(circles.end(), {{0, "CIRCLE"}, {10, std::to_string(i)}, {20, "0"}, {40, "0.4"}});
  const auto d = importError(drawing(circles), PlanFormat::Dxf, fine);
  EXPECT_TRUE(contains(d.what, "more than 2000000 vertices")) << d.format();
  EXPECT_GT(d.line, 0);
  PlanImportOptions bad;
  bad.scale = 0;
  EXPECT_TRUE(contains(importError(drawing(line("0", 0, 0, 1, 1)), PlanFormat::Dxf, bad).expected, "scale > 0"));
}

TEST(PlanImportWkt, PolygonsHolesAndLines) {
  const auto f = importOk("POLYGON ((0 0, 10 0, 10 8, 0 8, 0 0), (2 2, 3 2, 3 3, 2 3, 2 2))\n"
                          "LINESTRING (5 0, 5 6)\n"
                          "MULTILINESTRING ((1 7, 2 7), (8 1, 8 2, 9 2))",
                          PlanFormat::Wkt);
  EXPECT_EQ(f["walkable"][0], nlohmann::json::parse("[[0,0],[10,0],[10,8],[0,8]]"));
  EXPECT_EQ(f["obstacles"][0], nlohmann::json::parse("[[2,2],[3,2],[3,3],[2,3]]"));
  ASSERT_EQ(f["walls"].size(), 3u);
  EXPECT_EQ(f["walls"][2]["line"].size(), 3u);
}

TEST(PlanImportWkt, MultiPolygonsCollectionsDimensionsAndSrid) {
  const auto f = importOk("SRID=25832;GEOMETRYCOLLECTION Z (MULTIPOLYGON Z (((0 0 1, 4 0 1, 4 4 1, 0 4 1)), ((5 0 0, 9 0 0, 9 4 0))),"
                          " POINT (1 1), MULTIPOINT ((2 2), (3 3)), MULTIPOINT (2 2, 3 3),"
                          " GEOMETRYCOLLECTION (LINESTRING ZM (0 0 0 0, 1 1 0 0)), LINESTRING EMPTY);\n"
                          "polygon((10 0, 12 0, 12 2))",
                          PlanFormat::Wkt);
  EXPECT_EQ(f["walkable"].size(), 3u);
  EXPECT_EQ(f["walkable"][1], nlohmann::json::parse("[[5,0],[9,0],[9,4]]"));
  EXPECT_EQ(f["walls"].size(), 1u);
  PlanImportOptions mm;
  mm.scale = 0.001;
  EXPECT_EQ(importOk("POLYGON ((0 0, 1500 0, 1500 1000))", PlanFormat::Wkt, mm)["walkable"][0][1],
            nlohmann::json::parse("[1.5,0]"));
}

TEST(PlanImportWkt, BadTextGetsLineAndColumn) {
  auto d = importError("POLYGON ((0 0, 1 0, 1 1))\nCIRCULARSTRING (0 0, 1 1, 2 0)", PlanFormat::Wkt);
  EXPECT_EQ(d.line, 2);
  EXPECT_EQ(d.column, 1);
  EXPECT_TRUE(contains(d.what, "\"CIRCULARSTRING\" is not a geometry")) << d.format();
  EXPECT_TRUE(contains(d.expected, "MULTIPOLYGON")) << d.format();

  d = importError("POLYGON ((0 0, 1 0, 1 1)", PlanFormat::Wkt);
  EXPECT_TRUE(contains(d.what, "the end of the text where ')' belongs")) << d.format();
  EXPECT_EQ(d.line, 1);
  EXPECT_EQ(d.column, 25);

  d = importError("LINESTRING (0 0, 1)", PlanFormat::Wkt);
  EXPECT_TRUE(contains(d.what, "\")\" where a coordinate belongs")) << d.format();
  EXPECT_EQ(d.column, 19);
  d = importError("LINESTRING (0 0 0 0 0, 1 1)", PlanFormat::Wkt);
  EXPECT_TRUE(contains(d.what, "5 coordinates")) << d.format();

  d = importError("POLYGON ((0 0, 4 4, 4 0, 0 4))", PlanFormat::Wkt);
  EXPECT_TRUE(contains(d.what, "POLYGON crosses itself")) << d.format();
  EXPECT_EQ(d.column, 10);

  std::string deep;
  for (int i = 0; i < 40; ++i) deep += "GEOMETRYCOLLECTION (";
  d = importError(deep, PlanFormat::Wkt);
  EXPECT_TRUE(contains(d.what, "nested more than 32 deep")) << d.format();

  d = importError("  \n ", PlanFormat::Wkt);
  EXPECT_TRUE(contains(d.what, "no geometry")) << d.format();
  d = importError("POINT (1 1)", PlanFormat::Wkt);
  EXPECT_TRUE(contains(d.what, "holds no geometry to import")) << d.format();
}

TEST(PlanImport, FormatFromTheFileName) {
  EXPECT_EQ(planFormatOf("plans/Floor.DXF"), PlanFormat::Dxf);
  EXPECT_EQ(planFormatOf("a.wkt"), PlanFormat::Wkt);
  EXPECT_EQ(planFormatOf("w/Gallery.GLTF"), PlanFormat::Gltf);
  EXPECT_EQ(planFormatOf("w.glb"), PlanFormat::Gltf);
  EXPECT_FALSE(planFormatOf("a.json").has_value());
}

std::string fileText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(PlanImportGltf, AFlatWorldsFloorBecomesWalkableAndObstacles) {
  // scenarios/gallery.gltf: an L-shaped 30 x 25 m floor (docs/world-files.md) with pillars.
  const std::string path = std::string(THRONG_SOURCE_DIR) + "/scenarios/gallery.gltf";
  auto r = importPlan(fileText(path), PlanFormat::Gltf, path);
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  const nlohmann::json& f = r.value();
  ASSERT_EQ(f["walkable"].size(), 1u);
  double area = 0;  // shoelace
  const auto& ring = f["walkable"][0];
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    area += ring[j][0].get<double>() * ring[i][1].get<double>() - ring[i][0].get<double>() * ring[j][1].get<double>();
  }
  EXPECT_NEAR(std::fabs(area) / 2, 30.0 * 12 + 10.0 * 13, 1e-6);
  EXPECT_FALSE(f["obstacles"].empty());
  EXPECT_TRUE(f["walls"].empty());
  // Coordinates to the micrometre (the loader's floats are not carried over as 7.400000095...).
  for (const auto& poly : f["obstacles"]) {
    for (const auto& p : poly) EXPECT_EQ(p[0].get<double>(), std::round(p[0].get<double>() * 1e6) / 1e6);
  }
}

TEST(PlanImportGltf, AMultiLevelWorldIsRefusedAndABrokenOneLocated) {
  const std::string path = std::string(THRONG_SOURCE_DIR) + "/scenarios/two_floors.gltf";
  auto r = importPlan(fileText(path), PlanFormat::Gltf, path);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.errors()[0].what, "a multi-level world (floors at several heights)");
  auto broken = importPlan("{\"asset\": {\"version\": \"2.0\"}, \"nodes\": 5}", PlanFormat::Gltf, "broken.gltf");
  ASSERT_FALSE(broken.ok());
  EXPECT_EQ(broken.errors()[0].source, "broken.gltf");
}

}  // namespace
}  // namespace throng::io
