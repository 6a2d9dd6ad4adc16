// throng CLI output helpers — diagnostics on stderr (one line each) or as JSON, number and time
// formatting shared by the subcommands, and the input-file pre-check.
#pragma once
#include <cstdio>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "throng/core/diagnostic.hpp"

namespace throng::cli {

/// At most this many diagnostics are printed (text or JSON); the rest are counted. A hostile file
/// with 300,000 unknown keys gets 50 lines and "... and 299,950 more problems", not 300,000 lines.
inline constexpr std::size_t kMaxPrintedDiagnostics = 50;

/// Prints the first kMaxPrintedDiagnostics diagnostics, one line each, on stderr, then
/// "throng: ... and N more problems (not listed)" when there are more.
void printDiagnostics(const core::Diagnostics& diagnostics);

/// A command's failure on its input: the diagnostics as {"ok": false, "diagnostics", "diagnostics_total"?}
/// on stdout with `json`, else printDiagnostics; returns kExitFailure.
int reportFailure(const core::Diagnostics& diagnostics, bool json);

/// [{source, line, column, pointer, what, expected, hint}, ...]: the first `limit` diagnostics,
/// every text made printable (core::printable), so that dumping never fails on bad UTF-8.
[[nodiscard]] nlohmann::json diagnosticsToJson(const core::Diagnostics& diagnostics,
                                               std::size_t limit = kMaxPrintedDiagnostics);

/// A name or other string from an input file, as shown in text output: control characters
/// escaped, invalid UTF-8 as \xNN, at most `maxCharacters` characters.
[[nodiscard]] std::string displayText(std::string_view text, std::size_t maxCharacters = 200);

/// `value.dump()` that never throws: bytes that are not UTF-8 (a recording written by an older
/// throng) become U+FFFD.
[[nodiscard]] std::string dumpJson(const nlohmann::json& value);

/// One diagnostic naming `path` when it is not a readable regular file; empty when it is.
/// `what` names the kind of file in the message ("scenario", "recording").
[[nodiscard]] core::Diagnostics checkInputFile(const std::string& path, const char* what);

/// "12.3 ms", "1.23 s", "4 min 05 s", "1 h 02 min" for a duration in seconds.
[[nodiscard]] std::string formatSeconds(double seconds);
/// "12.3 k", "4.56 M" — three significant digits with an SI prefix.
[[nodiscard]] std::string formatSi(double value);
/// "512 B", "3.4 KiB", "1.2 GiB".
[[nodiscard]] std::string formatBytes(double bytes);

/// Writes `line` and a newline to `out` and flushes.
void printLine(std::FILE* out, const std::string& line);

}  // namespace throng::cli
