// throng::transport::detail::UdpEndpoint / UdpPeer — one socket, peers keyed by remote endpoint.
// A datagram is a whole message; an empty one is a keep-alive. Peers open only after the cookie
// round trip (docs/protocol.md "Opening a UDP session"): an unproven endpoint never gets more
// bytes than it sent. A closed peer is forgotten: it has to prove its address again.
#include "udp_endpoint.hpp"

#include <algorithm>
#include <span>
#include <utility>

#include "throng/protocol/fragments.hpp"
#include "throng/protocol/messages.hpp"
#include "transport_impl.hpp"

namespace throng::transport::detail {
namespace {

constexpr std::size_t kReceiveBufferBytes = 65536;  // larger than any UDP payload (65507)

std::string endpointText(const udp::endpoint& endpoint) {
  const auto address = endpoint.address();
  const std::string host = address.is_v6() ? "[" + address.to_string() + "]" : address.to_string();
  return host + ":" + std::to_string(endpoint.port());
}

/// A UdpHello: header, cookie, and at least a Hello's worth of bytes (kMinUdpHelloSize).
bool isUdpHello(std::span<const std::uint8_t> datagram) {
  return datagram.size() >= protocol::kMinUdpHelloSize && datagram[0] == protocol::kMagic &&
         datagram[1] == static_cast<std::uint8_t>(protocol::MessageType::UdpHello);
}

}  // namespace

UdpPeer::UdpPeer(UdpEndpoint& endpoint, PeerId id, udp::endpoint remote, const TransportOptions& options)
    : Peer(id, PeerKind::Udp),
      endpoint_(endpoint),
      remote_(std::move(remote)),
      lastSeen_(std::chrono::steady_clock::now()),
      bucket_(options.messagesPerSecond, options.burstMessages, TokenBucket::Clock::now()) {}

void UdpPeer::enqueue(QueuedMessage message) {
  asio::post(endpoint_.strand_, [endpoint = endpoint_.shared_from_this(), self = shared_from_this(),
                                m = std::move(message)]() mutable { endpoint->push(self, std::move(m)); });
}

void UdpPeer::requestClose(std::string reason, CloseKind, bool flush) {
  asio::post(endpoint_.strand_, [endpoint = endpoint_.shared_from_this(), self = shared_from_this(),
                                r = std::move(reason), flush]() mutable { endpoint->closePeer(self, std::move(r), flush); });
}

UdpEndpoint::UdpEndpoint(TransportImpl& transport)
    : transport_(transport),
      strand_(asio::make_strand(transport.ioc())),
      socket_(strand_),
      sweepTimer_(strand_),
      receiveBuffer_(kReceiveBufferBytes) {}

error_code UdpEndpoint::bind(const udp::endpoint& at) {
  error_code ec;
  socket_.open(at.protocol(), ec);
  if (!ec) socket_.bind(at, ec);
  return ec;
}

std::uint16_t UdpEndpoint::port() const {
  error_code ec;
  const auto local = socket_.local_endpoint(ec);
  return ec ? 0 : local.port();
}

void UdpEndpoint::start() {
  asio::dispatch(strand_, [self = shared_from_this()] {
    self->doReceive();
    self->scheduleSweep();
  });
}

void UdpEndpoint::shutdown(std::string reason) {
  asio::post(strand_, [self = shared_from_this(), reason = std::move(reason)] {
    self->stopped_ = true;
    std::vector<std::shared_ptr<UdpPeer>> all;
    for (const auto& [endpoint, peer] : self->peers_) all.push_back(peer);
    for (const auto& peer : all) self->closePeer(peer, reason, false);
    self->sweepTimer_.cancel();
    error_code ignored;
    self->socket_.close(ignored);
  });
}

void UdpEndpoint::doReceive() {
  if (stopped_) return;
  socket_.async_receive_from(asio::buffer(receiveBuffer_), sender_,
                             beast::bind_front_handler(&UdpEndpoint::onReceive, shared_from_this()));
}

void UdpEndpoint::onReceive(error_code ec, std::size_t bytes) {
  if (stopped_ || ec == asio::error::operation_aborted) return;
  if (ec) {  // e.g. an ICMP error from an earlier send: the socket itself is fine
    doReceive();
    return;
  }
  const auto datagram = std::span<const std::uint8_t>(receiveBuffer_.data(), bytes);
  if (auto it = peers_.find(sender_); it != peers_.end()) {
    const std::shared_ptr<UdpPeer> peer = it->second;  // a copy: closing it erases the map entry
    receiveFrom(peer, datagram);
  } else if (auto peer = handshake(bytes)) {
    // The message inside the UdpHello (the session's Hello) is the peer's first.
    receiveFrom(peer, datagram.subspan(protocol::kCookieMessageSize));
  }
  doReceive();
}

std::shared_ptr<UdpPeer> UdpEndpoint::handshake(std::size_t bytes) {
  const TransportOptions& options = transport_.options();
  const auto datagram = std::span<const std::uint8_t>(receiveBuffer_.data(), bytes);
  if (!isUdpHello(datagram) || bytes > options.maxDatagramBytes) {
    transport_.countUdpIgnored();  // no answer: whatever it is, the sender proved nothing
    return nullptr;
  }
  const auto now = CookieJar::Clock::now();
  protocol::CookieBytes cookie{};
  std::copy_n(datagram.begin() + 2, cookie.size(), cookie.begin());
  if (!cookies_.check(sender_, cookie, now)) {
    // No cookie yet (or an old or forged one): answer with this endpoint's cookie, 18 bytes for
    // at least 24, so a forged source address gains nothing by it.
    auto reply = std::make_shared<protocol::Bytes>(protocol::encode(protocol::Cookie{cookies_.issue(sender_, now)}));
    transport_.countUdpCookie();
    socket_.async_send_to(asio::buffer(*reply), sender_, [reply](error_code, std::size_t) {});
    return nullptr;
  }
  auto peer = std::make_shared<UdpPeer>(*this, transport_.nextPeerId(), sender_, options);
  if (!transport_.addPeer(peer)) {  // full or stopping: ignore the datagram
    transport_.countUdpIgnored();
    return nullptr;
  }
  peers_.emplace(sender_, peer);
  transport_.noteOpened();
  transport_.handler().onOpen(peer->id(), PeerKind::Udp, endpointText(sender_));
  return peer;
}

void UdpEndpoint::receiveFrom(const std::shared_ptr<UdpPeer>& peer, std::span<const std::uint8_t> datagram) {
  const TransportOptions& options = transport_.options();
  peer->lastSeen_ = std::chrono::steady_clock::now();
  if (peer->closing_) return;
  if (datagram.size() > options.maxDatagramBytes) {
    closePeer(peer, "message too large", false);
  } else if (!datagram.empty() && !isUdpHello(datagram)) {  // a repeated UdpHello is a keep-alive
    if (!peer->bucket_.take(TokenBucket::Clock::now())) {
      closePeer(peer, "rate limit", false);
    } else {
      transport_.countReceived(*peer, datagram.size());
      transport_.handler().onMessage(peer->id(), datagram);
    }
  }
}

void UdpEndpoint::scheduleSweep() {
  if (stopped_) return;
  const auto idle = transport_.options().udpIdleTimeout;
  const auto period = std::clamp<std::chrono::milliseconds>(idle / 4, std::chrono::milliseconds(10), std::chrono::milliseconds(1000));
  sweepTimer_.expires_after(period);
  sweepTimer_.async_wait([self = shared_from_this()](error_code ec) {
    if (ec || self->stopped_) return;
    self->sweep();
    self->scheduleSweep();
  });
}

void UdpEndpoint::sweep() {
  const auto deadline = std::chrono::steady_clock::now() - transport_.options().udpIdleTimeout;
  std::vector<std::shared_ptr<UdpPeer>> idle;
  for (const auto& [endpoint, peer] : peers_)
    if (peer->lastSeen_ < deadline) idle.push_back(peer);
  for (const auto& peer : idle) closePeer(peer, "timeout", false);
}

void UdpEndpoint::push(const std::shared_ptr<UdpPeer>& peer, QueuedMessage message) {
  if (peer->done_ || peer->closing_) return;
  const TransportOptions& options = transport_.options();
  if (const std::size_t replaced = peer->queue_.push(std::move(message)); replaced > 0)
    transport_.countDropped(*peer, replaced);
  if (peer->queue_.messages() > options.maxQueueMessages || peer->queue_.bytes() > options.maxQueueBytes) {
    closePeer(peer, "send queue limit", false);
    return;
  }
  updateQueueCounters(*peer);
  doSend(peer);
}

void UdpEndpoint::doSend(const std::shared_ptr<UdpPeer>& peer) {
  if (peer->writing_ || peer->done_) return;
  if (peer->nextFragment_ >= peer->fragments_.size()) {  // no fragmented message under way
    if (peer->queue_.empty()) {
      if (peer->closing_) finishPeer(peer);
      return;
    }
    peer->inFlight_ = peer->queue_.pop();
    const std::size_t fragmentBytes = transport_.options().udpFragmentBytes;
    peer->fragments_.clear();
    peer->nextFragment_ = 0;
    peer->fragmentBytesSent_ = 0;
    if (fragmentBytes > 0 && peer->inFlight_.data.size() > fragmentBytes) {
      peer->fragments_ = protocol::splitMessage(peer->inFlight_.data, peer->nextMessageId_++, fragmentBytes);
    }
  }
  const bool fragmented = !peer->fragments_.empty();
  const std::vector<std::uint8_t>& datagram = fragmented ? peer->fragments_[peer->nextFragment_] : peer->inFlight_.data;
  peer->writing_ = true;
  updateQueueCounters(*peer);
  socket_.async_send_to(asio::buffer(datagram), peer->remote_,
                        [self = shared_from_this(), peer, fragmented](error_code ec, std::size_t sent) {
                          peer->writing_ = false;
                          if (peer->done_) return;
                          if (fragmented) {
                            if (!ec) peer->fragmentBytesSent_ += sent;
                            if (++peer->nextFragment_ < peer->fragments_.size()) {
                              self->doSend(peer);  // the next fragment of the same message
                              return;
                            }
                            // The whole message went: one message, the bytes of all its datagrams.
                            if (peer->fragmentBytesSent_ > 0) self->transport_.countSent(*peer, peer->fragmentBytesSent_);
                            peer->fragments_.clear();
                            peer->nextFragment_ = 0;
                          } else if (!ec) {
                            self->transport_.countSent(*peer, peer->inFlight_.data.size());
                          }
                          peer->inFlight_ = {};
                          self->updateQueueCounters(*peer);
                          self->doSend(peer);
                        });
}

void UdpEndpoint::closePeer(const std::shared_ptr<UdpPeer>& peer, std::string reason, bool flush) {
  if (peer->done_ || peer->closing_) return;
  peer->closing_ = true;
  peer->closeReason_ = std::move(reason);
  if (!flush) peer->queue_.clear();
  if (!flush || (!peer->writing_ && peer->queue_.empty())) finishPeer(peer);
}

void UdpEndpoint::finishPeer(const std::shared_ptr<UdpPeer>& peer) {
  if (peer->done_) return;
  peer->done_ = true;
  peer->queue_.clear();  // inFlight_ stays until its send completes
  peer->counters().queueMessages.store(0);
  peer->counters().queueBytes.store(0);
  if (auto it = peers_.find(peer->remote_); it != peers_.end() && it->second == peer) peers_.erase(it);
  // Gone from the peer table first: once onClose runs, stats() and send() no longer know the id.
  transport_.removePeer(peer->id(), true);
  transport_.handler().onClose(peer->id(), peer->closeReason_);
}

void UdpEndpoint::updateQueueCounters(UdpPeer& peer) {
  peer.counters().queueMessages.store(peer.queue_.messages() + (peer.writing_ ? 1 : 0));
  peer.counters().queueBytes.store(peer.queue_.bytes() + (peer.writing_ ? peer.inFlight_.data.size() : 0));
}

}  // namespace throng::transport::detail
