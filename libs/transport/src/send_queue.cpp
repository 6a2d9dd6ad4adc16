// throng::transport::detail::SendQueue — Reliable in order, Latest replaced per slot (see header).
#include "send_queue.hpp"

#include <algorithm>
#include <utility>

namespace throng::transport::detail {

std::size_t SendQueue::push(QueuedMessage message) {
  std::size_t replaced = 0;
  if (message.cls == SendClass::Latest) {
    auto it = std::find_if(items_.begin(), items_.end(), [&](const QueuedMessage& q) {
      return q.cls == SendClass::Latest && q.slot == message.slot;
    });
    if (it != items_.end()) {
      bytes_ -= it->data.size();
      items_.erase(it);
      replaced = 1;
    }
  }
  bytes_ += message.data.size();
  items_.push_back(std::move(message));
  return replaced;
}

QueuedMessage SendQueue::pop() {
  QueuedMessage front = std::move(items_.front());
  items_.pop_front();
  bytes_ -= front.data.size();
  return front;
}

void SendQueue::clear() {
  items_.clear();
  bytes_ = 0;
}

}  // namespace throng::transport::detail
