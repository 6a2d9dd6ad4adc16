// throng CLI interrupt handling — SIGINT/SIGTERM set an atomic flag that the run loop polls once
// per tick, so Ctrl-C stops the simulation cleanly and the recording is closed as a complete file
// (marked not completed). A second signal while the first is being handled kills the process
// with the default action.
#pragma once

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
};

}  // namespace throng::cli
