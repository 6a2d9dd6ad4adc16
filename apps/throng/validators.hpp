// throng CLI flag validators — CLI11 checks with messages that state the unit and the limit
// (CLI11's own PositiveNumber prints "not in range 0 to 1.79e308").
#pragma once
#include <cmath>
#include <string>

#include <CLI/CLI.hpp>

namespace throng::cli {

/// A number > 0 (and finite); `unit` is named in the message ("s", "Hz"), may be empty.
inline CLI::Validator positiveNumber(const std::string& unit = "") {
  return CLI::Validator(
      [unit](std::string& text) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(text, v) || !std::isfinite(v) || v <= 0) {
          return "value " + text + " is not a number > 0" + (unit.empty() ? "" : " " + unit);
        }
        return {};
      },
      "> 0", "POSITIVE");
}

/// An integer in [lo, hi].
inline CLI::Validator integerRange(long long lo, long long hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) -> std::string {
        long long v = 0;
        if (!CLI::detail::lexical_cast(text, v) || v < lo || v > hi) {
          return "value " + text + " is not an integer from " + std::to_string(lo) + " to " + std::to_string(hi);
        }
        return {};
      },
      std::to_string(lo) + ".." + std::to_string(hi), "INTEGER_RANGE");
}

}  // namespace throng::cli
