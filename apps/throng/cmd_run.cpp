// `throng run SCENARIO.json` — loads and validates a scenario, opens the recording, then steps the
// World until the duration is reached, every agent has left, or SIGINT/SIGTERM arrives. Frame 0 is
// the state before the first tick; then every k-th tick is recorded (k from --fps and dt). Reads
// the scenario file; writes one SQLite recording, a progress line on stderr (terminal only) and a
// summary on stdout. Launched by mpirun with N > 1 ranks (OMPI_COMM_WORLD_SIZE or PMI_SIZE in the
// environment), every rank builds the world and they share the steer phase (libs/dist,
// docs/scaling.md); only rank 0 writes the recording and prints.
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "phase_timer.hpp"
#include "commands.hpp"
#include "output.hpp"
#include "progress.hpp"
#include "signal.hpp"
#include "stall_tracker.hpp"
#include "validators.hpp"
#include "throng/core/parallel.hpp"
#include "throng/core/simd.hpp"
#include "throng/recording/recorder.hpp"
#include "throng/io/scenario_loader.hpp"
#include "throng/sim/world.hpp"
#if THRONG_HAVE_MPI
#include "throng/dist/mpi_exchange.hpp"
#endif

namespace throng::cli {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// How often frames are recorded: every `stride` ticks, which is `fps` frames per second.
struct FramePlan {
  std::uint64_t stride = 1;  ///< ticks between recorded frames [>= 1]
  double fps = 10.0;         ///< the rate actually recorded [Hz]
  bool exact = true;         ///< false when the requested rate was rounded
};

FramePlan planFrames(double requestedFps, double dt) {
  const double ratio = 1.0 / (requestedFps * dt);
  FramePlan plan;
  plan.stride = static_cast<std::uint64_t>(std::max(1.0, std::round(ratio)));
  plan.exact = std::fabs(ratio - static_cast<double>(plan.stride)) <= 1e-6 * ratio;
  // dt is single precision (0.05f is not 0.05): keep the requested rate when it divides the tick rate.
  plan.fps = plan.exact ? requestedFps : 1.0 / (static_cast<double>(plan.stride) * dt);
  return plan;
}

/// Ranks mpirun started this process among (OpenMPI: OMPI_COMM_WORLD_SIZE; MPICH, Slurm: PMI_SIZE);
/// 1 when not launched by an MPI launcher.
std::uint32_t launchedRanks() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}) {
    if (const char* v = std::getenv(name); v != nullptr && *v != '\0') {
      const long n = std::strtol(v, nullptr, 10);
      if (n >= 1) return static_cast<std::uint32_t>(n);
    }
  }
  return 1;
}

/// This process's place among the ranks of an MPI run (rank 0 of 1 otherwise).
struct RankPlan {
  std::uint32_t rank = 0;
  std::uint32_t ranks = 1;
  /// Collective under MPI: true on every rank when true on any (the identity for one process).
  std::function<bool(bool)> anyRank = [](bool flag) { return flag; };
  [[nodiscard]] bool speaks() const { return rank == 0; }
};


enum class RunEnd { Duration, Finished, Interrupted, WriteError };

const char* endName(RunEnd end) {
  switch (end) {
    case RunEnd::Duration: return "duration";
    case RunEnd::Finished: return "finished";
    case RunEnd::Interrupted: return "interrupted";
    case RunEnd::WriteError: return "write error";
  }
  return "?";
}

struct LoopResult {
  RunEnd end = RunEnd::Duration;
  double wallSeconds = 0.0;
};

/// What agent `id` is doing (AgentInfo::state; "done" says where), or nullopt while standing is
/// its task: at an action point, in a Common Ground script (a visit, a wait its group agreed on), or
/// queuing for a lift or an escalator (also before its stop, where the queue reaches out that far).
std::optional<std::string> stallState(const sim::World& world, std::uint32_t id) {
  const auto info = world.agentInfo(id);
  if (!info || info->state == "at an action point" || info->state == "playing a Common Ground script" ||
      info->state == "at or on a lift or escalator" || info->state == "walking to a lift or escalator") {
    return std::nullopt;
  }
  if (info->state == "done") return std::string("done: stays at its last goal");
  return info->state;
}

