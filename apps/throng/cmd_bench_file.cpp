// `throng bench` with a scenario file ("mall" = the bundled scenarios/mall.json, or PATH.json):
// resolves --scenario to a file, loads it, then runs every thread count (and, with --record, each
// again while recording) from tick 0 until every agent has left or the scenario's duration
// (--duration caps it, --ticks too), printing a row per configuration with simulated time, wall
// time and × real time. The timing itself (BenchRunner::timeThrong) and the table are in
// cmd_bench.cpp. Reads the scenario file; writes the table or JSON lines on stdout, diagnostics
// and a progress line on stderr.
#include <algorithm>
#include <filesystem>
#include <iterator>
#include <string>
#include <system_error>
#include <vector>

#include <fmt/format.h>

#include "bench_files.hpp"
#include "cmd_bench_runner.hpp"
#include "commands.hpp"
#include "output.hpp"
#include "signal.hpp"
#include "validators.hpp"
#include "throng/io/scenario_loader.hpp"

namespace throng::cli::bench_detail {


std::string BenchRunner::scenarioPath() {
  const std::string& value = options_.scenario;
  const bool bundled = std::find_if(std::begin(kBundledBenchScenarios), std::end(kBundledBenchScenarios),
                                    [&](const char* name) { return value == name; }) !=
                       std::end(kBundledBenchScenarios);
  if (!bundled) {
    if (auto missing = checkInputFile(value, "scenario"); !missing.empty()) {
      printDiagnostics(missing);
      return {};
    }
    return value;
  }
  const auto candidates = bundledScenarioCandidates(value, currentExecutable());
  std::string tried;
  for (const auto& candidate : candidates) {
    std::error_code ec;
    if (std::filesystem::is_regular_file(candidate, ec)) return candidate.string();
    tried += fmt::format("\n  {}", std::filesystem::absolute(candidate, ec).string());
  }
  printLine(stderr, fmt::format("throng: bench --scenario {}: the bundled scenarios/{}.json was not found; tried "
                                "(relative to the current directory, then to the executable):{}\n"
                                "Run from the source tree or pass the file: --scenario PATH/{}.json",
                                value, value, tried, value));
  return {};
}

int BenchRunner::runFile() {
  filePath_ = scenarioPath();
  if (filePath_.empty()) return kExitFailure;
  label_ = std::filesystem::path(filePath_).stem().string();
  if (!options_.agents.empty()) {
    notes_.push_back("--agents is not used with a scenario file: its populations say who spawns");
  }
  if (!options_.noBaseline) {
    notes_.push_back("no DetourCrowd baseline for scenario files (it has no equivalent of their goals, groups and "
                     "social model); it runs with random, navmesh and musse");
  }
  InterruptGuard interrupts;
  status(fmt::format("{}: loading {}", label_, filePath_), true);
  auto loaded = io::loadScenarioFile(filePath_);
  if (!loaded) {
    progress_.clear();
    printDiagnostics(loaded.errors());
    return kExitFailure;
  }
  sim::ScenarioDesc& desc = loaded->desc;
  applyModel(desc, options_.model);
  applyRowOrder(desc, options_.rowOrder);
  if (options_.duration) desc.duration = std::min(desc.duration, static_cast<float>(*options_.duration));
  dt_ = desc.dt;
  duration_ = desc.duration;
  scenarioText_ = loaded->text;
  std::vector<int> threadCounts = options_.threads.empty() ? std::vector<int>{1, 2} : options_.threads;
  printHeader();
  for (const int threads : threadCounts) {
    for (const bool record : {false, true}) {
      if (record && !options_.record) continue;
      int ticks = options_.ticks;
      auto m = timeThrong(desc, loaded->navmesh, threads, ticks, record);
      if (InterruptGuard::requested()) {
        progress_.clear();
        printLine(stderr, "throng: bench interrupted");
        return kExitInterrupted;
      }
      if (!m) return kExitFailure;
      print(*m);
    }
  }
  progress_.clear();
  printFootnotes();
  return kExitOk;
}

}  // namespace throng::cli::bench_detail
