// throng::motion motion clips — Biovision Hierarchy (BVH) text parsed into a MotionClip: a skeleton
// (joints with offsets and channels) plus one row of channel values per frame. Action points of a
// scenario reference clips ("clip": "motions/look.bvh"); the clip's length gives the action's
// duration, and the viewer animates agents with it. Reads text (or one file); writes nothing.
// The simulation never sees a MotionClip: it gets the clip's path, name and duration through
// sim::PointDesc (clip, action, actionDuration).
//
// Accepted grammar (whitespace-separated tokens; one frame per line):
//   HIERARCHY
//   ROOT name { OFFSET x y z [CHANNELS n c1 .. cn] (JOINT name { ... } | End Site { OFFSET x y z })* }
//   MOTION
//   Frames: n
//   Frame Time: seconds
//   n rows of channelCount numbers
// Channel names: Xposition Yposition Zposition Xrotation Yrotation Zrotation, any order, each at
// most once per joint; rotations are in degrees, lengths in the file's unit (bundled clips: metres).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "throng/core/result.hpp"

namespace throng::motion {

/// Limits that keep hostile input cheap; exceeding one is a diagnostic, never a truncation.
inline constexpr std::size_t kMaxBvhBytes = 64u << 20;   ///< file size [bytes] (64 MiB)
inline constexpr std::size_t kMaxBvhJoints = 1024;       ///< joints, End Sites not counted
inline constexpr std::size_t kMaxBvhDepth = 64;          ///< nesting of JOINT blocks below ROOT
inline constexpr std::size_t kMaxBvhFrames = 1000000;    ///< frames per clip
inline constexpr double kMaxBvhFrameTime = 60.0;         ///< Frame Time [s] (must be > 0)
inline constexpr double kMaxBvhMagnitude = 1e9;          ///< largest |number| accepted (offsets, values)

enum class MotionChannel : std::uint8_t { Xposition, Yposition, Zposition, Xrotation, Yrotation, Zrotation };

/// "Xposition" … "Zrotation".
[[nodiscard]] std::string_view channelName(MotionChannel channel);

struct MotionClip {
  struct Joint {
    std::string name;                   ///< unique within the clip
    int parent = -1;                    ///< index into joints; -1 for the root
    std::array<float, 3> offset{};      ///< from the parent joint (file length unit)
    std::vector<MotionChannel> channels;  ///< in file order (0 to 6)
    std::size_t firstChannel = 0;       ///< column of channels[0] in a frame row
    bool hasEndSite = false;            ///< an "End Site" block closes this joint
    std::array<float, 3> endSite{};     ///< End Site offset from this joint (when hasEndSite)
  };

  std::string name;            ///< the file's stem ("look" for motions/look.bvh)
  std::vector<Joint> joints;   ///< depth-first file order: a parent comes before its children
  double frameTime = 0.0;      ///< [s] (0, kMaxBvhFrameTime]
  std::size_t frameCount = 0;  ///< [1, kMaxBvhFrames]
  std::size_t channelCount = 0;  ///< sum of the joints' channels (>= 1)
  std::vector<float> values;   ///< frameCount × channelCount, frame-major (degrees, file units)

  /// Length of the clip [s]: frameTime × frameCount (a looping clip's frame n equals frame 0).
  [[nodiscard]] double duration() const { return frameTime * static_cast<double>(frameCount); }
  /// The value of `channel` (a column, see Joint::firstChannel) in `frame`. Both must be in range.
  [[nodiscard]] float value(std::size_t frame, std::size_t channel) const {
    return values[frame * channelCount + channel];
  }
  /// Index of the joint named `name`, or -1.
  [[nodiscard]] int findJoint(std::string_view jointName) const;
};

/// Parses BVH text. `source` names the text in diagnostics (usually its path); the clip's name is
/// the stem of `source`. Every diagnostic has source:line:column, what was found and what was
/// expected; structural errors stop the parse, other problems are all reported (up to 50 bad frame
/// rows, 100 problems in all).
core::Result<MotionClip> parseBvh(std::string_view text, const std::string& source);

/// Reads a BVH file (a regular file of at most kMaxBvhBytes) and parses it. A missing or unreadable
/// file is one diagnostic with line 0 naming the path.
core::Result<MotionClip> loadBvhFile(const std::string& path);

}  // namespace throng::motion
