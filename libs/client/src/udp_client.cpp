// throng::client::UdpClient — blocking UDP client on a private io_context (see header). One
// receive stays pending between calls.
#include "throng/client/udp_client.hpp"

#include <deque>
#include <utility>

#include "throng/net/asio.hpp"
#include "client_io.hpp"
#include "throng/protocol/messages.hpp"

namespace throng::client {
using namespace detail;

struct UdpClient::Impl {
  asio::io_context ioc;  // first: destroyed last
  udp::socket socket{ioc};
  std::vector<std::uint8_t> buffer = std::vector<std::uint8_t>(65536);
  std::deque<std::vector<std::uint8_t>> inbox;
  bool receiving = false;
  std::string target;
  std::vector<std::uint8_t> first;  ///< the message open() carries; empty before open()
  protocol::CookieBytes cookie{};   ///< the newest cookie from the server (zeros: none yet)
  bool gotCookie = false;

  std::vector<std::uint8_t> udpHello() const {
    std::vector<std::uint8_t> out{protocol::kMagic, static_cast<std::uint8_t>(protocol::MessageType::UdpHello)};
    out.insert(out.end(), cookie.begin(), cookie.end());
    out.insert(out.end(), first.begin(), first.end());
    return out;
  }
  void sendHello() {
    const auto bytes = udpHello();
    error_code ignored;
    socket.send(asio::buffer(bytes), 0, ignored);
  }
  /// A Cookie datagram: kept and answered (after open()), never handed to receive().
  bool takeCookie(const std::vector<std::uint8_t>& d) {
    if (d.size() != protocol::kCookieMessageSize || d[0] != protocol::kMagic ||
        d[1] != static_cast<std::uint8_t>(protocol::MessageType::Cookie)) {
      return false;
    }
    if (first.empty()) return false;  // no session asked for: an ordinary datagram
    std::copy(d.begin() + 2, d.end(), cookie.begin());
    gotCookie = true;
    sendHello();
    return true;
  }

  void startReceive() {
    if (receiving || !socket.is_open()) return;
    receiving = true;
    socket.async_receive(asio::buffer(buffer), [this](error_code ec, std::size_t n) {
      receiving = false;
      if (ec == asio::error::operation_aborted) return;
      if (!ec) {
        std::vector<std::uint8_t> d(buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(n));
        if (!takeCookie(d)) inbox.push_back(std::move(d));
      }
      startReceive();  // ICMP "refused" and the like: keep listening
    });
  }
};

UdpClient::UdpClient(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
UdpClient::~UdpClient() {
  error_code ignored;
  if (impl_) impl_->socket.close(ignored);
}

core::Result<std::unique_ptr<UdpClient>> UdpClient::connect(const std::string& host, std::uint16_t port) {
  auto impl = std::make_unique<Impl>();
  impl->target = "udp://" + host + ":" + std::to_string(port);
  error_code ec;
  udp::resolver resolver(impl->ioc);
  const auto endpoints = resolver.resolve(udp::v4(), host, std::to_string(port), ec);
  if (!ec && endpoints.empty()) ec = asio::error::host_not_found;
  if (!ec) impl->socket.open(endpoints.begin()->endpoint().protocol(), ec);
  if (!ec) impl->socket.connect(endpoints.begin()->endpoint(), ec);
  if (ec) {
    core::Diagnostic d;
    d.source = impl->target;
    d.what = "cannot open UDP socket: " + ec.message();
    return d;
  }
  impl->startReceive();
  return std::unique_ptr<UdpClient>(new UdpClient(std::move(impl)));
}

core::Status UdpClient::open(std::span<const std::uint8_t> first, std::chrono::milliseconds timeout) {
  Impl& c = *impl_;
  c.first.assign(first.begin(), first.end());
  c.cookie = {};
  c.gotCookie = false;
  if (c.first.size() + protocol::kCookieMessageSize < protocol::kMinUdpHelloSize) {
    core::Diagnostic d;
    d.source = c.target;
    d.what = "a first message of " + std::to_string(c.first.size()) + " bytes";
    d.expected = "at least " + std::to_string(protocol::kMinUdpHelloSize - protocol::kCookieMessageSize) + " bytes (a Hello)";
    return d;
  }
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!c.gotCookie && std::chrono::steady_clock::now() < deadline) {
    c.sendHello();  // without a cookie: the server answers with one
    c.startReceive();
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    runUntil(c.ioc, [&] { return c.gotCookie; }, std::min(left, std::chrono::milliseconds(250)));
  }
  if (!c.gotCookie) {
    core::Diagnostic d;
    d.source = c.target;
    d.what = "no Cookie within " + std::to_string(timeout.count()) + " ms";
    d.expected = "a throng server (throng serve) at this UDP port";
    return d;
  }
  return core::Ok{};  // takeCookie sent the UdpHello with the cookie
}

core::Status UdpClient::reopen() {
  if (impl_->first.empty()) {
    core::Diagnostic d;
    d.source = impl_->target;
    d.what = "reopen() before open()";
    return d;
  }
  impl_->sendHello();
  return core::Ok{};
}

core::Status UdpClient::send(std::span<const std::uint8_t> message) {
  error_code ec;
  impl_->socket.send(asio::buffer(message.data(), message.size()), 0, ec);
  if (ec) {
    core::Diagnostic d;
    d.source = impl_->target;
    d.what = "send failed: " + ec.message();
    return d;
  }
  return core::Ok{};
}

std::optional<std::vector<std::uint8_t>> UdpClient::receive(std::chrono::milliseconds timeout) {
  Impl& c = *impl_;
  c.startReceive();
  runUntil(c.ioc, [&] { return !c.inbox.empty(); }, timeout);
  if (c.inbox.empty()) return std::nullopt;
  auto message = std::move(c.inbox.front());
  c.inbox.pop_front();
  return message;
}

std::uint16_t UdpClient::localPort() const {
  error_code ec;
  const auto local = impl_->socket.local_endpoint(ec);
  return ec ? 0 : local.port();
}

}  // namespace throng::client
