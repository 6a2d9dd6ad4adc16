// `throng bench` — times the full tick, then DetourCrowd on the same navmesh and agent count, and
// prints agent-steps/s, ms per tick (median, p99), peak RSS and bytes per agent. Two kinds of
// scenario: in-memory ones (throng/bench/scenarios.hpp) at each --agents count, timed for a number of
// ticks after a warm-up; and scenario files ("mall" or PATH.json) run from the start to their end,
// also reporting simulated time, wall time and × real time. With --record each configuration is
// timed again while writing a recording (recording::Recorder, frames at --fps, as `throng run` does) to a
// temporary file that is deleted afterwards. Reads the process's memory counters (/proc/self/statm,
// getrusage) and the scenario file; writes a table or JSON lines on stdout and a progress line on a
// terminal's stderr.
//
// This file: in-memory scenarios, timing one configuration (both kinds), the table and footnotes,
// and the command line; scenario files (resolving --scenario, running each configuration) are in
// cmd_bench_file.cpp, BenchRunner and Measurement in cmd_bench_runner.hpp.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <optional>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <malloc.h>
#include <nlohmann/json.hpp>
#include <sys/resource.h>
#include <unistd.h>

#include "phase_timer.hpp"
#include "bench_files.hpp"
#include "cmd_bench_runner.hpp"
#include "commands.hpp"
#include "output.hpp"
#include "progress.hpp"
#include "signal.hpp"
#include "validators.hpp"
#include "throng/bench/detour_crowd_baseline.hpp"
#include "throng/bench/scenarios.hpp"
#include "throng/core/parallel.hpp"
#include "throng/core/simd.hpp"
#include "throng/recording/recorder.hpp"
#include "throng/io/scenario_loader.hpp"
#include "throng/sim/world.hpp"

namespace throng::cli {
namespace {

using Clock = std::chrono::steady_clock;

constexpr double kTargetSecondsPerConfig = 3.0;  ///< without --ticks, time ticks until this much work [s]
constexpr int kMinAutoTicks = 10;
constexpr int kMaxAutoTicks = 3000;
constexpr std::uint64_t kRssSampleTicks = 32;  ///< file scenarios: resident memory read every this many ticks

/// Resident set size now [bytes] (/proc/self/statm), 0 when unknown.
double currentRss() {
  std::ifstream statm("/proc/self/statm");
  long long size = 0, resident = 0;
  if (!(statm >> size >> resident)) return 0.0;
  return static_cast<double>(resident) * static_cast<double>(::sysconf(_SC_PAGESIZE));
}

/// Peak resident set size of the process so far [bytes] (getrusage; Linux reports KiB).
double peakRss() {
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) * 1024.0;
}


/// Agents in a bench scenario (groups of a fixed size).
std::size_t agentCount(const sim::ScenarioDesc& desc) {
  std::size_t total = 0;
  for (const auto& p : desc.populations) total += static_cast<std::size_t>(p.groups) * p.sizeMin;
  return total;
}

double percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(values.size())));
  return values[std::clamp<std::size_t>(rank, 1, values.size()) - 1];
}

double roundMicro(double v) { return std::round(v * 1e6) / 1e6; }

/// When the timed ticks of one configuration stop. In-memory: a fixed --ticks, or (ticks <= 0) as
/// many as fit in kTargetSecondsPerConfig. File: the scenario's end (finished or duration, --ticks
/// caps), checked at frame ticks so runs with and without --record cover the same ticks.
struct TickPlan {
  bool fileMode = false;
  std::uint64_t stride = 1;      ///< ticks between recorded frames
  std::uint64_t totalTicks = 0;  ///< file mode: ticks to the end
  int ticks = 0;                 ///< --ticks (<= 0: automatic)

  [[nodiscard]] bool done(std::uint64_t tick, const sim::World& w, double totalSeconds) const {
    if (fileMode) return tick % stride == 0 && (w.finished() || tick >= totalTicks);
    return ticks > 0 ? tick >= static_cast<std::uint64_t>(ticks)
                     : (tick >= kMaxAutoTicks || (tick >= kMinAutoTicks && totalSeconds >= kTargetSecondsPerConfig));
  }
};

