// A TransportHandler for tests: records every callback (thread-safe), can echo messages back, and
// lets a test wait for a condition on what it recorded.
#pragma once
#include <chrono>
#include <condition_variable>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "throng/transport/transport.hpp"

namespace throng::transport::test {

class TestHandler : public TransportHandler {
 public:
  struct Opened {
    PeerId peer;
    PeerKind kind;
    std::string remote;
  };

  Transport* transport = nullptr;  ///< set after start; used by echo and hooks
  bool echo = false;
  std::function<void(PeerId, std::span<const std::uint8_t>)> messageHook;
  std::function<void(PeerId)> openHook;  ///< e.g. send a large first answer, as a Welcome

  void onOpen(PeerId peer, PeerKind kind, std::string remote) override {
    {
      std::lock_guard lock(mutex_);
      opened.push_back({peer, kind, std::move(remote)});
    }
    if (openHook) openHook(peer);
    cv_.notify_all();
  }
  void onMessage(PeerId peer, std::span<const std::uint8_t> message) override {
    std::vector<std::uint8_t> copy(message.begin(), message.end());
    {
      std::lock_guard lock(mutex_);
      messages[peer.value].push_back(copy);
    }
    if (echo && transport) transport->send(peer, copy);
    if (messageHook) messageHook(peer, message);
    cv_.notify_all();
  }
  void onClose(PeerId peer, std::string_view reason) override {
    std::lock_guard lock(mutex_);
    ++closeCount;
    closed[peer.value] = std::string(reason);
    cv_.notify_all();
  }

  /// Waits (up to `timeout`) until pred() holds; pred runs under the handler's lock.
  template <class Pred>
  bool waitFor(Pred pred, std::chrono::milliseconds timeout = std::chrono::milliseconds(5000)) {
    std::unique_lock lock(mutex_);
    return cv_.wait_for(lock, timeout, pred);
  }
  template <class F>
  auto locked(F f) {
    std::lock_guard lock(mutex_);
    return f();
  }

  std::vector<Opened> opened;
  std::map<std::uint64_t, std::vector<std::vector<std::uint8_t>>> messages;
  std::map<std::uint64_t, std::string> closed;
  std::size_t closeCount = 0;

 private:
  std::mutex mutex_;
  std::condition_variable cv_;
};

/// Options for tests: loopback, ports picked by the OS, short close timeout.
inline TransportOptions testOptions() {
  TransportOptions o;
  o.bindAddress = "127.0.0.1";
  o.httpPort = 0;
  o.udpPort = 0;
  o.closeTimeout = std::chrono::milliseconds(500);
  return o;
}

inline std::vector<std::uint8_t> bytes(std::string_view text) { return {text.begin(), text.end()}; }

}  // namespace throng::transport::test
