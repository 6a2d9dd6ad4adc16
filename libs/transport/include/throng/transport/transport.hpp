// throng::transport::Transport — moves whole binary messages between the server and its peers:
// HTTP (static files, /health, a dynamic GET hook, a POST hook) and WebSocket (/ws) on one TCP port, datagrams on
// a UDP port. Message-agnostic: it never looks inside a message. Reads sockets; writes sockets;
// calls the TransportHandler on its own thread. See docs/server.md ("Transport"). The places it
// reads and writes protocol bytes: a message too large for one datagram goes to a UDP peer as
// Fragment messages (docs/protocol.md "Fragment"), and a UDP peer opens only after a cookie round
// trip (UdpHello / Cookie, docs/protocol.md "Opening a UDP session").
#pragma once
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "throng/core/result.hpp"

namespace throng::transport {

/// One connection (WebSocket) or one remote endpoint (UDP). Unique per transport, never reused;
/// 0 is never a valid peer.
struct PeerId {
  std::uint64_t value = 0;
  friend bool operator==(PeerId, PeerId) = default;
  friend auto operator<=>(PeerId, PeerId) = default;
};

enum class PeerKind : std::uint8_t { WebSocket, Udp };

/// How a message queues behind others to the same peer.
enum class SendClass : std::uint8_t {
  Reliable,  ///< queued in order, never dropped (the peer is closed if its queue overflows)
  Latest,    ///< droppable state: replaces an unsent Latest message with the same slot
};

/// What send() did with a message.
enum class SendStatus : std::uint8_t {
  Queued,       ///< handed to the peer's queue (it may still be dropped if the peer closes)
  UnknownPeer,  ///< no such peer (closed, or never existed)
  TooLarge,     ///< larger than maxMessageBytes (WebSocket), or for UDP than what udpFragmentBytes
                ///< fragments can carry (protocol::maxFragmentedSize), or maxDatagramBytes when 0
  ShuttingDown, ///< shutdown() was called
};

/// A response produced by TransportOptions::httpHandler.
struct HttpResponse {
  unsigned status = 200;                  ///< HTTP status code
  std::string contentType = "application/octet-stream";
  std::string body;                       ///< used when `file` is empty
  std::filesystem::path file;             ///< when set: serve this file (Content-Type from `contentType`)
};

/// A POST request handed to TransportOptions::postHandler.
/// The path part of a request target: everything before '?' or '#'.
[[nodiscard]] std::string_view targetPath(std::string_view target);

/// The value of `key` in a request target's query string, %XX and '+' decoded; nullopt when the
/// key is absent, an escape is malformed or the value decodes to a NUL byte.
[[nodiscard]] std::optional<std::string> queryValue(std::string_view target, std::string_view key);

struct HttpRequest {
  std::string target;       ///< path and query string, as sent
  std::string contentType;  ///< the Content-Type header, may be empty
  std::string body;         ///< at most TransportOptions::maxPostBytes
};

/// Decodes %XX escapes (and '+' as a space in a query value): a path segment or query value of a
/// request target. nullopt for a malformed escape or a decoded NUL byte.
[[nodiscard]] std::optional<std::string> percentDecode(std::string_view text, bool plusIsSpace = false);

namespace detail {
struct PostState;
}

/// Answers one POST, from any thread, once: copies share one answer and the first respond() wins.
/// When the last copy goes without an answer the client gets 500. cancelled() turns true when the
/// client hangs up or the transport shuts down: long work should stop then. Every responder must
/// be answered or dropped before the Transport is destroyed.
class HttpResponder {
 public:
  explicit HttpResponder(std::shared_ptr<detail::PostState> state);
  void respond(HttpResponse response) const;
  [[nodiscard]] bool cancelled() const;
  /// Non-zero once cancelled (the shape io::LoadOptions::cancel takes); valid while a copy lives.
  [[nodiscard]] const std::atomic<int>& cancelFlag() const;

 private:
  std::shared_ptr<detail::PostState> state_;
};

struct TransportOptions {
  std::string bindAddress = "127.0.0.1";  ///< IPv4 or IPv6 literal ("0.0.0.0" for all interfaces)
  std::uint16_t httpPort = 8080;          ///< HTTP + WebSocket; 0 = pick a free port
  std::uint16_t udpPort = 8081;           ///< 0 = pick a free port
  bool enableUdp = true;                  ///< false: no UDP socket (udpPort() returns 0)
  std::filesystem::path staticRoot;       ///< files served over HTTP; empty = none
  /// Dynamic GET/HEAD paths, tried before the static files (target includes the query string).
  /// Runs on the transport thread: keep it quick and thread-safe. nullopt = not handled.
  std::function<std::optional<HttpResponse>(std::string_view target)> httpHandler;
  /// POST requests (none when empty: POST is answered 405). Runs on the transport thread and must
  /// return at once: true when it took the request (it answers through the responder, now or later
  /// from another thread), false for 404. A throwing hook answers 500. The connection waits for
  /// the answer without a timeout; a client that hangs up meanwhile cancels the responder.
  std::function<bool(HttpRequest request, HttpResponder responder)> postHandler;
  std::size_t maxPostBytes = 8 << 20;  ///< POST body limit [bytes]; a larger body is answered 413

