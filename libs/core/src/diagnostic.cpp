// throng::core::Diagnostic — formats one problem in user input as a single line
// ("file:line:col /pointer: what; expected E (hint)") and finds "did you mean" candidates.
// Also printable(): input text made safe to echo (text.hpp). Reads only its arguments; no state.
#include "throng/core/diagnostic.hpp"
#include "throng/core/text.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>

namespace throng::core {

std::size_t utf8SequenceLength(std::string_view text, std::size_t i) {
  const auto at = [&](std::size_t k) { return i + k < text.size() ? static_cast<unsigned char>(text[i + k]) : 0u; };
  const auto cont = [&](std::size_t k, unsigned lo = 0x80, unsigned hi = 0xBF) { return at(k) >= lo && at(k) <= hi; };
  const unsigned c = at(0);
  if (i >= text.size()) return 0;
  if (c < 0x80) return 1;
  if (c >= 0xC2 && c <= 0xDF) return cont(1) ? 2 : 0;
  if (c == 0xE0) return cont(1, 0xA0) && cont(2) ? 3 : 0;
  if ((c >= 0xE1 && c <= 0xEC) || c == 0xEE || c == 0xEF) return cont(1) && cont(2) ? 3 : 0;
  if (c == 0xED) return cont(1, 0x80, 0x9F) && cont(2) ? 3 : 0;  // no UTF-16 surrogates
  if (c == 0xF0) return cont(1, 0x90) && cont(2) && cont(3) ? 4 : 0;
  if (c >= 0xF1 && c <= 0xF3) return cont(1) && cont(2) && cont(3) ? 4 : 0;
  if (c == 0xF4) return cont(1, 0x80, 0x8F) && cont(2) && cont(3) ? 4 : 0;
  return 0;
}

bool isUtf8(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = utf8SequenceLength(text, i);
    if (n == 0) return false;
    i += n;
  }
  return true;
}

std::string printable(std::string_view text, std::size_t maxCodePoints) {
  std::string out;
  out.reserve(std::min<std::size_t>(text.size(), 4096));
  std::size_t kept = 0;
  for (std::size_t i = 0; i < text.size();) {
    if (kept == maxCodePoints) {
      out += "...";
      break;
    }
    ++kept;
    const auto c = static_cast<unsigned char>(text[i]);
    const std::size_t n = utf8SequenceLength(text, i);
    char buf[8];
    if (n == 0) {
      std::snprintf(buf, sizeof buf, "\\x%02X", c);
      out += buf;
      ++i;
      continue;
    }
    if (c < 0x20 || c == 0x7F) {
      switch (c) {
        case '\n': out += "\\n"; break;
        case '\r': out += "\\r"; break;
        case '\t': out += "\\t"; break;
        default:
          std::snprintf(buf, sizeof buf, "\\u%04X", c);
          out += buf;
      }
      ++i;
      continue;
    }
    if (c == 0xC2 && static_cast<unsigned char>(text[i + 1]) < 0xA0) {  // C1 controls U+0080..U+009F
      std::snprintf(buf, sizeof buf, "\\u%04X", static_cast<unsigned char>(text[i + 1]));
      out += buf;
      i += n;
      continue;
    }
    out.append(text.substr(i, n));
    i += n;
  }
  return out;
}

std::string Diagnostic::format() const {
  std::string out = printable(source);
  if (line > 0) {
    out += ':' + std::to_string(line);
    if (column > 0) out += ':' + std::to_string(column);
  }
  if (!pointer.empty()) {
    if (!out.empty()) out += ' ';
    out += printable(pointer);
  }
  if (!out.empty()) out += ": ";
  out += printable(what);
  if (!expected.empty()) out += "; expected " + printable(expected);
  if (!hint.empty()) out += " (" + printable(hint) + ")";
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
  // Words longer than this are no typos worth an O(n·m) distance (hostile input: 1 MB keys).
  constexpr std::size_t kLongest = 128;
  if (word.size() > kLongest) return {};
  const std::size_t threshold = std::max<std::size_t>(2, word.size() / 3);
  std::size_t best = threshold + 1;
  std::string match;
  for (const auto& c : candidates) {
    if (c.empty() || c.size() > kLongest) continue;
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
