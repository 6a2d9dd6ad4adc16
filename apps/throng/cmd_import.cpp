// `throng import PLAN.dxf|.wkt|.gltf|.glb` — a floor plan → a scenario skeleton (docs/import.md): the
// plan's walkable outlines, obstacles and walls (io::importPlan) with empty points and populations,
// formatted for diffs and written atomically; an existing file is kept unless --force.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "output.hpp"
#include "throng/io/plan_import.hpp"
#include "throng/io/scenario_writer.hpp"

namespace throng::cli {
namespace {

namespace fs = std::filesystem;

const std::vector<std::pair<std::string, io::PlanRole>> kRoles = {
    {"walkable", io::PlanRole::Walkable}, {"obstacle", io::PlanRole::Obstacle}, {"wall", io::PlanRole::Wall}, {"ignore", io::PlanRole::Ignore}};

/// "NAME=ROLE" → (name, role); an error text for CLI11 otherwise (empty when fine).
std::string parseLayer(const std::string& spec, std::pair<std::string, io::PlanRole>* out) {
  const std::size_t eq = spec.rfind('=');
  const std::string role = eq == std::string::npos ? "" : spec.substr(eq + 1);
  for (const auto& [name, value] : kRoles) {
    if (role != name) continue;
    if (eq == 0) return "--layer " + spec + ": expected NAME=ROLE with a layer name before '='";
    if (out != nullptr) *out = {spec.substr(0, eq), value};
    return {};
  }
  return "--layer " + spec + ": expected NAME=ROLE with ROLE walkable, obstacle, wall or ignore";
}

/// The whole scenario: header, the plan's geometry, empty points and populations, in reading order.
nlohmann::ordered_json skeleton(const nlohmann::json& fragment, const std::string& name) {
  nlohmann::ordered_json s;
  s["format"] = "throng/1";
  s["name"] = name;
  for (const char* key : {"walkable", "obstacles", "walls"}) s[key] = fragment.at(key);
  s["points"] = nlohmann::ordered_json::array();
  s["populations"] = nlohmann::ordered_json::array();
  return s;
}

io::PlanImportOptions planOptions(const ImportOptions& o) {
  io::PlanImportOptions p;
  p.scale = o.scale;
  p.wallThickness = o.wallThickness;
  for (const std::string& spec : o.layers) {
    std::pair<std::string, io::PlanRole> layer;
    parseLayer(spec, &layer);  // checked by the flag's validator
    p.layers[layer.first] = layer.second;
  }
  return p;
}

core::Result<std::string> readPlan(const std::string& path) {
  if (auto missing = checkInputFile(path, "plan"); !missing.empty()) return missing;
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in.good() && !in.eof()) return core::Diagnostic{path, 0, 0, "", "cannot read the plan file", "a readable file", ""};
  return text.str();
}

}  // namespace

CLI::App* addImportCommand(CLI::App& app, ImportOptions& options) {
  CLI::App* cmd = app.add_subcommand("import", "Make a scenario skeleton from a floor plan (DXF, WKT or a flat glTF world)");
  cmd->footer(
      "Make a scenario skeleton from a floor plan: the plan's walkable outlines, obstacles and walls\n"
      "in metres, with empty \"points\" and \"populations\" to fill in (docs/import.md). DXF (ASCII):\n"
      "LINE, LWPOLYLINE, POLYLINE, CIRCLE and ARC entities; open lines become walls, closed shapes\n"
      "walkable outlines on layers named ...walk..., ...floor... or ...room..., walls on ...wall...,\n"
      "obstacles elsewhere (--layer overrides); $INSUNITS converts mm, cm, in, ft to metres. WKT:\n"
      "POLYGON (outer ring walkable, holes obstacles), MULTIPOLYGON, LINESTRING and MULTILINESTRING\n"
      "(walls), GEOMETRYCOLLECTION. Without a walkable outline the bounding rectangle is walkable.\n"
      "Problems are printed one per line (DXF file:line, WKT file:line:column), exit 1, nothing written.");
  cmd->add_option("plan", options.plan, "Floor plan file (.dxf, .wkt, or a flat glTF world .gltf, .glb)")->required()->type_name("PLAN.dxf|.wkt|.gltf|.glb");
  cmd->add_option("-o,--out", options.out,
                  "Scenario file to write; default: the plan's name with .json in the current directory; - for stdout")
      ->type_name("SCENARIO.json");
  cmd->add_option("--scale", options.scale, "Multiplies every coordinate after the file's unit conversion (default 1)")
      ->type_name("S")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--layer", options.layers,
                  "What a DXF layer's closed shapes become: NAME=walkable, obstacle, wall or ignore (ignore drops its "
                  "open lines too); repeatable")
      ->type_name("NAME=ROLE")
      ->allow_extra_args(false)  // one NAME=ROLE per --layer: the plan after it stays the plan
      ->check(CLI::Validator([](std::string& spec) { return parseLayer(spec, nullptr); }, ""));
  cmd->add_option("--wall-thickness", options.wallThickness, "Thickness of the imported walls [m] (default 0.2)")
      ->type_name("M")
      ->check(CLI::Range(0.01, 5.0));
  cmd->add_flag("--force", options.force, "Overwrite an existing scenario file");
  cmd->add_flag("--json", options.json,
                "Print {\"ok\":bool,\"out\",\"walkable\",\"obstacles\",\"walls\"} (counts), or the diagnostics as "
                "throng check --json does");
  return cmd;
}

int runImport(const ImportOptions& options) {
  const auto format = io::planFormatOf(options.plan);
  if (!format) {
    return reportFailure({core::Diagnostic{options.plan, 0, 0, "", "unknown plan format", "a .dxf, .wkt, .gltf or .glb file", ""}}, options.json);
  }
  auto text = readPlan(options.plan);
  if (!text) return reportFailure(text.errors(), options.json);
  auto fragment = io::importPlan(text.value(), *format, options.plan, planOptions(options));
  if (!fragment) return reportFailure(fragment.errors(), options.json);

  const std::string name = fs::path(options.plan).stem().string();
  const std::string json = io::formatJsonForDiffs(skeleton(fragment.value(), name));
  const std::string out = options.out.empty() ? name + ".json" : options.out;
  if (out == "-") {
    std::fputs(json.c_str(), stdout);
    return kExitOk;
  }
  if (auto written = io::writeFileAtomically(out, json, options.force); !written) return reportFailure(written.errors(), options.json);
  const auto count = [&](const char* key) { return fragment.value()[key].size(); };
  if (options.json) {
    printLine(stdout, dumpJson({{"ok", true}, {"out", out}, {"walkable", count("walkable")}, {"obstacles", count("obstacles")},
                                {"walls", count("walls")}}));
  } else {
    printLine(stdout, fmt::format("wrote {}: {} walkable polygons, {} obstacles, {} walls; add points and populations, "
                                  "then run 'throng check {}'",
                                  displayText(out), count("walkable"), count("obstacles"), count("walls"), displayText(out)));
  }
  return kExitOk;
}

}  // namespace throng::cli
