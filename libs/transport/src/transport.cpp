// throng::transport::Transport — start (validate, bind, run threads), the thread-safe send/close
// entry points, shutdown, and the peer registry. See docs/server.md ("Transport").
#include <algorithm>
#include <utility>

#include "http_session.hpp"
#include "transport_impl.hpp"
#include "udp_endpoint.hpp"
#include "throng/protocol/fragments.hpp"

namespace throng::transport {
namespace detail {
namespace {

constexpr std::size_t kMaxThreads = 64;
constexpr std::size_t kMaxUdpPayload = 65507;
constexpr auto kAcceptRetry = std::chrono::milliseconds(50);

/// The transport whose io thread this is (nullptr elsewhere).
thread_local const TransportImpl* tCurrentTransport = nullptr;

core::Diagnostic optionError(std::string field, std::string what, std::string expected) {
  core::Diagnostic d;
  d.source = "TransportOptions";
  d.pointer = "/" + std::move(field);
  d.what = std::move(what);
  d.expected = std::move(expected);
  return d;
}

core::Diagnostics validate(const TransportOptions& o) {
  core::Diagnostics errors;
  if (o.threads < 1 || o.threads > kMaxThreads)
    errors.push_back(optionError("threads", std::to_string(o.threads) + " threads", "1 to 64"));
  if (o.maxMessageBytes < 1)
    errors.push_back(optionError("maxMessageBytes", "0 bytes", "at least 1 byte"));
  if (o.enableUdp && (o.maxDatagramBytes < 1 || o.maxDatagramBytes > kMaxUdpPayload))
    errors.push_back(optionError("maxDatagramBytes", std::to_string(o.maxDatagramBytes) + " bytes", "1 to 65507 bytes (1200 recommended)"));
  if (o.enableUdp && o.udpFragmentBytes != 0 &&
      (o.udpFragmentBytes < protocol::kMinFragmentDatagram || o.udpFragmentBytes > kMaxUdpPayload))
    errors.push_back(optionError("udpFragmentBytes", std::to_string(o.udpFragmentBytes) + " bytes",
                                 "0 (never fragment) or 64 to 65507 bytes (1200 recommended)"));
  if (o.maxQueueMessages < 1)
    errors.push_back(optionError("maxQueueMessages", "0 messages", "at least 1 message"));
  if (o.maxQueueBytes < 1)
    errors.push_back(optionError("maxQueueBytes", "0 bytes", "at least 1 byte"));
  if (o.maxPeers < 1)
    errors.push_back(optionError("maxPeers", "0 peers", "at least 1 peer"));
  if (o.enableUdp && o.maxUdpPeers < 1)
    errors.push_back(optionError("maxUdpPeers", "0 peers", "at least 1 peer"));
  if (o.messagesPerSecond < 0.0 || !(o.burstMessages >= 1.0))
    errors.push_back(optionError("messagesPerSecond", "negative rate or burst below 1", "rate >= 0 per second (0 = unlimited), burst >= 1 message"));
  if (o.udpIdleTimeout.count() <= 0 || o.wsIdleTimeout.count() <= 0 || o.httpTimeout.count() <= 0 || o.closeTimeout.count() <= 0)
    errors.push_back(optionError("udpIdleTimeout", "a timeout of 0 ms or less", "every timeout above 0 ms"));
  return errors;
}

core::Diagnostic bindError(const std::string& address, std::uint16_t port, const char* what, const error_code& ec) {
  core::Diagnostic d;
  d.source = address + ":" + std::to_string(port);
  d.what = std::string("cannot listen for ") + what + ": " + ec.message();
  d.expected = "a free port on a local address";
  d.hint = "choose another port, or 0 for any free port";
  return d;
}

}  // namespace

TransportImpl::TransportImpl(TransportOptions options, TransportHandler& handler)
    : options_(std::move(options)),
      handler_(handler),
      acceptStrand_(asio::make_strand(ioc_)),
      acceptor_(acceptStrand_) {}

TransportImpl::~TransportImpl() { shutdown("server shutting down"); }

core::Status TransportImpl::listen() {
  error_code ec;
  const auto address = asio::ip::make_address(options_.bindAddress, ec);
  if (ec) {
    core::Diagnostic d;
    d.source = "TransportOptions";
    d.pointer = "/bindAddress";
    d.what = "\"" + options_.bindAddress + "\" is not an IP address";
    d.expected = "an IPv4 or IPv6 literal such as 127.0.0.1 or 0.0.0.0";
    return d;
  }
  const tcp::endpoint httpAt(address, options_.httpPort);
  acceptor_.open(httpAt.protocol(), ec);
  if (!ec) acceptor_.set_option(asio::socket_base::reuse_address(true), ec);
  if (!ec) acceptor_.bind(httpAt, ec);
  if (!ec) acceptor_.listen(asio::socket_base::max_listen_connections, ec);
  if (ec) return bindError(options_.bindAddress, options_.httpPort, "HTTP and WebSocket (TCP)", ec);
  httpPort_ = acceptor_.local_endpoint(ec).port();

  if (options_.enableUdp) {
    udp_ = std::make_shared<UdpEndpoint>(*this);
    ec = udp_->bind(udp::endpoint(address, options_.udpPort));
    if (ec) return bindError(options_.bindAddress, options_.udpPort, "UDP", ec);
    udpPort_ = udp_->port();
  }
  return core::Ok{};
}

void TransportImpl::run() {
  work_.emplace(asio::make_work_guard(ioc_));
  asio::post(acceptStrand_, [this] { doAccept(); });
  if (udp_) udp_->start();
  threads_.reserve(options_.threads);
  for (std::size_t i = 0; i < options_.threads; ++i) {
    threads_.emplace_back([this] {
      tCurrentTransport = this;
      for (;;) {
        try {
          ioc_.run();
          return;
        } catch (...) {
          // A handler callback threw: the peer it concerned may be stuck, the others go on.
        }
      }
    });
  }
}

void TransportImpl::doAccept() {
  acceptor_.async_accept(asio::make_strand(ioc_), [this](error_code ec, tcp::socket socket) {
    if (stopping_ || !acceptor_.is_open() || ec == asio::error::operation_aborted) return;
    if (!ec) {
      std::make_shared<HttpSession>(*this, std::move(socket))->start();
      doAccept();
      return;
    }
    // Out of descriptors or similar: try again shortly instead of spinning.
    auto timer = std::make_shared<asio::steady_timer>(acceptStrand_, kAcceptRetry);
    timer->async_wait([this, timer](error_code) {
      if (!stopping_) doAccept();
    });
  });
}

bool TransportImpl::onTransportThread() const { return tCurrentTransport == this; }

SendStatus TransportImpl::send(PeerId id, std::vector<std::uint8_t> message, SendClass cls, std::uint32_t slot) {
  if (stopping_) return SendStatus::ShuttingDown;
  std::shared_ptr<Peer> peer;
  {
    std::lock_guard lock(mutex_);
    const auto it = peers_.find(id.value);
    if (it == peers_.end()) return SendStatus::UnknownPeer;
    peer = it->second;
  }
  std::size_t limit = options_.maxMessageBytes;
  if (peer->kind() == PeerKind::Udp) {
    limit = options_.udpFragmentBytes > 0 ? protocol::maxFragmentedSize(options_.udpFragmentBytes) : options_.maxDatagramBytes;
  }
  if (message.size() > limit) return SendStatus::TooLarge;
  peer->enqueue(QueuedMessage{std::move(message), cls, slot});
  return SendStatus::Queued;
}

void TransportImpl::close(PeerId id, std::string reason) {
  std::shared_ptr<Peer> peer;
  {
    std::lock_guard lock(mutex_);
    const auto it = peers_.find(id.value);
    if (it == peers_.end()) return;
    peer = it->second;
  }
  peer->requestClose(std::move(reason), CloseKind::Normal, true);
}

void TransportImpl::shutdown(std::string reason) {
  if (stopping_.exchange(true)) {
    if (!onTransportThread()) joinThreads();
    return;
  }
  if (!work_) return;  // never started
  asio::post(acceptStrand_, [this] {
    error_code ignored;
    acceptor_.close(ignored);
  });
  if (udp_) udp_->shutdown(reason);
  std::vector<std::shared_ptr<Peer>> peers;
  std::vector<std::function<void()>> closers;
  {
    std::lock_guard lock(mutex_);
    for (const auto& [id, peer] : peers_)
      if (peer->kind() == PeerKind::WebSocket) peers.push_back(peer);
    for (const auto& [id, closer] : http_) closers.push_back(closer);
  }
  for (const auto& peer : peers) peer->requestClose(reason, CloseKind::GoingAway, true);
  for (const auto& closer : closers) closer();
  if (onTransportThread()) return;  // the destructor joins

  {
    std::unique_lock lock(mutex_);
    drained_.wait_for(lock, options_.closeTimeout + std::chrono::seconds(1),
                      [&] { return peers_.empty() && http_.empty(); });
  }
  joinThreads();
  std::lock_guard lock(mutex_);
  peers_.clear();
  webSocketPeers_ = udpPeers_ = 0;
  http_.clear();
}

void TransportImpl::joinThreads() {
  if (joined_.exchange(true)) return;
  work_.reset();
  ioc_.stop();
  for (auto& t : threads_) {
    if (t.get_id() == std::this_thread::get_id()) t.detach();  // destroyed from a callback: cannot join itself
    else t.join();
  }
}

std::optional<PeerStats> TransportImpl::stats(PeerId id) const {
  std::lock_guard lock(mutex_);
  const auto it = peers_.find(id.value);
  if (it == peers_.end()) return std::nullopt;
  return it->second->snapshot();
}

TransportTotals TransportImpl::totals() const {
  TransportTotals t;
  {
    std::lock_guard lock(mutex_);
    t.livePeers = peers_.size();
    for (const auto& [id, peer] : peers_) {
      if (peer->kind() == PeerKind::WebSocket) ++t.liveWebSocketPeers;
      else ++t.liveUdpPeers;
    }
    t.liveHttpConnections = http_.size();
  }
  t.peersOpened = peersOpened_.load();
  t.peersClosed = peersClosed_.load();
  t.bytesSent = bytesSent_.load();
  t.bytesReceived = bytesReceived_.load();
  t.messagesSent = messagesSent_.load();
  t.messagesReceived = messagesReceived_.load();
  t.droppedLatest = droppedLatest_.load();
  t.httpRequests = httpRequests_.load();
  t.udpCookiesSent = udpCookiesSent_.load();
  t.udpIgnored = udpIgnored_.load();
  return t;
}

bool TransportImpl::addPeer(std::shared_ptr<Peer> peer) {
  std::lock_guard lock(mutex_);
  const bool udp = peer->kind() == PeerKind::Udp;
  std::size_t& count = udp ? udpPeers_ : webSocketPeers_;
  if (stopping_ || count >= (udp ? options_.maxUdpPeers : options_.maxPeers)) return false;
  if (peers_.emplace(peer->id().value, std::move(peer)).second) ++count;
  return true;
}

std::size_t TransportImpl::peerCount(PeerKind kind) const {
  std::lock_guard lock(mutex_);
  return kind == PeerKind::Udp ? udpPeers_ : webSocketPeers_;
}

void TransportImpl::removePeer(PeerId id, bool opened) {
  {
    std::lock_guard lock(mutex_);
    if (const auto it = peers_.find(id.value); it != peers_.end()) {
      --(it->second->kind() == PeerKind::Udp ? udpPeers_ : webSocketPeers_);
      peers_.erase(it);
    }
  }
  if (opened) peersClosed_.fetch_add(1);
  drained_.notify_all();
}

std::uint64_t TransportImpl::addHttpConnection(std::function<void()> closer) {
  std::lock_guard lock(mutex_);
  const std::uint64_t id = nextHttpId_++;
  http_.emplace(id, std::move(closer));
  return id;
}

void TransportImpl::removeHttpConnection(std::uint64_t id) {
  {
    std::lock_guard lock(mutex_);
    http_.erase(id);
  }
  drained_.notify_all();
}

void TransportImpl::countSent(Peer& peer, std::size_t bytes) {
  peer.counters().bytesSent.fetch_add(bytes);
  peer.counters().messagesSent.fetch_add(1);
  bytesSent_.fetch_add(bytes);
  messagesSent_.fetch_add(1);
}

void TransportImpl::countReceived(Peer& peer, std::size_t bytes) {
  peer.counters().bytesReceived.fetch_add(bytes);
  peer.counters().messagesReceived.fetch_add(1);
  bytesReceived_.fetch_add(bytes);
  messagesReceived_.fetch_add(1);
}

void TransportImpl::countDropped(Peer& peer, std::size_t n) {
  peer.counters().droppedLatest.fetch_add(n);
  droppedLatest_.fetch_add(n);
}

}  // namespace detail

core::Result<std::unique_ptr<Transport>> Transport::start(TransportOptions options, TransportHandler& handler) {
  if (auto errors = detail::validate(options); !errors.empty()) return errors;
  auto impl = std::make_unique<detail::TransportImpl>(std::move(options), handler);
  if (auto status = impl->listen(); !status) return std::move(status).takeErrors();
  impl->run();
  return std::unique_ptr<Transport>(std::move(impl));
}

}  // namespace throng::transport
