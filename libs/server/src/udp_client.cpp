// throng::server::UdpClient — blocking UDP client on a private io_context (see header). One
// receive stays pending between calls.
#include "throng/server/udp_client.hpp"

#include <deque>
#include <utility>

#include "asio.hpp"
#include "client_io.hpp"

namespace throng::server {
using namespace detail;

struct UdpClient::Impl {
  net::io_context ioc;  // first: destroyed last
  udp::socket socket{ioc};
  std::vector<std::uint8_t> buffer = std::vector<std::uint8_t>(65536);
  std::deque<std::vector<std::uint8_t>> inbox;
  bool receiving = false;
  std::string target;

  void startReceive() {
    if (receiving || !socket.is_open()) return;
    receiving = true;
    socket.async_receive(net::buffer(buffer), [this](error_code ec, std::size_t n) {
      receiving = false;
      if (ec == net::error::operation_aborted) return;
      if (!ec) inbox.emplace_back(buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(n));
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
  if (!ec && endpoints.empty()) ec = net::error::host_not_found;
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

core::Status UdpClient::send(std::span<const std::uint8_t> message) {
  error_code ec;
  impl_->socket.send(net::buffer(message.data(), message.size()), 0, ec);
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

}  // namespace throng::server