/// Steps the world and pushes every `plan.stride`-th frame. Stops at `totalTicks`, when the world
/// is finished, or on a signal; except after a signal it steps on to the next multiple of the
/// stride so the last frame carries every event (an empty world steps in no time). Under MPI every
/// rank takes the same decisions: a signal is looked at (collectively) at frame ticks only, and
/// only rank 0 has a recorder; the others drop their frames (takeFrame() also clears the events).
LoopResult simulate(sim::World& world, recording::Recorder* recorder, const core::TaskSystem& tasks,
                    std::uint64_t totalTicks, const FramePlan& plan, double duration, ProgressLine& progress,
                    const RankPlan& ranks, sim::PhaseObserver* phases, StallTracker* stalls) {
  LoopResult result;
  const auto start = Clock::now();
  auto push = [&](sim::FramePtr frame) {
    if (stalls != nullptr) stalls->observe(*frame, [&world](std::uint32_t id) { return stallState(world, id); });
    if (recorder != nullptr) recorder->push(std::move(frame));
  };
  push(world.takeFrame());  // frame 0: the initial state at tick 0
  std::uint64_t tick = 0;
  while (true) {
    const bool atFrame = tick % plan.stride == 0;
    const bool interrupted = ranks.ranks == 1 ? InterruptGuard::requested()
                                              : atFrame && ranks.anyRank(InterruptGuard::requested());
    if (interrupted) {
      result.end = RunEnd::Interrupted;
      break;
    }
    // The first failed write (disk full, file too large) ends the run: nothing after it could be
    // recorded. Under MPI rank 0 tells the others at the next frame tick.
    const bool writeFailed = recorder != nullptr && recorder->failed();
    if (ranks.ranks == 1 ? writeFailed : atFrame && ranks.anyRank(writeFailed)) {
      result.end = RunEnd::WriteError;
      break;
    }
    if (atFrame && world.finished()) {
      result.end = RunEnd::Finished;
      break;
    }
    if (atFrame && tick >= totalTicks) {
      result.end = RunEnd::Duration;
      break;
    }
    world.step(tasks, phases);
    ++tick;
    if (tick % plan.stride == 0) push(world.takeFrame());
    if (progress.due()) {
      const auto& s = world.stats();
      progress.draw(formatRunProgress({s.time, duration, s.active, s.exited, secondsSince(start)}, progress.width()));
    }
  }
  result.wallSeconds = secondsSince(start);
  return result;
}

struct RunSummary {
  std::string scenario;
  std::uint64_t seed = 0;
  RunEnd end = RunEnd::Duration;
  sim::WorldStats stats;
  bool hasExit = false;
  bool evacuation = false;          ///< isEvacuation(scenario)
  std::vector<StallSpan> stalls;    ///< agents that made no progress for stallSeconds or more
  double stallSeconds = 0.0;
  double stallRadius = 0.0;         ///< [m]
  double wallSeconds = 0.0;
  double setupSeconds = 0.0;
  std::string recording;
  std::uint64_t frames = 0;
  double fps = 0.0;
  std::uint64_t stateHash = 0;      ///< World::stateHash at the end (id, position, velocity bits)
  sim::PartitionStats partition;    ///< ranks > 1: rank 0's share and the exchange totals
  std::uint64_t exchangedBytes = 0; ///< every rank's blocks, summed over ranks and ticks [bytes]
  std::vector<std::pair<std::string, double>> phaseSeconds;  ///< --phase-times: rank 0's [s]
};

/// An evacuation: every agent heads for an exit, its goals all exits or places it only passes
/// (interest points): no action points, no wandering, no automatic goals, no Common Ground goals.
bool isEvacuation(const sim::ScenarioDesc& desc) {
  if (desc.populations.empty() || desc.social.enabled) return false;
  return std::all_of(desc.populations.begin(), desc.populations.end(), [&](const sim::PopulationDesc& pop) {
    if (pop.goals.empty() || pop.wander || pop.autoGoals) return false;
    if (desc.points[pop.goals.back()].kind != sim::PointKind::Exit) return false;
    return std::none_of(pop.goals.begin(), pop.goals.end(),
                        [&](std::uint32_t g) { return desc.points[g].kind == sim::PointKind::Action; });
  });
}

/// Time until the last agent left, when every agent has left through an exit; < 0 otherwise.
double lastExitTime(const RunSummary& r) {
  const bool everyoneOut = r.stats.active == 0 && r.stats.scheduled == 0 && r.stats.exited > 0;
  return r.hasExit && everyoneOut ? r.stats.lastExitTime : -1.0;
}

