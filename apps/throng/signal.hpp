// throng CLI interrupt handling — SIGINT/SIGTERM set an atomic flag that scenario loading polls
// (io::LoadOptions::cancel) and the run loop polls once per tick, so Ctrl-C stops a long check or
// the simulation cleanly and the recording is closed as a complete file
// (marked not completed). A second signal while the first is being handled kills the process
// with the default action.
#pragma once
#include <atomic>

namespace throng::cli {

/// Installs the handlers on construction and restores the previous ones on destruction.
class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

  /// True once SIGINT or SIGTERM arrived since construction.
  [[nodiscard]] static bool requested();
  /// The signal number that arrived (0 if none).
  [[nodiscard]] static int signal();
  /// The flag itself (non-zero once a signal arrived), for work that polls it outside the CLI:
  /// io::LoadOptions::cancel lets Ctrl-C stop a long scenario validation.
  [[nodiscard]] static const std::atomic<int>& flag();
};

}  // namespace throng::cli
