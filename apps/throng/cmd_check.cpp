// `throng check SCENARIO.json` — loads and validates a scenario (navmesh built, reachability
// checked) without simulating; prints every problem, one line each, or a one-line summary, and
// warns (closedExitWarnings) of populations left without a way out by exits the timeline closes
// for good.
#include <algorithm>
#include <map>
#include <string>
#include <vector>

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

/// For each exit the timeline closes and never opens again: the index of that last "close" entry.
std::map<std::uint32_t, std::size_t> exitsClosedForGood(const sim::ScenarioDesc& desc) {
  std::map<std::uint32_t, std::size_t> last;  // exit → its last timeline entry (entries are in time order)
  for (std::size_t i = 0; i < desc.timeline.size(); ++i) {
    const sim::TimelineEntry& e = desc.timeline[i];
    if (e.action == sim::TimelineAction::CloseExit || e.action == sim::TimelineAction::OpenExit) last[e.point] = i;
  }
  std::erase_if(last, [&](const auto& entry) { return desc.timeline[entry.second].action != sim::TimelineAction::CloseExit; });
  return last;
}

/// Warnings, not errors (the run is still valid: its agents wait at the door to the end): a
/// population whose fixed goal is an exit the timeline closes for good, or whose every exit to
/// choose from closes for good.
std::vector<std::string> closedExitWarnings(const sim::ScenarioDesc& desc) {
  const std::map<std::uint32_t, std::size_t> closed = exitsClosedForGood(desc);
  std::vector<std::string> out;
  if (closed.empty()) return out;
  auto exitText = [&](std::uint32_t point) {
    const std::size_t entry = closed.at(point);
    return fmt::format("exit \"{}\" closes at {:g} s (/timeline/{}) and never opens again", displayText(desc.points[point].id),
                       desc.timeline[entry].time, entry);
  };
  for (std::size_t p = 0; p < desc.populations.size(); ++p) {
    const sim::PopulationDesc& pop = desc.populations[p];
    for (std::size_t g = 0; g < pop.goals.size(); ++g) {
      if (!closed.contains(pop.goals[g])) continue;
      out.push_back(fmt::format("/populations/{}/goals/{}: {}; population \"{}\" walks to it and cannot leave after that "
                                "(give it \"exits\" to choose another, or open the exit again)",
                                p, g, exitText(pop.goals[g]), displayText(pop.id)));
    }
    const bool allClosed = !pop.exits.empty() &&
                           std::all_of(pop.exits.begin(), pop.exits.end(), [&](std::uint32_t e) { return closed.contains(e); });
    if (!allClosed) continue;
    std::string which;
    for (std::uint32_t e : pop.exits) which += (which.empty() ? "" : "; ") + exitText(e);
    out.push_back(fmt::format("/populations/{}/exits: every exit of population \"{}\" closes for good ({}); its agents "
                              "cannot leave after the last closes",
                              p, displayText(pop.id), which));
  }
  return out;
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
  const std::vector<std::string> warnings = closedExitWarnings(desc);
  const std::size_t polygons = loaded->navmesh ? loaded->navmesh->polygonCount() : 0;
  if (options.json) {
    nlohmann::json out{{"ok", true},
                       {"name", desc.name},
                       {"populations", desc.populations.size()},
                       {"agents_min", agents.min},
                       {"agents_max", agents.max},
                       {"points", desc.points.size()},
                       {"navmesh_polygons", polygons},
                       {"nav_margin_m", desc.navRadius()},
                       {"diagnostics", nlohmann::json::array()}};
    if (!warnings.empty()) out["warnings"] = warnings;  // only then: other answers stay as they were
    printLine(stdout, dumpJson(out));
    return kExitOk;
  }
  for (const std::string& w : warnings) {
    printLine(stderr, fmt::format("throng check: warning: {}: {}", displayText(options.scenario), w));
  }
  const std::string agentText = agents.min == agents.max ? fmt::format("{} agents", agents.min)
                                                         : fmt::format("{}-{} agents", agents.min, agents.max);
  printLine(stdout, fmt::format("ok: {}: {} populations, {}, {} points, navmesh {} polygons (centres kept {:.3g} m from walls)",
                                displayText(desc.name), desc.populations.size(), agentText, desc.points.size(), polygons,
                                desc.navRadius()));
  return kExitOk;
}

}  // namespace throng::cli