/// The same, for evacuations only.
double evacuationTime(const RunSummary& r) { return r.evacuation ? lastExitTime(r) : -1.0; }

/// "finished (...)": why the run ended before its duration, without contradicting the counts.
std::string finishedText(const sim::WorldStats& s) {
  if (s.active == 0) return "finished (every agent left)";
  return fmt::format("finished (every agent reached its last goal; {} stay{} there)", s.active, s.active == 1 ? "s" : "");
}

/// "agent 24 36.0–264.0 s, agent 7 ..." (the first `limit`, then how many more).
std::string stallsText(const std::vector<StallSpan>& spans, std::size_t limit) {
  std::string text;
  for (std::size_t i = 0; i < spans.size() && i < limit; ++i) {
    text += fmt::format("{}agent {} {:.1f}–{:.1f} s ({})", i == 0 ? "" : "; ", spans[i].agent, spans[i].from, spans[i].to,
                        spans[i].state);
  }
  if (spans.size() > limit) text += fmt::format(" and {} more (--json lists them all)", spans.size() - limit);
  return text;
}

/// Agent-steps whose body overlapped a neighbour by more than 1 cm, in per cent of all.
double overlapShare(const sim::WorldStats& s) {
  return s.agentSteps > 0 ? 100.0 * static_cast<double>(s.overlapAgentSteps) / static_cast<double>(s.agentSteps) : 0.0;
}

double agentStepsPerSecond(const RunSummary& r) {
  return r.wallSeconds > 0 ? static_cast<double>(r.stats.agentSteps) / r.wallSeconds : 0.0;
}

void printSummaryJson(const RunSummary& r) {
  const double evac = evacuationTime(r);
  nlohmann::json out{{"scenario", r.scenario},
                     {"seed", r.seed},
                     {"status", endName(r.end)},
                     {"interrupted", r.end == RunEnd::Interrupted},
                     {"agents_spawned", r.stats.spawned},
                     {"agents_exited", r.stats.exited},
                     {"agents_active", r.stats.active},
                     {"agents_scheduled", r.stats.scheduled},
                     {"ticks", r.stats.tick},
                     {"simulated_time_s", r.stats.time},
                     {"evacuation", r.evacuation},
                     {"evacuation_time_s", evac >= 0 ? nlohmann::json(evac) : nlohmann::json(nullptr)},
                     {"last_exit_time_s", r.stats.lastExitTime >= 0 ? nlohmann::json(r.stats.lastExitTime) : nlohmann::json(nullptr)},
                     {"mean_walking_speed_mps", r.stats.meanWalkingSpeed()},
                     {"wall_time_s", r.wallSeconds},
                     {"setup_time_s", r.setupSeconds},
                     {"agent_steps", r.stats.agentSteps},
                     {"max_overlap_m", r.stats.maxOverlap},
                     {"overlap_share_pct", overlapShare(r.stats)},
                     {"agent_steps_per_s", agentStepsPerSecond(r)},
                     {"recording", {{"path", r.recording}, {"frames", r.frames}, {"fps", r.fps}}},
                     {"state_hash", fmt::format("{:016x}", r.stateHash)},
                     {"simd", std::string(core::simdPathName(core::simdPath()))}};
  nlohmann::json stalled = nlohmann::json::array();
  for (const StallSpan& span : r.stalls) {
    stalled.push_back({{"agent", span.agent}, {"from_s", span.from}, {"to_s", span.to}, {"state", span.state}});
  }
  out["stalled_agents"] = std::move(stalled);
  out["stall_min_s"] = r.stallSeconds;
  out["stall_radius_m"] = r.stallRadius;
  if (!r.phaseSeconds.empty()) {
    nlohmann::json phases = nlohmann::json::object();
    for (const auto& [name, seconds] : r.phaseSeconds) phases[name] = seconds;
    out["phase_seconds"] = phases;
  }
  if (r.partition.ranks > 1) {
    const auto& p = r.partition;
    out["mpi"] = {{"ranks", p.ranks},
                  {"migrations", p.migrations},
                  {"rebalance_moves", p.rebalanceMoves},
                  {"exchanged_bytes", r.exchangedBytes},
                  {"bytes_per_agent_step", p.agentSteps > 0 ? static_cast<double>(r.exchangedBytes) / static_cast<double>(p.agentSteps) : 0.0},
                  {"rank0_share", p.agentSteps > 0 ? static_cast<double>(p.ownedAgentSteps) / static_cast<double>(p.agentSteps) : 0.0}};
  }
  printLine(stdout, dumpJson(out));
}

