// throng::server::UdpClient — a small blocking UDP client for tests and load generators: one
// connected socket, one datagram per message. Reads and writes a socket.
#pragma once
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "throng/core/result.hpp"

namespace throng::server {

class UdpClient {
 public:
  static core::Result<std::unique_ptr<UdpClient>> connect(const std::string& host, std::uint16_t port);
  ~UdpClient();
  UdpClient(const UdpClient&) = delete;
  UdpClient& operator=(const UdpClient&) = delete;

  /// Sends one datagram (at most 65507 bytes).
  core::Status send(std::span<const std::uint8_t> message);
  /// The next datagram, or nullopt after `timeout`.
  std::optional<std::vector<std::uint8_t>> receive(std::chrono::milliseconds timeout);
  [[nodiscard]] std::uint16_t localPort() const;

 private:
  struct Impl;
  explicit UdpClient(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace throng::server
