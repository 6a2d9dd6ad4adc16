// Tests for libs/client/src/ws_client.cpp against a one-connection Beast WebSocket peer: a binary
// message goes out and comes back in order, the peer's close code and reason are reported after
// the messages before it, and connecting where nobody listens is a diagnostic.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "throng/client/ws_client.hpp"
#include "throng/net/asio.hpp"

namespace throng::client {
namespace {
using namespace std::chrono_literals;
using namespace throng::net;

TEST(WsClient, SendsReceivesAndReportsThePeersClose) {
  asio::io_context ioc;
  tcp::acceptor acceptor(ioc, tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
  std::thread peer([&] {
    tcp::socket socket(ioc);
    acceptor.accept(socket);
    websocket::stream<tcp::socket> ws(std::move(socket));
    ws.accept();
    beast::flat_buffer buffer;
    ws.read(buffer);  // the client's message, echoed twice
    ws.binary(true);
    ws.write(buffer.data());
    ws.write(buffer.data());
    ws.close(websocket::close_reason(websocket::close_code::policy_error, "enough"));
    error_code ec;
    while (!ec) ws.read(buffer, ec);  // until the client's close answer
  });

  WsClientOptions options;
  options.port = acceptor.local_endpoint().port();
  auto connected = WsClient::connect(options);
  ASSERT_TRUE(connected.ok()) << connected.errors().front().what;
  WsClient& client = *connected.value();
  const std::vector<std::uint8_t> message{1, 2, 3, 250};
  ASSERT_TRUE(client.send(message).ok());
  for (int i = 0; i < 2; ++i) {
    const ClientEvent e = client.receive(5s);
    ASSERT_EQ(e.kind, ClientEvent::Kind::Message);
    EXPECT_EQ(e.message, message);
  }
  const ClientEvent closed = client.receive(5s);
  EXPECT_EQ(closed.kind, ClientEvent::Kind::Closed);
  EXPECT_EQ(closed.closeCode, static_cast<std::uint16_t>(websocket::close_code::policy_error));
  EXPECT_EQ(closed.closeReason, "enough");
  EXPECT_FALSE(client.isOpen());
  peer.join();
}

TEST(WsClient, ConnectingWhereNobodyListensIsADiagnostic) {
  std::uint16_t closedPort = 0;
  {
    asio::io_context ioc;
    tcp::acceptor probe(ioc, tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
    closedPort = probe.local_endpoint().port();
  }
  WsClientOptions options;
  options.port = closedPort;
  options.timeout = 2000ms;
  auto connected = WsClient::connect(options);
  ASSERT_FALSE(connected.ok());
  EXPECT_NE(connected.errors().front().source.find(std::to_string(closedPort)), std::string::npos) << connected.errors().front().source;
}

}  // namespace
}  // namespace throng::client
