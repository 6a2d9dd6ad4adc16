// Tests for libs/client/src/udp_client.cpp against a bare UDP socket standing in for the server:
// the UdpHello it sends decodes as the protocol's UdpHello (zero cookie first, then the server's
// cookie), a Cookie is answered and never handed to receive(), other datagrams are, and open()
// gives up with a diagnostic when no Cookie comes.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "throng/client/udp_client.hpp"
#include "throng/net/asio.hpp"
#include "throng/protocol/messages.hpp"

namespace throng::client {
namespace {
using namespace std::chrono_literals;
using namespace throng::net;

/// A UDP socket on 127.0.0.1 that the test drives by hand (blocking calls with a deadline).
struct FakeServer {
  asio::io_context ioc;
  udp::socket socket{ioc, udp::endpoint(asio::ip::make_address("127.0.0.1"), 0)};
  udp::endpoint client;

  std::uint16_t port() const { return socket.local_endpoint().port(); }
  std::vector<std::uint8_t> receive() {
    std::vector<std::uint8_t> buffer(65536);
    const std::size_t n = socket.receive_from(asio::buffer(buffer), client);
    buffer.resize(n);
    return buffer;
  }
  void send(const std::vector<std::uint8_t>& datagram) { socket.send_to(asio::buffer(datagram), client); }
};

protocol::UdpHello decodeUdpHello(const std::vector<std::uint8_t>& datagram) {
  auto decoded = protocol::decodeAny(datagram);
  EXPECT_TRUE(decoded.ok()) << (decoded.ok() ? "" : decoded.errors().front().what);
  if (!decoded.ok()) return {};
  const auto* hello = std::get_if<protocol::UdpHello>(&decoded.value());
  EXPECT_NE(hello, nullptr);
  return hello ? *hello : protocol::UdpHello{};
}

TEST(UdpClient, OpensWithTheCookieRoundTripAndKeepsCookiesFromReceive) {
  FakeServer server;
  auto connected = UdpClient::connect("127.0.0.1", server.port());
  ASSERT_TRUE(connected.ok());
  UdpClient& client = *connected.value();
  const protocol::Bytes hello = protocol::encode(protocol::Hello{protocol::kProtocolVersion, protocol::ClientKind::Native, "tester"});
  const protocol::CookieBytes cookie{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16};

  std::thread serverSide([&] {
    const protocol::UdpHello first = decodeUdpHello(server.receive());
    EXPECT_EQ(first.cookie, protocol::CookieBytes{});  // no cookie yet
    EXPECT_EQ(first.hello.clientName, "tester");
    server.send(protocol::encode(protocol::Cookie{cookie}));
    protocol::UdpHello proven = decodeUdpHello(server.receive());
    while (proven.cookie == protocol::CookieBytes{}) proven = decodeUdpHello(server.receive());  // a resend
    EXPECT_EQ(proven.cookie, cookie);
    EXPECT_EQ(proven.hello.clientName, "tester");
    server.send(protocol::encode(protocol::Cookie{cookie}));  // answered, not delivered
    server.send({protocol::kMagic, 0x42});                     // delivered
  });
  ASSERT_TRUE(client.open(hello, 5s).ok());
  const auto message = client.receive(5s);
  serverSide.join();
  ASSERT_TRUE(message.has_value());
  EXPECT_EQ(*message, (std::vector<std::uint8_t>{protocol::kMagic, 0x42}));
  EXPECT_FALSE(client.receive(50ms).has_value());
  EXPECT_NE(client.localPort(), 0);
}

TEST(UdpClient, OpenFailsWithoutACookieAndRefusesAShortFirstMessageOrAnEarlyReopen) {
  FakeServer silent;  // bound, never answers
  auto connected = UdpClient::connect("127.0.0.1", silent.port());
  ASSERT_TRUE(connected.ok());
  const protocol::Bytes hello = protocol::encode(protocol::Hello{});
  const auto timedOut = connected.value()->open(hello, 300ms);
  ASSERT_FALSE(timedOut.ok());
  EXPECT_NE(timedOut.errors().front().what.find("no Cookie within 300 ms"), std::string::npos);
  EXPECT_NE(timedOut.errors().front().source.find("udp://127.0.0.1:"), std::string::npos);

  const std::vector<std::uint8_t> tooShort{protocol::kMagic};
  const auto refused = connected.value()->open(tooShort, 300ms);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.errors().front().expected.find("a Hello"), std::string::npos);

  auto fresh = UdpClient::connect("127.0.0.1", silent.port());
  ASSERT_TRUE(fresh.ok());
  const auto early = fresh.value()->reopen();
  ASSERT_FALSE(early.ok());
  EXPECT_EQ(early.errors().front().what, "reopen() before open()");
}

}  // namespace
}  // namespace throng::client
