// throng::transport::detail::HttpSession — one TCP connection before (or instead of) a WebSocket
// upgrade: reads HTTP/1.1 requests (keep-alive), answers GET/HEAD from /health, the dynamic hook
// and the static root, and hands an upgrade on /ws to a new WsPeer.
#pragma once
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "throng/net/asio.hpp"

namespace throng::transport::detail {
using namespace throng::net;  // asio::, beast::, tcp, udp, error_code

class TransportImpl;

class HttpSession final : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(TransportImpl& transport, tcp::socket&& socket);
  void start();
  /// Any thread: drop the connection.
  void requestClose();

 private:
  void doRead();
  void onRead(error_code ec, std::size_t bytes);
  /// How a request is answered: its HTTP version, keep-alive, and HEAD (headers only).
  struct Reply {
    unsigned version = 11;
    bool keepAlive = false;
    bool head = false;
  };
  /// One request: the /ws upgrade, 405, /health, the dynamic hook, then the static files.
  void handle(http::request<http::string_body>&& request);
  /// TransportOptions::httpHandler's answer, if it has one (a throwing hook answers 500).
  bool serveDynamic(const Reply& reply, std::string_view target);
  void sendFile(const Reply& reply, const std::filesystem::path& path, std::string_view contentType);
  void sendText(const Reply& reply, http::status status, std::string_view contentType, std::string body);
  void upgrade(http::request<http::string_body>&& request);
  template <class Body>
  void send(http::response<Body>&& response);
  void onWrite(bool close, error_code ec);
  void finish();

  TransportImpl& transport_;
  beast::tcp_stream stream_;
  asio::any_io_executor executor_;  // kept: stream_ is moved out on upgrade
  beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::string_body>> parser_;
  std::string remote_;
  std::uint64_t registration_ = 0;
  bool done_ = false;
};

/// Accepted path of the WebSocket endpoint.
inline constexpr std::string_view kWebSocketPath = "/ws";

}  // namespace throng::transport::detail
