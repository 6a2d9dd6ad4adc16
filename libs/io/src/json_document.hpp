// throng::io::JsonDocument — JSON text parsed into nlohmann::ordered_json values plus, for every
// value, the line:column where it (and, for object members, its key) starts, looked up by JSON
// Pointer. nlohmann::json keeps no positions, so this is a small recursive-descent reader of
// RFC 8259 JSON. Time and memory are linear in the text: positions live in a tree parallel to the
// values (no pointer strings are built while parsing), duplicate keys are found with a hash index
// once an object has more than a few keys, strings must be UTF-8 and nesting is bounded.
// Reads text; writes the value tree and the position tree. Private to throng_io.
#pragma once
#include <nlohmann/json.hpp>

#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "throng/core/result.hpp"
#include "throng/core/text.hpp"

namespace throng::io {

using Json = nlohmann::ordered_json;

/// 1-based line and column (columns count Unicode code points, tabs count as one).
struct SourcePos {
  int line = 0;
  int column = 0;
};

class JsonDocument {
 public:
  /// Limits that keep hostile input cheap: nesting depth (arrays and objects inside each other)
  /// and text size.
  static constexpr int kMaxDepth = 64;
  static constexpr std::size_t kMaxBytes = 64u << 20;  ///< 64 MiB

  /// Parses `text`; a syntax error (also: a string that is not UTF-8, a duplicate key, nesting
  /// deeper than kMaxDepth) is one diagnostic with line:column and what was expected.
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
  /// One value's positions and where its children's node ids are in children_ (arrays: by index,
  /// objects: in member order).
  struct Node {
    SourcePos value;
    SourcePos key;  ///< line 0 unless the value is an object member
    std::uint32_t firstChild = 0;
    std::uint32_t childCount = 0;
  };
  /// The node `pointer` names, or its nearest existing ancestor (`exact` false then).
  [[nodiscard]] std::uint32_t find(std::string_view pointer, bool& exact) const;

  Json root_;
  std::string source_;
  std::vector<Node> nodes_;               ///< in document order; nodes_[0] is the root
  std::vector<std::uint32_t> children_;   ///< node ids, each container's children contiguous
  /// Objects with many members (node id → key → member index): lookups stay O(1) however many
  /// keys a hostile object has.
  std::unordered_map<std::uint32_t, std::unordered_map<std::string, std::uint32_t>> keyIndex_;
};

/// Escapes one reference token of a JSON Pointer ("~" → "~0", "/" → "~1").
[[nodiscard]] std::string escapePointerToken(std::string_view token);

/// A short description of a JSON value's type for "wrong type" messages ("a string", "an array").
[[nodiscard]] std::string describeType(const Json& value);

}  // namespace throng::io
