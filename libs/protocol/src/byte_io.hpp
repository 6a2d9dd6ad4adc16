// throng::protocol byte I/O (private) — ByteWriter appends little-endian integers, LEB128 varints,
// zigzag signed varints and length-prefixed strings; ByteReader reads them back with bounds checks,
// remembering the first error (field, byte offset, what was expected) instead of throwing.
#pragma once
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "throng/core/diagnostic.hpp"

namespace throng::protocol::detail {

[[nodiscard]] inline std::uint64_t zigzag(std::int64_t v) {
  return (static_cast<std::uint64_t>(v) << 1) ^ static_cast<std::uint64_t>(v >> 63);
}
[[nodiscard]] inline std::int64_t unzigzag(std::uint64_t v) {
  return static_cast<std::int64_t>(v >> 1) ^ -static_cast<std::int64_t>(v & 1);
}

class ByteWriter {
 public:
  explicit ByteWriter(std::vector<std::uint8_t>& out) : out_(out) {}
  void u8(std::uint8_t v) { out_.push_back(v); }
  void u16(std::uint16_t v) { le(v, 2); }
  void u32(std::uint32_t v) { le(v, 4); }
  void u64(std::uint64_t v) { le(v, 8); }
  void i16(std::int16_t v) { u16(static_cast<std::uint16_t>(v)); }
  void i32(std::int32_t v) { u32(static_cast<std::uint32_t>(v)); }
  void f32(float v) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &v, 4);
    u32(bits);
  }
  void f64(double v) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &v, 8);
    u64(bits);
  }
  void varint(std::uint64_t v) {
    while (v >= 0x80) {
      out_.push_back(static_cast<std::uint8_t>(v | 0x80));
      v >>= 7;
    }
    out_.push_back(static_cast<std::uint8_t>(v));
  }
  void svarint(std::int64_t v) { varint(zigzag(v)); }
  void bytes(std::span<const std::uint8_t> b) { out_.insert(out_.end(), b.begin(), b.end()); }
  /// varint length + bytes (the caller keeps within the limits).
  void string(const std::string& s) {
    varint(s.size());
    out_.insert(out_.end(), s.begin(), s.end());
  }
  [[nodiscard]] std::size_t size() const { return out_.size(); }

 private:
  void le(std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) out_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  std::vector<std::uint8_t>& out_;
};

/// Reads with bounds checks. After the first error every read returns 0 and ok() is false;
/// `base` is added to offsets in messages (the payload's position in its message), `where`
/// names the region ("byte" or "payload byte").
class ByteReader {
 public:
  ByteReader(std::span<const std::uint8_t> data, std::string message, const char* where = "byte")
      : data_(data), message_(std::move(message)), where_(where) {}

  [[nodiscard]] bool ok() const { return error_.what.empty(); }
  [[nodiscard]] std::size_t offset() const { return pos_; }
  [[nodiscard]] std::size_t remaining() const { return data_.size() - pos_; }
  [[nodiscard]] bool atEnd() const { return pos_ == data_.size(); }
  [[nodiscard]] const core::Diagnostic& error() const { return error_; }

  /// Records an error at byte `at` for `field` (first error wins).
  void fail(const char* field, std::size_t at, std::string what, std::string expected);
  void fail(const char* field, std::string what, std::string expected) { fail(field, pos_, std::move(what), std::move(expected)); }

  std::uint8_t u8(const char* field) { return static_cast<std::uint8_t>(le(field, 1)); }
  std::uint16_t u16(const char* field) { return static_cast<std::uint16_t>(le(field, 2)); }
  std::uint32_t u32(const char* field) { return static_cast<std::uint32_t>(le(field, 4)); }
  std::uint64_t u64(const char* field) { return le(field, 8); }
  std::int16_t i16(const char* field) { return static_cast<std::int16_t>(u16(field)); }
  std::int32_t i32(const char* field) { return static_cast<std::int32_t>(u32(field)); }
  float f32(const char* field) {
    const std::uint32_t bits = u32(field);
    float v = 0;
    std::memcpy(&v, &bits, 4);
    return v;
  }
  double f64(const char* field) {
    const std::uint64_t bits = u64(field);
    double v = 0;
    std::memcpy(&v, &bits, 8);
    return v;
  }
  /// LEB128, at most 10 bytes, value ≤ `max`.
  std::uint64_t varint(const char* field, std::uint64_t max = ~std::uint64_t{0});
  std::int64_t svarint(const char* field, std::int64_t min, std::int64_t max);
  /// varint length ≤ maxLength, then the bytes.
  std::string string(const char* field, std::size_t maxLength);
  /// `n` raw bytes (n checked against remaining()).
  std::span<const std::uint8_t> bytes(const char* field, std::size_t n);
  /// An error when bytes are left over.
  void expectEnd();

 private:
  std::uint64_t le(const char* field, int n);
  std::span<const std::uint8_t> data_;
  std::size_t pos_ = 0;
  std::string message_;
  const char* where_;
  core::Diagnostic error_;
};

}  // namespace throng::protocol::detail
