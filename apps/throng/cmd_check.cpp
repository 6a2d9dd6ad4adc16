// `throng check SCENARIO.json` — loads and validates a scenario (navmesh built, reachability
// checked) without simulating; prints every problem, one line each, or a one-line summary.
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "output.hpp"
#include "signal.hpp"
#include "throng/io/scenario_loader.hpp"

namespace throng::cli {
namespace {

struct AgentRange {
  std::uint64_t min = 0;
  std::uint64_t max = 0;
};

AgentRange agentRange(const sim::ScenarioDesc& desc) {
  AgentRange r;
  for (const auto& p : desc.populations) {
    r.min += static_cast<std::uint64_t>(p.groups) * p.sizeMin;
    r.max += static_cast<std::uint64_t>(p.groups) * p.sizeMax;
  }
  return r;
}

}  // namespace

CLI::App* addCheckCommand(CLI::App& app, CheckOptions& options) {
  CLI::App* cmd = app.add_subcommand("check", "Validate a scenario without running it");
  cmd->footer(
      "Validate a scenario without running it: parse the JSON, check every value, build the\n"
      "navmesh and check that spawns and goals are reachable. Prints every problem, one line each\n"
      "(file:line:column JSON-pointer: what; expected ...), the first 50 and a count of the rest,\n"
      "and exits 1 if there is any. Ctrl-C stops the checks (exit 130).");
  cmd->add_option("scenario", options.scenario, "Scenario JSON file")->required()->type_name("SCENARIO.json");
  cmd->add_flag("--json", options.json,
                "Print {\"ok\":bool,\"diagnostics\":[{source,line,column,pointer,what,expected,hint}...]} (at most 50 "
                "diagnostics; \"diagnostics_total\" counts them when there are more)");
  return cmd;
}

int runCheck(const CheckOptions& options) {
  if (auto missing = checkInputFile(options.scenario, "scenario"); !missing.empty()) {
    return reportFailure(missing, options.json);
  }
  InterruptGuard interrupts;  // Ctrl-C stops a long validation (exit 130)
  io::LoadOptions load;
  load.cancel = &InterruptGuard::flag();
  auto loaded = io::loadScenarioFile(options.scenario, load);
  if (InterruptGuard::requested()) {
    printLine(stderr, fmt::format("throng: interrupted; {} was not checked completely", displayText(options.scenario)));
    return kExitInterrupted;
  }
  if (!loaded) return reportFailure(loaded.errors(), options.json);

  const sim::ScenarioDesc& desc = loaded->desc;
  const AgentRange agents = agentRange(desc);
  const std::size_t polygons = loaded->navmesh ? loaded->navmesh->polygonCount() : 0;
  if (options.json) {
    nlohmann::json out{{"ok", true},
                       {"name", desc.name},
                       {"populations", desc.populations.size()},
                       {"agents_min", agents.min},
                       {"agents_max", agents.max},
                       {"points", desc.points.size()},
                       {"navmesh_polygons", polygons},
                       {"diagnostics", nlohmann::json::array()}};
    printLine(stdout, dumpJson(out));
    return kExitOk;
  }
  const std::string agentText = agents.min == agents.max ? fmt::format("{} agents", agents.min)
                                                         : fmt::format("{}-{} agents", agents.min, agents.max);
  printLine(stdout, fmt::format("ok: {}: {} populations, {}, {} points, navmesh {} polygons", displayText(desc.name),
                                desc.populations.size(), agentText, desc.points.size(), polygons));
  return kExitOk;
}

}  // namespace throng::cli