/// What the timed ticks measured.
struct TimedTicks {
  std::vector<double> ms;     ///< each tick [ms]
  double totalSeconds = 0.0;  ///< their sum [s]
  double rssPeak = 0.0;       ///< resident memory, sampled (file mode) and at the end [bytes]
  std::size_t agentsPeak = 0; ///< most agents present at once
};

/// Steps and times each tick until the plan is done or Ctrl-C, recording every stride-th frame;
/// `onTick(tick, totalSeconds)` after each (the progress line).
TimedTicks runTimedTicks(sim::World& w, const core::TaskSystem& tasks, recording::Recorder* recorder, const TickPlan& plan,
                         sim::PhaseObserver* phases, const std::function<void(std::uint64_t, double)>& onTick) {
  TimedTicks t;
  t.rssPeak = currentRss();
  t.agentsPeak = w.stats().active;
  for (std::uint64_t tick = 0; !InterruptGuard::requested(); ++tick) {
    if (plan.done(tick, w, t.totalSeconds)) break;
    const auto t0 = Clock::now();
    w.step(tasks, phases);
    if (recorder && (tick + 1) % plan.stride == 0) recorder->push(w.takeFrame());
    const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    t.totalSeconds += seconds;
    t.ms.push_back(seconds * 1000.0);
    t.agentsPeak = std::max<std::size_t>(t.agentsPeak, w.stats().active);
    if (plan.fileMode && tick % kRssSampleTicks == 0) t.rssPeak = std::max(t.rssPeak, currentRss());
    onTick(tick, t.totalSeconds);
  }
  t.rssPeak = std::max(t.rssPeak, currentRss());
  return t;
}

/// The world's counters before the timed ticks, to measure the timed ticks alone.
struct WorldBefore {
  std::uint64_t agentSteps = 0;
  double time = 0.0;     ///< [s]
  double walked = 0.0;   ///< [m]
};

/// Rates, percentiles and memory of the timed ticks into `m`.
void fillMeasurement(bench_detail::Measurement& m, const TimedTicks& timed, const sim::WorldStats& after, const WorldBefore& before,
                     double dt) {
  const auto steps = static_cast<double>(after.agentSteps - before.agentSteps);
  m.agentStepsPerSec = timed.totalSeconds > 0 ? steps / timed.totalSeconds : 0.0;
  // Distance walked per agent-second, over every agent of the timed ticks (as DetourCrowd's).
  m.meanSpeed = steps > 0 ? (after.walkedDistance - before.walked) / (steps * dt) : 0.0;
  m.msMedian = percentile(timed.ms, 0.5);
  m.msP99 = percentile(timed.ms, 0.99);
  m.peakRssBytes = peakRss();
  m.simulatedSeconds = after.time - before.time;
  m.wallSeconds = timed.totalSeconds;
}

}  // namespace

