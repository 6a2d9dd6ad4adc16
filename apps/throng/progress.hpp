// throng CLI progress line — one status line on a terminal's stderr, redrawn in place with '\r'
// about ten times a second and cleared before the summary. Off a terminal (pipes, files, CI) it
// draws nothing. The formatting functions are pure so they can be tested without a terminal.
#pragma once
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>

namespace throng::cli {

/// What the run loop reports to the progress line.
struct RunProgress {
  double simTime = 0.0;      ///< simulated time so far [s]
  double duration = 0.0;     ///< simulated time the run ends at, at the latest [s]
  std::uint32_t active = 0;  ///< agents in the world now
  std::uint32_t exited = 0;  ///< agents that left through an exit
  double wallSeconds = 0.0;  ///< wall time since the loop started [s]
};

/// "[#####.....]" filling `fraction` (clamped to [0,1]) of `width` characters, brackets included.
[[nodiscard]] std::string formatBar(double fraction, int width);

/// "m:ss" or "h:mm:ss"; "--:--" when not finite or negative.
[[nodiscard]] std::string formatClock(double seconds);

/// One line at most `width` columns: simulated/total time (padded to a fixed width), a bar of at
/// least 12 columns, percentage, agents active/exited, speed as a multiple of real time and the
/// remaining wall time; the right part is written shorter before the bar is dropped.
[[nodiscard]] std::string formatRunProgress(const RunProgress& progress, int width);

class ProgressLine {
 public:
  /// Draws on `out` only when `enabled` and `out` is a terminal.
  ProgressLine(std::FILE* out, bool enabled);
  ~ProgressLine();  ///< clears the line
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  [[nodiscard]] bool enabled() const { return enabled_; }
  /// Columns available (the terminal's width, 80 when unknown).
  [[nodiscard]] int width() const { return width_; }
  /// True when a redraw is due (at most ~10 per second); cheap enough to call every tick.
  [[nodiscard]] bool due();
  /// Replaces the line with `text`, cut to the width.
  void draw(const std::string& text);
  /// Erases the line so the next output starts on a clean line.
  void clear();

  /// Whether `out` is a terminal; columns of the terminal behind file descriptor `fd` (fallback 80).
  [[nodiscard]] static bool isTerminal(std::FILE* out);
  [[nodiscard]] static int terminalWidth(int fd);

 private:
  static constexpr std::chrono::milliseconds kRefresh{100};
  std::FILE* out_;
  bool enabled_;
  bool drawn_ = false;
  int width_ = 80;
  std::chrono::steady_clock::time_point last_{};
};

}  // namespace throng::cli
