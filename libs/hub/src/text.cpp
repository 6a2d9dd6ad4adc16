// Text checks for what clients send (see text.hpp).
#include "throng/hub/text.hpp"

#include "throng/core/text.hpp"

#include <cstdint>
#include <cstdio>

namespace throng::hub {
namespace {

/// The length of the well-formed UTF-8 sequence starting at `i`, or 0 when it is ill-formed.
std::size_t sequenceAt(std::string_view s, std::size_t i) { return core::utf8SequenceLength(s, i); }

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
