// `throng serve`'s real-time loop (serve_loop.hpp): the publisher's thread, the tick loop's steps
// (the next frame, the status window, the status line) and percentile.
#include "serve_loop.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <unistd.h>

#include "output.hpp"
#include "signal.hpp"
#include "throng/protocol/messages.hpp"

namespace throng::cli::serve {

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t k = std::min(v.size() - 1, static_cast<std::size_t>(p * static_cast<double>(v.size())));
  return v[k];
}

void Publisher::loop() {
  while (true) {
    sim::FramePtr frame;
    {
      std::unique_lock lock(mutex_);
      ready_.wait(lock, [&] { return pending_ != nullptr || stop_; });
      if (stop_) return;
      frame = std::move(pending_);
      pending_.reset();
    }
    const auto p0 = Clock::now();
    hub_.publish(*frame, bridge_.now(), &tasks_);
    const double ms = std::chrono::duration<double, std::milli>(Clock::now() - p0).count();
    std::lock_guard lock(mutex_);
    ms_.push_back(ms);
  }
}

TickLoop::TickLoop(const ServeOptions& options, Served& served, hub::Hub& hub, const Bridge& bridge, WorldQueries& queries,
         TickWindow& window, hub::TickWatch& tickWatch, Publisher& publisher, const RecordingRoutes* recordings)
    : options_(options),
      served_(served),
      hub_(hub),
      bridge_(bridge),
      queries_(queries),
      window_(window),
      tickWatch_(tickWatch),
      publisher_(publisher),
      recordings_(recordings),
      clock_(served.replay ? served.replay->duration() : 0.0, true),
      tasks_(options.threads),
      terminal_(isatty(fileno(stderr)) != 0) {}

std::string TickLoop::run() {
  const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / served_.tickRate));
  auto next = Clock::now();
  while (true) {
    if (InterruptGuard::requested()) return "interrupted (Ctrl-C)";
    if (options_.duration && bridge_.now() >= *options_.duration) return "duration reached";
    if (recordings_ && recordings_->pending()) return kOpenRecording;
    const auto t0 = Clock::now();
    tickWatch_.started(bridge_.now());
    const sim::FramePtr frame = nextFrame();
    hub_.observe(*frame);
    queries_.answer(served_.replay ? nullptr : served_.live.world.get(), hub_);
    const auto t1 = Clock::now();
    publisher_.offer(frame);
    tickMs_.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    next += period;
    tickWatch_.finished(bridge_.now(), t1 > next);
    if (t1 > next) {
      next = t1;  // late: start the next tick now, never try to catch up in a burst
    } else {
      std::this_thread::sleep_until(next);
    }
    const double now = bridge_.now();
    if (now - lastWindow_ >= 1.0) refreshWindow(now);
    if (!options_.quiet && terminal_ && now - lastStatus_ >= 1.0) printStatus(*frame, now);
  }
}

sim::FramePtr TickLoop::nextFrame() {
  if (!served_.replay) {
    hub_.applyToWorld(*served_.live.world);
    served_.live.world->step(tasks_);
    return served_.live.world->takeFrame();
  }
  // Playback: the clients' controls move the clock; the frame is the recorded one at its time.
  bool changed = false;
  for (const protocol::ReplayControl& c : hub_.takeReplayControls()) changed = clock_.apply(c) || changed;
  const double wall = bridge_.now();
  changed = clock_.advance(wall - lastReplayWall_) || changed;
  lastReplayWall_ = wall;
  if (changed || wall - lastReplayStatus_ >= 1.0) {
    lastReplayStatus_ = wall;
    hub_.broadcast(protocol::encode(clock_.status()));
  }
  return served_.replay->frameAt(clock_.time());
}

/// Tick and publish percentiles over the last 10 s, for /api/status.
void TickLoop::refreshWindow(double now) {
  lastWindow_ = now;
  const std::size_t recent = std::min<std::size_t>(tickMs_.size(), static_cast<std::size_t>(served_.tickRate * 10));
  std::vector<double> window(tickMs_.end() - static_cast<std::ptrdiff_t>(recent), tickMs_.end());
  std::vector<double> publishWindow = publisher_.recentMs(recent);
  std::lock_guard lock(window_.mutex);
  window_.tickMedianMs = percentile(window, 0.5);
  window_.tickP99Ms = percentile(window, 0.99);
  window_.publishMedianMs = percentile(publishWindow, 0.5);
  window_.publishP99Ms = percentile(publishWindow, 0.99);
}

/// The status line on a terminal's stderr.
void TickLoop::printStatus(const sim::Frame& frame, double now) {
  const hub::HubStatus s = hub_.status();
  const double kbit = static_cast<double>(s.crowdBytes - lastBytes_) * 8.0 / 1000.0 / (now - lastStatus_);
  lastBytes_ = s.crowdBytes;
  lastStatus_ = now;
  double p99 = 0.0;
  {
    std::lock_guard lock(window_.mutex);
    p99 = window_.tickP99Ms;
  }
  std::fprintf(stderr, "\r  t %s  agents %zu  clients %zu (%zu participants)  tick p99 %.1f ms  out %.0f kbit/s   ",
               formatSeconds(frame.time).c_str(), frame.size(), s.clients, s.participants, p99, kbit);
  std::fflush(stderr);
}

}  // namespace throng::cli::serve
