// throng::client::UdpClient — a small blocking UDP client for tests and load generators: one
// connected socket, one datagram per message, and the client side of the cookie round trip that
// opens a UDP session (docs/protocol.md "Opening a UDP session"). Reads and writes a socket.
#pragma once
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "throng/core/result.hpp"

namespace throng::client {

class UdpClient {
 public:
  static core::Result<std::unique_ptr<UdpClient>> connect(const std::string& host, std::uint16_t port);
  ~UdpClient();
  UdpClient(const UdpClient&) = delete;
  UdpClient& operator=(const UdpClient&) = delete;

  /// Opens the session: sends `first` (a whole message: a Hello for a throng server) inside a
  /// UdpHello without a cookie, resending it every 250 ms until the server's Cookie comes (or
  /// `timeout` passes: an error), then sends the UdpHello again with the cookie; the server opens
  /// the peer on that one and takes `first` as its first message. UDP may lose that datagram:
  /// reopen() repeats it (an open peer ignores the repeat). Datagrams other than the Cookie that
  /// arrive meanwhile stay for receive().
  core::Status open(std::span<const std::uint8_t> first, std::chrono::milliseconds timeout);
  /// Sends the last UdpHello again (with the newest cookie).
  core::Status reopen();
  /// Sends one datagram (at most 65507 bytes).
  core::Status send(std::span<const std::uint8_t> message);
  /// The next datagram, or nullopt after `timeout`. A Cookie from the server after open() (the
  /// session was forgotten, or the cookie had expired) is not returned: it is answered at once
  /// with the UdpHello carrying it.
  std::optional<std::vector<std::uint8_t>> receive(std::chrono::milliseconds timeout);
  [[nodiscard]] std::uint16_t localPort() const;

 private:
  struct Impl;
  explicit UdpClient(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace throng::client
