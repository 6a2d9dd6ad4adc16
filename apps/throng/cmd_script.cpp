// `throng script FILE.sqlite --agent ID [--coordination N] [--json]` — the action script of one
// character (Park, Peng, Quek, Cao, Tables 3 and 5): for every Common Ground coordination the agent
// took part in, a header and one row per entry of all its actors ordered by start time, plus the
// agent's trajectory. --json prints one object an animation engine can read: the coordinations
// with their entries and the per-frame trajectory (time, position, velocity, heading, clip).
#include <algorithm>
#include <cmath>
#include <optional>
#include <set>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "output.hpp"
#include "throng/recording/recorder.hpp"
#include "throng/recording/recording_social.hpp"

namespace throng::cli {
namespace {

using nlohmann::json;

/// "A", "B", "C1".. from the coordination's actor list; the role when the agent is not in it.
std::string actorLabel(const recording::CoordinationInfo& c, const recording::ScriptEntryInfo& e) {
  if (e.agent == c.initiator) return "A";
  for (std::size_t i = 0; i < c.respondents.size(); ++i) {
    if (c.respondents[i] == e.agent) return i == 0 ? "B" : fmt::format("C{}", i);
  }
  return e.role == "initiator" ? "A" : e.role == "respondent" ? "B" : "C?";
}

std::string timeText(double t) { return std::isfinite(t) ? fmt::format("{:.2f}", t) : "-"; }

std::string targetText(const recording::ScriptEntryInfo& e) {
  const std::string at = std::isfinite(e.targetX) && std::isfinite(e.targetY)
                             ? fmt::format("({:.2f}, {:.2f})", e.targetX, e.targetY) : std::string("(?)");
  if (e.targetType == "agent") return fmt::format("agent {} {}", e.targetAgent.value_or(0), at);
  if (e.targetType == "point") return at;
  return "-";
}

json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json entryJson(const recording::CoordinationInfo& c, const recording::ScriptEntryInfo& e) {
  json target{{"type", e.targetType}};
  if (e.targetAgent) target["agent"] = *e.targetAgent;
  if (e.targetType != "none") {
    target["x"] = number(e.targetX);
    target["y"] = number(e.targetY);
  }
  return {{"step", recording::scriptStepLabel(e.step, e.part, 0)},
          {"step_number", e.step},
          {"part", e.part},
          {"attempt", e.attempt},
          {"actor", actorLabel(c, e)},
          {"agent", e.agent},
          {"role", e.role},
          {"seq", e.seq},
          {"plan", e.plan},
          {"motion", e.motion},
          {"behaviour", e.behaviour},
          {"target", target},
          {"planned_start", number(e.plannedStart)},
          {"planned_duration", number(e.plannedDuration)},
          {"start", number(e.start)},
          {"duration", number(e.duration)}};
}

/// The unknown parts of a coordination that had not ended when the recording stopped.
constexpr const char* kUnfinished = "unfinished at end of recording";

json text(const std::string& s) { return s.empty() ? json(nullptr) : json(s); }

json coordinationJson(const recording::CoordinationInfo& c) {
  if (!c.finished) {
    return {{"id", c.id},
            {"group", c.group},
            {"initiator", c.initiator},
            {"respondents", c.respondents},
            {"finished", false},
            {"goal_point", c.goalPointId.empty() && c.trigger.empty()
                               ? json(nullptr)
                               : json{{"index", c.goalPoint}, {"id", text(c.goalPointId)}, {"category", text(c.goalCategory)}}},
            {"goal_kind", nullptr},
            {"trigger", text(c.trigger)},
            {"relation", nullptr},
            {"plan", nullptr},
            {"outcome", "unfinished"},
            {"retries", nullptr},
            {"t0", number(c.start)},
            {"t8", nullptr},
            {"end", nullptr}};
  }
  return {{"id", c.id},
          {"group", c.group},
          {"initiator", c.initiator},
          {"respondents", c.respondents},
          {"goal_point", {{"index", c.goalPoint}, {"id", c.goalPointId}, {"category", c.goalCategory}}},
          {"goal_kind", c.goalKind},
          {"trigger", c.trigger},
          {"relation", c.relation.empty() ? json(nullptr) : json(c.relation)},
          {"plan", c.plan},
          {"outcome", c.outcome},
          {"retries", c.retries},
          {"t0", number(c.start)},
          {"t8", number(c.execute)},
          {"end", number(c.end)},
          {"finished", true}};
}

void printCoordination(const recording::CoordinationInfo& c, const std::vector<recording::ScriptEntryInfo>& entries) {
  std::string respondents;
  for (std::size_t i = 0; i < c.respondents.size(); ++i) {
    respondents += fmt::format("{}{} {}", i == 0 ? "" : ", ", i == 0 ? std::string("B") : fmt::format("C{}", i),
                               c.respondents[i]);
  }
  if (!c.finished) {
    printLine(stdout, fmt::format("coordination {}  group {}  initiator A {}  respondents {}  ({})", c.id, c.group,
                                  c.initiator, respondents.empty() ? "none recorded yet" : respondents, kUnfinished));
    printLine(stdout, fmt::format("  goal point {}  goal by {}  outcome {}",
                                  c.goalPointId.empty() && c.trigger.empty()
                                      ? std::string("unknown")
                                      : fmt::format("{} ({}{})", c.goalPoint, c.goalPointId.empty() ? "?" : c.goalPointId,
                                                    c.goalCategory.empty() ? "" : ", " + c.goalCategory),
                                  c.trigger.empty() ? "-" : c.trigger, kUnfinished));
    printLine(stdout, fmt::format("  t0 {} s  t8 -  end -", timeText(c.start)));
  } else {
  printLine(stdout, fmt::format("coordination {}  group {}  initiator A {}  respondents {}", c.id, c.group,
                                c.initiator, respondents.empty() ? "none" : respondents));
  printLine(stdout, fmt::format("  goal point {} ({}{})  {} goal by {}  relation {}  plan {}  outcome {}{}",
                                c.goalPoint, c.goalPointId.empty() ? "?" : c.goalPointId,
                                c.goalCategory.empty() ? "" : ", " + c.goalCategory, c.goalKind, c.trigger,
                                c.relation.empty() ? "-" : c.relation, c.plan, c.outcome,
                                c.retries > 0 ? fmt::format(" ({} {})", c.retries, c.retries == 1 ? "retry" : "retries") : ""));
  printLine(stdout, fmt::format("  t0 {} s  t8 {} s  end {} s", timeText(c.start), timeText(c.execute), timeText(c.end)));
  }
  printLine(stdout, fmt::format("  {:<12} {:<10} {:<14} {:<20} {:<28} {:>9} {:>9} {:>9}", "step", "actor", "motion",
                                "behaviour", "target", "planned", "start", "duration"));
  if (entries.empty()) printLine(stdout, "  (no script entries recorded)");
  for (const recording::ScriptEntryInfo& e : entries) {
    printLine(stdout, fmt::format("  {:<12} {:<10} {:<14} {:<20} {:<28} {:>9} {:>9} {:>9}",
                                  recording::scriptStepLabel(e.step, e.part, e.attempt),
                                  fmt::format("{} {}", actorLabel(c, e), e.agent), e.motion, e.behaviour, targetText(e),
                                  timeText(e.plannedStart), timeText(e.start), timeText(e.duration)));
  }
  printLine(stdout, "");
}


/// The agent's trajectory from a recording with Common Ground data; nullopt after printing why
/// not (no file, no Common Ground data, no such agent).
std::optional<recording::AgentTrack> readTrack(const std::string& path, std::uint32_t agent) {
  if (auto missing = checkInputFile(path, "recording"); !missing.empty()) {
    printDiagnostics(missing);
    return std::nullopt;
  }
  const auto hasCg = recording::hasCommonGroundData(path);
  if (!hasCg) {
    printDiagnostics(hasCg.errors());
    return std::nullopt;
  }
  if (!hasCg.value()) {
    printLine(stderr, fmt::format("{}: no Common Ground data in {}; expected a recording of a scenario with a "
                                  "\"social\" section", path, path));
    return std::nullopt;
  }
  auto track = recording::readAgentTrack(path, agent);
  if (!track) {
    printDiagnostics(track.errors());
    return std::nullopt;
  }
  if (!track->known) {
    const auto summary = recording::readRecordingSummary(path);
    printLine(stderr, fmt::format("{}: agent {} not found; expected a stable agent id{}", path, agent,
                                  summary && summary->agents > 0
                                      ? fmt::format(" (the recording has {} agents)", summary->agents) : ""));
    return std::nullopt;
  }
  return std::move(track).value();
}

/// Every coordination, finished or not, and the ids of those the agent took part in (by its own
/// entries, or as an actor: a lone visit, or an actor whose entries were not recorded); nullopt
/// after printing a read error.
std::optional<std::set<std::uint32_t>> agentCoordinations(const std::string& path, std::uint32_t agent,
                                                          std::vector<recording::CoordinationInfo>& all) {
  const auto own = recording::readScript(path, agent);
  auto finished = recording::readCoordinations(path);
  const auto unfinished = recording::readUnfinishedCoordinations(path);
  if (!own || !finished || !unfinished) {
    printDiagnostics(!own ? own.errors() : !finished ? finished.errors() : unfinished.errors());
    return std::nullopt;
  }
  all = std::move(finished).value();
  all.insert(all.end(), unfinished->begin(), unfinished->end());
  std::set<std::uint32_t> ids;
  for (const auto& e : own.value()) ids.insert(e.coordination);
  for (const auto& c : all) {
    if (c.initiator == agent || std::find(c.respondents.begin(), c.respondents.end(), agent) != c.respondents.end()) {
      ids.insert(c.id);
    }
  }
  return ids;
}

/// Coordination `id` from the list; when the file has entries but no coordination row or start
/// event (a file cut short), one made up from the entries (actors, the trajectory's group).
recording::CoordinationInfo coordinationOf(std::uint32_t id, const std::vector<recording::CoordinationInfo>& list,
                                    const std::vector<recording::ScriptEntryInfo>& entries, const recording::AgentTrack& track,
                                    std::uint32_t agent) {
  const auto it = std::find_if(list.begin(), list.end(), [&](const recording::CoordinationInfo& c) { return c.id == id; });
  if (it != list.end()) return *it;
  recording::CoordinationInfo c;
  c.id = id;
  c.finished = false;
  c.group = track.group.value_or(0);  // the trajectory's group numbering
  c.initiator = agent;
  c.start = c.execute = c.end = std::nan("");
  for (const auto& e : entries) {
    if (e.role == "initiator") c.initiator = e.agent;
  }
  for (const auto& e : entries) {
    if (e.agent != c.initiator && std::find(c.respondents.begin(), c.respondents.end(), e.agent) == c.respondents.end()) {
      c.respondents.push_back(e.agent);
    }
  }
  return c;
}

/// The per-frame trajectory for --json.
json trajectoryJson(const recording::AgentTrack& track) {
  json traj = json::array();
  for (const recording::TrackSample& s : track.samples) {
    json row{{"frame", s.frame}, {"time", number(s.time)}, {"x", number(s.x)},      {"y", number(s.y)},
             {"vx", number(s.vx)}, {"vy", number(s.vy)},   {"ori_x", number(s.oriX)}, {"ori_y", number(s.oriY)}};
    if (s.clip >= 0) {
      row["clip"] = s.clip;
      if (static_cast<std::size_t>(s.clip) < track.clips.size()) row["clip_name"] = track.clips[static_cast<std::size_t>(s.clip)];
      row["phase"] = number(s.phase);
    }
    traj.push_back(std::move(row));
  }
  return traj;
}

/// The trajectory's one-line summary.
void printTrajectory(std::uint32_t agent, const recording::AgentTrack& track) {
  const auto& samples = track.samples;
  if (samples.empty()) {
    printLine(stdout, fmt::format("trajectory   agent {}: no recorded frames", agent));
    return;
  }
  printLine(stdout, fmt::format("trajectory   agent {}{}: {} frames, t = {:.2f} .. {:.2f} s, from ({:.2f}, {:.2f}) to ({:.2f}, {:.2f})",
                                agent, track.group ? fmt::format(" (group {})", *track.group) : "",
                                samples.size(), samples.front().time, samples.back().time, samples.front().x,
                                samples.front().y, samples.back().x, samples.back().y));
}

}  // namespace

CLI::App* addScriptCommand(CLI::App& app, ScriptOptions& options) {
  CLI::App* cmd = app.add_subcommand("script", "Show the action script of one character");
  cmd->footer(
      "Show the Common Ground action script of one character (Park et al., Tables 3 and 5): for every\n"
      "coordination it took part in, the coordination (group, actors, goal, relation, plan, outcome,\n"
      "t0/t8/end) and every entry of all its actors by start time (step, actor, motion, behaviour,\n"
      "target, planned start, start, duration), then the character's trajectory. A coordination still\n"
      "running when the recording ended is marked \"unfinished at end of recording\" (its plan and outcome\n"
      "are unknown; JSON: \"finished\": false). Groups are numbered as in the trajectory (stable group ids).\n"
      "--json prints one object with the coordinations, their entries and the per-frame trajectory.");
  cmd->add_option("recording", options.recording, "Recording written by 'throng run'")
      ->required()
      ->type_name("FILE.sqlite");
  cmd->add_option("--agent", options.agent, "Stable agent id (spawn order, 0-based)")->required()->type_name("ID");
  cmd->add_option("--coordination", options.coordination, "Only this coordination id")->type_name("N");
  cmd->add_flag("--json", options.json, "Print one JSON object (coordinations, entries, trajectory)");
  return cmd;
}

int runScript(const ScriptOptions& options) {
  const std::string& path = options.recording;
  const std::optional<recording::AgentTrack> track = readTrack(path, options.agent);
  if (!track) return kExitFailure;
  std::vector<recording::CoordinationInfo> all;
  auto found = agentCoordinations(path, options.agent, all);
  if (!found) return kExitFailure;
  std::set<std::uint32_t> ids = std::move(*found);
  if (options.coordination) {
    if (ids.count(*options.coordination) == 0) {
      printLine(stderr, fmt::format("{}: agent {} took no part in coordination {}; expected one of: {}", path,
                                    options.agent, *options.coordination,
                                    ids.empty() ? std::string("none") : fmt::format("{}", fmt::join(ids, ", "))));
      return kExitFailure;
    }
    ids = {*options.coordination};
  }

  json coordinations = json::array();
  for (const std::uint32_t id : ids) {
    auto entries = recording::readCoordinationScript(path, id);
    if (!entries) {
      printDiagnostics(entries.errors());
      return kExitFailure;
    }
    const recording::CoordinationInfo c = coordinationOf(id, all, *entries, *track, options.agent);
    if (options.json) {
      json j = coordinationJson(c);
      j["entries"] = json::array();
      for (const auto& e : *entries) j["entries"].push_back(entryJson(c, e));
      coordinations.push_back(std::move(j));
    } else {
      printCoordination(c, *entries);
    }
  }

  if (options.json) {
    json out{{"recording", path},
             {"agent", options.agent},
             {"group", track->group ? json(*track->group) : json(nullptr)},
             {"population", track->population},
             {"coordinations", std::move(coordinations)},
             {"trajectory", trajectoryJson(*track)}};
    printLine(stdout, out.dump());
    return kExitOk;
  }
  if (ids.empty()) printLine(stdout, fmt::format("agent {} took part in no coordination", options.agent));
  printTrajectory(options.agent, *track);
  return kExitOk;
}

}  // namespace throng::cli
