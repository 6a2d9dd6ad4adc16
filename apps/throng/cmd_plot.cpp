// `throng plot` — PNG plots of a recording for reports (docs/plot.md): trajectories, density and
// speed heatmaps, passings and flow at a measurement line, a fundamental diagram. Checks the flags
// and that the recording is a readable file, then hands them to scripts/plot.py (found and run as
// `throng verify` runs verify.py: python_script.hpp), which reads the recording, measures it with
// python/throng/analysis.py and scripts/validation/measures.py and writes the figures.
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "bench_files.hpp"
#include "commands.hpp"
#include "output.hpp"
#include "python_script.hpp"

namespace throng::cli {
namespace {

namespace fs = std::filesystem;

/// "x0,y0,x1,y1" with every number as given (shortest round-trip form).
std::string joinNumbers(const std::vector<double>& values) {
  std::string out;
  for (double v : values) out += (out.empty() ? "" : ",") + fmt::format("{}", v);
  return out;
}

std::vector<std::string> scriptArguments(const PlotOptions& o) {
  std::vector<std::string> args{o.recording};
  if (!o.out.empty()) args.insert(args.end(), {"--out", o.out});
  if (!o.what.empty()) {
    std::string what;
    for (const auto& w : o.what) what += (what.empty() ? "" : ",") + w;
    args.insert(args.end(), {"--what", what});
  }
  if (!o.line.empty()) args.insert(args.end(), {"--line", joinNumbers(o.line)});
  if (!o.area.empty()) args.insert(args.end(), {"--area", joinNumbers(o.area)});
  args.insert(args.end(), {"--cell", fmt::format("{}", o.cell)});
  if (o.density != "classic") args.insert(args.end(), {"--density", o.density});
  if (o.speed != "classic") args.insert(args.end(), {"--speed", o.speed});
  if (o.json) args.emplace_back("--json");
  args.insert(args.end(), {"--prog", "throng plot"});
  return args;
}

}  // namespace

CLI::App* addPlotCommand(CLI::App& app, PlotOptions& options) {
  CLI::App* cmd = app.add_subcommand("plot", "Draw a recording's trajectories, heatmaps, flow and fundamental diagram as PNGs");
  cmd->footer(
      "Write PNG figures of a recording for reports: trajectories over the walkable area, the classic density\n"
      "and the mean speed per grid cell (averaged over the recording), cumulative passings and flow at a\n"
      "measurement line, and the fundamental diagram (density and mean speed per frame in a measurement area,\n"
      "with Weidmann's curve). Without --line, a line lies 1 m in front of each exit; without --area, the area\n"
      "is 2 m deep behind the first exit's line. Exit 0 when written, 1 for a recording that cannot be read or\n"
      "a line or area that measures nothing, 2 for bad flags. Runs scripts/plot.py with python3 (numpy, pandas\n"
      "and matplotlib from Debian); docs/plot.md defines every measure. Example:\n"
      "  throng plot bottleneck.sqlite --line 10,4.5,10,5.5 --area 7,3.5,9,6.5");
  cmd->add_option("recording", options.recording, "Recording written by 'throng run'")->required()->type_name("FILE.sqlite");
  cmd->add_option("--out", options.out, "Directory for the PNGs (default: the recording's name without .sqlite, plus -plots)")
      ->type_name("DIR");
  cmd->add_option("--what", options.what, "Figures to draw: trajectories, density, speed, flow, fd (default: all)")
      ->delimiter(',')
      ->check(CLI::IsMember({"trajectories", "density", "speed", "flow", "fd"}))
      ->type_name("LIST");
  cmd->add_option("--line", options.line, "Measurement line from (x0, y0) to (x1, y1) [m] (default: one in front of each exit)")
      ->delimiter(',')
      ->expected(4)
      ->type_name("X0,Y0,X1,Y1");
  cmd->add_option("--area", options.area, "Measurement area: the rectangle with opposite corners (x0, y0), (x1, y1) [m]")
      ->delimiter(',')
      ->expected(4)
      ->type_name("X0,Y0,X1,Y1");
  cmd->add_option("--cell", options.cell, "Heatmap cell size [m]")->check(CLI::Range(0.05, 100.0))->default_str("0.5");
  cmd->add_option("--density", options.density, "The density heatmap's definition (PedPy's): classic (persons in the "
                                                "cell / its area) or voronoi (Voronoi cells cut to 2 m, shared by area)")
      ->check(CLI::IsMember({"classic", "voronoi"}))
      ->capture_default_str();
  cmd->add_option("--speed", options.speed, "The speed heatmap's definition: classic (mean speed of those in the cell) "
                                            "or voronoi (each one's speed over their Voronoi cell, cut to 2 m, by area)")
      ->check(CLI::IsMember({"classic", "voronoi"}))
      ->capture_default_str();
  cmd->add_flag("--json", options.json, "Print the written files and the measured numbers as one JSON object");
  return cmd;
}

int runPlot(const PlotOptions& options) {
  if (auto missing = checkInputFile(options.recording, "recording"); !missing.empty()) {
    printDiagnostics(missing);
    return kExitFailure;
  }
  const fs::path script = findBundledScript(currentExecutable(), "plot.py", fs::path(THRONG_SOURCE_DIR) / "scripts");
  if (script.empty()) {
    printLine(stderr, fmt::format("throng plot: error: scripts/plot.py not found (looked in <prefix>/share/throng/scripts "
                                  "and {}/scripts); run it from a source checkout",
                                  THRONG_SOURCE_DIR));
    return kExitFailure;
  }
  const std::string python = findPython();
  if (python.empty()) {
    printLine(stderr, "throng plot: error: python3 not found (install python3, python3-numpy, python3-pandas and "
                      "python3-matplotlib)");
    return kExitFailure;
  }
  std::vector<std::string> argv{python, script.string()};
  const auto rest = scriptArguments(options);
  argv.insert(argv.end(), rest.begin(), rest.end());
  return runScriptAndWait(argv, "plot");
}

}  // namespace throng::cli
