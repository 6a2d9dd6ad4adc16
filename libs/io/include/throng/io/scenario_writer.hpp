// throng::io scenario writer — a scenario (or any JSON) as text formatted for diffs, and a file
// written atomically (a temporary file in the same directory, flushed, then renamed over the
// target or linked where nothing exists yet), for `throng import` and editors saving scenarios.
// Writes only the file it is given.
#pragma once
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "throng/core/result.hpp"

namespace throng::io {

/// JSON text for diffs: 2-space indent, one object member or array element per line, except that an
/// array of numbers, strings, booleans or nulls (a point [x, y]) stays on one line: "[0, 1.5]".
/// Keys keep their order. Ends with a newline; bytes that are not UTF-8 become U+FFFD.
[[nodiscard]] std::string formatJsonForDiffs(const nlohmann::ordered_json& value);

/// Writes `text` to `path` so that a reader sees the old file or the whole new one, never a part,
/// and a crash leaves no half-written file. With `overwrite` false an existing `path` is an error
/// (checked atomically: the new file is linked, not renamed). Diagnostics name `path`.
[[nodiscard]] core::Status writeFileAtomically(const std::string& path, std::string_view text, bool overwrite);

}  // namespace throng::io
