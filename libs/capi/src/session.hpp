// throng::capi::Session — what one throng_world handle holds: the World, its worker threads, the
// optional Recorder and the events not yet handed out, stepped exactly as `throng run` steps them
// (frame 0 before the first tick, then every stride-th tick recorded with the events since). The
// C boundary (throng_c.cpp) checks arguments and handles; this class assumes they are valid.
#pragma once
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "throng/core/parallel.hpp"
#include "throng/core/result.hpp"
#include "throng/io/scenario_loader.hpp"
#include "throng/recording/recorder.hpp"
#include "throng/sim/world.hpp"

namespace throng::capi {

/// What throng_world_options asks of a new world (checked by the caller).
struct SessionOptions {
  std::optional<std::uint64_t> seed;
  int threads = 1;
  std::optional<double> duration;  ///< [s], > 0
};

/// Why stepping stopped early.
enum class StepEnd { Done, Finished, WriteFailed };

class Session {
 public:
  static core::Result<std::unique_ptr<Session>> create(std::shared_ptr<const io::LoadedScenario> scenario,
                                                       const SessionOptions& options);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  /// Steps up to `ticks` ticks; `stepped` counts them. Stops when finished or a write failed.
  StepEnd step(std::uint64_t ticks, std::uint64_t& stepped);
  /// Steps until `until` [s] or finished, ending on a recorded tick (Simulation.run in Python).
  StepEnd run(double until);

  /// The agents present now (a frame taken at most once per tick; its events become pending).
  const sim::Frame& frame();
  /// Stable group id of each agent of `frame`, in its order.
  [[nodiscard]] std::vector<std::uint32_t> groupsOf(const sim::Frame& frame) const;
  /// Moves up to `capacity` oldest pending events into `out`; returns how many.
  std::size_t takeEvents(sim::Event* out, std::size_t capacity);
  [[nodiscard]] std::size_t pendingEvents();

  /// Opens the recording (only at tick 0; checked by the caller) and writes frame 0.
  core::Status record(const std::string& path, double fps, bool force);
  /// Closes it, completed; `frames` receives the frames written.
  core::Status closeRecording(std::uint64_t& frames);
  [[nodiscard]] bool recording() const { return recorder_ != nullptr; }

  [[nodiscard]] sim::World& world() { return *world_; }
  [[nodiscard]] const sim::World& world() const { return *world_; }
  [[nodiscard]] const sim::ScenarioDesc& desc() const { return desc_; }

 private:
  Session() = default;
  void tick();
  void keep(const sim::FramePtr& frame);
  void push(sim::FramePtr frame);

  std::shared_ptr<const io::LoadedScenario> loaded_;
  sim::ScenarioDesc desc_;
  std::unique_ptr<sim::World> world_;
  std::unique_ptr<core::TaskSystem> tasks_;
  std::unique_ptr<recording::Recorder> recorder_;
  std::uint64_t stride_ = 1;       ///< ticks between recorded frames (1 when not recording)
  sim::FramePtr current_;          ///< the frame of the current tick, once taken
  recording::FrameCarry carry_;    ///< what frames taken for the caller drained, for the next recorded one
  std::deque<sim::Event> pending_; ///< events not yet handed out
};

}  // namespace throng::capi
