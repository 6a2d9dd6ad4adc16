// throng::recording recording text — how numbers become text in a recording: metadata values (TEXT
// column, written the way Python's str(float) writes them, as JuPedSim does) and WKT coordinates
// (shortest round-trip decimal, trimmed like shapely.to_wkt). Reads nothing, writes strings.
#pragma once
#include <charconv>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace throng::recording {

/// Shortest decimal that reads back as exactly `v` ("4.5", "20", "1e+22"); -0 becomes "0".
inline std::string shortestText(double v) {
  if (v == 0.0) v = 0.0;  // drop the sign of -0
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

/// Python's str(float): shortest round-trip text, with ".0" when it reads as an integer.
inline std::string pythonFloatText(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  std::string s = shortestText(v);
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

/// The double nearest the shortest decimal of a float: 0.1f becomes 0.1, not 0.10000000149….
/// Used for geometry, which the scenario gave as decimals and stored as float.
inline double floatAsDecimal(float v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  double d = 0.0;
  std::from_chars(buf, r.ptr, d);
  return d;
}

inline std::optional<double> parseDouble(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  double d = 0.0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), d);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size()) return std::nullopt;
  return d;
}

inline std::optional<std::int64_t> parseInt(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  std::int64_t v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (r.ec == std::errc() && r.ptr == s.data() + s.size()) return v;
  // Python writers may store an integer as "2.0".
  const auto d = parseDouble(s);
  if (d && std::isfinite(*d) && std::floor(*d) == *d && std::fabs(*d) < 9.0e15) {
    return static_cast<std::int64_t>(*d);
  }
  return std::nullopt;
}

}  // namespace throng::recording
