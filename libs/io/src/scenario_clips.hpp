// throng::io scenario clips — loads the motion clip (BVH) of every action point that names one
// ("clip": "motions/look.bvh", relative to the scenario file's directory), and derives the point's
// defaults from it: actionDuration = the clip's duration unless "duration" is given, action = the
// clip's name unless "action" is given. Reads the JSON (which keys were given), the clip files and
// the clips' directory (for "did you mean"); writes PointDesc fields, the clips and diagnostics.
// Private to throng_io.
#pragma once
#include "json_document.hpp"
#include "scenario_parser.hpp"
#include "throng/io/scenario_loader.hpp"

namespace throng::io {

/// Most directory entries looked at (to a depth of 3) when suggesting a clip path.
inline constexpr std::size_t kMaxClipSuggestionEntries = 4096;

/// Loads every referenced clip once (keyed by the path as written); a missing or unreadable file
/// is one diagnostic at /points/N/clip, a malformed one keeps the BVH file's own line:column
/// diagnostics plus one at /points/N/clip.
[[nodiscard]] MotionClips loadScenarioClips(const JsonDocument& doc, ParsedScenario& parsed,
                                            core::Diagnostics& diagnostics);

}  // namespace throng::io