void printSummaryText(const RunSummary& r) {
  const auto& s = r.stats;
  auto row = [](const char* key, const std::string& value) { printLine(stdout, fmt::format("{:<14}{}", key, value)); };
  row("scenario", fmt::format("{} (seed {})", displayText(r.scenario), r.seed));
  row("status", r.end == RunEnd::Interrupted ? "interrupted (recording closed, marked not completed)"
                : r.end == RunEnd::Finished  ? finishedText(s)
                                             : "duration reached");
  row("agents", fmt::format("{} spawned, {} exited, {} still inside", s.spawned, s.exited, s.active));
  row("simulated", fmt::format("{:.2f} s ({} ticks)", s.time, s.tick));
  if (r.evacuation) {
    const double evac = evacuationTime(r);
    if (evac >= 0) row("evacuation", fmt::format("{:.2f} s (last agent out)", evac));
    else row("evacuation", fmt::format("incomplete: {} agents inside, {} not spawned yet", s.active, s.scheduled));
  } else if (r.hasExit && s.exited > 0) {
    row("exits", fmt::format("{} agents left, the last at {:.2f} s", s.exited, s.lastExitTime));
  }
  if (!r.stalls.empty()) {
    std::vector<std::uint32_t> ids;
    for (const StallSpan& span : r.stalls) ids.push_back(span.agent);
    std::sort(ids.begin(), ids.end());
    const auto agents = static_cast<std::size_t>(std::unique(ids.begin(), ids.end()) - ids.begin());
    row("stalled", fmt::format("{} agent{} stood still (within {:g} m) for {:g} s or more{}: {}", agents,
                               agents == 1 ? "" : "s", r.stallRadius, r.stallSeconds,
                               r.stalls.size() > agents ? fmt::format(", {} spells", r.stalls.size()) : "",
                               stallsText(r.stalls, 10)));
  }
  row("mean speed", fmt::format("{:.2f} m/s (walking agents)", s.meanWalkingSpeed()));
  row("overlaps", fmt::format("discs of the body radius: deepest {:.2f} m; {:.1f} % of agent-steps overlap a neighbour by more than 1 cm",
                              s.maxOverlap, overlapShare(s)));
  const double realTime = r.wallSeconds > 0 ? s.time / r.wallSeconds : 0.0;
  row("wall time", fmt::format("{} ({:.1f}x real time; setup {})", formatSeconds(r.wallSeconds), realTime,
                               formatSeconds(r.setupSeconds)));
  row("throughput", fmt::format("{} agent-steps/s", formatSi(agentStepsPerSecond(r))));
  row("recording", fmt::format("{} ({} frames at {:g} fps)", r.recording, r.frames, r.fps));
  if (!r.phaseSeconds.empty()) {
    double total = 0.0;
    for (const auto& entry : r.phaseSeconds) total += entry.second;
    std::string text;
    for (const auto& [name, seconds] : r.phaseSeconds) {
      text += fmt::format("{}{} {:.3f} s ({:.1f} %)", text.empty() ? "" : ", ", name, seconds,
                          total > 0 ? 100.0 * seconds / total : 0.0);
    }
    row("phases", text);
  }
  if (r.partition.ranks > 1) {
    const auto& p = r.partition;
    row("MPI", fmt::format("{} ranks, {} migrations ({} more by rebalancing), exchange {:.2f} MB ({:g} B per agent-step); "
                           "rank 0 steered {:.1f} %",
                           p.ranks, p.migrations, p.rebalanceMoves, static_cast<double>(r.exchangedBytes) / 1e6,
                           p.agentSteps > 0 ? static_cast<double>(r.exchangedBytes) / static_cast<double>(p.agentSteps) : 0.0,
                           p.agentSteps > 0 ? 100.0 * static_cast<double>(p.ownedAgentSteps) / static_cast<double>(p.agentSteps) : 0.0));
  }
}

std::string defaultOutput(const std::string& scenarioPath) {
  return std::filesystem::path(scenarioPath).stem().string() + ".sqlite";
}

}  // namespace

