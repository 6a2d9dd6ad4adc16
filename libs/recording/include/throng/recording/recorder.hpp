// throng::recording::Recorder — writes frames to SQLite in JuPedSim's trajectory format (version 2) plus
// throng's own tables, on its own thread, in batched WAL transactions. Lossless with backpressure:
// push() blocks while the queue is full. A killed process leaves a valid file holding everything
// up to the last committed batch; close() (also on Ctrl-C) leaves a complete single file.
#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "throng/core/result.hpp"
#include "throng/sim/frame.hpp"
#include "throng/sim/scenario.hpp"

namespace throng::recording {

struct RecordingOptions {
  std::string path;                ///< output file (.sqlite)
  bool force = false;              ///< overwrite an existing file
  double fps = 10.0;               ///< frames per second written (metadata `fps`)
  std::uint64_t seed = 0;          ///< seed actually used
  std::string scenarioText;        ///< the scenario JSON, stored for provenance
  /// The glTF / GLB world file the scenario came from, by file name (metadata `throng_world_file`,
  /// written only when set): a replay serves its materials when it finds that file again.
  std::string worldFile;
  std::size_t framesPerBatch = 50; ///< frames per transaction [Limit: >= 1]
  std::size_t queueFrames = 64;    ///< frames queued before push() blocks [Limit: >= 1]
};

/// What frames taken between recorded ticks drained from the world (events, Common Ground script
/// records, coordinations), carried into the next recorded frame, so a recording misses nothing a
/// caller read first (the C API's and the Python module's sessions).
class FrameCarry {
 public:
  /// Keeps `frame`'s records for the next recorded frame.
  void add(const sim::Frame& frame);
  /// `frame` itself when nothing is carried; else a copy with the carried records before its own
  /// (and nothing carried any more).
  [[nodiscard]] sim::FramePtr merge(sim::FramePtr frame);

 private:
  sim::Frame carried_;
};

class Recorder {
 public:
  /// Checks the path (exists without force, unwritable directory) and creates the file with its
  /// schema and metadata. Call before simulating so bad paths are reported before any work.
  static core::Result<std::unique_ptr<Recorder>> open(const sim::ScenarioDesc& scenario,
                                                      const RecordingOptions& options);
  ~Recorder();  ///< closes if still open

  /// Queues a frame (blocks while the queue is full). Frame numbers are assigned in push order
  /// starting at 0. After a write error (failed()) frames are dropped.
  void push(sim::FramePtr frame);

  /// True once a write failed (disk full, file too large, I/O error): nothing more is written, so
  /// the caller should stop simulating and close(), which reports the error and leaves the file
  /// with every batch committed before it (marked not completed).
  [[nodiscard]] bool failed() const;

  /// Flushes everything, writes the final metadata (frames, duration, finished flag), checkpoints
  /// the WAL into the main file and closes. Returns the first write error, if any.
  core::Status close(bool completed);

  [[nodiscard]] std::uint64_t framesWritten() const;

 private:
  Recorder();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// What a recording holds (for `throng info`).
struct RecordingSummary {
  std::string path;
  int formatVersion = 0;          ///< JuPedSim trajectory format version (2)
  std::string scenarioName;
  std::uint64_t seed = 0;
  double fps = 0.0;
  std::uint64_t frames = 0;
  std::uint64_t agents = 0;       ///< distinct agent ids
  std::uint64_t rows = 0;         ///< trajectory rows
  double duration = 0.0;          ///< time from the first to the last frame, (frames - 1) / fps [s]
  bool completed = false;         ///< false when the run was cut short (killed or interrupted)
  std::string throngVersion;
  std::vector<std::pair<std::string, std::uint64_t>> populations;  ///< id → agents
  std::uint64_t events = 0;
  std::string commonGround;       ///< "on" / "off"; empty when the scenario had no social section
  std::string models;             ///< metadata throng_models: JSON, population id → model and parameters; empty in older recordings
  std::string simd;               ///< metadata throng_simd: the hot loops' SIMD path ("avx2", "portable"); empty in older recordings
  std::uint64_t coordinations = 0;///< Common Ground interactions recorded (throng_coordinations rows)
  /// Multi-level worlds (a throng_heights table): lowest and highest agent height recorded [m].
  std::optional<std::pair<double, double>> heights;
};

/// Opens a recording read-only and summarises it; bad or foreign files give a diagnostic.
core::Result<RecordingSummary> readRecordingSummary(const std::string& path);

/// An event kind as recordings name it (throng_events.kind: "spawn", "exit", "goal_reached", …).
[[nodiscard]] const char* eventKindName(sim::EventKind kind);

}  // namespace throng::recording
