// BenchRunner — the state and steps of one `throng bench` invocation, shared by cmd_bench.cpp
// (in-memory scenarios, timing one configuration, the table, the command line) and
// cmd_bench_file.cpp (scenario files run from the start to their end). Measurement is one row of
// the table (one engine and configuration). Private to the throng program.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bench_files.hpp"
#include "commands.hpp"
#include "progress.hpp"
#include "throng/bench/scenarios.hpp"
#include "throng/nav/navmesh.hpp"
#include "throng/sim/scenario.hpp"
#include "throng/sim/world.hpp"

namespace throng::recording {
class Recorder;
}  // namespace throng::recording

namespace throng::cli::bench_detail {

/// `--model NAME`: every population of `desc` walks with that model and its defaults (empty: as given).
inline void applyModel(sim::ScenarioDesc& desc, const std::string& name) {
  if (name.empty()) return;
  const sim::ModelInfo* model = sim::findModel(name);
  if (model == nullptr) return;  // CLI11 checked the name
  for (sim::PopulationDesc& pop : desc.populations) pop.model = sim::ModelDesc(model->kind);
}

/// `--row-order auto|id|spatial` (sim::RowOrder; CLI11 checked the name).
inline void applyRowOrder(sim::ScenarioDesc& desc, const std::string& name) {
  desc.rowOrder = name == "id" ? sim::RowOrder::Id : name == "spatial" ? sim::RowOrder::Spatial : sim::RowOrder::Auto;
}

/// The engine name DetourCrowd's rows carry (bench::BaselineResult::engine).
inline constexpr const char* kDetourCrowdEngine = "detourcrowd";

struct Measurement {
  std::string engine;
  std::size_t agents = 0;  ///< in-memory: N; file: most agents present at once
  int threads = 1;
  int ticks = 0;
  double agentStepsPerSec = 0.0;
  double msMedian = 0.0;
  double msP99 = 0.0;
  double bytesPerAgent = 0.0;
  double peakRssBytes = 0.0;
  double simulatedSeconds = 0.0;  ///< simulated time of the timed ticks [s]
  double wallSeconds = 0.0;       ///< wall time of the timed ticks (file + recording: and closing it) [s]
  std::optional<double> recordedFps;  ///< the frame rate written, for "throng+rec"
  std::uint64_t frames = 0;
  double closeSeconds = 0.0;      ///< closing the recording (flush, checkpoint) [s]
  std::optional<double> speedup;  ///< throng / DetourCrowd agent-steps/s, same agent count
  double meanSpeed = 0.0;         ///< agents' mean speed over the timed ticks, all agents [m/s]
  std::vector<std::pair<std::string, double>> phaseMs;  ///< --phase-times: each phase's ms per timed tick

  [[nodiscard]] double realtimeFactor() const { return wallSeconds > 0 ? simulatedSeconds / wallSeconds : 0.0; }
};

class BenchRunner {
 public:
  explicit BenchRunner(const BenchOptions& options)
      : options_(options),
        fileMode_(!bench::layoutFromName(options.scenario)),
        progress_(stderr, true) {}

  int run();

 private:
  int runLayouts();
  int runFile();
  /// Resolves --scenario to a file path ("mall" → the bundled file); empty after printing why not.
  std::string scenarioPath();
  std::optional<Measurement> timeThrong(const sim::ScenarioDesc& desc,
                                        const std::shared_ptr<const nav::NavMesh>& navmesh, int threads,
                                        int& ticks, bool record);
  /// --record's recording of one configuration at `path`; nullptr after printing why not.
  std::unique_ptr<recording::Recorder> openRecording(const sim::ScenarioDesc& desc, double fps, const std::string& path);
  /// Closes --record's recording (`completed` unless interrupted): close time and frames into `m`;
  /// false after printing why it failed.
  bool closeRecording(recording::Recorder& recorder, const std::string& label, bool completed, Measurement& m);
  /// The progress line during the timed ticks (`ticks` <= 0: automatic count).
  void drawTickProgress(const std::string& label, const sim::World& w, std::uint64_t tick, int ticks, double totalSeconds);
  std::optional<Measurement> timeBaseline(const sim::ScenarioDesc& desc,
                                          const std::shared_ptr<const nav::NavMesh>& navmesh, int ticks);
  void status(const std::string& text, bool force = false);
  void printHeader() const;
  void print(const Measurement& m);
  void printFootnotes() const;

  const BenchOptions& options_;
  bench::Layout layout_ = bench::layoutFromName(options_.scenario).value_or(bench::Layout::Random);
  bool fileMode_ = false;
  std::string label_;         ///< the "scenario" column: layout name or the file's name without .json
  std::string filePath_;      ///< file mode: the scenario file read
  std::string scenarioText_;  ///< file mode: its text (stored in --record recordings)
  double dt_ = bench::kDt;     ///< time step of the scenario [s]
  double duration_ = 0.0;     ///< file mode: simulated time at most [s]
  ProgressLine progress_;
  std::vector<std::string> notes_;
};

}  // namespace throng::cli::bench_detail