CLI::App* addRunCommand(CLI::App& app, RunOptions& options) {
  CLI::App* cmd = app.add_subcommand("run", "Simulate a scenario and record the trajectories");
  cmd->footer(
      "Simulate a scenario and record the trajectories to SQLite (JuPedSim trajectory format v2).\n"
      "The scenario is validated first (every problem reported, exit 1, no file written), then the\n"
      "recording is opened, then the crowd is simulated until --duration or until every agent has\n"
      "left. Ctrl-C stops cleanly: the recording is closed as a valid file marked not completed,\n"
      "and the exit code is 130.\n"
      "The summary gives an evacuation time only for evacuations (every population heads for an exit\n"
      "without action points, wandering or generated goals) and names stalled agents: those that stood\n"
      "within 0.5 m for 60 s or more outside actions and Common Ground scripts, with when and why.\n"
      "Under mpirun (N > 1 ranks: OMPI_COMM_WORLD_SIZE or PMI_SIZE set), every rank simulates the\n"
      "world and they share the steer phase; rank 0 alone writes the recording and prints. The\n"
      "trajectories are identical to one process (docs/scaling.md).");
  cmd->add_option("scenario", options.scenario, "Scenario JSON file")->required()->type_name("SCENARIO.json");
  cmd->add_option("--seed", options.seed, "Random seed; overrides the scenario's \"seed\"")->type_name("N");
  cmd->add_option("--duration", options.duration,
                  "Simulated time [s]; overrides the scenario's \"duration\". The run also ends once every "
                  "agent has left")
      ->type_name("S")
      ->check(positiveNumber("s"));
  cmd->add_option("--threads", options.threads, "Worker threads; 0 = all hardware threads. Results do not depend on it")
      ->type_name("N")
      ->check(integerRange(0, 1024))
      ->capture_default_str();
  cmd->add_option("--out", options.out,
                  "Recording file; default: <scenario file name without .json>.sqlite in the current directory")
      ->type_name("FILE.sqlite");
  cmd->add_flag("--force", options.force, "Overwrite an existing recording file");
  cmd->add_option_function<std::string>(
         "--common-ground",
         [&options](const std::string& v) { options.commonGround = v == "on"; },
         "Common Ground coordination on or off (overrides the scenario's \"social\"/\"commonGround\"; off: agents "
         "visit their generated goals alone, without telling their group)")
      ->check(CLI::IsMember({"on", "off"}))
      ->type_name("on|off");
  cmd->add_option("--fps", options.fps,
                  "Recorded frames per second [Hz]: every k-th tick is written, k = round(1/(fps*dt)) >= 1; "
                  "the rate actually used is stored in the recording")
      ->type_name("F")
      ->check(positiveNumber("Hz"))
      ->capture_default_str();
  cmd->add_flag("--phase-times", options.phaseTimes,
                "Time every phase of the tick and print the totals (rank 0's under MPI; the clock reads cost a "
                "little)");
  cmd->add_flag("--quiet,-q", options.quiet, "Print nothing but errors (no progress, no warnings, no text summary)");
  cmd->add_flag("--json", options.json, "Print the summary as one JSON object on stdout (also with --quiet)");
  return cmd;
}

