// throng::client::WsClient — blocking WebSocket client on a private io_context (see header).
// One read stays pending between calls, so no message is lost and pings get answered whenever
// the client runs I/O.
#include "throng/client/ws_client.hpp"

#include <deque>
#include <utility>

#include "throng/net/asio.hpp"
#include "client_io.hpp"

namespace throng::client {
using namespace detail;

namespace {
core::Diagnostic clientError(const WsClientOptions& o, std::string what) {
  core::Diagnostic d;
  d.source = "ws://" + o.host + ":" + std::to_string(o.port) + o.path;
  d.what = std::move(what);
  return d;
}
}  // namespace

struct WsClient::Impl {
  explicit Impl(WsClientOptions o) : options(std::move(o)) {}

  asio::io_context ioc;  // first: destroyed last
  WsClientOptions options;
  websocket::stream<beast::tcp_stream> ws{ioc};
  beast::flat_buffer buffer;
  std::deque<std::vector<std::uint8_t>> inbox;
  bool reading = false;
  bool closed = false;
  std::uint16_t closeCode = 0;
  std::string closeReason;

  void startRead() {
    if (reading || closed) return;
    reading = true;
    ws.async_read(buffer, [this](error_code ec, std::size_t) {
      reading = false;
      if (ec) {
        markClosed(ec);
        return;
      }
      const auto data = buffer.data();
      const auto* bytes = static_cast<const std::uint8_t*>(data.data());
      inbox.emplace_back(bytes, bytes + data.size());
      buffer.consume(data.size());
      startRead();
    });
  }

  void markClosed(error_code ec) {
    if (closed) return;
    closed = true;
    if (ec == websocket::error::closed) {
      closeCode = ws.reason().code;
      closeReason.assign(ws.reason().reason.data(), ws.reason().reason.size());
    } else {
      closeReason = ec.message();
    }
  }

  core::Status write(std::span<const std::uint8_t> message, bool text) {
    if (closed) return clientError(options, "connection closed: " + closeReason);
    startRead();
    bool done = false;
    error_code result;
    ws.text(text);
    ws.async_write(asio::buffer(message.data(), message.size()), [&](error_code ec, std::size_t) {
      done = true;
      result = ec;
    });
    if (!runUntil(ioc, [&] { return done; }, options.timeout)) {
      beast::get_lowest_layer(ws).close();
      runUntil(ioc, [&] { return done; }, std::chrono::milliseconds(1000));
      markClosed(beast::error::timeout);
      return clientError(options, "send timed out");
    }
    if (result) {
      // The server may have closed at the frame's header while the rest was still going out: let
      // the pending read see its close frame first, so the close code and reason are the server's.
      runUntil(ioc, [&] { return !reading; }, std::chrono::milliseconds(1000));
      markClosed(result);
      return clientError(options, "send failed: " + result.message());
    }
    return core::Ok{};
  }
};

WsClient::WsClient(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

WsClient::~WsClient() {
  if (impl_) beast::get_lowest_layer(impl_->ws).close();
}

core::Result<std::unique_ptr<WsClient>> WsClient::connect(const WsClientOptions& options) {
  auto impl = std::make_unique<Impl>(options);
  Impl& c = *impl;
  c.ws.read_message_max(options.maxMessageBytes);
  c.ws.binary(true);

  tcp::resolver resolver(c.ioc);
  bool done = false;
  error_code result;
  resolver.async_resolve(options.host, std::to_string(options.port),
                         [&](error_code ec, tcp::resolver::results_type endpoints) {
                           if (ec) {
                             done = true;
                             result = ec;
                             return;
                           }
                           beast::get_lowest_layer(c.ws).expires_after(options.timeout);
                           beast::get_lowest_layer(c.ws).async_connect(endpoints, [&](error_code ec2, const tcp::endpoint&) {
                             if (ec2) {
                               done = true;
                               result = ec2;
                               return;
                             }
                             beast::get_lowest_layer(c.ws).expires_never();
                             c.ws.set_option(websocket::stream_base::timeout::suggested(beast::role_type::client));
                             c.ws.async_handshake(options.host + ":" + std::to_string(options.port), options.path,
                                                  [&](error_code ec3) {
                                                    done = true;
                                                    result = ec3;
                                                  });
                           });
                         });
  if (!runUntil(c.ioc, [&] { return done; }, options.timeout + std::chrono::milliseconds(500))) {
    resolver.cancel();
    beast::get_lowest_layer(c.ws).close();
    runUntil(c.ioc, [&] { return done; }, std::chrono::milliseconds(1000));
    return clientError(options, "connect timed out");
  }
  if (result) return clientError(options, "cannot connect: " + result.message());
  c.startRead();
  return std::unique_ptr<WsClient>(new WsClient(std::move(impl)));
}

core::Status WsClient::send(std::span<const std::uint8_t> message) { return impl_->write(message, false); }

core::Status WsClient::sendText(std::string_view text) {
  return impl_->write(std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()), true);
}

ClientEvent WsClient::receive(std::chrono::milliseconds timeout) {
  Impl& c = *impl_;
  c.startRead();
  runUntil(c.ioc, [&] { return !c.inbox.empty() || c.closed; }, timeout);
  ClientEvent event;
  if (!c.inbox.empty()) {
    event.kind = ClientEvent::Kind::Message;
    event.message = std::move(c.inbox.front());
    c.inbox.pop_front();
  } else if (c.closed) {
    event.kind = ClientEvent::Kind::Closed;
    event.closeCode = c.closeCode;
    event.closeReason = c.closeReason;
  }
  return event;
}

std::size_t WsClient::poll() {
  Impl& c = *impl_;
  c.startRead();
  if (c.ioc.stopped()) c.ioc.restart();
  c.ioc.poll();
  return c.inbox.size();
}

bool WsClient::isOpen() const { return !impl_->closed; }

void WsClient::close(std::string_view reason) {
  Impl& c = *impl_;
  if (c.closed) return;
  c.startRead();
  bool done = false;
  websocket::close_reason why(websocket::close_code::normal);
  why.reason = std::string(reason.substr(0, 123));
  c.ws.async_close(why, [&](error_code) { done = true; });
  if (!runUntil(c.ioc, [&] { return done && !c.reading; }, c.options.timeout)) {
    beast::get_lowest_layer(c.ws).close();
    runUntil(c.ioc, [&] { return done && !c.reading; }, std::chrono::milliseconds(1000));
  }
  c.closed = true;
  if (c.closeReason.empty()) c.closeReason = "closed by client";
}

}  // namespace throng::client
