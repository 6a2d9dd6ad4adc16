// throng::transport::detail::UdpEndpoint — the one UDP socket. An endpoint without a peer gets at most
// a Cookie (18 bytes) for a UdpHello (≥ 24 bytes) and nothing for anything else; a UdpHello that
// carries the endpoint's valid cookie opens a UdpPeer (while under maxUdpPeers) and the message
// inside it is the peer's first. Then each datagram is one message, silent peers time out, and
// each peer's SendQueue goes out one datagram at a time (a message over udpFragmentBytes as
// several Fragment datagrams, split when it leaves the queue). All on one strand.
#pragma once
#include <chrono>
#include <map>
#include <memory>
#include <string>
#include <span>
#include <vector>

#include "throng/net/asio.hpp"
#include "peer.hpp"
#include "token_bucket.hpp"
#include "udp_cookie.hpp"

namespace throng::transport::detail {
using namespace throng::net;  // asio::, beast::, tcp, udp, error_code

class TransportImpl;
class UdpEndpoint;

class UdpPeer final : public Peer, public std::enable_shared_from_this<UdpPeer> {
 public:
  UdpPeer(UdpEndpoint& endpoint, PeerId id, udp::endpoint remote, const TransportOptions& options);
  void enqueue(QueuedMessage message) override;
  void requestClose(std::string reason, CloseKind kind, bool flush) override;

 private:
  friend class UdpEndpoint;
  UdpEndpoint& endpoint_;
  udp::endpoint remote_;
  SendQueue queue_;
  QueuedMessage inFlight_;
  /// inFlight_ as Fragment datagrams when it is over udpFragmentBytes (else empty), and the next
  /// one to send; the whole message stays in the queue until it is popped, so a Latest
  /// replacement replaces all of its fragments.
  std::vector<std::vector<std::uint8_t>> fragments_;
  std::size_t nextFragment_ = 0;
  std::size_t fragmentBytesSent_ = 0;
  std::uint64_t nextMessageId_ = 0;  ///< Fragment::messageId of the next fragmented message
  bool writing_ = false;
  bool closing_ = false;
  bool done_ = false;
  std::string closeReason_;
  std::chrono::steady_clock::time_point lastSeen_;
  TokenBucket bucket_;
};

class UdpEndpoint final : public std::enable_shared_from_this<UdpEndpoint> {
 public:
  explicit UdpEndpoint(TransportImpl& transport);

  /// Opens and binds; an error message on failure.
  error_code bind(const udp::endpoint& at);
  std::uint16_t port() const;
  void start();
  /// Any thread: close every peer with `reason` and the socket.
  void shutdown(std::string reason);

 private:
  friend class UdpPeer;
  using Strand = asio::strand<asio::io_context::executor_type>;

  void doReceive();
  void onReceive(error_code ec, std::size_t bytes);
  /// A datagram from an endpoint without a peer: answer a UdpHello with a Cookie, or open the
  /// peer when its cookie is valid (returned; nullptr when nothing was opened).
  std::shared_ptr<UdpPeer> handshake(std::size_t bytes);
  /// One message (or keep-alive) from an open peer.
  void receiveFrom(const std::shared_ptr<UdpPeer>& peer, std::span<const std::uint8_t> datagram);
  void scheduleSweep();
  void sweep();
  void push(const std::shared_ptr<UdpPeer>& peer, QueuedMessage message);
  void doSend(const std::shared_ptr<UdpPeer>& peer);
  void closePeer(const std::shared_ptr<UdpPeer>& peer, std::string reason, bool flush);
  void finishPeer(const std::shared_ptr<UdpPeer>& peer);
  void updateQueueCounters(UdpPeer& peer);

  TransportImpl& transport_;
  Strand strand_;
  udp::socket socket_;
  asio::steady_timer sweepTimer_;
  std::vector<std::uint8_t> receiveBuffer_;
  udp::endpoint sender_;
  std::map<udp::endpoint, std::shared_ptr<UdpPeer>> peers_;
  CookieJar cookies_;
  bool stopped_ = false;
};

}  // namespace throng::transport::detail
