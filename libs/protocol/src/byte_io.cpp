// throng::protocol byte I/O (private) — bounds-checked reads of the wire's integer, varint and
// string encodings; the first error keeps field, byte offset and what was expected.
#include "byte_io.hpp"

#include <string>

namespace throng::protocol::detail {

void ByteReader::fail(const char* field, std::size_t at, std::string what, std::string expected) {
  if (!ok()) return;
  error_.column = static_cast<int>(at + 1);
  error_.pointer = "/" + message_ + "/" + field;
  error_.what = std::move(what) + " at " + where_ + " " + std::to_string(at);
  error_.expected = std::move(expected);
  pos_ = data_.size();
}

std::uint64_t ByteReader::le(const char* field, int n) {
  if (!ok()) return 0;
  if (remaining() < static_cast<std::size_t>(n)) {
    fail(field, "truncated: " + std::to_string(remaining()) + " bytes left",
         std::to_string(n) + " bytes (little-endian integer)");
    return 0;
  }
  std::uint64_t v = 0;
  for (int i = 0; i < n; ++i) v |= static_cast<std::uint64_t>(data_[pos_ + i]) << (8 * i);
  pos_ += n;
  return v;
}

std::uint64_t ByteReader::varint(const char* field, std::uint64_t max) {
  if (!ok()) return 0;
  const std::size_t start = pos_;
  std::uint64_t v = 0;
  for (int i = 0; i < 10; ++i) {
    if (pos_ >= data_.size()) {
      fail(field, start, "truncated varint", "a LEB128 varint (last byte < 0x80)");
      return 0;
    }
    const std::uint8_t b = data_[pos_++];
    if (i == 9 && b > 1) {
      fail(field, start, "varint overflows 64 bits", "a LEB128 varint of at most 64 bits");
      return 0;
    }
    v |= static_cast<std::uint64_t>(b & 0x7f) << (7 * i);
    if ((b & 0x80) == 0) {
      if (v > max) {
        fail(field, start, "value " + std::to_string(v) + " out of range", "at most " + std::to_string(max));
        return 0;
      }
      return v;
    }
  }
  fail(field, start, "varint longer than 10 bytes", "a LEB128 varint of at most 10 bytes");
  return 0;
}

std::int64_t ByteReader::svarint(const char* field, std::int64_t min, std::int64_t max) {
  const std::size_t start = pos_;
  const std::int64_t v = unzigzag(varint(field));
  if (ok() && (v < min || v > max)) {
    fail(field, start, "value " + std::to_string(v) + " out of range",
         "a value in [" + std::to_string(min) + ", " + std::to_string(max) + "]");
    return 0;
  }
  return v;
}

std::string ByteReader::string(const char* field, std::size_t maxLength) {
  const std::size_t start = pos_;
  const std::uint64_t n = varint(field);
  if (!ok()) return {};
  if (n > maxLength) {
    fail(field, start, "string of " + std::to_string(n) + " bytes too long",
         "at most " + std::to_string(maxLength) + " bytes");
    return {};
  }
  const auto b = bytes(field, static_cast<std::size_t>(n));
  return std::string(b.begin(), b.end());
}

std::span<const std::uint8_t> ByteReader::bytes(const char* field, std::size_t n) {
  if (!ok()) return {};
  if (remaining() < n) {
    fail(field, "truncated: " + std::to_string(remaining()) + " bytes left", std::to_string(n) + " bytes");
    return {};
  }
  auto s = data_.subspan(pos_, n);
  pos_ += n;
  return s;
}

void ByteReader::expectEnd() {
  if (ok() && !atEnd()) fail("end", std::to_string(remaining()) + " trailing bytes", "the end of the message");
}

}  // namespace throng::protocol::detail
