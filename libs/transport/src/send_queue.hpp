// throng::transport::detail::SendQueue — one peer's unsent messages: Reliable ones in order, Latest
// ones replaced per slot (the older unsent one is removed, the new one goes to the back), so what
// is sent is always a subsequence of what was queued, in queue order. Pure data; no I/O.
#pragma once
#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

#include "throng/transport/transport.hpp"

namespace throng::transport::detail {

struct QueuedMessage {
  std::vector<std::uint8_t> data;
  SendClass cls = SendClass::Reliable;
  std::uint32_t slot = 0;
};

class SendQueue {
 public:
  /// Appends `message`; returns how many unsent Latest messages it replaced (0 or 1).
  std::size_t push(QueuedMessage message);
  /// Removes and returns the front message. Precondition: !empty().
  QueuedMessage pop();
  void clear();

  [[nodiscard]] bool empty() const { return items_.empty(); }
  [[nodiscard]] std::size_t messages() const { return items_.size(); }
  [[nodiscard]] std::size_t bytes() const { return bytes_; }

 private:
  std::deque<QueuedMessage> items_;
  std::size_t bytes_ = 0;
};

}  // namespace throng::transport::detail
