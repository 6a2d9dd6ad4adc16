// throng::transport::detail::WsPeer — one WebSocket connection (see header). The read loop never
// stops before the socket closes: while closing it keeps reading so the peer's close frame is
// seen, dropping data; a close that takes longer than closeTimeout drops the socket.
#include "ws_peer.hpp"

#include <algorithm>
#include <limits>
#include <span>
#include <utility>

#include "transport_impl.hpp"

namespace throng::transport::detail {
namespace {

constexpr std::size_t kReadChunk = 64 * 1024;
constexpr std::size_t kMaxCloseReason = 123;  // RFC 6455: 125-byte control payload minus the code

websocket::close_code closeCode(CloseKind kind) {
  switch (kind) {
    case CloseKind::Normal: return websocket::close_code::normal;
    case CloseKind::GoingAway: return websocket::close_code::going_away;
    case CloseKind::Policy: return websocket::close_code::policy_error;
    case CloseKind::TooBig: return websocket::close_code::too_big;
    case CloseKind::BadData: return websocket::close_code::unknown_data;
  }
  return websocket::close_code::normal;
}

/// At most 123 bytes, not cutting a UTF-8 sequence.
std::string truncateReason(std::string reason) {
  if (reason.size() <= kMaxCloseReason) return reason;
  std::size_t n = kMaxCloseReason;
  while (n > 0 && (static_cast<unsigned char>(reason[n]) & 0xC0) == 0x80) --n;
  reason.resize(n);
  return reason;
}

/// Beast refuses a frame header declaring more than this (see start()); between maxMessageBytes
/// and this, onRead refuses it with a reason as soon as the first bytes of its payload arrive.
std::size_t headerRefusal(std::size_t maxMessageBytes) {
  constexpr std::size_t kHeaderRefusal = 4;
  return maxMessageBytes > std::numeric_limits<std::size_t>::max() / kHeaderRefusal ? maxMessageBytes
                                                                                  : maxMessageBytes * kHeaderRefusal;
}

std::string describe(error_code ec) {
  if (ec == beast::error::timeout) return "timeout";
  if (ec == asio::error::eof || ec == asio::error::connection_reset || ec == asio::error::broken_pipe)
    return "connection lost";
  return ec.message();
}

}  // namespace

WsPeer::WsPeer(TransportImpl& transport, PeerId id, beast::tcp_stream&& stream, std::string remote)
    : Peer(id, PeerKind::WebSocket),
      transport_(transport),
      ws_(std::move(stream)),
      remote_(std::move(remote)),
      closeTimer_(ws_.get_executor()),
      bucket_(transport.options().messagesPerSecond, transport.options().burstMessages,
              TokenBucket::Clock::now()) {}

void WsPeer::start(http::request<http::string_body> request) {
  const TransportOptions& options = transport_.options();
  beast::get_lowest_layer(ws_).expires_never();  // the websocket has its own timeouts
  websocket::stream_base::timeout timeouts{};
  timeouts.handshake_timeout = options.httpTimeout;
  timeouts.idle_timeout = options.wsIdleTimeout;
  timeouts.keep_alive_pings = true;
  ws_.set_option(timeouts);
  ws_.set_option(websocket::stream_base::decorator(
      [](websocket::response_type& res) { res.set(http::field::server, "throng"); }));
  // Sizes are checked against the frame headers, before the payload arrives (onRead): a header
  // declaring more than kHeaderRefusal × maxMessageBytes (up to 2^63 - 1) already fails the read
  // at the header, in Beast: close code 1009 without a reason text, then Beast's teardown.
  ws_.read_message_max(headerRefusal(options.maxMessageBytes));
  ws_.binary(true);
  upgrade_ = std::move(request);
  ws_.async_accept(upgrade_, beast::bind_front_handler(&WsPeer::onAccept, shared_from_this()));
}

void WsPeer::onAccept(error_code ec) {
  upgrade_ = {};
  if (ec) {
    finish(describe(ec));
    return;
  }
  state_ = State::Open;
  transport_.noteOpened();
  transport_.handler().onOpen(id(), PeerKind::WebSocket, remote_);
  if (!closeReason_.empty()) {  // close asked for during the handshake
    std::string reason = std::exchange(closeReason_, {});
    beginClose(std::move(reason), closeKind_, false);
  }
  doRead();
}

void WsPeer::doRead() {
  ws_.async_read_some(buffer_, kReadChunk, beast::bind_front_handler(&WsPeer::onRead, shared_from_this()));
}

void WsPeer::onRead(error_code ec, std::size_t) {
  if (ec) {
    std::string reason;
    if (ec == websocket::error::message_too_big) {
      reason = "message too large";  // refused at its frame header (close code 1009 sent)
    } else if (ec == websocket::error::closed) {
      const auto& peerReason = ws_.reason().reason;
      reason = peerReason.empty() ? std::string("closed by peer") : std::string(peerReason.data(), peerReason.size());
    } else {
      reason = describe(ec);
    }
    finish(closeReason_.empty() ? std::move(reason) : closeReason_);
    return;
  }
  if (state_ == State::Done) return;
  if (!discarding_) {
    if (ws_.got_text()) {
      discarding_ = true;
      beginClose("text frame: binary messages only", CloseKind::BadData, false);
    } else if (buffer_.size() > transport_.options().maxMessageBytes || declaredTooLarge()) {
      discarding_ = true;
      beginClose("message too large", CloseKind::TooBig, false);
    } else if (ws_.is_message_done()) {
      deliver();
    }
  }
  if (discarding_) buffer_.consume(buffer_.size());
  doRead();
}

bool WsPeer::declaredTooLarge() {
  if (ws_.is_message_done()) return false;
  // What the current frame's header says is still to come (read_size_hint(1): the frame's
  // remaining bytes while one is under way, 1 between frames).
  const std::size_t rest = ws_.read_size_hint(1);
  return rest > 1 && rest > transport_.options().maxMessageBytes - std::min(buffer_.size(), transport_.options().maxMessageBytes);
}

void WsPeer::deliver() {
  const auto data = buffer_.data();
  const std::size_t size = data.size();
  if (!bucket_.take(TokenBucket::Clock::now())) {
    discarding_ = true;
    beginClose("rate limit", CloseKind::Policy, false);
    return;
  }
  transport_.countReceived(*this, size);
  if (state_ == State::Open)
    transport_.handler().onMessage(id(), std::span<const std::uint8_t>(static_cast<const std::uint8_t*>(data.data()), size));
  buffer_.consume(size);
}

void WsPeer::enqueue(QueuedMessage message) {
  asio::post(ws_.get_executor(), [self = shared_from_this(), m = std::move(message)]() mutable { self->push(std::move(m)); });
}

void WsPeer::requestClose(std::string reason, CloseKind kind, bool flush) {
  asio::post(ws_.get_executor(), [self = shared_from_this(), r = std::move(reason), kind, flush]() mutable {
    self->beginClose(std::move(r), kind, flush);
  });
}

void WsPeer::push(QueuedMessage message) {
  if (state_ != State::Open) return;  // closing or closed: nothing more goes out
  const TransportOptions& options = transport_.options();
  if (const std::size_t replaced = queue_.push(std::move(message)); replaced > 0)
    transport_.countDropped(*this, replaced);
  if (queue_.messages() > options.maxQueueMessages || queue_.bytes() > options.maxQueueBytes) {
    beginClose("send queue limit", CloseKind::Policy, false);
    return;
  }
  updateQueueCounters();
  doWrite();
}

void WsPeer::doWrite() {
  if (writing_ || state_ == State::Done || state_ == State::Handshaking) return;
  if (queue_.empty()) {
    maybeSendClose();
    return;
  }
  inFlight_ = queue_.pop();
  writing_ = true;
  updateQueueCounters();
  ws_.binary(true);
  ws_.async_write(asio::buffer(inFlight_.data), beast::bind_front_handler(&WsPeer::onWrite, shared_from_this()));
}

void WsPeer::onWrite(error_code ec, std::size_t) {
  writing_ = false;
  if (ec) {
    finish(closeReason_.empty() ? describe(ec) : closeReason_);
    return;
  }
  if (state_ == State::Done) return;
  transport_.countSent(*this, inFlight_.data.size());
  inFlight_ = {};
  updateQueueCounters();
  doWrite();
}

void WsPeer::beginClose(std::string reason, CloseKind kind, bool flush) {
  if (state_ == State::Done || state_ == State::Closing) return;  // the first reason wins
  if (state_ == State::Handshaking) {
    if (closeReason_.empty()) {
      closeReason_ = std::move(reason);
      closeKind_ = kind;
    }
    return;
  }
  state_ = State::Closing;
  closeReason_ = std::move(reason);
  closeKind_ = kind;
  if (!flush) queue_.clear();
  updateQueueCounters();
  closeTimer_.expires_after(transport_.options().closeTimeout);
  closeTimer_.async_wait([self = shared_from_this()](error_code ec) {
    if (!ec) self->finish(self->closeReason_);
  });
  maybeSendClose();
}

void WsPeer::maybeSendClose() {
  if (state_ != State::Closing || closeSent_ || writing_ || !queue_.empty()) return;
  closeSent_ = true;
  websocket::close_reason reason;
  reason.code = closeCode(closeKind_);
  reason.reason = truncateReason(closeReason_);
  ws_.async_close(reason, [self = shared_from_this()](error_code) { self->finish(self->closeReason_); });
}

void WsPeer::finish(std::string reason) {
  if (state_ == State::Done) return;
  const bool opened = state_ != State::Handshaking;
  state_ = State::Done;
  closeTimer_.cancel();
  beast::get_lowest_layer(ws_).close();
  queue_.clear();  // inFlight_ stays until its (aborted) write completes
  counters().queueMessages.store(0);
  counters().queueBytes.store(0);
  // Gone from the peer table first: once onClose runs, stats() and send() no longer know the id.
  transport_.removePeer(id(), opened);
  if (opened) transport_.handler().onClose(id(), reason);
}

void WsPeer::updateQueueCounters() {
  counters().queueMessages.store(queue_.messages() + (writing_ ? 1 : 0));
  counters().queueBytes.store(queue_.bytes() + (writing_ ? inFlight_.data.size() : 0));
}

}  // namespace throng::transport::detail
