// throng CLI output helpers — see output.hpp.
#include "output.hpp"

#include "commands.hpp"

#include "throng/core/text.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <system_error>

#include <fmt/format.h>

namespace throng::cli {

void printDiagnostics(const core::Diagnostics& diagnostics) {
  const std::size_t shown = std::min(diagnostics.size(), kMaxPrintedDiagnostics);
  for (std::size_t i = 0; i < shown; ++i) printLine(stderr, diagnostics[i].format());
  if (diagnostics.size() > shown) {
    const std::size_t more = diagnostics.size() - shown;
    printLine(stderr, fmt::format("throng: ... and {} more problem{} (not listed; {} in all)", more, more == 1 ? "" : "s",
                                  diagnostics.size()));
  }
}

int reportFailure(const core::Diagnostics& diagnostics, bool json) {
  if (json) {
    nlohmann::json out{{"ok", false}, {"diagnostics", diagnosticsToJson(diagnostics)}};
    if (diagnostics.size() > kMaxPrintedDiagnostics) out["diagnostics_total"] = diagnostics.size();
    printLine(stdout, dumpJson(out));
  } else {
    printDiagnostics(diagnostics);
  }
  return kExitFailure;
}

nlohmann::json diagnosticsToJson(const core::Diagnostics& diagnostics, std::size_t limit) {
  auto list = nlohmann::json::array();
  const std::size_t shown = std::min(diagnostics.size(), limit);
  for (std::size_t i = 0; i < shown; ++i) {
    const core::Diagnostic& d = diagnostics[i];
    list.push_back({{"source", core::printable(d.source)},
                    {"line", d.line},
                    {"column", d.column},
                    {"pointer", core::printable(d.pointer)},
                    {"what", core::printable(d.what)},
                    {"expected", core::printable(d.expected)},
                    {"hint", core::printable(d.hint)}});
  }
  return list;
}

std::string displayText(std::string_view text, std::size_t maxCharacters) { return core::printable(text, maxCharacters); }

std::string dumpJson(const nlohmann::json& value) {
  return value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

core::Diagnostics checkInputFile(const std::string& path, const char* what) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const auto status = fs::status(path, ec);
  core::Diagnostic d;
  d.source = path;
  if (ec || !fs::exists(status)) {
    d.what = fmt::format("{} file not found", what);
    d.expected = "an existing, readable file";
  } else if (fs::is_directory(status)) {
    d.what = fmt::format("is a directory, not a {} file", what);
    d.expected = "a regular file";
  } else if (std::ifstream probe(path, std::ios::binary); !probe) {
    d.what = fmt::format("cannot open the {} file for reading", what);
    d.expected = "a readable file (check permissions)";
  } else {
    return {};
  }
  return {d};
}

std::string formatSeconds(double seconds) {
  if (!std::isfinite(seconds)) return "?";
  if (seconds < 0.1) return fmt::format("{:.1f} ms", seconds * 1000.0);
  if (seconds < 60.0) return fmt::format("{:.2f} s", seconds);
  const auto total = static_cast<long long>(std::llround(seconds));
  if (total < 3600) return fmt::format("{} min {:02} s", total / 60, total % 60);
  return fmt::format("{} h {:02} min", total / 3600, (total % 3600) / 60);
}

std::string formatSi(double value) {
  static constexpr const char* kPrefixes[] = {"", " k", " M", " G", " T"};
  int p = 0;
  double v = value;
  while (std::fabs(v) >= 1000.0 && p < 4) {
    v /= 1000.0;
    ++p;
  }
  if (p == 0) return fmt::format("{:.0f}", v);
  return fmt::format("{:.{}f}{}", v, std::fabs(v) < 10 ? 2 : std::fabs(v) < 100 ? 1 : 0, kPrefixes[p]);
}

std::string formatBytes(double bytes) {
  static constexpr const char* kUnits[] = {"B", "KiB", "MiB", "GiB", "TiB"};
  int u = 0;
  double v = bytes;
  while (std::fabs(v) >= 1024.0 && u < 4) {
    v /= 1024.0;
    ++u;
  }
  if (u == 0) return fmt::format("{:.0f} B", v);
  return fmt::format("{:.1f} {}", v, kUnits[u]);
}

void printLine(std::FILE* out, const std::string& line) {
  std::fputs(line.c_str(), out);
  std::fputc('\n', out);
  std::fflush(out);
}

}  // namespace throng::cli
