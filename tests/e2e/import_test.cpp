// `throng import` end to end: a DXF floor plan in millimetres (room, wall with a door gap, a
// column) and a WKT plan become scenario skeletons formatted for diffs that `throng check` accepts
// and `throng run` runs once a population is added; an existing file is kept without --force; a bad
// plan gives a located error and writes nothing; bad flags exit 2.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace throng::e2e {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string dxf(const std::vector<std::pair<int, std::string>>& groups) {
  std::string out;
  for (const auto& [code, value] : groups) out += std::to_string(code) + "\n" + value + "\n";
  return out;
}

/// A 12 m × 8 m room (mm), a wall across it at x = 6 m with a 1.2 m door (y 3.4 .. 4.6 m), a column.
const std::string kPlan = dxf({{0, "SECTION"}, {2, "HEADER"}, {9, "$INSUNITS"}, {70, "4"}, {0, "ENDSEC"},
                               {0, "SECTION"}, {2, "ENTITIES"},
                               {0, "LWPOLYLINE"}, {8, "FLOOR"}, {90, "4"}, {70, "1"},
                               {10, "0"}, {20, "0"}, {10, "12000"}, {20, "0"}, {10, "12000"}, {20, "8000"}, {10, "0"}, {20, "8000"},
                               {0, "LINE"}, {8, "A-WALL"}, {10, "6000"}, {20, "0"}, {11, "6000"}, {21, "3300"},
                               {0, "LINE"}, {8, "A-WALL"}, {10, "6000"}, {20, "4700"}, {11, "6000"}, {21, "8000"},
                               {0, "CIRCLE"}, {8, "COLUMNS"}, {10, "9000"}, {20, "2000"}, {40, "300"},
                               {0, "ENDSEC"}, {0, "EOF"}});

/// The skeleton with an exit at the right wall and 20 people in the left half.
std::string withCrowd(const std::string& skeleton) {
  json s = json::parse(skeleton);
  s["points"] = json::parse(R"([{"id": "exit", "kind": "exit", "polygon": [[11, 3], [12, 3], [12, 5], [11, 5]]}])");
  s["populations"] = json::parse(R"([{"id": "crowd", "groups": 20, "spawn": {"polygon": [[1, 1], [5, 1], [5, 7], [1, 7]]},
                                     "goals": ["exit"]}])");
  return s.dump(2);
}

TEST(CliImport, DxfPlanBecomesARunnableScenario) {
  ScratchDir dir("import-dxf");
  dir.write("plan.dxf", kPlan);
  const CliResult r = runThrong({"import", "plan.dxf"}, dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "wrote plan.json: 1 walkable polygons, 1 obstacles, 2 walls")) << r.out;
  const std::string text = readFile(dir / "plan.json");
  // Formatted for diffs: 2-space indent, one point per line.
  EXPECT_TRUE(contains(text, "{\n  \"format\": \"throng/1\",\n  \"name\": \"plan\",\n  \"walkable\": [\n    [\n      [0, 0],\n"))
      << text;
  const json s = json::parse(text);
  EXPECT_EQ(s["walkable"][0][2], json::parse("[12, 8]"));  // millimetres → metres
  EXPECT_EQ(s["walls"][1]["line"], json::parse("[[6, 4.7], [6, 8]]"));
  EXPECT_EQ(s["obstacles"][0].size(), 32u);  // the column
  EXPECT_TRUE(s["points"].empty() && s["populations"].empty());
  // As written it checks (no population yet); with a crowd it checks and runs through the door.
  EXPECT_EQ(runThrong({"check", "plan.json"}, dir.path()).exitCode, 0);
  dir.write("crowd.json", withCrowd(text));
  const CliResult check = runThrong({"check", "crowd.json"}, dir.path());
  EXPECT_EQ(check.exitCode, 0) << check.err;
  const CliResult run = runThrong({"run", "crowd.json", "--duration", "40", "--json", "-q"}, dir.path());
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_GT(json::parse(run.out)["agents_exited"].get<int>(), 0) << run.out;
}

TEST(CliImport, ClosingTheDoorIsSeenByCheck) {
  ScratchDir dir("import-closed");
  std::string closed = kPlan;
  closed.replace(closed.find("3300"), 4, "8000");  // the first wall now spans the room
  dir.write("plan.dxf", closed);
  ASSERT_EQ(runThrong({"import", "plan.dxf", "-o", "s.json"}, dir.path()).exitCode, 0);
  dir.write("crowd.json", withCrowd(readFile(dir / "s.json")));
  const CliResult check = runThrong({"check", "crowd.json"}, dir.path());
  EXPECT_EQ(check.exitCode, 1);
  EXPECT_TRUE(contains(check.err, "cannot be reached")) << check.err;
}

