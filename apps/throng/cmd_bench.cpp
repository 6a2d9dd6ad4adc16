// `throng bench` — times the full tick on in-memory scenarios (bench_scenarios.hpp) for each agent
// count and thread count, then DetourCrowd on the same navmesh and agent count, and prints
// agent-steps/s, ms per tick (median, p99), peak RSS and bytes per agent. Reads the process's
// memory counters (/proc/self/statm, getrusage); writes a table or JSON lines on stdout and a
// progress line on a terminal's stderr.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <optional>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <malloc.h>
#include <nlohmann/json.hpp>
#include <sys/resource.h>
#include <unistd.h>

#include "bench_scenarios.hpp"
#include "commands.hpp"
#include "output.hpp"
#include "progress.hpp"
#include "signal.hpp"
#include "validators.hpp"
#include "throng/core/parallel.hpp"
#include "throng/sim/world.hpp"
#if THRONG_HAVE_BASELINES
#include "baselines/detour_crowd_baseline.hpp"
#endif

namespace throng::cli {
namespace {

using Clock = std::chrono::steady_clock;

constexpr double kTargetSecondsPerConfig = 3.0;  ///< without --ticks, time ticks until this much work [s]
constexpr int kMinAutoTicks = 10;
constexpr int kMaxAutoTicks = 3000;

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

struct Measurement {
  std::string engine;
  std::size_t agents = 0;
  int threads = 1;
  int ticks = 0;
  double agentStepsPerSec = 0.0;
  double msMedian = 0.0;
  double msP99 = 0.0;
  double bytesPerAgent = 0.0;
  double peakRssBytes = 0.0;
  std::optional<double> speedup;  ///< throng / DetourCrowd agent-steps/s, same agent count
};

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

class BenchRunner {
 public:
  explicit BenchRunner(const BenchOptions& options)
      : options_(options),
        layout_(options.scenario == "navmesh" ? BenchLayout::Navmesh
                : options.scenario == "musse" ? BenchLayout::Musse
                                              : BenchLayout::Random),
        progress_(stderr, true) {}

  int run();

 private:
  std::optional<Measurement> timeThrong(const sim::ScenarioDesc& desc,
                                        const std::shared_ptr<const nav::NavMesh>& navmesh, int threads,
                                        int& ticks);
  std::optional<Measurement> timeBaseline(const sim::ScenarioDesc& desc,
                                          const std::shared_ptr<const nav::NavMesh>& navmesh, int ticks);
  void status(const std::string& text, bool force = false);
  void printHeader() const;
  void print(const Measurement& m);
  void printFootnotes() const;