namespace bench_detail {

void BenchRunner::status(const std::string& text, bool force) {
  if (force || progress_.due()) progress_.draw(text);
}

std::unique_ptr<recording::Recorder> BenchRunner::openRecording(const sim::ScenarioDesc& desc, double fps,
                                                         const std::string& path) {
  recording::RecordingOptions recording;
  recording.path = path;
  recording.force = true;
  recording.fps = fps;
  recording.seed = desc.seed;
  recording.scenarioText = scenarioText_;
  auto opened = recording::Recorder::open(desc, recording);
  if (!opened) {
    progress_.clear();
    printLine(stderr, "throng: bench --record: cannot open the temporary recording:");
    printDiagnostics(opened.errors());
    return nullptr;
  }
  return std::move(*opened);
}

bool BenchRunner::closeRecording(recording::Recorder& recorder, const std::string& label, bool completed, Measurement& m) {
  // Closing flushes the frames still queued and checkpoints the file.
  status(label + ": closing the recording", true);
  const auto t0 = Clock::now();
  const core::Status closed = recorder.close(completed);
  m.closeSeconds = std::chrono::duration<double>(Clock::now() - t0).count();
  if (!closed) {
    progress_.clear();
    printDiagnostics(closed.errors());
    return false;
  }
  m.frames = recorder.framesWritten();
  return true;
}

void BenchRunner::drawTickProgress(const std::string& label, const sim::World& w, std::uint64_t tick, int ticks,
                                   double totalSeconds) {
  if (!progress_.due()) return;
  progress_.draw(fileMode_ ? fmt::format("{}: t = {:.0f}/{:.0f} s, {} agents", label, w.stats().time, duration_,
                                         w.stats().active)
                 : ticks > 0 ? fmt::format("{}: tick {}/{}", label, tick + 1, ticks)
                             : fmt::format("{}: tick {} ({:.1f}/{:.0f} s)", label, tick + 1, totalSeconds,
                                           kTargetSecondsPerConfig));
}

std::optional<Measurement> BenchRunner::timeThrong(const sim::ScenarioDesc& desc,
                                                   const std::shared_ptr<const nav::NavMesh>& navmesh, int threads,
                                                   int& ticks, bool record) {
  const std::size_t n = fileMode_ ? 0 : agentCount(desc);
  const std::string label = fileMode_ ? fmt::format("{}{} threads={}", label_, record ? " +rec" : "", threads)
                                      : fmt::format("throng{} {} N={} threads={}", record ? "+rec" : "", label_, n,
                                                    threads);
  status(label + ": building world", true);
  ::malloc_trim(0);  // hand freed pages back so the growth below is this world's
  const double rssBefore = currentRss();
  auto world = sim::World::create(desc, navmesh);
  if (!world) {
    progress_.clear();
    printDiagnostics(world.errors());
    return std::nullopt;
  }
  const core::TaskSystem tasks(threads);
  sim::World& w = **world;

  // Frames every `stride` ticks, as `throng run`.
  double fps = options_.fps;
  TickPlan plan;
  plan.fileMode = fileMode_;
  plan.stride = benchFrameStride(options_.fps, dt_, fps);
  plan.ticks = ticks;
  const auto toEnd = static_cast<std::uint64_t>(std::max(0LL, std::llround(duration_ / dt_)));
  plan.totalTicks = ticks > 0 ? std::min<std::uint64_t>(toEnd, static_cast<std::uint64_t>(ticks)) : toEnd;
  std::optional<TempRecording> temp;  // declared before the recorder: the file is deleted after it closes
  std::unique_ptr<recording::Recorder> recorder;
  if (record) {
    temp.emplace();
    recorder = openRecording(desc, fps, temp->path());
    if (!recorder) return std::nullopt;
  }

  for (int i = 0; !fileMode_ && i < options_.warmup && !InterruptGuard::requested(); ++i) {
    w.step(tasks);
    status(fmt::format("{}: warm-up {}/{}", label, i + 1, options_.warmup));
  }
  double bytesPerAgent = n > 0 ? std::max(0.0, currentRss() - rssBefore) / static_cast<double>(n) : 0.0;
  if (recorder) recorder->push(w.takeFrame());  // frame 0: the state before the first timed tick

  PhaseTimer phases;  // --phase-times: the timed ticks only
  const WorldBefore before{w.stats().agentSteps, w.stats().time, w.stats().walkedDistance};
  TimedTicks timed = runTimedTicks(w, tasks, recorder.get(), plan, options_.phaseTimes ? &phases : nullptr,
                                   [&](std::uint64_t tick, double totalSeconds) {
                                     drawTickProgress(label, w, tick, ticks, totalSeconds);
                                   });
  const bool interrupted = InterruptGuard::requested();
  Measurement m;
  if (recorder) {
    if (!closeRecording(*recorder, label, !interrupted, m)) return std::nullopt;
    // Part of a whole run's cost, so counted in a file scenario's wall time; an in-memory row
    // times the ticks only.
    if (fileMode_) timed.totalSeconds += m.closeSeconds;
    m.recordedFps = fps;
  }
  ticks = static_cast<int>(timed.ms.size());
  if (interrupted) return std::nullopt;
  for (const auto& [name, seconds] : phases.totals()) {
    m.phaseMs.emplace_back(name, ticks > 0 ? 1000.0 * seconds / ticks : 0.0);
  }
  if (fileMode_) {
    bytesPerAgent = timed.agentsPeak > 0 ? std::max(0.0, timed.rssPeak - rssBefore) / static_cast<double>(timed.agentsPeak)
                                         : 0.0;
  }
  m.engine = record ? "throng+rec" : "throng";
  m.agents = fileMode_ ? timed.agentsPeak : n;
  m.threads = tasks.threads();
  m.ticks = ticks;
  m.bytesPerAgent = bytesPerAgent;
  fillMeasurement(m, timed, w.stats(), before, dt_);
  return m;
}

std::optional<Measurement> BenchRunner::timeBaseline(const sim::ScenarioDesc& desc,
                                                     const std::shared_ptr<const nav::NavMesh>& navmesh, int ticks) {
  const std::size_t n = agentCount(desc);
  const std::string label = fmt::format("detourcrowd {} N={}", label_, n);
  status(label + ": starting", true);
  bench::BaselineConfig config;
  config.navmesh = navmesh;
  config.starts = bench::drawStarts(navmesh, n, options_.seed);
  config.radius = bench::kRadius;
  config.speed = bench::kSpeed;
  config.dt = bench::kDt;
  config.seed = options_.seed;
  config.warmupTicks = options_.warmup;
  config.ticks = ticks;
  config.progress = [&](int done, int total) {
    status(fmt::format("{}: {} {}/{}", label, done <= options_.warmup ? "warm-up" : "tick",
                       done <= options_.warmup ? done : done - options_.warmup,
                       done <= options_.warmup ? options_.warmup : total - options_.warmup),
           done == total);
  };
  ::malloc_trim(0);
  auto result = bench::runDetourCrowd(config);
  if (!result) {
    progress_.clear();
    printLine(stderr, "throng: DetourCrowd baseline failed:");
    printDiagnostics(result.errors());
    return std::nullopt;
  }
  Measurement m;
  m.engine = result->engine;
  m.agents = result->agents;
  m.threads = 1;
  m.ticks = result->ticks;
  m.agentStepsPerSec = result->agentStepsPerSec;
  m.msMedian = result->msPerTickMedian;
  m.msP99 = result->msPerTickP99;
  m.bytesPerAgent = result->bytesPerAgent;
  m.meanSpeed = result->meanSpeed;
  m.peakRssBytes = peakRss();
  m.simulatedSeconds = result->ticks * static_cast<double>(bench::kDt);
  m.wallSeconds = m.agentStepsPerSec > 0 ? static_cast<double>(result->ticks * result->agents) / m.agentStepsPerSec
                                         : 0.0;
  return m;
}

void BenchRunner::printHeader() const {
  if (options_.json) return;
  const std::size_t width = std::max<std::size_t>(8, label_.size());
  std::string header = fmt::format("{:<12} {:<{}} {:>8} {:>7} {:>6} {:>14} {:>11} {:>11} {:>11} {:>10} {:>9}",
                                   "engine", "scenario", width, fileMode_ ? "peak N" : "agents", "threads", "ticks",
                                   "agent-steps/s", "ms/tick med", "ms/tick p99", "bytes/agent", "peak RSS", "speed m/s");
  header += fileMode_ ? fmt::format(" {:>10} {:>9} {:>8}", "simulated", "wall", "x real") : fmt::format(" {:>8}", "vs DC");
  printLine(stdout, header);
}

void BenchRunner::print(const Measurement& m) {
  progress_.clear();
  if (options_.json) {
    nlohmann::json line{{"engine", m.engine},
                        {"scenario", label_},
                        {"agents", m.agents},
                        {"threads", m.threads},
                        {"ticks", m.ticks},
                        {"warmup_ticks", fileMode_ ? 0 : options_.warmup},
                        {"dt_s", roundMicro(dt_)},
                        {"agent_steps_per_s", m.agentStepsPerSec},
                        {"ms_per_tick_median", m.msMedian},
                        {"ms_per_tick_p99", m.msP99},
                        {"bytes_per_agent", m.bytesPerAgent},
                        {"peak_rss_bytes", m.peakRssBytes},
                        {"simulated_s", roundMicro(m.simulatedSeconds)},
                        {"wall_s", m.wallSeconds},
                        {"realtime_factor", m.realtimeFactor()},
                        {"mean_speed_mps", m.meanSpeed}};
    if (m.engine != kDetourCrowdEngine) {
      line["speedup_vs_detourcrowd"] = m.speedup ? nlohmann::json(*m.speedup) : nlohmann::json(nullptr);
    }
    if (fileMode_) line["scenario_file"] = filePath_;
    if (m.engine != kDetourCrowdEngine) line["model"] = options_.model.empty() ? (fileMode_ ? "scenario" : "orca") : options_.model;
    if (m.engine != kDetourCrowdEngine) line["row_order"] = options_.rowOrder;
    if (m.engine != kDetourCrowdEngine) line["simd"] = std::string(core::simdPathName(core::simdPath()));
    if (m.recordedFps) {
      line["recording"] = {{"fps", *m.recordedFps}, {"frames", m.frames}, {"close_s", m.closeSeconds}};
    }
    if (!m.phaseMs.empty()) {
      nlohmann::json phaseMs = nlohmann::json::object();
      for (const auto& [name, value] : m.phaseMs) phaseMs[name] = value;
      line["phase_ms_per_tick"] = phaseMs;
    }
    printLine(stdout, line.dump());
    return;
  }
  const std::size_t width = std::max<std::size_t>(8, label_.size());
  std::string row = fmt::format("{:<12} {:<{}} {:>8} {:>7} {:>6} {:>14} {:>11.3f} {:>11.3f} {:>11.0f} {:>10} {:>9.2f}",
                                m.engine, label_, width, m.agents, m.threads, m.ticks, formatSi(m.agentStepsPerSec),
                                m.msMedian, m.msP99, m.bytesPerAgent, formatBytes(m.peakRssBytes), m.meanSpeed);
  row += fileMode_ ? fmt::format(" {:>10} {:>9} {:>7.1f}x", fmt::format("{:.1f} s", m.simulatedSeconds),
                                 formatSeconds(m.wallSeconds), m.realtimeFactor())
                   : fmt::format(" {:>8}", m.speedup ? fmt::format("{:.2f}x", *m.speedup) : "-");
  printLine(stdout, row);
  if (!m.phaseMs.empty()) {
    std::string phasesLine = "  ms/tick by phase:";
    for (const auto& [name, value] : m.phaseMs) phasesLine += fmt::format(" {} {:.2f}", name, value);
    printLine(stdout, phasesLine);
  }
}

void BenchRunner::printFootnotes() const {
  if (options_.json) {
    for (const auto& note : notes_) printLine(stderr, "note: " + note);
    return;
  }
  printLine(stdout, "");
  if (fileMode_) {
    printLine(stdout, fmt::format("scenario: {} (dt {:g} s), each configuration run from tick 0 until every agent has "
                                  "left or t = {:g} s; every tick timed alone (steady_clock), World::create not timed",
                                  filePath_, dt_, duration_));
    printLine(stdout, "bytes/agent: peak growth of resident memory from before World::create (sampled every 32 "
                      "ticks) divided by the most agents present at once (peak N); x real: simulated / wall time");
  } else {
    printLine(stdout, fmt::format("scenario: {} — square of side sqrt(N) m (1 agent/m²), radius {} m, speed {} m/s, "
                                  "dt {} s, agents wander between random points{}",
                                  label_, bench::kRadius, bench::kSpeed, bench::kDt,
                                  layout_ == bench::Layout::Navmesh ? "; 1 m pillars every 8 m" : ""));
    printLine(stdout, fmt::format("timing: {} untimed warm-up ticks, then each tick timed alone (steady_clock)",
                                  options_.warmup));
    printLine(stdout, "bytes/agent: growth of resident memory from before World::create to after warm-up, divided "
                      "by N (the shared navmesh is built before and not counted); peak RSS: the process's so far");
    printLine(stdout, "vs DC: throng agent-steps/s divided by DetourCrowd's at the same N, on the same navmesh; "
                      "DetourCrowd starts are drawn uniformly on the navmesh (same distribution, not the same points); "
                      "DetourCrowd runs on one thread, so the threads=1 row compares like with like");
    printLine(stdout, "speed m/s: distance walked per agent-second over the timed ticks, every agent counted "
                      "(both engines alike)");
  }
  if (options_.record) {
    printLine(stdout, fmt::format("throng+rec: the same configuration again, writing a recording at {:g} fps to a "
                                  "temporary file (deleted afterwards) as `throng run` does; its tick times include "
                                  "taking and queueing frames (the writer thread runs beside the ticks){}",
                                  options_.fps,
                                  fileMode_ ? ", its wall time and x real also closing the file (flush, checkpoint)"
                                            : "; closing the file is not timed"));
  }
  printLine(stdout, fmt::format("simd: {} (the vector path of throng's hot loops; THRONG_SIMD=portable or avx2 picks one, "
                                "with the same trajectories)",
                                core::simdPathName(core::simdPath())));
  for (const auto& note : notes_) printLine(stdout, "note: " + note);
}

int BenchRunner::runLayouts() {
  label_ = options_.scenario;
  std::vector<std::size_t> counts = options_.agents.empty() ? std::vector<std::size_t>{1000, 10000, 100000}
                                                            : options_.agents;
  std::vector<int> threadCounts = options_.threads.empty() ? std::vector<int>{1, 2} : options_.threads;
  if (options_.duration) notes_.push_back("--duration is used with scenario files only (here: --ticks)");
  InterruptGuard interrupts;
  printHeader();
  for (const std::size_t n : counts) {
    sim::ScenarioDesc desc = bench::makeScenario(layout_, n, options_.seed);
    applyModel(desc, options_.model);
    applyRowOrder(desc, options_.rowOrder);
    duration_ = desc.duration;
    status(fmt::format("{} N={}: building navmesh", label_, n), true);
    auto navmesh = bench::buildNavMesh(desc);
    if (!navmesh) {
      progress_.clear();
      printDiagnostics(navmesh.errors());
      return kExitFailure;
    }
    std::vector<Measurement> group;
    int ticks = options_.ticks;
    for (const int threads : threadCounts) {
      int configTicks = ticks;
      auto m = timeThrong(desc, *navmesh, threads, configTicks, false);
      if (InterruptGuard::requested()) break;
      if (!m) return kExitFailure;
      if (ticks <= 0) ticks = configTicks;  // the first configuration's tick count sets the baseline's
      group.push_back(*m);
      if (options_.record) {
        int recTicks = configTicks;  // the same ticks as without recording
        auto rec = timeThrong(desc, *navmesh, threads, recTicks, true);
        if (InterruptGuard::requested()) break;
        if (!rec) return kExitFailure;
        group.push_back(*rec);
      }
    }
    std::optional<Measurement> baseline;
    if (!InterruptGuard::requested() && !options_.noBaseline) {
      if (n <= options_.baselineMax) {
        baseline = timeBaseline(desc, *navmesh, std::max(ticks, 1));
      } else {
        notes_.push_back(fmt::format("DetourCrowd skipped at N = {} (above --baseline-max {})", n, options_.baselineMax));
      }
    }
    if (baseline) {
      for (auto& m : group) {
        if (baseline->agentStepsPerSec > 0) m.speedup = m.agentStepsPerSec / baseline->agentStepsPerSec;
      }
      print(*baseline);
    }
    for (const auto& m : group) print(m);
    if (InterruptGuard::requested()) {
      progress_.clear();
      printLine(stderr, "throng: bench interrupted");
      return kExitInterrupted;
    }
  }
  progress_.clear();
  printFootnotes();
  return kExitOk;
}

int BenchRunner::run() { return fileMode_ ? runFile() : runLayouts(); }

}  // namespace bench_detail


