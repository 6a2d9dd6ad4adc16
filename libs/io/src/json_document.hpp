// throng::io::JsonDocument — JSON text parsed into nlohmann::ordered_json values plus a map from
// every JSON Pointer to the line:column where its value (and, for object members, its key) starts.
// nlohmann::json keeps no positions, so this is a small recursive-descent reader of RFC 8259 JSON.
// Reads text; writes the value tree and the position map. Private to throng_io.
#pragma once
#include <nlohmann/json.hpp>

#include <string>
#include <string_view>
#include <unordered_map>

#include "throng/core/result.hpp"

namespace throng::io {

using Json = nlohmann::ordered_json;

/// 1-based line and column (columns count Unicode code points, tabs count as one).
struct SourcePos {
  int line = 0;
  int column = 0;
};

class JsonDocument {
 public:
  /// Limits that keep hostile input cheap: nesting depth and text size.
  static constexpr int kMaxDepth = 64;
  static constexpr std::size_t kMaxBytes = 64u << 20;  ///< 64 MiB

  /// Parses `text`; a syntax error is one diagnostic with line:column and what was expected.
  static core::Result<JsonDocument> parse(std::string_view text, const std::string& source);

  [[nodiscard]] const Json& root() const { return root_; }
  [[nodiscard]] const std::string& source() const { return source_; }

  /// Where the value at `pointer` starts; falls back to the nearest ancestor that has a position.
  [[nodiscard]] SourcePos position(const std::string& pointer) const;
  /// Where the key of the object member at `pointer` starts (its value's position otherwise).
  [[nodiscard]] SourcePos keyPosition(const std::string& pointer) const;

  /// A diagnostic located at the value at `pointer` (or at its key when `atKey`).
  [[nodiscard]] core::Diagnostic diagnostic(const std::string& pointer, std::string what, std::string expected,
                                            std::string hint = {}, bool atKey = false) const;

 private:
  friend class JsonReader;
  Json root_;
  std::string source_;
  std::unordered_map<std::string, SourcePos> values_;
  std::unordered_map<std::string, SourcePos> keys_;
};

/// Escapes one reference token of a JSON Pointer ("~" → "~0", "/" → "~1").
[[nodiscard]] std::string escapePointerToken(std::string_view token);

/// A short description of a JSON value's type for "wrong type" messages ("a string", "an array").
[[nodiscard]] std::string describeType(const Json& value);

}  // namespace throng::io
