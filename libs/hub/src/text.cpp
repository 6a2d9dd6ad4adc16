// Text checks for what clients send (see text.hpp).
#include "throng/hub/text.hpp"

#include <cstdint>
#include <cstdio>

namespace throng::hub {
namespace {

/// The length of the well-formed UTF-8 sequence starting at `i`, or 0 when it is ill-formed.
std::size_t sequenceAt(std::string_view s, std::size_t i) {
  const auto b = [&](std::size_t k) { return static_cast<std::uint8_t>(s[k]); };
  const std::uint8_t c = b(i);
  if (c < 0x80) return 1;
  std::size_t n = 0;
  std::uint8_t lo = 0x80, hi = 0xBF;  // the allowed range of the second byte
  if (c >= 0xC2 && c <= 0xDF) {
    n = 2;
  } else if (c >= 0xE0 && c <= 0xEF) {
    n = 3;
    if (c == 0xE0) lo = 0xA0;  // no overlong forms
    if (c == 0xED) hi = 0x9F;  // no surrogates
  } else if (c >= 0xF0 && c <= 0xF4) {
    n = 4;
    if (c == 0xF0) lo = 0x90;  // no overlong forms
    if (c == 0xF4) hi = 0x8F;  // nothing above U+10FFFF
  } else {
    return 0;
  }
  if (i + n > s.size()) return 0;
  if (b(i + 1) < lo || b(i + 1) > hi) return 0;
  for (std::size_t k = 2; k < n; ++k) {
    if ((b(i + k) & 0xC0u) != 0x80u) return 0;
  }
  return n;
}

std::string hex(std::uint8_t c) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "\\x%02X", static_cast<unsigned>(c));
  return buf;
}

}  // namespace

std::optional<std::size_t> invalidUtf8At(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = sequenceAt(text, i);
    if (n == 0) return i;
    i += n;
  }
  return std::nullopt;
}

std::string describeByte(std::string_view text, std::size_t offset) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "byte %zu (0x%02X)", offset,
                offset < text.size() ? static_cast<unsigned>(static_cast<std::uint8_t>(text[offset])) : 0u);
  return buf;
}

std::string printable(std::string_view text, std::size_t maxBytes) {
  constexpr std::string_view kCut = "...";
  if (maxBytes < kCut.size()) maxBytes = kCut.size();
  std::string out;
  std::size_t fits = 0;  // the longest prefix of whole pieces that leaves room for "..."
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = sequenceAt(text, i);
    const auto c = static_cast<std::uint8_t>(text[i]);
    if (n == 0 || (n == 1 && (c < 0x20 || c == 0x7F))) {
      out += hex(c);
      i += 1;
    } else {
      out.append(text.substr(i, n));
      i += n;
    }
    if (out.size() <= maxBytes - kCut.size()) fits = out.size();
    if (out.size() > maxBytes) break;
  }
  if (out.size() <= maxBytes) return out;
  out.resize(fits);
  out += kCut;
  return out;
}

std::string validUtf8(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = sequenceAt(text, i);
    if (n == 0) {
      out += "\xEF\xBF\xBD";
      i += 1;
    } else {
      out.append(text.substr(i, n));
      i += n;
    }
  }
  return out;
}

std::string_view cutUtf8(std::string_view text, std::size_t maxBytes) {
  if (text.size() <= maxBytes) return text;
  std::size_t end = maxBytes;
  while (end > 0 && (static_cast<std::uint8_t>(text[end]) & 0xC0u) == 0x80u) --end;
  return text.substr(0, end);
}

}  // namespace throng::hub