  const BenchOptions& options_;
  BenchLayout layout_;
  ProgressLine progress_;
  std::vector<std::string> notes_;
};

void BenchRunner::status(const std::string& text, bool force) {
  if (force || progress_.due()) progress_.draw(text);
}

std::optional<Measurement> BenchRunner::timeThrong(const sim::ScenarioDesc& desc,
                                                   const std::shared_ptr<const nav::NavMesh>& navmesh, int threads,
                                                   int& ticks) {
  const std::size_t n = agentCount(desc);
  const std::string label = fmt::format("throng {} N={} threads={}", options_.scenario, n, threads);
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

  for (int i = 0; i < options_.warmup && !InterruptGuard::requested(); ++i) {
    w.step(tasks);
    status(fmt::format("{}: warm-up {}/{}", label, i + 1, options_.warmup));
  }
  const double bytesPerAgent = n > 0 ? std::max(0.0, currentRss() - rssBefore) / static_cast<double>(n) : 0.0;

  // Fixed --ticks, or (ticks <= 0) as many as fit in kTargetSecondsPerConfig, within the limits.
  const bool fixed = ticks > 0;
  std::vector<double> ms;
  const std::uint64_t stepsBefore = w.stats().agentSteps;
  double totalSeconds = 0.0;
  for (int i = 0; !InterruptGuard::requested(); ++i) {
    if (fixed ? i >= ticks : (i >= kMaxAutoTicks || (i >= kMinAutoTicks && totalSeconds >= kTargetSecondsPerConfig))) {
      break;
    }
    const auto t0 = Clock::now();
    w.step(tasks);
    const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    totalSeconds += seconds;
    ms.push_back(seconds * 1000.0);
    status(fixed ? fmt::format("{}: tick {}/{}", label, i + 1, ticks)
                 : fmt::format("{}: tick {} ({:.1f}/{:.0f} s)", label, i + 1, totalSeconds, kTargetSecondsPerConfig));
  }
  ticks = static_cast<int>(ms.size());
  if (InterruptGuard::requested()) return std::nullopt;

  Measurement m;
  m.engine = "throng";
  m.agents = n;
  m.threads = tasks.threads();
  m.ticks = ticks;
  const auto steps = static_cast<double>(w.stats().agentSteps - stepsBefore);
  m.agentStepsPerSec = totalSeconds > 0 ? steps / totalSeconds : 0.0;
  m.msMedian = percentile(ms, 0.5);
  m.msP99 = percentile(ms, 0.99);
  m.bytesPerAgent = bytesPerAgent;
  m.peakRssBytes = peakRss();
  return m;
}

std::optional<Measurement> BenchRunner::timeBaseline(const sim::ScenarioDesc& desc,
                                                     const std::shared_ptr<const nav::NavMesh>& navmesh, int ticks) {
#if THRONG_HAVE_BASELINES
  const std::size_t n = agentCount(desc);
  status(fmt::format("detourcrowd {} N={}: running {} ticks", options_.scenario, n, ticks), true);
  baselines::BaselineConfig config;
  config.navmesh = navmesh;
  config.starts = drawBenchStarts(navmesh, n, options_.seed);
  config.radius = kBenchRadius;
  config.speed = kBenchSpeed;
  config.dt = kBenchDt;
  config.seed = options_.seed;
  config.warmupTicks = options_.warmup;
  config.ticks = ticks;
  ::malloc_trim(0);
  auto result = baselines::runDetourCrowd(config);
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
  m.peakRssBytes = peakRss();
  return m;
#else
  (void)desc;
  (void)navmesh;
  (void)ticks;
  return std::nullopt;
#endif
}

void BenchRunner::printHeader() const {
  if (options_.json) return;
  printLine(stdout, fmt::format("{:<12} {:<8} {:>8} {:>7} {:>6} {:>14} {:>11} {:>11} {:>11} {:>10} {:>8}", "engine",
                                "scenario", "agents", "threads", "ticks", "agent-steps/s", "ms/tick med",
                                "ms/tick p99", "bytes/agent", "peak RSS", "vs DC"));
}

void BenchRunner::print(const Measurement& m) {
  progress_.clear();
  if (options_.json) {
    nlohmann::json line{{"engine", m.engine},
                        {"scenario", options_.scenario},
                        {"agents", m.agents},
                        {"threads", m.threads},
                        {"ticks", m.ticks},
                        {"warmup_ticks", options_.warmup},
                        {"dt_s", std::round(static_cast<double>(kBenchDt) * 1e6) / 1e6},
                        {"agent_steps_per_s", m.agentStepsPerSec},
                        {"ms_per_tick_median", m.msMedian},
                        {"ms_per_tick_p99", m.msP99},
                        {"bytes_per_agent", m.bytesPerAgent},
                        {"peak_rss_bytes", m.peakRssBytes}};
    if (m.engine == "throng") {
      line["speedup_vs_detourcrowd"] = m.speedup ? nlohmann::json(*m.speedup) : nlohmann::json(nullptr);
    }
    printLine(stdout, line.dump());
    return;
  }
  printLine(stdout, fmt::format("{:<12} {:<8} {:>8} {:>7} {:>6} {:>14} {:>11.3f} {:>11.3f} {:>11.0f} {:>10} {:>8}",
                                m.engine, options_.scenario, m.agents, m.threads, m.ticks,
                                formatSi(m.agentStepsPerSec), m.msMedian, m.msP99, m.bytesPerAgent,
                                formatBytes(m.peakRssBytes), m.speedup ? fmt::format("{:.2f}x", *m.speedup) : "-"));
}

void BenchRunner::printFootnotes() const {
  if (options_.json) {
    for (const auto& note : notes_) printLine(stderr, "note: " + note);
    return;
  }
  printLine(stdout, "");
  printLine(stdout, fmt::format("scenario: {} — square of side sqrt(N) m (1 agent/m²), radius {} m, speed {} m/s, "
                                "dt {} s, agents wander between random points{}",
                                options_.scenario, kBenchRadius, kBenchSpeed, kBenchDt,
                                layout_ == BenchLayout::Navmesh ? "; 1 m pillars every 8 m" : ""));
  printLine(stdout, fmt::format("timing: {} untimed warm-up ticks, then each tick timed alone (steady_clock)",
                                options_.warmup));
  printLine(stdout, "bytes/agent: growth of resident memory from before World::create to after warm-up, divided by "
                    "N (the shared navmesh is built before and not counted); peak RSS: the process's so far");
  printLine(stdout, "vs DC: throng agent-steps/s divided by DetourCrowd's at the same N, on the same navmesh; "
                    "DetourCrowd starts are drawn uniformly on the navmesh (same distribution, not the same points)");
  for (const auto& note : notes_) printLine(stdout, "note: " + note);
}

int BenchRunner::run() {
  std::vector<std::size_t> counts = options_.agents.empty() ? std::vector<std::size_t>{1000, 10000, 100000}
                                                            : options_.agents;
  std::vector<int> threadCounts = options_.threads.empty() ? std::vector<int>{1, 2} : options_.threads;
  bool baselineAvailable = true;
#if !THRONG_HAVE_BASELINES
  baselineAvailable = false;
  if (!options_.noBaseline) notes_.push_back("DetourCrowd baseline not built (THRONG_BUILD_BENCHES=OFF)");
#endif
  InterruptGuard interrupts;
  printHeader();
  for (const std::size_t n : counts) {
    const sim::ScenarioDesc desc = makeBenchScenario(layout_, n, options_.seed);
    status(fmt::format("{} N={}: building navmesh", options_.scenario, n), true);
    auto navmesh = buildBenchNavMesh(desc);
    if (!navmesh) {
      progress_.clear();
      printDiagnostics(navmesh.errors());
      return kExitFailure;
    }
    std::vector<Measurement> group;
    int ticks = options_.ticks;
    for (const int threads : threadCounts) {
      int configTicks = ticks;
      auto m = timeThrong(desc, *navmesh, threads, configTicks);
      if (InterruptGuard::requested()) break;
      if (!m) return kExitFailure;
      if (ticks <= 0) ticks = configTicks;  // the first configuration's tick count sets the baseline's
      group.push_back(*m);
    }
    std::optional<Measurement> baseline;
    if (!InterruptGuard::requested() && !options_.noBaseline && baselineAvailable) {
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

}  // namespace

CLI::App* addBenchCommand(CLI::App& app, BenchOptions& options) {
  CLI::App* cmd = app.add_subcommand("bench", "Measure simulation speed and memory against DetourCrowd");
  cmd->footer(
      "Measure simulation speed and memory. For each agent count and thread count it builds the scenario\n"
      "in memory, runs untimed warm-up ticks, then times every tick and prints agent-steps per second,\n"
      "milliseconds per tick (median, p99), peak RSS and bytes per agent; then runs DetourCrowd on the same\n"
      "navmesh and agent count (one thread) and prints the ratio.");
  cmd->add_option("--agents", options.agents,
                  "Agent counts, repeatable or comma-separated; default 1000,10000,100000")
      ->delimiter(',')
      ->type_name("N[,N...]")
      ->check(integerRange(1, 10'000'000));
  cmd->add_option("--threads", options.threads,
                  "Thread counts, repeatable or comma-separated; 0 = all hardware threads; default 1,2")
      ->delimiter(',')
      ->type_name("T[,T...]")
      ->check(integerRange(0, 1024));
  cmd->add_option("--scenario", options.scenario,
                  "random: open square, 1 agent/m², agents wander; navmesh: the same plus 1 m pillars every 8 m; musse: random with the crowd model on (flocking groups of 3)")
      ->check(CLI::IsMember({"random", "navmesh", "musse"}))
      ->capture_default_str();
  cmd->add_option("--ticks", options.ticks,
                  "Timed ticks per configuration (dt = 0.1 s); 0 = as many as fit in 3 s (10 to 3000); DetourCrowd "
                  "runs as many as throng's first thread count")
      ->type_name("N")
      ->check(integerRange(0, 1'000'000))
      ->capture_default_str();
  cmd->add_option("--warmup", options.warmup, "Untimed ticks before timing")
      ->type_name("N")
      ->check(integerRange(0, 100'000))
      ->capture_default_str();
  cmd->add_option("--seed", options.seed, "Random seed for spawns and goals")->type_name("N")->capture_default_str();
  cmd->add_flag("--json", options.json,
                "One JSON object per line and engine/configuration: engine, scenario, agents, threads, ticks, "
                "agent_steps_per_s, ms_per_tick_median, ms_per_tick_p99, bytes_per_agent, peak_rss_bytes");
  cmd->add_flag("--no-baseline", options.noBaseline, "Skip the DetourCrowd baseline");
  cmd->add_option("--baseline-max", options.baselineMax,
                  "Largest agent count DetourCrowd is run at (it is slow)")
      ->type_name("N")
      ->capture_default_str();
  return cmd;
}

int runBench(const BenchOptions& options) { return BenchRunner(options).run(); }

}  // namespace throng::cli
