// throng::recording recorded frames — every frame of a `throng run` recording read into memory as an
// immutable sim::Frame, for replaying it (hub::Replay): positions and headings (trajectory_data),
// heights (throng_heights), clips and phases (throng_animation, or derived from the motion when
// the file has none), ticks and times (throng_frames), plus the fps and the scenario JSON
// (metadata). Tables in docs/recording-format.md. Reads the file read-only, once; writes nothing.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "throng/core/result.hpp"
#include "throng/sim/animation.hpp"
#include "throng/sim/frame.hpp"

namespace throng::recording {

// How a recording without throng_animation rows is animated: clip 1 (walk) where the agent moved
// faster than kStandingSpeed since the previous frame, else clip 0 (idle); the walk phase advances
// with the distance walked (kWalkCycle per cycle), the idle phase with time (kIdleCycle per cycle).
inline constexpr double kWalkCycle = 1.4;      ///< metres walked per walk cycle (throng_clips row 1) [m]
inline constexpr double kIdleCycle = 2.0;      ///< seconds per idle cycle (throng_clips row 0) [s]
inline constexpr double kStandingSpeed = 0.1;  ///< slower than this counts as standing [m/s]
static_assert(static_cast<float>(kWalkCycle) == sim::kWalkCycleLength && static_cast<float>(kIdleCycle) == sim::kIdleCycle,
              "the replay animates with the cycles the simulation records");

/// Recordings with more frames than this are refused.
inline constexpr std::int64_t kMaxRecordedFrames = 100'000'000;

struct FrameReadOptions {
  /// Refuse a recording whose frames would need more memory than this (estimated from its rows:
  /// about 32 bytes per agent and frame, 400 per frame) [bytes] [Limit: > 0].
  std::size_t maxBytes = std::size_t{2} << 30;
};

/// Every frame of a recording.
struct RecordedFrames {
  std::string scenarioText;   ///< metadata `throng_scenario`, the scenario JSON `throng run` read
  std::string worldFile;      ///< metadata `throng_world_file` (the glTF / GLB file's name), empty when absent
  double fps = 0.0;           ///< metadata `fps` [Hz], > 0
  bool hasAnimation = false;  ///< throng_animation had rows (else every clip and phase is derived)
  std::vector<double> times;  ///< per frame, relative to the first (times[0] = 0), non-decreasing [s]
  /// One per frame (frames numbered from 0 to the highest recorded or listed), never null: ids
  /// ascending; posX/posY, oriX/oriY (unit), clip, phase and mode (clip 0 → Waiting, 1 → Walking,
  /// ≥ 2 → Acting) per agent; posZ only on a multi-level world (throng_heights); velX/velY empty (not
  /// recorded); tick as recorded (else the frame number); time = times[frame]; no events.
  std::vector<sim::FramePtr> frames;
};

/// Reads a recording written by `throng run`. Errors (one Diagnostic, `source` = the path): no such
/// file, not a regular file, not SQLite, no trajectory_data / metadata tables, no scenario stored
/// (metadata `throng_scenario`), bad fps, no frames, too many frames, too large for maxBytes, an
/// agent id outside [0, 2^32) or a non-finite position in trajectory_data, an unreadable table.
core::Result<RecordedFrames> readRecordedFrames(const std::string& path, const FrameReadOptions& options = {});

}  // namespace throng::recording
