// throng CLI progress line — see progress.hpp. Reads the terminal size (TIOCGWINSZ) once per
// redraw so resizing the window is followed.
#include "progress.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <sys/ioctl.h>
#include <unistd.h>

namespace throng::cli {

std::string formatBar(double fraction, int width) {
  if (width < 3) return {};
  const int inner = width - 2;
  const double f = std::isfinite(fraction) ? std::clamp(fraction, 0.0, 1.0) : 0.0;
  const int full = static_cast<int>(std::floor(f * inner));
  std::string bar = "[";
  bar.append(static_cast<std::size_t>(full), '#');
  bar.append(static_cast<std::size_t>(inner - full), '.');
  bar += ']';
  return bar;
}

std::string formatClock(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0 || seconds > 360000.0) return "--:--";
  const auto s = static_cast<long long>(std::llround(seconds));
  if (s < 3600) return fmt::format("{}:{:02}", s / 60, s % 60);
  return fmt::format("{}:{:02}:{:02}", s / 3600, (s % 3600) / 60, s % 60);
}

std::string formatRunProgress(const RunProgress& p, int width) {
  const double fraction = p.duration > 0 ? p.simTime / p.duration : 0.0;
  const double speed = p.wallSeconds > 0 ? p.simTime / p.wallSeconds : 0.0;
  const double eta = speed > 0 ? (p.duration - p.simTime) / speed : -1.0;
  // The simulated time is padded to the duration's width so the line does not shift as it grows.
  const std::string total = fmt::format("{:.1f}", p.duration);
  const std::string left = fmt::format("{:>{}.1f}/{} s", p.simTime, total.size(), total);
  const double percent = std::clamp(fraction, 0.0, 1.0) * 100.0;
  // Longest first; the bar keeps its place by shortening the right part when the line is narrow.
  const std::string rights[] = {
      fmt::format("{:3.0f}%  {} active {} exited  {:.1f}x real time  ETA {}", percent, p.active, p.exited, speed,
                  formatClock(eta)),
      fmt::format("{:3.0f}%  {} active {} exited  {:.1f}x  ETA {}", percent, p.active, p.exited, speed, formatClock(eta)),
      fmt::format("{:3.0f}%  {}/{} in/out  {:.0f}x  ETA {}", percent, p.active, p.exited, speed, formatClock(eta)),
  };
  constexpr int kMinBar = 12;
  std::string line;
  for (const std::string& right : rights) {
    // Leave the last column free: writing into it wraps on some terminals.
    const int room = width - 1 - static_cast<int>(left.size() + right.size()) - 2;
    if (room >= kMinBar || &right == &rights[2]) {
      line = left;
      if (room >= kMinBar) line += " " + formatBar(fraction, std::min(room, 60)) + " ";
      else line += "  ";
      line += right;
      break;
    }
  }
  if (width > 1 && static_cast<int>(line.size()) > width - 1) line.resize(static_cast<std::size_t>(width - 1));
  return line;
}

ProgressLine::ProgressLine(std::FILE* out, bool enabled)
    : out_(out), enabled_(enabled && isTerminal(out)) {
  if (enabled_) width_ = terminalWidth(fileno(out_));
}

ProgressLine::~ProgressLine() { clear(); }

bool ProgressLine::due() {
  if (!enabled_) return false;
  const auto now = std::chrono::steady_clock::now();
  if (drawn_ && now - last_ < kRefresh) return false;
  last_ = now;
  return true;
}

void ProgressLine::draw(const std::string& text) {
  if (!enabled_) return;
  width_ = terminalWidth(fileno(out_));
  std::string line = text;
  if (width_ > 1 && static_cast<int>(line.size()) > width_ - 1) line.resize(static_cast<std::size_t>(width_ - 1));
  // '\r', the text, then erase to the end of the line (ANSI EL) so a shorter line leaves no tail.
  std::fputs("\r", out_);
  std::fputs(line.c_str(), out_);
  std::fputs("\x1b[K", out_);
  std::fflush(out_);
  drawn_ = true;
}

void ProgressLine::clear() {
  if (!enabled_ || !drawn_) return;
  std::fputs("\r\x1b[K", out_);
  std::fflush(out_);
  drawn_ = false;
}

bool ProgressLine::isTerminal(std::FILE* out) { return out != nullptr && ::isatty(fileno(out)) == 1; }

int ProgressLine::terminalWidth(int fd) {
  winsize size{};
  if (::ioctl(fd, TIOCGWINSZ, &size) == 0 && size.ws_col > 0) return size.ws_col;
  return 80;
}

}  // namespace throng::cli
