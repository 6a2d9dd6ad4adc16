// throng::transport::detail::HttpSession — one TCP connection before (or instead of) a WebSocket
// upgrade: reads HTTP/1.1 requests (keep-alive), answers GET/HEAD from /health, the dynamic hook
// and the static root, hands POST to the POST hook (PostState: its pending answer) and an upgrade
// on /ws to a new WsPeer.
#pragma once
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "throng/net/asio.hpp"
#include "throng/transport/transport.hpp"

namespace throng::transport::detail {
using namespace throng::net;  // asio::, beast::, tcp, udp, error_code

class TransportImpl;
class HttpSession;

/// One POST waiting for its answer (HttpResponder's shared state). Holds the session until then.
struct PostState {
  std::atomic<int> cancelled{0};
  std::atomic<bool> answered{false};
  std::shared_ptr<HttpSession> session;  ///< reset by the answer
  /// Answers 500 when the last responder goes without an answer.
  ~PostState();
  /// The first call hands `response` to the session's executor; later calls do nothing.
  void answer(HttpResponse response);
};

class HttpSession final : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(TransportImpl& transport, tcp::socket&& socket);
  void start();
  /// Any thread: drop the connection.
  void requestClose();

 private:
  friend struct PostState;
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
  /// Hands a POST to TransportOptions::postHandler and watches for the client hanging up.
  void handlePost(const Reply& reply, http::request<http::string_body>&& request);
  /// Readable socket while a POST is pending: nothing to read means the client has gone.
  void watchForHangUp();
  /// On the executor: the POST hook's answer.
  void sendPostAnswer(HttpResponse response);
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
  std::weak_ptr<PostState> pending_;  ///< the POST waiting for its answer
  Reply postReply_;
  bool done_ = false;
};

/// Accepted path of the WebSocket endpoint.
inline constexpr std::string_view kWebSocketPath = "/ws";

}  // namespace throng::transport::detail