CLI::App* addBenchCommand(CLI::App& app, BenchOptions& options) {
  CLI::App* cmd = app.add_subcommand("bench", "Measure simulation speed and memory against DetourCrowd");
  cmd->footer(
      "Measure simulation speed and memory.\n"
      "In-memory scenarios (random, navmesh, musse): for each agent count and thread count it builds the\n"
      "scenario, runs untimed warm-up ticks, then times every tick and prints agent-steps per second,\n"
      "milliseconds per tick (median, p99), peak RSS and bytes per agent; then runs DetourCrowd on the same\n"
      "navmesh and agent count (one thread) and prints the ratio.\n"
      "Scenario files (mall = the bundled scenarios/mall.json, or any PATH.json): for each thread count the\n"
      "whole scenario runs from the start until every agent has left or its duration (--duration caps it);\n"
      "only the ticks are timed. It also prints the simulated time, the wall time and x real time\n"
      "(simulated / wall). No DetourCrowd baseline; --agents, --warmup and --seed are not used.\n"
      "--record times every configuration a second time while writing a recording at --fps frames per\n"
      "second to a temporary file (deleted afterwards), as `throng run` does: engine \"throng+rec\".");
  cmd->add_option("--agents", options.agents,
                  "Agent counts (in-memory scenarios), repeatable or comma-separated; default 1000,10000,100000")
      ->delimiter(',')
      ->type_name("N[,N...]")
      ->check(integerRange(1, 10'000'000));
  cmd->add_option("--threads", options.threads,
                  "Thread counts, repeatable or comma-separated; 0 = all hardware threads; default 1,2")
      ->delimiter(',')
      ->type_name("T[,T...]")
      ->check(integerRange(0, 1024));
  cmd->add_option("--scenario", options.scenario,
                  "random: open square, 1 agent/m², agents wander; navmesh: the same plus 1 m pillars every 8 m; "
                  "musse: random with the crowd model on (flocking groups of 3); mall: the bundled "
                  "scenarios/mall.json (looked up in the current directory, then from the executable); PATH.json: "
                  "any scenario file, run from start to end")
      ->type_name("NAME|PATH.json")
      ->check(CLI::Validator([](std::string& value) { return checkBenchScenarioValue(value); },
                             "random|navmesh|musse|mall|PATH.json", "BENCH_SCENARIO"))
      ->capture_default_str();
  cmd->add_option("--ticks", options.ticks,
                  "Timed ticks per configuration (dt = 0.1 s); 0 = as many as fit in 3 s (10 to 3000); DetourCrowd "
                  "runs as many as throng's first thread count. Scenario files: at most this many ticks (0 = to the "
                  "end)")
      ->type_name("N")
      ->check(integerRange(0, 1'000'000))
      ->capture_default_str();
  cmd->add_option("--warmup", options.warmup, "Untimed ticks before timing (in-memory scenarios)")
      ->type_name("N")
      ->check(integerRange(0, 100'000))
      ->capture_default_str();
  cmd->add_option("--seed", options.seed, "Random seed for spawns and goals (in-memory scenarios; a file keeps its own)")
      ->type_name("N")
      ->capture_default_str();
  cmd->add_option("--duration", options.duration,
                  "Scenario files: simulate at most this long [s] (the file's \"duration\" when shorter)")
      ->type_name("S")
      ->check(positiveNumber("s"));
  cmd->add_flag("--record", options.record,
                "Also time each configuration while recording (engine throng+rec): frames at --fps to a temporary "
                "SQLite file ($TMPDIR or /tmp), deleted afterwards");
  cmd->add_option("--fps", options.fps, "Recorded frames per second with --record [Hz] (every round(1/(fps*dt))-th tick)")
      ->type_name("F")
      ->check(positiveNumber("Hz"))
      ->capture_default_str();
  cmd->add_flag("--json", options.json,
                "One JSON object per line and engine/configuration: engine, scenario, agents, threads, ticks, "
                "agent_steps_per_s, ms_per_tick_median, ms_per_tick_p99, bytes_per_agent, peak_rss_bytes, "
                "simulated_s, wall_s, realtime_factor, mean_speed_mps; throng rows speedup_vs_detourcrowd (scenario files also "
                "scenario_file; throng+rec recording)");
  cmd->add_flag("--phase-times", options.phaseTimes,
                "Also time every phase of the tick (decide, plan, sense, steer, integrate, ...) over the timed ticks "
                "and print each one's ms per tick (JSON: phase_ms_per_tick); the clock reads cost a little");
  std::vector<std::string> models;
  for (const sim::ModelInfo& m : sim::modelCatalogue()) models.emplace_back(m.name);
  cmd->add_option("--model", options.model,
                  "Every population walks with this avoidance model, with its default parameters (docs/scenario-format.md, "
                  "\"Models\"); default: in-memory scenarios ORCA, a scenario file its own")
      ->type_name("NAME")
      ->check(CLI::IsMember(models));
  cmd->add_option("--row-order", options.rowOrder,
                  fmt::format("How the world keeps its agent rows: auto (spatially from {} agents), id (ascending id) or "
                              "spatial (sorted along a Hilbert curve every {:g} simulated seconds); the same trajectories for "
                              "any thread count either way (docs/performance.md, \"Row order\")",
                              sim::kSpatialRowsMinAgents, sim::kRowSortPeriod))
      ->type_name("ORDER")
      ->check(CLI::IsMember({"auto", "id", "spatial"}))
      ->capture_default_str();
  cmd->add_flag("--no-baseline", options.noBaseline, "Skip the DetourCrowd baseline");
  cmd->add_option("--baseline-max", options.baselineMax,
                  "Largest agent count DetourCrowd is run at (it is slow)")
      ->type_name("N")
      ->capture_default_str();
  return cmd;
}

int runBench(const BenchOptions& options) { return bench_detail::BenchRunner(options).run(); }

}  // namespace throng::cli