// throng::core::Diagnostic — formats one problem in user input as a single line
// ("file:line:col /pointer: what; expected E (hint)") and finds "did you mean" candidates.
// Reads only its arguments; no state.
#include "throng/core/diagnostic.hpp"

#include <algorithm>
#include <cctype>

namespace throng::core {

std::string Diagnostic::format() const {
  std::string out = source;
  if (line > 0) {
    out += ':' + std::to_string(line);
    if (column > 0) out += ':' + std::to_string(column);
  }
  if (!pointer.empty()) {
    if (!out.empty()) out += ' ';
    out += pointer;
  }
  if (!out.empty()) out += ": ";
  out += what;
  if (!expected.empty()) out += "; expected " + expected;
  if (!hint.empty()) out += " (" + hint + ")";
  return out;
}

std::string formatAll(const Diagnostics& diagnostics) {
  std::string out;
  for (std::size_t i = 0; i < diagnostics.size(); ++i) {
    if (i > 0) out += '\n';
    out += diagnostics[i].format();
  }
  return out;
}

namespace {

/// Levenshtein distance, case-insensitive (a typo in case is still a typo worth pointing at).
std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                        std::tolower(static_cast<unsigned char>(b[j - 1]));
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (same ? 0 : 1)});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

}  // namespace

std::string closestMatch(const std::string& word, const std::vector<std::string>& candidates) {
  // A likely typo: at most max(2, len/3) edits away; ties go to the first candidate (stable).
  const std::size_t threshold = std::max<std::size_t>(2, word.size() / 3);
  std::size_t best = threshold + 1;
  std::string match;
  for (const auto& c : candidates) {
    if (c.empty()) continue;
    // Cheap length filter before the O(n·m) distance.
    const std::size_t lenDiff = c.size() > word.size() ? c.size() - word.size() : word.size() - c.size();
    if (lenDiff >= best) continue;
    const std::size_t d = editDistance(word, c);
    if (d < best && d < c.size()) {  // never suggest a word sharing nothing with the input
      best = d;
      match = c;
    }
  }
  return match;
}

}  // namespace throng::core
