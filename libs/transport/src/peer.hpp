// throng::transport::detail::Peer — what the transport's registry knows about an open peer, whatever
// its kind: id, counters readable from any thread, and the two thread-safe entry points
// (enqueue, requestClose) that post onto the peer's strand.
#pragma once
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "send_queue.hpp"
#include "throng/transport/transport.hpp"

namespace throng::transport::detail {

struct PeerCounters {
  std::atomic<std::uint64_t> bytesSent{0};
  std::atomic<std::uint64_t> bytesReceived{0};
  std::atomic<std::uint64_t> messagesSent{0};
  std::atomic<std::uint64_t> messagesReceived{0};
  std::atomic<std::uint64_t> droppedLatest{0};
  std::atomic<std::size_t> queueMessages{0};
  std::atomic<std::size_t> queueBytes{0};
};

/// How a close was asked for; maps to a WebSocket close code.
enum class CloseKind : std::uint8_t { Normal, GoingAway, Policy, TooBig, BadData };

class Peer {
 public:
  Peer(PeerId id, PeerKind kind) : id_(id), kind_(kind) {}
  virtual ~Peer() = default;
  Peer(const Peer&) = delete;
  Peer& operator=(const Peer&) = delete;

  [[nodiscard]] PeerId id() const { return id_; }
  [[nodiscard]] PeerKind kind() const { return kind_; }
  PeerCounters& counters() { return counters_; }

  /// Any thread: queue a message (size already checked by the caller).
  virtual void enqueue(QueuedMessage message) = 0;
  /// Any thread: close after flushing (flush) or at once.
  virtual void requestClose(std::string reason, CloseKind kind, bool flush) = 0;

  [[nodiscard]] PeerStats snapshot() const {
    PeerStats s;
    s.kind = kind_;
    s.bytesSent = counters_.bytesSent.load();
    s.bytesReceived = counters_.bytesReceived.load();
    s.messagesSent = counters_.messagesSent.load();
    s.messagesReceived = counters_.messagesReceived.load();
    s.droppedLatest = counters_.droppedLatest.load();
    s.queueMessages = counters_.queueMessages.load();
    s.queueBytes = counters_.queueBytes.load();
    return s;
  }

 private:
  PeerId id_;
  PeerKind kind_;
  PeerCounters counters_;
};

}  // namespace throng::transport::detail
