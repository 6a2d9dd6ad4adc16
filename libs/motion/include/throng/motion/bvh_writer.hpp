// throng::motion motion clip writer — a MotionClip (see bvh.hpp) as Biovision Hierarchy (BVH) text that
// parseBvh reads back to the same clip: same joints (names, parents, offsets, channels in the same
// order, End Sites), frame count, frame time and values. Writes text, or one file atomically.
//
// Precision: every number is written in the shortest decimal form that reads back to the same
// value (std::to_chars): offsets and channel values as float (at most 9 significant digits), the
// frame time as double (at most 17). A round trip through parseBvh is therefore exact; a value of
// -0 is written as 0. Output layout: two-space indentation per level, "\n" line ends, one frame per
// line, columns in the joints' depth-first file order (a joint's channels are adjacent).
#pragma once
#include <string>

#include "throng/core/result.hpp"
#include "throng/motion/bvh.hpp"

namespace throng::motion {

/// BVH text for `clip`. The clip should be well formed (as parseBvh returns it: joints depth-first
/// with parents before children, unique single-word names, values.size() == frameCount ×
/// channelCount); a missing value is written as 0 and surplus values are ignored, never read out of
/// range. Use saveBvhFile to have the clip checked first.
[[nodiscard]] std::string writeBvh(const MotionClip& clip);

/// Checks that `clip` can be written as BVH that parseBvh accepts: at least one joint, exactly one
/// root (joints[0]), parents before children in depth-first order, unique non-empty joint names
/// without whitespace or lone braces, at most 6 channels per joint with none repeated, channel
/// columns that match the joints (a joint without channels may have any firstChannel), frameCount
/// and frameTime within the limits of bvh.hpp, values.size() == frameCount × channelCount and every
/// number finite with |x| <= kMaxBvhMagnitude. Diagnostics name `source` (line 0) and the offending
/// joint or frame.
core::Status checkMotionClip(const MotionClip& clip, const std::string& source);

/// Checks `clip` (checkMotionClip) and writes writeBvh(clip) to `path` atomically: the text goes to
/// a new temporary file in the same directory, which is flushed and then renamed over `path`. On
/// any failure nothing is left behind (the temporary file is removed, an existing `path` is
/// untouched) and the diagnostic names `path` (line 0), what failed and why (the system's error).
core::Status saveBvhFile(const std::string& path, const MotionClip& clip);

}  // namespace throng::motion
