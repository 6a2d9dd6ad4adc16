// throng::core::Handle / SlotMap — generational handles instead of pointers (after Box2D's id.h).
// A handle is a 1-based slot index plus a generation; index 0 is the null handle. A stale handle
// (its slot freed and reused) never resolves.
#pragma once
#include <cstdint>
#include <optional>
#include <vector>

#include "throng/core/assert.hpp"

namespace throng::core {

template <class Tag>
struct Handle {
  std::uint32_t index = 0;       ///< 1-based slot; 0 = null
  std::uint32_t generation = 0;  ///< bumped each time the slot is freed

  [[nodiscard]] constexpr bool isNull() const { return index == 0; }
  constexpr bool operator==(const Handle&) const = default;
  [[nodiscard]] constexpr std::uint64_t pack() const {
    return (std::uint64_t{generation} << 32) | index;
  }
  static constexpr Handle unpack(std::uint64_t v) {
    return {static_cast<std::uint32_t>(v & 0xffffffffu), static_cast<std::uint32_t>(v >> 32)};
  }
};

/// Maps handles to a dense row index (or any uint32 payload). Free slots are reused in LIFO order,
/// which is deterministic because every insert and erase happens in the ordered command phase.
template <class Tag>
class SlotMap {
 public:
  using Id = Handle<Tag>;

  Id insert(std::uint32_t payload) {
    std::uint32_t slot;
    if (!free_.empty()) {
      slot = free_.back();
      free_.pop_back();
    } else {
      slot = static_cast<std::uint32_t>(slots_.size());
      slots_.push_back({0, 1, false});
    }
    slots_[slot].payload = payload;
    slots_[slot].live = true;
    return {slot + 1, slots_[slot].generation};
  }

  void erase(Id id) {
    THRONG_ASSERT(contains(id));
    Slot& s = slots_[id.index - 1];
    s.live = false;
    ++s.generation;
    free_.push_back(id.index - 1);
  }

  [[nodiscard]] bool contains(Id id) const {
    return id.index != 0 && id.index <= slots_.size() && slots_[id.index - 1].live &&
           slots_[id.index - 1].generation == id.generation;
  }

  [[nodiscard]] std::optional<std::uint32_t> find(Id id) const {
    if (!contains(id)) return std::nullopt;
    return slots_[id.index - 1].payload;
  }

  /// Updates the payload of a live handle (used when swap-remove moves a row).
  void set(Id id, std::uint32_t payload) {
    THRONG_ASSERT(contains(id));
    slots_[id.index - 1].payload = payload;
  }

  [[nodiscard]] std::size_t size() const { return slots_.size() - free_.size(); }

 private:
  struct Slot {
    std::uint32_t payload;
    std::uint32_t generation;
    bool live;
  };
  std::vector<Slot> slots_;
  std::vector<std::uint32_t> free_;
};

}  // namespace throng::core