TEST(CliImport, WktPlanAndJsonSummary) {
  ScratchDir dir("import-wkt");
  dir.write("hall.wkt", "POLYGON ((0 0, 12 0, 12 8, 0 8, 0 0), (8 3, 9 3, 9 5, 8 5, 8 3))\nLINESTRING (6 0, 6 3)\n");
  const CliResult r = runThrong({"import", "hall.wkt", "-o", "hall.json", "--json", "--wall-thickness", "0.3"}, dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(json::parse(r.out), json::parse(R"({"ok": true, "out": "hall.json", "walkable": 1, "obstacles": 1, "walls": 1})"));
  const json s = json::parse(readFile(dir / "hall.json"));
  EXPECT_EQ(s["walls"][0]["thickness"], 0.3);
  dir.write("crowd.json", withCrowd(readFile(dir / "hall.json")));
  EXPECT_EQ(runThrong({"check", "crowd.json"}, dir.path()).exitCode, 0);
}

TEST(CliImport, KeepsAnExistingFileWithoutForce) {
  ScratchDir dir("import-force");
  dir.write("plan.dxf", kPlan);
  dir.write("plan.json", "mine\n");
  const CliResult r = runThrong({"import", "plan.dxf"}, dir.path());
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_TRUE(contains(r.err, "plan.json: file exists; expected a new file name, or --force to overwrite it")) << r.err;
  EXPECT_EQ(readFile(dir / "plan.json"), "mine\n");
  EXPECT_EQ(runThrong({"import", "plan.dxf", "--force"}, dir.path()).exitCode, 0);
  EXPECT_TRUE(contains(readFile(dir / "plan.json"), "\"walls\"")) << readFile(dir / "plan.json");
  for (const auto& entry : fs::directory_iterator(dir.path())) {
    EXPECT_FALSE(contains(entry.path().filename().string(), ".throng-")) << "temporary file left: " << entry.path();
  }
}

TEST(CliImport, BadPlansAreLocatedAndWriteNothing) {
  ScratchDir dir("import-bad");
  std::string bad = kPlan;
  bad.replace(bad.find("12000"), 5, "12,000");
  dir.write("plan.dxf", bad);
  CliResult r = runThrong({"import", "plan.dxf"}, dir.path());
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_TRUE(contains(r.err, "plan.dxf:28: value \"12,000\" of group code 10 is not a number")) << r.err;
  EXPECT_FALSE(fs::exists(dir / "plan.json"));

  dir.write("plan.wkt", "POLYGON ((0 0, 1 0, 1 1)\n");
  r = runThrong({"import", "plan.wkt", "--json"}, dir.path());
  EXPECT_EQ(r.exitCode, 1);
  const json out = json::parse(r.out);
  EXPECT_EQ(out["ok"], false);
  EXPECT_EQ(out["diagnostics"][0]["line"], 2);

  dir.write("plan.svg", "<svg/>");
  r = runThrong({"import", "plan.svg"}, dir.path());
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_TRUE(contains(r.err, "unknown plan format; expected a .dxf, .wkt, .gltf or .glb file")) << r.err;
  r = runThrong({"import", "missing.dxf"}, dir.path());
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_TRUE(contains(r.err, "plan file not found")) << r.err;
}

TEST(CliImport, FlagsAndHelp) {
  ScratchDir dir("import-flags");
  dir.write("plan.dxf", kPlan);
  for (const std::vector<std::string>& args : {std::vector<std::string>{"import", "plan.dxf", "--layer", "FLOOR=floor"},
                                               {"import", "plan.dxf", "--layer", "=wall"},
                                               {"import", "plan.dxf", "--scale", "0"},
                                               {"import", "plan.dxf", "--wall-thickness", "9"},
                                               {"import"}}) {
    const CliResult r = runThrong(args, dir.path());
    EXPECT_EQ(r.exitCode, 2) << args.back() << ": " << r.err;
  }
  // --layer before the plan takes one NAME=ROLE each; the ignored layer's column is gone; --scale 2.
  const CliResult r = runThrong({"import", "--layer", "columns=ignore", "--layer", "floor=walkable", "plan.dxf", "-o", "-", "--scale", "2"},
                                dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const json s = json::parse(r.out);
  EXPECT_EQ(s["walkable"][0], json::parse("[[0, 0], [24, 0], [24, 16], [0, 16]]"));
  EXPECT_TRUE(s["obstacles"].empty());
  EXPECT_EQ(s["walls"][0]["line"][1], json::parse("[12, 6.6]"));
  const CliResult help = runThrong({"import", "--help"}, dir.path());
  for (const char* flag : {"--out", "--scale", "--layer", "--wall-thickness", "--force", "--json", "PLAN.dxf"}) {
    EXPECT_TRUE(contains(help.out, flag)) << flag;
  }
}

}  // namespace
}  // namespace throng::e2e
