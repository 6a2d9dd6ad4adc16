// throng::capi::Session: stepping, frames, events and the recording of one C API world, the same
// way `throng run` (apps/throng/cmd_run.cpp) and the Python module (python/src/module.cpp) do it.
#include "session.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

namespace throng::capi {

core::Result<std::unique_ptr<Session>> Session::create(std::shared_ptr<const io::LoadedScenario> scenario,
                                                       const SessionOptions& options) {
  std::unique_ptr<Session> s(new Session());
  s->loaded_ = std::move(scenario);
  s->desc_ = s->loaded_->desc;
  if (options.seed) s->desc_.seed = *options.seed;
  if (options.duration) s->desc_.duration = static_cast<float>(*options.duration);
  auto world = sim::World::create(s->desc_, s->loaded_->navmesh);
  if (!world) return core::Result<std::unique_ptr<Session>>(world.errors());
  s->world_ = std::move(world).value();
  s->tasks_ = std::make_unique<core::TaskSystem>(options.threads);
  s->keep(s->world_->takeFrame());  // frame 0: the state before the first tick
  return s;
}

Session::~Session() {
  if (recorder_) (void)recorder_->close(true);
}

void Session::tick() {
  world_->step(*tasks_);
  current_.reset();
  if (recorder_ && world_->stats().tick % stride_ == 0) push(world_->takeFrame());
}

StepEnd Session::step(std::uint64_t ticks, std::uint64_t& stepped) {
  stepped = 0;
  for (; stepped < ticks; ++stepped) {
    if (recorder_ && recorder_->failed()) return StepEnd::WriteFailed;
    if (world_->finished()) return StepEnd::Finished;
    tick();
  }
  return StepEnd::Done;
}

StepEnd Session::run(double until) {
  // `until` is finite and >= 0 (checked by the caller); beyond 2^63 ticks means "until finished".
  const double ticks = std::round(until / desc_.dt);
  const std::uint64_t endTick = ticks < 9.2e18 ? static_cast<std::uint64_t>(ticks) : UINT64_MAX;
  while (true) {
    if (recorder_ && recorder_->failed()) return StepEnd::WriteFailed;
    const std::uint64_t t = world_->stats().tick;
    if (t % stride_ == 0 && (world_->finished() || t >= endTick)) return StepEnd::Done;
    tick();
  }
}

const sim::Frame& Session::frame() {
  if (!current_ || current_->tick != world_->stats().tick) keep(world_->takeFrame());
  return *current_;
}

/// A frame taken for the caller: its events become pending and, while recording, go with its
/// script records into the next recorded frame (the recording misses nothing the caller read).
void Session::keep(const sim::FramePtr& frame) {
  pending_.insert(pending_.end(), frame->events.begin(), frame->events.end());
  if (recorder_) carry_.add(*frame);
  current_ = frame;
}

/// A recorded tick's frame, preceded by whatever frames taken since the last one drained.
void Session::push(sim::FramePtr frame) {
  pending_.insert(pending_.end(), frame->events.begin(), frame->events.end());
  current_ = frame;
  recorder_->push(carry_.merge(std::move(frame)));
}

std::vector<std::uint32_t> Session::groupsOf(const sim::Frame& frame) const {
  const std::uint32_t none = 0xffffffffu;
  std::vector<std::uint32_t> groupOfId(frame.ids.empty() ? 0 : frame.ids.back() + 1, none);
  const auto groups = static_cast<std::uint32_t>(world_->groupCount());
  for (std::uint32_t g = 0; g < groups; ++g) {
    const auto info = world_->groupInfo(world_->groupById(g));
    if (!info) continue;
    for (std::uint32_t m : info->members) {
      if (m < groupOfId.size()) groupOfId[m] = info->id;
    }
  }
  std::vector<std::uint32_t> out(frame.size());
  for (std::size_t i = 0; i < frame.size(); ++i) out[i] = groupOfId[frame.ids[i]];
  return out;
}

std::size_t Session::pendingEvents() {
  frame();  // drains the world's events of this tick
  return pending_.size();
}

std::size_t Session::takeEvents(sim::Event* out, std::size_t capacity) {
  frame();
  const std::size_t n = std::min(capacity, pending_.size());
  std::copy_n(pending_.begin(), n, out);
  pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(n));
  return n;
}

core::Status Session::record(const std::string& path, double fps, bool force) {
  // The CLI's frame plan (cmd_run.cpp planFrames): every stride-th tick, the rate actually recorded.
  const double ratio = 1.0 / (fps * desc_.dt);
  const auto stride = static_cast<std::uint64_t>(std::max(1.0, std::round(ratio)));
  const bool exact = std::fabs(ratio - static_cast<double>(stride)) <= 1e-6 * ratio;
  recording::RecordingOptions r;
  r.path = path;
  r.force = force;
  r.fps = exact ? fps : 1.0 / (static_cast<double>(stride) * desc_.dt);
  r.seed = desc_.seed;
  r.scenarioText = loaded_->text;
  auto opened = recording::Recorder::open(desc_, r);
  if (!opened) return core::Status(opened.errors());
  frame();  // frame 0 (taken when the world was built), before the recorder would carry its events twice
  recorder_ = std::move(opened).value();
  stride_ = stride;
  recorder_->push(current_);
  return core::Status(core::Ok{});
}

core::Status Session::closeRecording(std::uint64_t& frames) {
  const core::Status status = recorder_->close(true);
  frames = recorder_->framesWritten();
  recorder_.reset();
  carry_ = {};
  stride_ = 1;
  return status;
}

}  // namespace throng::capi