namespace {

/// The exit code of a step that ends the run early; nullopt: go on.
using EarlyExit = std::optional<int>;

/// Loads and validates the scenario (Ctrl-C stops a long validation); nothing is written when it
/// is bad. Every rank takes the same path; only rank 0 prints.
EarlyExit loadForRun(const RunOptions& options, const RankPlan& ranks, std::optional<io::LoadedScenario>& out) {
  const bool speaks = ranks.speaks();
  if (auto missing = checkInputFile(options.scenario, "scenario"); !missing.empty()) {
    if (speaks) printDiagnostics(missing);
    return kExitFailure;
  }
  io::LoadOptions load;
  load.cancel = &InterruptGuard::flag();  // Ctrl-C stops a long validation too
  auto loaded = io::loadScenarioFile(options.scenario, load);
  if (!loaded && ranks.anyRank(InterruptGuard::requested())) {
    if (speaks) printLine(stderr, "throng: interrupted while checking the scenario; nothing written");
    return kExitInterrupted;
  }
  if (!loaded) {
    if (speaks) printDiagnostics(loaded.errors());
    return kExitFailure;
  }
  out.emplace(std::move(loaded).value());
  return std::nullopt;
}

/// --seed, --common-ground and --duration over the scenario's own values.
EarlyExit applyOverrides(const RunOptions& options, bool speaks, sim::ScenarioDesc& desc) {
  if (options.seed) desc.seed = *options.seed;
  if (options.commonGround) {
    if (!desc.social.enabled) {
      if (speaks) {
        std::fprintf(stderr, "throng run: --common-ground: %s has no \"social\" section; nothing to switch\n",
                     options.scenario.c_str());
      }
      return kExitUsage;
    }
    desc.social.commonGround = *options.commonGround;
  }
  if (options.duration) desc.duration = static_cast<float>(*options.duration);
  return std::nullopt;
}

/// The file name of a glTF / GLB world the scenario is read from (stored so that a replay can draw
/// its materials); empty for a scenario JSON.
std::string worldFileName(const std::string& scenario) {
  const std::filesystem::path p(scenario);
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".gltf" || ext == ".glb" ? p.filename().string() : std::string();
}

recording::RecordingOptions recordingOptions(const RunOptions& options, const io::LoadedScenario& loaded, const FramePlan& plan) {
  recording::RecordingOptions recording;
  recording.path = options.out.empty() ? defaultOutput(options.scenario) : options.out;
  recording.force = options.force;
  recording.fps = plan.fps;
  recording.seed = loaded.desc.seed;
  recording.scenarioText = loaded.text;
  recording.worldFile = worldFileName(options.scenario);
  return recording;
}

/// Opens the recording (rank 0 only): a bad or existing path fails before any simulation.
EarlyExit openRecorder(const sim::ScenarioDesc& desc, const recording::RecordingOptions& recording, const RankPlan& ranks,
                       std::unique_ptr<recording::Recorder>& recorder) {
  bool openFailed = false;
  if (ranks.speaks()) {
    auto opened = recording::Recorder::open(desc, recording);
    if (!opened) {
      printDiagnostics(opened.errors());
      openFailed = true;
    } else {
      recorder = std::move(opened.value());
    }
  }
  if (ranks.anyRank(openFailed)) return kExitFailure;
  return std::nullopt;
}

/// Closes the recording, completed unless interrupted or a write failed; a failure says how much
/// of the file holds.
EarlyExit closeRecording(recording::Recorder* recorder, RunEnd end, const sim::World& world, const std::string& path) {
  if (recorder) {
    const core::Status closed = recorder->close(end != RunEnd::Interrupted && end != RunEnd::WriteError);
    if (!closed) {
      printDiagnostics(closed.errors());
      printLine(stderr, fmt::format("throng: {} at t = {:.2f} s; {} holds the {} frames written before the error and "
                                    "is marked not completed",
                                    end == RunEnd::WriteError ? "stopped at the first write error" : "the recording failed",
                                    world.stats().time, path, recorder->framesWritten()));
      return kExitFailure;
    }
  }
  if (end == RunEnd::WriteError) return kExitFailure;  // another rank's recorder failed (MPI)
  return std::nullopt;
}

/// What the summary reports, from the world at the end and the run's own counters.
void summarize(RunSummary& summary, const sim::ScenarioDesc& desc, const LoopResult& loop, const sim::World& world,
               StallTracker& stalls, const recording::Recorder* recorder, const std::string& path, const FramePlan& plan,
               const PhaseTimer& phaseTimer) {
  summary.scenario = desc.name;
  summary.seed = desc.seed;
  summary.end = loop.end;
  summary.stats = world.stats();
  summary.hasExit = desc.hasExit();
  summary.evacuation = isEvacuation(desc);
  summary.stalls = stalls.finish(summary.stats.time);
  summary.stallSeconds = stalls.minSeconds();
  summary.stallRadius = stalls.radius();
  summary.wallSeconds = loop.wallSeconds;
  summary.recording = path;
  summary.frames = recorder ? recorder->framesWritten() : 0;
  summary.fps = plan.fps;
  summary.stateHash = world.stateHash();
  summary.partition = world.partitionStats();
  summary.exchangedBytes = summary.partition.gatheredBytes;
  summary.phaseSeconds = phaseTimer.totals();  // every rank's blocks, as every rank received them
}

/// Prints the summary (rank 0: JSON or text) and gives the exit code.
int finishRun(const RunOptions& options, const RunSummary& summary, bool speaks) {
  if (!speaks) return summary.end == RunEnd::Interrupted ? kExitInterrupted : kExitOk;
  if (options.json) printSummaryJson(summary);
  else if (!options.quiet) printSummaryText(summary);
  if (summary.end == RunEnd::Interrupted) {
    if (options.quiet && !options.json) {
      printLine(stderr, fmt::format("throng: interrupted at t = {:.2f} s; {} is closed and marked not completed",
                                    summary.stats.time, summary.recording));
    }
    return kExitInterrupted;
  }
  return kExitOk;
}

/// The run on one rank (of one, or of an MPI job: then `exchange` shares the steer phase).
int runOn(const RunOptions& options, const RankPlan& ranks, sim::StepExchange* exchange) {
  const auto setupStart = Clock::now();
  // Installed first so Ctrl-C during a long load is handled too (before any file exists).
  InterruptGuard interrupts;
  const bool speaks = ranks.speaks();  // only rank 0 prints; every rank takes the same path

  // 1. Load and validate: nothing is written when the scenario is bad.
  std::optional<io::LoadedScenario> loaded;
  if (auto exit = loadForRun(options, ranks, loaded)) return *exit;
  sim::ScenarioDesc& desc = loaded->desc;
  if (auto exit = applyOverrides(options, speaks, desc)) return *exit;
  const FramePlan plan = planFrames(options.fps, desc.dt);
  if (!plan.exact && !options.quiet && speaks) {
    printLine(stderr, "throng: warning: " +
                          fmt::format("--fps {:g} does not divide the tick rate {:g} Hz (dt = {:g} s); recording every {} "
                                      "ticks = {:.4g} fps",
                                      options.fps, 1.0 / desc.dt, desc.dt, plan.stride, plan.fps));
  }
  auto world = sim::World::create(desc, loaded->navmesh);
  if (!world) {
    if (speaks) printDiagnostics(world.errors());
    return kExitFailure;
  }
  if (ranks.anyRank(InterruptGuard::requested())) {
    if (speaks) printLine(stderr, "throng: interrupted before simulating; nothing written");
    return kExitInterrupted;
  }

  // 2. Open the recording.
  const recording::RecordingOptions recording = recordingOptions(options, *loaded, plan);
  std::unique_ptr<recording::Recorder> recorder;
  if (auto exit = openRecorder(desc, recording, ranks, recorder)) return *exit;

  // 3. Simulate.
  const core::TaskSystem tasks(options.threads);
  if (exchange != nullptr) (*world)->setPartition(exchange);
  const auto totalTicks = static_cast<std::uint64_t>(std::max(0LL, std::llround(static_cast<double>(desc.duration) / desc.dt)));
  RunSummary summary;
  summary.setupSeconds = secondsSince(setupStart);
  LoopResult loop;
  PhaseTimer phaseTimer;
  StallTracker stalls;
  {
    ProgressLine progress(stderr, !options.quiet && speaks);  // cleared when it goes out of scope
    loop = simulate(**world, recorder.get(), tasks, totalTicks, plan, desc.duration, progress, ranks,
                    options.phaseTimes ? &phaseTimer : nullptr, speaks ? &stalls : nullptr);
  }
  if (auto exit = closeRecording(recorder.get(), loop.end, **world, recording.path)) return *exit;
  summarize(summary, desc, loop, **world, stalls, recorder.get(), recording.path, plan, phaseTimer);
  return finishRun(options, summary, speaks);
}

}  // namespace

int runRun(const RunOptions& options) {
  const std::uint32_t launched = launchedRanks();
  if (launched <= 1) return runOn(options, RankPlan{}, nullptr);
#if THRONG_HAVE_MPI
  auto session = dist::MpiSession::start();
  if (!session) {
    printDiagnostics(session.errors());
    return kExitFailure;
  }
  dist::MpiSession& mpi = **session;
  RankPlan ranks;
  ranks.rank = mpi.rank();
  ranks.ranks = mpi.ranks();
  ranks.anyRank = [&mpi](bool flag) { return mpi.anyRank(flag); };
  if (ranks.ranks <= 1) return runOn(options, RankPlan{}, nullptr);
  dist::MpiExchange exchange(mpi);
  return runOn(options, ranks, &exchange);
#else
  printLine(stderr, fmt::format("throng run: launched by an MPI launcher with {} ranks, but this throng was built "
                                "without MPI (install libopenmpi-dev and reconfigure); run it as one process",
                                launched));
  return kExitFailure;
#endif
}

}  // namespace throng::cli
