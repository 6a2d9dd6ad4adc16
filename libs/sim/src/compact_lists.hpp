// Compact per-agent and per-group lists (docs/performance.md, "Memory per agent"):
//   MemberList  a group's members (stable ids): up to 3 stored inline, more on the heap. 16 bytes
//               (an empty std::vector is 24), and a group of one to three needs no heap block.
//   CornerPath  an agent's string-pulled path and the corner it walks to: up to 2 corners inline,
//               longer paths in one exactly sized heap block. 24 bytes (a std::vector + index was 28
//               plus a heap block of at least 32 bytes for every path).
// Both hold trivially copyable values only; copies are deep, moves steal the heap block.
#pragma once
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <span>
#include <utility>
#include <vector>

#include "throng/core/vec2.hpp"

namespace throng::sim {

/// Stable ids in ascending order (callers keep the order), as a small vector: 16 bytes, up to 3 ids
/// without a heap block. On the heap, the inline words hold the block's address (copied in and out
/// with memcpy, so the list keeps 4-byte alignment) and its capacity.
class MemberList {
 public:
  static constexpr std::uint32_t kInline = 3;

  MemberList() noexcept {}
  MemberList(const MemberList& o) { assign(o.data(), o.size()); }
  MemberList(MemberList&& o) noexcept { steal(o); }
  MemberList& operator=(const MemberList& o) {
    if (this != &o) assign(o.data(), o.size());
    return *this;
  }
  MemberList& operator=(MemberList&& o) noexcept {
    if (this != &o) {
      release();
      steal(o);
    }
    return *this;
  }
  ~MemberList() { release(); }

  [[nodiscard]] std::uint32_t* data() { return onHeap() ? heap() : words_; }
  [[nodiscard]] const std::uint32_t* data() const { return onHeap() ? heap() : words_; }
  [[nodiscard]] std::uint32_t size() const { return bits_ & ~kHeapBit; }
  [[nodiscard]] bool empty() const { return size() == 0; }
  [[nodiscard]] std::uint32_t* begin() { return data(); }
  [[nodiscard]] std::uint32_t* end() { return data() + size(); }
  [[nodiscard]] const std::uint32_t* begin() const { return data(); }
  [[nodiscard]] const std::uint32_t* end() const { return data() + size(); }
  [[nodiscard]] std::uint32_t operator[](std::size_t i) const { return data()[i]; }
  [[nodiscard]] std::uint32_t front() const { return data()[0]; }
  [[nodiscard]] std::vector<std::uint32_t> toVector() const { return {begin(), end()}; }

  void push_back(std::uint32_t v) {
    const std::uint32_t n = size();
    grow(n + 1);
    data()[n] = v;
    ++bits_;
  }
  /// Inserts `v` before position `at` (an iterator of this list).
  void insert(const std::uint32_t* at, std::uint32_t v) {
    const auto i = static_cast<std::size_t>(at - data());
    const std::uint32_t n = size();
    grow(n + 1);
    std::uint32_t* d = data();
    std::memmove(d + i + 1, d + i, (n - i) * sizeof(std::uint32_t));
    d[i] = v;
    ++bits_;
  }
  /// Removes every element equal to `v` (as std::erase).
  void erase(std::uint32_t v) {
    std::uint32_t* d = data();
    const auto n = static_cast<std::uint32_t>(std::remove(d, d + size(), v) - d);
    bits_ = (bits_ & kHeapBit) | n;
  }

 private:
  static constexpr std::uint32_t kHeapBit = 0x80000000u;
  static_assert(sizeof(std::uint32_t*) == 2 * sizeof(std::uint32_t));

  [[nodiscard]] bool onHeap() const { return (bits_ & kHeapBit) != 0; }
  [[nodiscard]] std::uint32_t capacity() const { return onHeap() ? words_[2] : kInline; }
  [[nodiscard]] std::uint32_t* heap() const {
    std::uint32_t* p;
    std::memcpy(&p, words_, sizeof p);
    return p;
  }
  void assign(const std::uint32_t* src, std::uint32_t n) {
    bits_ &= kHeapBit;  // size 0, keeps its block
    grow(n);
    std::memmove(data(), src, n * sizeof(std::uint32_t));
    bits_ |= n;
  }
  void grow(std::uint32_t need) {
    if (need <= capacity()) return;
    const std::uint32_t cap = std::max(need, capacity() * 2);
    const std::uint32_t n = size();
    auto* block = new std::uint32_t[cap];
    std::memcpy(block, data(), n * sizeof(std::uint32_t));
    release();
    std::memcpy(words_, &block, sizeof block);
    words_[2] = cap;
    bits_ = kHeapBit | n;
  }
  void release() {
    if (onHeap()) delete[] heap();
    bits_ &= ~kHeapBit;
  }
  void steal(MemberList& o) {
    bits_ = o.bits_;
    std::memcpy(words_, o.words_, sizeof words_);
    o.bits_ = 0;
  }

  std::uint32_t words_[kInline] = {};
  std::uint32_t bits_ = 0;  ///< size [Limit: < 2^31], top bit: on the heap
};
static_assert(sizeof(MemberList) == 16);

/// A path's corners [m] and the index of the corner being walked to.
class CornerPath {
 public:
  static constexpr std::uint32_t kInline = 2;

  CornerPath() noexcept {}
  CornerPath(const CornerPath& o) : index(o.index) { assign(o.data(), o.size_); }
  CornerPath(CornerPath&& o) noexcept { steal(o); }
  CornerPath& operator=(const CornerPath& o) {
    if (this != &o) {
      assign(o.data(), o.size_);
      index = o.index;
    }
    return *this;
  }
  CornerPath& operator=(CornerPath&& o) noexcept {
    if (this != &o) {
      release();
      steal(o);
    }
    return *this;
  }
  ~CornerPath() { release(); }

  [[nodiscard]] const core::Vec2* data() const { return size_ > kInline ? heap_ : inline_; }
  [[nodiscard]] std::uint32_t size() const { return size_; }
  [[nodiscard]] bool empty() const { return size_ == 0; }
  [[nodiscard]] const core::Vec2& operator[](std::size_t i) const { return data()[i]; }

  /// Replaces the corners (the index restarts at the first).
  void assign(std::span<const core::Vec2> corners) {
    assign(corners.data(), static_cast<std::uint32_t>(corners.size()));
    index = 0;
  }
  /// No path (walk straight at the target).
  void clear() {
    release();
    index = 0;
  }

 private:

  void assign(const core::Vec2* src, std::uint32_t n) {
    if (n > kInline) {
      auto* block = new core::Vec2[n];
      std::copy(src, src + n, block);
      release();
      heap_ = block;
    } else {
      core::Vec2 tmp[kInline];
      std::copy(src, src + n, tmp);
      release();
      std::copy(tmp, tmp + n, inline_);
    }
    size_ = n;
  }
  void release() {
    if (size_ > kInline) delete[] heap_;
    size_ = 0;
  }
  void steal(CornerPath& o) {
    size_ = o.size_;
    index = o.index;
    if (size_ > kInline) heap_ = o.heap_;
    else std::copy(o.inline_, o.inline_ + kInline, inline_);
    o.size_ = 0;
    o.index = 0;
  }

  union {
    core::Vec2 inline_[kInline];
    core::Vec2* heap_;
  };
  std::uint32_t size_ = 0;

 public:
  std::uint32_t index = 0;  ///< corner walked to: [0, size]
};
static_assert(sizeof(CornerPath) == 24);

}  // namespace throng::sim
