// throng::client::WsClient — a small blocking WebSocket client for tests and load generators:
// connects to ws://host:port/path, sends binary messages, and receives messages or the close
// frame's reason. Each client owns its io_context and does I/O only inside its calls (connect,
// send, receive, poll, close), so many clients can share one thread. Reads and writes a socket.
#pragma once
#include <chrono>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "throng/core/result.hpp"

namespace throng::client {

struct WsClientOptions {
  std::string host = "127.0.0.1";
  std::uint16_t port = 8080;
  std::string path = "/ws";
  std::chrono::milliseconds timeout{5000};  ///< for connect, each send and close
  std::size_t maxMessageBytes = 16 << 20;   ///< larger incoming messages fail the connection
};

/// What receive() saw.
struct ClientEvent {
  enum class Kind : std::uint8_t { Message, Closed, Timeout };
  Kind kind = Kind::Timeout;
  std::vector<std::uint8_t> message;  ///< Message: the payload
  std::uint16_t closeCode = 0;        ///< Closed: the server's close code (0: no close frame)
  std::string closeReason;            ///< Closed: the server's reason, or what ended the connection
};

class WsClient {
 public:
  static core::Result<std::unique_ptr<WsClient>> connect(const WsClientOptions& options);
  ~WsClient();
  WsClient(const WsClient&) = delete;
  WsClient& operator=(const WsClient&) = delete;

  /// Writes one binary message; returns when it is written (or failed, or timed out).
  core::Status send(std::span<const std::uint8_t> message);
  /// Writes one text frame (the transport refuses them; for tests).
  core::Status sendText(std::string_view text);
  /// The next message (in order), then the close, else Timeout after `timeout`.
  ClientEvent receive(std::chrono::milliseconds timeout);
  /// Runs ready I/O without blocking (answers pings, queues messages); returns messages waiting.
  std::size_t poll();
  /// True until the connection has ended (messages may still be waiting).
  [[nodiscard]] bool isOpen() const;
  /// Close handshake with `reason`, bounded by the timeout. Messages not yet received are lost.
  void close(std::string_view reason = "bye");

 private:
  struct Impl;
  explicit WsClient(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace throng::client
