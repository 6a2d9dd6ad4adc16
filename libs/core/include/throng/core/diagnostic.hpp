// throng::core::Diagnostic — one problem found in user input, with where it is and what was
// expected; formatted as one line:
//   mall.json:14:7 /populations/0/goals/1: unknown point "exitt"; expected an id from /points (did you mean "exit"?)
#pragma once
#include <string>
#include <vector>

namespace throng::core {

struct Diagnostic {
  std::string source;   ///< file path, or a peer address ("127.0.0.1:4312")
  int line = 0;         ///< 1-based; 0 when unknown
  int column = 0;       ///< 1-based; 0 when unknown
  std::string pointer;  ///< JSON Pointer into the document ("/populations/0/goals/1"), may be empty
  std::string what;     ///< what is wrong
  std::string expected; ///< what was expected, may be empty
  std::string hint;     ///< "did you mean ..." and the like, may be empty

  /// "source:line:col pointer: what; expected E (hint)".
  [[nodiscard]] std::string format() const;
};

using Diagnostics = std::vector<Diagnostic>;

/// Joins every diagnostic's format() with newlines.
[[nodiscard]] std::string formatAll(const Diagnostics& diagnostics);

/// The candidate closest to `word` by edit distance, if close enough to be a likely typo;
/// empty otherwise. Used for "did you mean" hints.
[[nodiscard]] std::string closestMatch(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace throng::core
