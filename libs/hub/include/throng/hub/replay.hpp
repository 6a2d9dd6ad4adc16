// throng::hub replay — what `throng serve FILE.sqlite` plays instead of a live simulation: Replay
// reads a recording written by `throng run` (JuPedSim trajectory tables + throng's tables,
// docs/recording-format.md) into memory and hands out its frames by time; ReplayClock is the
// timeline that ReplayControl messages drive (play, pause, seek, speed). Reads the recording
// once, at open; writes nothing.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "throng/core/result.hpp"
#include "throng/protocol/messages.hpp"
#include "throng/sim/frame.hpp"

namespace throng::hub {

/// Recordings larger than this in memory (estimated from their rows) are refused at open [bytes].
inline constexpr std::size_t kMaxReplayBytes = std::size_t{2} << 30;

/// A recording loaded for replay. Every frame is read at open (about 27 bytes per agent and frame)
/// and kept as an immutable sim::Frame,
/// so frameAt() is a binary search and never touches the file. Cheap to copy (shared state).
class Replay {
 public:
  /// Opens a recording written by `throng run`. Errors (one Diagnostic, `source` = the path): no
  /// such file, not a regular file, not SQLite, no trajectory_data / metadata tables, no scenario
  /// stored (metadata `throng_scenario`, so not a throng recording), bad fps, no frames, too large.
  static core::Result<Replay> open(const std::string& path);

  /// Time from the first to the last frame [s] (0 for a single frame).
  [[nodiscard]] double duration() const;
  /// Recorded frames per second [Hz] (metadata `fps`).
  [[nodiscard]] double fps() const;
  [[nodiscard]] std::size_t frameCount() const;
  /// The scenario JSON stored in the recording (metadata `throng_scenario`), as `throng run` read it.
  [[nodiscard]] const std::string& scenarioText() const;
  /// The glTF / GLB file the recorded world was read from, by name (metadata `throng_world_file`);
  /// empty for a scenario JSON and for recordings written before the key existed.
  [[nodiscard]] const std::string& worldFile() const;
  /// Whether the recording had throng_animation rows; when not, clip and phase are derived (clip 1
  /// walk when the agent moved faster than 0.1 m/s since the previous frame, else 0 idle; walk phase
  /// from the distance walked, 1.4 m per cycle, idle phase from time, 2 s per cycle).
  [[nodiscard]] bool hasAnimation() const;

  /// Index of the frame shown at recording time t [s]: the last frame at or before t, clamped to
  /// [0, frameCount() − 1] (NaN → 0).
  [[nodiscard]] std::size_t frameIndexAt(double t) const;
  /// Recording time of frame `index` [s], relative to the first frame (clamped index).
  [[nodiscard]] double frameTime(std::size_t index) const;
  /// The recorded frame at time t (see frameIndexAt). ids ascending; posX/posY, oriX/oriY (unit),
  /// clip, phase and mode (clip 0 → Waiting, 1 → Walking, ≥ 2 → Acting) per agent; velX/velY
  /// EMPTY (not recorded; saves memory); tick as recorded; time = recording time of the frame;
  /// events, script and coordinations empty. Never null; the same pointer for the same frame.
  [[nodiscard]] sim::FramePtr frameAt(double t) const;

 private:
  struct Data;
  explicit Replay(std::shared_ptr<const Data> data);
  std::shared_ptr<const Data> data_;
};

/// The replay timeline: recording time in [0, duration], playing or paused, a speed factor.
/// Pure (no clock): the caller passes wall time to advance(). Reaching the end pauses at duration;
/// Play at the end starts again from 0.
class ReplayClock {
 public:
  /// Starts at time 0, at speed 1, playing when `playing`. A negative or NaN duration counts as 0.
  explicit ReplayClock(double duration, bool playing = true);

  /// Carries out a ReplayControl command (value as in protocol::ReplayControl: seek time [s] is
  /// clamped to [0, duration]; speed is clamped to [1/1024, kMaxReplaySpeed]; a NaN value is ignored).
  /// Returns true when the state (time, playing or speed) changed.
  bool apply(protocol::ReplayCommand command, double value);
  bool apply(const protocol::ReplayControl& control) { return apply(control.command, control.value); }

  bool play();                 ///< see apply
  bool pause();                ///< see apply
  bool seek(double seconds);   ///< see apply
  bool setSpeed(double factor);///< see apply

  /// Moves time forward by wallSeconds × speed when playing (wallSeconds ≤ 0 or NaN: nothing).
  /// Returns true when this reached the end and paused (worth a ReplayStatus).
  bool advance(double wallSeconds);

  [[nodiscard]] double time() const { return time_; }           ///< [s]
  [[nodiscard]] double duration() const { return duration_; }   ///< [s]
  [[nodiscard]] bool playing() const { return playing_; }
  [[nodiscard]] double speed() const { return speed_; }
  [[nodiscard]] protocol::ReplayStatus status() const;

 private:
  double duration_ = 0.0;
  double time_ = 0.0;
  double speed_ = 1.0;
  bool playing_ = false;
};

}  // namespace throng::hub
