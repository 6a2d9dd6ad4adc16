// throng::hub replay — Replay::open reads a `throng run` recording through throng::recording's
// frame reader (readRecordedFrames: one immutable sim::Frame per frame, its time, the fps and the
// scenario JSON) and hands the frames out by time; ReplayClock is the play / pause / seek / speed
// timeline. Reads the recording once, at open; writes nothing.
#include "throng/hub/replay.hpp"

#include <algorithm>
#include <cmath>

#include "throng/recording/frame_reader.hpp"

namespace throng::hub {
namespace {

constexpr double kMinSpeed = 1.0 / 1024.0;  ///< slowest speed factor (stays > 0 as a float)

}  // namespace

struct Replay::Data {
  recording::RecordedFrames recorded;
};

Replay::Replay(std::shared_ptr<const Data> data) : data_(std::move(data)) {}

core::Result<Replay> Replay::open(const std::string& path) {
  auto recorded = recording::readRecordedFrames(path, recording::FrameReadOptions{kMaxReplayBytes});
  if (!recorded) return recorded.errors();
  auto data = std::make_shared<Data>();
  data->recorded = std::move(recorded).value();
  return Replay(std::move(data));
}

double Replay::duration() const { return data_->recorded.times.back(); }
double Replay::fps() const { return data_->recorded.fps; }
std::size_t Replay::frameCount() const { return data_->recorded.frames.size(); }
const std::string& Replay::scenarioText() const { return data_->recorded.scenarioText; }
const std::string& Replay::worldFile() const { return data_->recorded.worldFile; }
bool Replay::hasAnimation() const { return data_->recorded.hasAnimation; }

std::size_t Replay::frameIndexAt(double t) const {
  const auto& times = data_->recorded.times;
  if (!(t > 0.0)) return 0;  // also NaN
  const auto it = std::upper_bound(times.begin(), times.end(), t);
  return static_cast<std::size_t>(it - times.begin()) - 1;  // times[0] == 0 ≤ t: it > begin
}

double Replay::frameTime(std::size_t index) const {
  const auto& times = data_->recorded.times;
  return times[std::min(index, times.size() - 1)];
}

sim::FramePtr Replay::frameAt(double t) const { return data_->recorded.frames[frameIndexAt(t)]; }

// --- ReplayClock ----------------------------------------------------------------------------

ReplayClock::ReplayClock(double duration, bool playing)
    : duration_(std::isfinite(duration) && duration > 0.0 ? duration : 0.0), playing_(playing) {}

bool ReplayClock::play() {
  bool changed = !playing_;
  if (time_ >= duration_ && duration_ > 0.0) {  // at the end: start again
    time_ = 0.0;
    changed = true;
  }
  playing_ = true;
  return changed;
}

bool ReplayClock::pause() {
  const bool changed = playing_;
  playing_ = false;
  return changed;
}

bool ReplayClock::seek(double seconds) {
  if (std::isnan(seconds)) return false;
  const double t = std::clamp(seconds, 0.0, duration_);
  const bool changed = t != time_;
  time_ = t;
  return changed;
}

bool ReplayClock::setSpeed(double factor) {
  if (std::isnan(factor)) return false;
  const double s = std::clamp(factor, kMinSpeed, protocol::kMaxReplaySpeed);
  const bool changed = s != speed_;
  speed_ = s;
  return changed;
}

bool ReplayClock::apply(protocol::ReplayCommand command, double value) {
  switch (command) {
    case protocol::ReplayCommand::Play: return play();
    case protocol::ReplayCommand::Pause: return pause();
    case protocol::ReplayCommand::Seek: return seek(value);
    case protocol::ReplayCommand::Speed: return setSpeed(value);
  }
  return false;
}

bool ReplayClock::advance(double wallSeconds) {
  if (!playing_ || !(wallSeconds > 0.0)) return false;
  time_ = std::min(duration_, time_ + wallSeconds * speed_);
  if (time_ >= duration_) {
    playing_ = false;
    return true;
  }
  return false;
}

protocol::ReplayStatus ReplayClock::status() const {
  return protocol::ReplayStatus{time_, duration_, playing_, static_cast<float>(speed_)};
}

}  // namespace throng::hub
