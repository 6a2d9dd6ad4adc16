// Tests for libs/client/src/http_client.cpp against a one-shot TCP peer that writes a canned
// HTTP/1.1 response: status, Content-Type, Content-Length and body come back, the request line
// carries the method and the target as given, HEAD reads no body, and a refused connection or a
// silent peer is a diagnostic naming the URL.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>

#include "throng/client/http_client.hpp"
#include "throng/net/asio.hpp"

namespace throng::client {
namespace {
using namespace std::chrono_literals;
using namespace throng::net;

/// Accepts one connection on 127.0.0.1, reads the request head, answers `response` (if any).
struct OneShotServer {
  asio::io_context ioc;
  tcp::acceptor acceptor{ioc, tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0)};
  std::string request;
  std::thread thread;

  explicit OneShotServer(std::string response) {
    thread = std::thread([this, response = std::move(response)] {
      tcp::socket socket(ioc);
      acceptor.accept(socket);
      asio::streambuf buffer;
      error_code ec;
      asio::read_until(socket, buffer, "\r\n\r\n", ec);
      request.assign(asio::buffers_begin(buffer.data()), asio::buffers_end(buffer.data()));
      if (response.empty()) {
        std::this_thread::sleep_for(600ms);  // say nothing past the client's timeout
        return;
      }
      asio::write(socket, asio::buffer(response), ec);
      socket.shutdown(tcp::socket::shutdown_both, ec);
    });
  }
  ~OneShotServer() { finish(); }
  /// Waits for the peer's thread; the request it read.
  const std::string& finish() {
    if (thread.joinable()) thread.join();
    return request;
  }
  std::uint16_t port() const { return acceptor.local_endpoint().port(); }
};

TEST(HttpRequest, ReadsStatusHeadersAndBody) {
  OneShotServer server("HTTP/1.1 404 Not Found\r\nContent-Type: text/plain\r\nContent-Length: 5\r\n\r\nnope!");
  auto reply = httpRequest("127.0.0.1", server.port(), "GET", "/a%2Fb?x=1", 2000ms);
  ASSERT_TRUE(reply.ok()) << reply.errors().front().what;
  EXPECT_EQ(reply.value().status, 404u);
  EXPECT_EQ(reply.value().contentType, "text/plain");
  EXPECT_EQ(reply.value().contentLength, 5u);
  EXPECT_EQ(reply.value().body, "nope!");
  const std::string& request = server.finish();
  EXPECT_EQ(request.rfind("GET /a%2Fb?x=1 HTTP/1.1\r\n", 0), 0u) << request;
}

TEST(HttpRequest, HeadReadsTheLengthButNoBody) {
  OneShotServer server("HTTP/1.1 200 OK\r\nContent-Type: application/json\r\nContent-Length: 1234\r\n\r\n");
  auto reply = httpRequest("127.0.0.1", server.port(), "HEAD", "/api/status", 2000ms);
  ASSERT_TRUE(reply.ok()) << reply.errors().front().what;
  EXPECT_EQ(reply.value().status, 200u);
  EXPECT_EQ(reply.value().contentLength, 1234u);
  EXPECT_TRUE(reply.value().body.empty());
}

TEST(HttpRequest, ASilentPeerTimesOut) {
  OneShotServer server("");
  auto reply = httpRequest("127.0.0.1", server.port(), "GET", "/slow", 200ms);
  ASSERT_FALSE(reply.ok());
  // The stream's own deadline fires first ("GET failed: ... timeout"); the outer one says
  // "request timed out".
  EXPECT_NE(reply.errors().front().what.find("time"), std::string::npos) << reply.errors().front().what;
  EXPECT_EQ(reply.errors().front().source, "http://127.0.0.1:" + std::to_string(server.port()) + "/slow");
}

TEST(HttpRequest, ARefusedConnectionIsADiagnostic) {
  std::uint16_t closedPort = 0;
  {
    asio::io_context ioc;
    tcp::acceptor probe(ioc, tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
    closedPort = probe.local_endpoint().port();
  }  // closed again: nobody listens there now
  auto reply = httpRequest("127.0.0.1", closedPort, "GET", "/", 2000ms);
  ASSERT_FALSE(reply.ok());
  EXPECT_EQ(reply.errors().front().what.rfind("GET failed: ", 0), 0u) << reply.errors().front().what;
}

}  // namespace
}  // namespace throng::client
