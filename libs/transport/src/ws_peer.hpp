// throng::transport::detail::WsPeer — one WebSocket connection: completes the handshake of an
// upgraded HTTP request, reads binary messages (size, type and rate checked) into
// TransportHandler::onMessage, writes its SendQueue one message at a time, and closes with a
// reason. Everything runs on the connection's strand.
#pragma once
#include <memory>
#include <string>

#include "throng/net/asio.hpp"
#include "peer.hpp"
#include "token_bucket.hpp"

namespace throng::transport::detail {
using namespace throng::net;  // asio::, beast::, tcp, udp, error_code

class TransportImpl;

class WsPeer final : public Peer, public std::enable_shared_from_this<WsPeer> {
 public:
  WsPeer(TransportImpl& transport, PeerId id, beast::tcp_stream&& stream, std::string remote);

  /// Accepts the upgrade request (the peer must already be registered).
  void start(http::request<http::string_body> request);

  void enqueue(QueuedMessage message) override;
  void requestClose(std::string reason, CloseKind kind, bool flush) override;

 private:
  enum class State { Handshaking, Open, Closing, Done };

  void onAccept(error_code ec);
  void doRead();
  void onRead(error_code ec, std::size_t bytes);
  void deliver();
  /// The message under way is over maxMessageBytes by what its frame header declares.
  bool declaredTooLarge();
  void push(QueuedMessage message);
  void doWrite();
  void onWrite(error_code ec, std::size_t bytes);
  void beginClose(std::string reason, CloseKind kind, bool flush);
  void maybeSendClose();
  void finish(std::string reason);
  void updateQueueCounters();

  TransportImpl& transport_;
  websocket::stream<beast::tcp_stream> ws_;
  std::string remote_;
  http::request<http::string_body> upgrade_;  // kept alive during the handshake
  beast::flat_buffer buffer_;
  SendQueue queue_;
  QueuedMessage inFlight_;
  bool writing_ = false;
  bool discarding_ = false;  // closing because of what was read: read on, but drop the data
  bool closeSent_ = false;
  State state_ = State::Handshaking;
  std::string closeReason_;
  CloseKind closeKind_ = CloseKind::Normal;
  asio::steady_timer closeTimer_;
  TokenBucket bucket_;
};

}  // namespace throng::transport::detail
