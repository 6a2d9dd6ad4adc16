// throng::transport::detail::CookieJar — the stateless proof-of-address cookies of the UDP handshake
// (docs/protocol.md "Opening a UDP session"): a cookie is a keyed hash (two SipHash-2-4 with a
// random per-process key) of the client's address, port and the current 10-second interval. The
// server keeps nothing per cookie; a cookie checks for the interval it was issued in and the next
// one (so it lives 10 to 20 s). Time is passed in. Pure computation.
#pragma once
#include <array>
#include <chrono>
#include <cstdint>
#include <span>

#include "throng/net/asio.hpp"
#include "throng/protocol/messages.hpp"

namespace throng::transport::detail {
using namespace throng::net;  // asio::, beast::, tcp, udp, error_code

/// SipHash-2-4 of `data` under the 128-bit key (k0, k1) (Aumasson and Bernstein, 2012).
[[nodiscard]] std::uint64_t sipHash24(std::uint64_t k0, std::uint64_t k1, std::span<const std::uint8_t> data);

class CookieJar {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr std::chrono::seconds kInterval{10};

  /// A random key (std::random_device).
  CookieJar();
  /// A fixed key (tests).
  explicit CookieJar(const std::array<std::uint64_t, 4>& key) : key_(key) {}

  /// The cookie for `remote` at `now`.
  [[nodiscard]] protocol::CookieBytes issue(const udp::endpoint& remote, Clock::time_point now) const;
  /// Whether `cookie` was issued to `remote` in the interval of `now` or the one before.
  [[nodiscard]] bool check(const udp::endpoint& remote, const protocol::CookieBytes& cookie, Clock::time_point now) const;

 private:
  [[nodiscard]] protocol::CookieBytes make(const udp::endpoint& remote, std::int64_t interval) const;
  std::array<std::uint64_t, 4> key_;
};

}  // namespace throng::transport::detail
