// `throng serve`'s real-time loop: Publisher (each client's crowd frame encoded and sent on a
// thread of its own) and TickLoop (one frame per period on the simulation thread: stepped, or a
// recording's at the replay clock), and percentile, for the status window and the summary.
#pragma once
#include <algorithm>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "commands.hpp"
#include "recording_routes.hpp"
#include "serve_api.hpp"
#include "serve_bridge.hpp"
#include "serve_world.hpp"
#include "throng/core/parallel.hpp"
#include "throng/hub/hub.hpp"
#include "throng/hub/replay.hpp"
#include "throng/hub/tick_watch.hpp"
#include "throng/sim/world.hpp"

namespace throng::cli::serve {

/// The value at quantile `p` (0..1) of `v`; 0 when it is empty.
[[nodiscard]] double percentile(std::vector<double> v, double p);

/// Encodes and sends each client's crowd frame on its own thread, so the tick stays on time
/// whatever the clients cost; when it falls behind it skips to the newest frame.
class Publisher {
 public:
  Publisher(hub::Hub& hub, const Bridge& bridge, int threads)
      : hub_(hub), bridge_(bridge), tasks_(threads), thread_([this] { loop(); }) {}
  ~Publisher() { stop(); }
  Publisher(const Publisher&) = delete;
  Publisher& operator=(const Publisher&) = delete;

  /// The newest frame; one not yet taken is replaced (and counted as skipped).
  void offer(sim::FramePtr frame) {
    {
      std::lock_guard lock(mutex_);
      if (pending_) ++skipped_;
      pending_ = std::move(frame);
    }
    ready_.notify_one();
  }
  /// The last `n` publish times [ms].
  std::vector<double> recentMs(std::size_t n) {
    std::lock_guard lock(mutex_);
    n = std::min(ms_.size(), n);
    return {ms_.end() - static_cast<std::ptrdiff_t>(n), ms_.end()};
  }
  /// Ends the thread (a frame waiting is dropped). Idempotent.
  void stop() {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
    }
    ready_.notify_one();
    if (thread_.joinable()) thread_.join();
  }
  // After stop():
  [[nodiscard]] const std::vector<double>& ms() const { return ms_; }
  [[nodiscard]] std::uint64_t skipped() const { return skipped_; }

 private:
  void loop();

  hub::Hub& hub_;
  const Bridge& bridge_;
  core::TaskSystem tasks_;
  std::mutex mutex_;
  std::condition_variable ready_;
  sim::FramePtr pending_;
  bool stop_ = false;
  std::vector<double> ms_;
  std::uint64_t skipped_ = 0;
  std::thread thread_;  // last: starts once everything above exists
};

/// What TickLoop::run returns when a viewer asked to open a recording.
inline constexpr const char* kOpenRecording = "open a recording";

/// The real-time loop on the simulation thread: one frame per period (stepped, or the recording's
/// at the replay clock), questions answered, the frame handed to the publisher, the status window
/// and line refreshed once a second. Runs until Ctrl-C or --duration.
class TickLoop {
 public:
  TickLoop(const ServeOptions& options, Served& served, hub::Hub& hub, const Bridge& bridge, WorldQueries& queries,
           TickWindow& window, hub::TickWatch& tickWatch, Publisher& publisher, const RecordingRoutes* recordings);

  /// Why it ended: "interrupted (Ctrl-C)", "duration reached" or kOpenRecording (a viewer asked
  /// for another recording: see RecordingRoutes::takeOpen). May be called again after kOpenRecording.
  std::string run();
  [[nodiscard]] const std::vector<double>& tickMs() const { return tickMs_; }
  [[nodiscard]] bool terminal() const { return terminal_; }

 private:
  sim::FramePtr nextFrame();

  /// Tick and publish percentiles over the last 10 s, for /api/status.
  void refreshWindow(double now);

  /// The status line on a terminal's stderr.
  void printStatus(const sim::Frame& frame, double now);

  const ServeOptions& options_;
  Served& served_;
  hub::Hub& hub_;
  const Bridge& bridge_;
  WorldQueries& queries_;
  TickWindow& window_;
  hub::TickWatch& tickWatch_;
  Publisher& publisher_;
  const RecordingRoutes* recordings_;
  hub::ReplayClock clock_;
  core::TaskSystem tasks_;
  const bool terminal_;
  std::vector<double> tickMs_;
  double lastStatus_ = 0.0, lastWindow_ = 0.0, lastReplayWall_ = 0.0, lastReplayStatus_ = -1.0;
  std::uint64_t lastBytes_ = 0;
};

}  // namespace throng::cli::serve
