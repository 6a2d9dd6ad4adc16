// `throng info FILE.sqlite` — summarises a recording (read-only): scenario, seed, agents, frames,
// fps, duration, whether the run completed, populations, Common Ground (on/off, coordinations) and
// format version.
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "output.hpp"
#include "throng/recording/recorder.hpp"

namespace throng::cli {

CLI::App* addInfoCommand(CLI::App& app, InfoOptions& options) {
  CLI::App* cmd = app.add_subcommand("info", "Show what a recording holds");
  cmd->footer(
      "Show what a recording holds: scenario name, seed, agents, frames, frame rate, duration,\n"
      "whether the run completed (false when interrupted or killed), populations, avoidance models, the SIMD\n"
      "path that wrote it, Common Ground (on or off, and how many coordinations were recorded) and format\n"
      "version.");
  cmd->add_option("recording", options.recording, "Recording written by 'throng run'")
      ->required()
      ->type_name("FILE.sqlite");
  cmd->add_flag("--json", options.json, "Print the summary as one JSON object");
  return cmd;
}

int runInfo(const InfoOptions& options) {
  auto missing = checkInputFile(options.recording, "recording");
  if (!missing.empty()) {
    printDiagnostics(missing);
    return kExitFailure;
  }
  auto summary = recording::readRecordingSummary(options.recording);
  if (!summary) {
    printDiagnostics(summary.errors());
    return kExitFailure;
  }
  const recording::RecordingSummary& s = *summary;
  if (options.json) {
    auto populations = nlohmann::json::array();
    for (const auto& [id, count] : s.populations) populations.push_back({{"id", id}, {"agents", count}});
    nlohmann::json out{{"path", s.path.empty() ? options.recording : s.path},
                       {"scenario", s.scenarioName},
                       {"seed", s.seed},
                       {"agents", s.agents},
                       {"frames", s.frames},
                       {"fps", s.fps},
                       {"duration_s", s.duration},
                       {"completed", s.completed},
                       {"rows", s.rows},
                       {"events", s.events},
                       {"populations", populations},
                       {"common_ground", s.commonGround.empty() ? nlohmann::json(nullptr) : nlohmann::json(s.commonGround)},
                       {"coordinations", s.coordinations},
                       {"format_version", s.formatVersion},
                       {"throng_version", s.throngVersion}};
    // The avoidance model of each population (throng_models); null when the recording predates it
    // or the text is not JSON (a hand-edited file).
    out["models"] = s.models.empty() ? nlohmann::json(nullptr) : nlohmann::json::parse(s.models, nullptr, false);
    if (out["models"].is_discarded()) out["models"] = nullptr;
    out["simd"] = s.simd.empty() ? nlohmann::json(nullptr) : nlohmann::json(s.simd);
    out["heights_m"] = s.heights ? nlohmann::json{s.heights->first, s.heights->second} : nlohmann::json(nullptr);
    printLine(stdout, dumpJson(out));
    return kExitOk;
  }
  std::string populations;
  for (const auto& [id, count] : s.populations) {
    if (!populations.empty()) populations += ", ";
    populations += fmt::format("{} ({} agents)", displayText(id, 80), count);
  }
  if (populations.empty()) populations = "none";
  printLine(stdout, fmt::format("recording    {}", displayText(options.recording)));
  printLine(stdout, fmt::format("scenario     {}", displayText(s.scenarioName)));
  printLine(stdout, fmt::format("seed         {}", s.seed));
  printLine(stdout, fmt::format("agents       {}", s.agents));
  printLine(stdout, fmt::format("frames       {} at {:g} fps ({:.2f} s)", s.frames, s.fps, s.duration));
  printLine(stdout, fmt::format("completed    {}", s.completed ? "yes" : "no (interrupted or killed)"));
  printLine(stdout, fmt::format("populations  {}", populations));
  printLine(stdout, fmt::format("rows         {} trajectory rows, {} events", s.rows, s.events));
  if (s.heights) {
    printLine(stdout, fmt::format("heights      {:.2f} to {:.2f} m (a multi-level world: throng_heights)", s.heights->first,
                                  s.heights->second));
  }
  if (!s.models.empty()) printLine(stdout, fmt::format("models       {}", displayText(s.models, 400)));
  if (!s.simd.empty()) {
    printLine(stdout, fmt::format("simd         {} (the vector path of the hot loops; every path gives the same trajectories)",
                                  displayText(s.simd, 40)));
  }
  if (!s.commonGround.empty()) {
    printLine(stdout, fmt::format("common ground {}: {} coordinations (throng script / throng metrics read them)", s.commonGround,
                                  s.coordinations));
  }
  printLine(stdout, fmt::format("format       JuPedSim trajectory version {}{}", s.formatVersion,
                                s.throngVersion.empty() ? "" : fmt::format(", written by throng {}", displayText(s.throngVersion, 80))));
  return kExitOk;
}

}  // namespace throng::cli
