// throng::transport::detail::TransportImpl — owns the io_context and threads, the TCP acceptor, the
// UDP endpoint and the registry of open peers (the only state shared across threads, behind one
// mutex). Peers and HTTP sessions call back into it to register, unregister and count.
#pragma once
#include <atomic>
#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <unordered_map>
#include <vector>

#include "throng/net/asio.hpp"
#include "peer.hpp"
#include "throng/transport/transport.hpp"

namespace throng::transport::detail {
using namespace throng::net;  // asio::, beast::, tcp, udp, error_code

class UdpEndpoint;

class TransportImpl final : public Transport {
 public:
  TransportImpl(TransportOptions options, TransportHandler& handler);
  ~TransportImpl() override;

  core::Status listen();
  void run();

  std::uint16_t httpPort() const override { return httpPort_; }
  std::uint16_t udpPort() const override { return udpPort_; }
  SendStatus send(PeerId peer, std::vector<std::uint8_t> message, SendClass cls, std::uint32_t slot) override;
  void close(PeerId peer, std::string reason) override;
  void shutdown(std::string reason) override;
  std::optional<PeerStats> stats(PeerId peer) const override;
  TransportTotals totals() const override;

  // --- for peers and sessions ---
  const TransportOptions& options() const { return options_; }
  TransportHandler& handler() { return handler_; }
  asio::io_context& ioc() { return ioc_; }
  bool stopping() const { return stopping_.load(); }
  PeerId nextPeerId() { return PeerId{nextId_.fetch_add(1)}; }
  /// Registers a peer; false when maxPeers WebSocket (maxUdpPeers UDP) peers of its kind are
  /// open or the transport is stopping.
  bool addPeer(std::shared_ptr<Peer> peer);
  /// Open peers of one kind.
  std::size_t peerCount(PeerKind kind) const;
  /// Unregisters; `opened` says whether onOpen was called (then onClose counts as closed).
  void removePeer(PeerId peer, bool opened);
  void noteOpened() { peersOpened_.fetch_add(1); }
  std::uint64_t addHttpConnection(std::function<void()> closer);
  void removeHttpConnection(std::uint64_t id);
  void countSent(Peer& peer, std::size_t bytes);
  void countReceived(Peer& peer, std::size_t bytes);
  void countDropped(Peer& peer, std::size_t n);
  void countHttpRequest() { httpRequests_.fetch_add(1); }
  void countUdpCookie() { udpCookiesSent_.fetch_add(1); }
  void countUdpIgnored() { udpIgnored_.fetch_add(1); }

 private:
  void doAccept();
  bool onTransportThread() const;
  void joinThreads();

  asio::io_context ioc_;  // first member: destroyed last, after everything bound to it
  TransportOptions options_;
  TransportHandler& handler_;
  std::optional<asio::executor_work_guard<asio::io_context::executor_type>> work_;
  asio::strand<asio::io_context::executor_type> acceptStrand_;
  tcp::acceptor acceptor_;
  std::shared_ptr<UdpEndpoint> udp_;
  std::uint16_t httpPort_ = 0;
  std::uint16_t udpPort_ = 0;
  std::vector<std::thread> threads_;

  mutable std::mutex mutex_;
  std::condition_variable drained_;
  std::unordered_map<std::uint64_t, std::shared_ptr<Peer>> peers_;
  std::size_t webSocketPeers_ = 0, udpPeers_ = 0;  ///< peers_ by kind
  std::unordered_map<std::uint64_t, std::function<void()>> http_;  // id -> closes the socket
  std::uint64_t nextHttpId_ = 1;

  std::atomic<bool> stopping_{false};
  std::atomic<bool> joined_{false};
  std::atomic<std::uint64_t> nextId_{1};
  std::atomic<std::uint64_t> peersOpened_{0}, peersClosed_{0}, bytesSent_{0}, bytesReceived_{0},
      messagesSent_{0}, messagesReceived_{0}, droppedLatest_{0}, httpRequests_{0}, udpCookiesSent_{0}, udpIgnored_{0};
};

}  // namespace throng::transport::detail
