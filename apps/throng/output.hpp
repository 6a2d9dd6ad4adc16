// throng CLI output helpers — diagnostics on stderr (one line each) or as JSON, number and time
// formatting shared by the subcommands, and the input-file pre-check.
#pragma once
#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "throng/core/diagnostic.hpp"

namespace throng::cli {

/// Prints every diagnostic, one line each, on stderr.
void printDiagnostics(const core::Diagnostics& diagnostics);

/// [{source, line, column, pointer, what, expected, hint}, ...]
[[nodiscard]] nlohmann::json diagnosticsToJson(const core::Diagnostics& diagnostics);

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
