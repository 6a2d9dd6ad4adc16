// `throng serve`'s Bridge: the transport's callbacks (libs/transport) handed to the hub in use
// (libs/hub), and the hub's sends handed to the transport; the server's clock (Clock, now()).
// Header only: every part of the server (serve_api, serve_loop, serve_session) refers to it.
#pragma once
#include <chrono>
#include <optional>
#include <shared_mutex>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "throng/hub/hub.hpp"
#include "throng/transport/transport.hpp"

namespace throng::cli::serve {

using Clock = std::chrono::steady_clock;


/// Connects the transport's callbacks to the hub, and the hub's sends to the transport. The hub
/// changes when a viewer opens another recording (setHub, simulation thread): without one, a new
/// connection is closed at once (its viewer reconnects to the next hub) and messages are dropped.
class Bridge final : public transport::TransportHandler, public hub::Outbox {
 public:
  explicit Bridge(Clock::time_point start) : start_(start) {}
  void attach(transport::Transport* t) { transport_ = t; }
  void setHub(hub::Hub* h) {
    std::unique_lock lock(hubMutex_);
    hub_ = h;
  }
  [[nodiscard]] double now() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

  // TransportHandler (transport thread).
  void onOpen(transport::PeerId peer, transport::PeerKind kind, std::string remote) override {
    std::shared_lock lock(hubMutex_);
    if (hub_) {
      hub_->onOpen(peer.value, std::move(remote), now());
    } else if (transport_) {
      transport_->close(peer, "switching recordings");
    }
  }
  void onMessage(transport::PeerId peer, std::span<const std::uint8_t> message) override {
    std::shared_lock lock(hubMutex_);
    if (hub_) hub_->onMessage(peer.value, message, now());
  }
  void onClose(transport::PeerId peer, std::string_view reason) override {
    std::shared_lock lock(hubMutex_);
    if (hub_) hub_->onClose(peer.value, reason);
  }

  // Outbox (either thread, hub mutex held; the transport only posts).
  void send(hub::PeerKey peer, std::vector<std::uint8_t> message, bool latest, std::uint32_t slot) override {
    if (transport_) {
      transport_->send(transport::PeerId{peer}, std::move(message),
                       latest ? transport::SendClass::Latest : transport::SendClass::Reliable, slot);
    }
  }
  void close(hub::PeerKey peer, std::string reason) override {
    if (transport_) transport_->close(transport::PeerId{peer}, std::move(reason));
  }
  [[nodiscard]] std::optional<hub::LinkCounters> link(hub::PeerKey peer) const override {
    if (!transport_) return std::nullopt;
    auto s = transport_->stats(transport::PeerId{peer});
    if (!s) return std::nullopt;
    return hub::LinkCounters{s->bytesSent, s->droppedLatest, s->queueBytes};
  }

 private:
  Clock::time_point start_;
  std::shared_mutex hubMutex_;
  hub::Hub* hub_ = nullptr;
  transport::Transport* transport_ = nullptr;
};

}  // namespace throng::cli::serve