  std::size_t threads = 1;                    ///< io threads [limit: 1..64]
  std::size_t maxMessageBytes = 1 << 20;      ///< incoming and outgoing WebSocket message [bytes]
  std::size_t maxDatagramBytes = 1200;        ///< UDP payload received; sent too when udpFragmentBytes is 0 [bytes, limit: 1..65507]
  /// Outgoing UDP datagram size [bytes, limit: 0 or 64..65507]: a message larger than this goes out
  /// as protocol Fragment datagrams of at most this size (each message whole in its queue slot,
  /// split only when sent); 0 = never fragment (a message over maxDatagramBytes is TooLarge).
  std::size_t udpFragmentBytes = 1200;
  std::size_t maxQueueBytes = 4 << 20;        ///< unsent bytes per peer before "send queue limit"
  std::size_t maxQueueMessages = 256;         ///< unsent messages per peer before "send queue limit"
  std::size_t maxPeers = 1000;                ///< WebSocket peers; more upgrades are answered HTTP 503
  /// UDP peers (each opened by a cookie round trip, docs/protocol.md "Opening a UDP session"); a
  /// proven UdpHello beyond them is ignored. Separate from maxPeers: UDP never takes a /ws slot.
  std::size_t maxUdpPeers = 1000;
  double messagesPerSecond = 200.0;           ///< incoming rate per peer [1/s]; 0 = unlimited
  double burstMessages = 400.0;               ///< token bucket size [messages]
  std::chrono::milliseconds udpIdleTimeout{10000};  ///< UDP peer silent this long: closed ("timeout")
  std::chrono::milliseconds wsIdleTimeout{30000};   ///< WebSocket: pinged at half, closed at full
  std::chrono::milliseconds httpTimeout{30000};     ///< one HTTP request / handshake must finish within
  std::chrono::milliseconds closeTimeout{2000};     ///< a close handshake longer than this: socket dropped
};

/// Callbacks from the transport. They run on a transport thread (with threads == 1, always the
/// same one); callbacks for one peer never overlap. Must not block and must not call shutdown().
class TransportHandler {
 public:
  virtual ~TransportHandler() = default;
  /// A WebSocket completed its handshake, or a UDP endpoint proved its address (a UdpHello with
  /// a valid cookie; the message inside it is then the peer's first onMessage). `remote` is
  /// "address:port".
  virtual void onOpen(PeerId peer, PeerKind kind, std::string remote) = 0;
  /// One whole message (WebSocket binary message or one UDP datagram; empty datagrams are
  /// keep-alives and are not delivered). The span is valid only during the call.
  virtual void onMessage(PeerId peer, std::span<const std::uint8_t> message) = 0;
  /// Called exactly once per opened peer, after which the id is dead.
  virtual void onClose(PeerId peer, std::string_view reason) = 0;
};

/// Per-peer counters (a snapshot; counters only grow).
struct PeerStats {
  PeerKind kind = PeerKind::WebSocket;
  std::uint64_t bytesSent = 0;         ///< payload bytes written to the socket
  std::uint64_t bytesReceived = 0;     ///< payload bytes of received messages
  std::uint64_t messagesSent = 0;
  std::uint64_t messagesReceived = 0;
  std::uint64_t droppedLatest = 0;     ///< Latest messages replaced before they were sent
  std::size_t queueMessages = 0;       ///< unsent messages (including the one being written)
  std::size_t queueBytes = 0;          ///< unsent bytes (including the one being written)
};

/// Whole-transport counters.
struct TransportTotals {
  std::size_t livePeers = 0;           ///< WebSocket + UDP peers open now
  std::size_t liveWebSocketPeers = 0;
  std::size_t liveUdpPeers = 0;
  std::size_t liveHttpConnections = 0; ///< TCP connections not (yet) upgraded
  std::uint64_t peersOpened = 0;
  std::uint64_t peersClosed = 0;
  std::uint64_t bytesSent = 0;
  std::uint64_t bytesReceived = 0;
  std::uint64_t messagesSent = 0;
  std::uint64_t messagesReceived = 0;
  std::uint64_t droppedLatest = 0;
  std::uint64_t httpRequests = 0;
  std::uint64_t udpCookiesSent = 0;    ///< Cookie datagrams answering UdpHellos of unproven endpoints
  /// Datagrams from endpoints without a peer that opened nothing and got no answer (not a
  /// UdpHello, too short, too large, or the UDP peer limit reached).
  std::uint64_t udpIgnored = 0;
};

class Transport {
 public:
  /// Binds both ports and starts the io threads. Errors (port in use, bad address, bad options)
  /// come back as diagnostics naming the address and port.
  static core::Result<std::unique_ptr<Transport>> start(TransportOptions options, TransportHandler& handler);

  virtual ~Transport() = default;  ///< shuts down ("server shutting down") if not done yet

  [[nodiscard]] virtual std::uint16_t httpPort() const = 0;  ///< the bound port
  [[nodiscard]] virtual std::uint16_t udpPort() const = 0;   ///< the bound port; 0 without UDP

  /// Thread-safe, never blocks on the peer. `slot` only matters for SendClass::Latest: an unsent
  /// Latest message with the same slot is removed and this one is queued at the end, so what a
  /// peer receives is always a subsequence of what was sent, in send order.
  virtual SendStatus send(PeerId peer, std::vector<std::uint8_t> message,
                          SendClass cls = SendClass::Reliable, std::uint32_t slot = 0) = 0;

  /// Thread-safe. Sends what is queued, then a WebSocket close frame with `reason` (truncated to
  /// 123 bytes); a UDP peer is forgotten. onClose(peer, reason) follows.
  virtual void close(PeerId peer, std::string reason) = 0;

  /// Closes every peer with `reason`, stops accepting, waits (at most about closeTimeout) for the
  /// close handshakes and joins the threads. Idempotent. Not from a handler callback.
  virtual void shutdown(std::string reason) = 0;

  [[nodiscard]] virtual std::optional<PeerStats> stats(PeerId peer) const = 0;
  [[nodiscard]] virtual TransportTotals totals() const = 0;
};

}  // namespace throng::transport
