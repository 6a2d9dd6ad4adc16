// Tests for libs/transport/src/ws_peer.cpp and transport.cpp over real WebSockets: echo, ordering,
// Latest replacement, the send-queue cut-off, oversized/text frames, rate limit, close reasons,
// shutdown, the peer limit, and thousands of connect/disconnect cycles leaving nothing behind.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <thread>

#include "test_handler.hpp"
#include "throng/client/http_client.hpp"
#include "throng/client/ws_client.hpp"

namespace throng::transport::test {
using client::ClientEvent;
using client::WsClient;
using client::WsClientOptions;
using client::httpRequest;
namespace {
using namespace std::chrono_literals;

struct Server {
  explicit Server(TransportOptions options = testOptions()) {
    auto started = Transport::start(std::move(options), handler);
    EXPECT_TRUE(started.ok()) << core::formatAll(started.errors());
    transport = std::move(started.value());
    handler.transport = transport.get();
  }
  std::unique_ptr<WsClient> connect() {
    WsClientOptions o;
    o.port = transport->httpPort();
    auto client = WsClient::connect(o);
    EXPECT_TRUE(client.ok()) << (client.ok() ? "" : core::formatAll(client.errors()));
    return client.ok() ? std::move(client.value()) : nullptr;
  }
  /// The id of the n-th opened peer (waits for it).
  PeerId peer(std::size_t n) {
    EXPECT_TRUE(handler.waitFor([&] { return handler.opened.size() > n; }));
    return handler.locked([&] { return handler.opened.at(n).peer; });
  }
  bool waitDrained() {
    for (int i = 0; i < 500; ++i) {
      const auto t = transport->totals();
      if (t.livePeers == 0 && t.liveHttpConnections == 0) return true;
      std::this_thread::sleep_for(10ms);
    }
    return false;
  }

  TestHandler handler;
  std::unique_ptr<Transport> transport;
};

std::vector<std::uint8_t> numbered(std::uint32_t n, std::size_t size = 4) {
  std::vector<std::uint8_t> m(size, 0);
  for (int i = 0; i < 4; ++i) m[i] = static_cast<std::uint8_t>(n >> (8 * i));
  return m;
}
std::uint32_t number(const std::vector<std::uint8_t>& m) {
  std::uint32_t n = 0;
  for (int i = 0; i < 4; ++i) n |= static_cast<std::uint32_t>(m.at(i)) << (8 * i);
  return n;
}

TEST(WebSocket, EchoOpenAndClose) {
  Server server;
  server.handler.echo = true;
  auto client = server.connect();
  ASSERT_TRUE(client);
  const PeerId id = server.peer(0);
  EXPECT_EQ(server.handler.locked([&] { return server.handler.opened[0].kind; }), PeerKind::WebSocket);
  EXPECT_EQ(server.handler.locked([&] { return server.handler.opened[0].remote.rfind("127.0.0.1:", 0); }), 0u);
  ASSERT_TRUE(client->send(bytes("hello")).ok());
  const ClientEvent event = client->receive(5s);
  ASSERT_EQ(event.kind, ClientEvent::Kind::Message);
  EXPECT_EQ(event.message, bytes("hello"));
  const auto stats = server.transport->stats(id);
  ASSERT_TRUE(stats);
  EXPECT_EQ(stats->messagesReceived, 1u);
  EXPECT_EQ(stats->bytesReceived, 5u);
  client->close("done here");
  EXPECT_TRUE(server.handler.waitFor([&] { return server.handler.closed.count(id.value) > 0; }));
  EXPECT_EQ(server.handler.locked([&] { return server.handler.closed[id.value]; }), "done here");
  EXPECT_FALSE(server.transport->stats(id));
  EXPECT_EQ(server.transport->send(id, bytes("late")), SendStatus::UnknownPeer);
}

TEST(WebSocket, ReliableMessagesArriveInOrder) {
  TransportOptions options = testOptions();
  options.maxQueueMessages = 4096;  // the whole burst is queued at once
  options.burstMessages = 1000;
  Server server(options);
  auto client = server.connect();
  ASSERT_TRUE(client);
  const PeerId id = server.peer(0);
  constexpr std::uint32_t kCount = 2000;
  for (std::uint32_t i = 0; i < kCount; ++i)
    ASSERT_EQ(server.transport->send(id, numbered(i, 4 + i % 300)), SendStatus::Queued);
  for (std::uint32_t i = 0; i < kCount; ++i) {
    const ClientEvent event = client->receive(5s);
    ASSERT_EQ(event.kind, ClientEvent::Kind::Message) << i;
    ASSERT_EQ(number(event.message), i);
    ASSERT_EQ(event.message.size(), 4 + i % 300);
  }
  // And the other way.
  for (std::uint32_t i = 0; i < 500; ++i) ASSERT_TRUE(client->send(numbered(i)).ok());  // within the rate limit's burst
  ASSERT_TRUE(server.handler.waitFor([&] { return server.handler.messages[id.value].size() == 500; }));
  server.handler.locked([&] {
    for (std::uint32_t i = 0; i < 500; ++i) EXPECT_EQ(number(server.handler.messages[id.value][i]), i);
    return 0;
  });
}

TEST(WebSocket, LatestReplacesUnsentStateAndKeepsOrder) {
  Server server;
  // A burst sent from the transport thread: everything after the first write queues behind it.
  server.handler.messageHook = [&](PeerId peer, std::span<const std::uint8_t>) {
    for (std::uint32_t i = 1; i <= 100; ++i) {
      server.transport->send(peer, numbered(i), SendClass::Latest, 0);
      if (i % 25 == 0) server.transport->send(peer, numbered(1000 + i), SendClass::Reliable);
    }
    server.transport->send(peer, numbered(9999), SendClass::Reliable);
  };
  auto client = server.connect();
  ASSERT_TRUE(client);
  const PeerId id = server.peer(0);
  ASSERT_TRUE(client->send(bytes("go")).ok());
  std::vector<std::uint32_t> got;
  while (got.empty() || got.back() != 9999) {
    const ClientEvent event = client->receive(5s);
    ASSERT_EQ(event.kind, ClientEvent::Kind::Message);
    got.push_back(number(event.message));
  }
  std::vector<std::uint32_t> latest, reliable;
  for (std::uint32_t n : got) (n <= 100 ? latest : reliable).push_back(n);
  EXPECT_EQ(reliable, (std::vector<std::uint32_t>{1025, 1050, 1075, 1100, 9999}));  // none lost
  ASSERT_FALSE(latest.empty());
  EXPECT_EQ(latest.back(), 100u);                     // the newest state arrives
  EXPECT_LT(latest.size(), 100u);                     // stale states were dropped
  // A subsequence of the send order: Latest i went out after i - 1 states and (i - 1) / 25 reliables.
  auto sendOrder = [](std::uint32_t n) { return n == 9999 ? 105u : n > 1000 ? (n - 1000) + (n - 1000) / 25 : n + (n - 1) / 25; };
  for (std::size_t k = 1; k < got.size(); ++k) EXPECT_LT(sendOrder(got[k - 1]), sendOrder(got[k])) << k;
  const auto stats = server.transport->stats(id);
  ASSERT_TRUE(stats);
  EXPECT_EQ(stats->droppedLatest + latest.size(), 100u);
  EXPECT_EQ(server.transport->totals().droppedLatest, stats->droppedLatest);
}

TEST(WebSocket, NeverReadingClientIsCutOffOthersGoOn) {
  TransportOptions options = testOptions();
  options.maxQueueMessages = 100000;  // the byte limit cuts: the reader's tiny messages never reach it
  options.maxQueueBytes = 512 * 1024;
  options.closeTimeout = 200ms;
  Server server(options);
  auto stalled = server.connect();  // never reads
  const PeerId stalledId = server.peer(0);  // onOpen order need not follow connect order: wait
  auto reader = server.connect();
  const PeerId readerId = server.peer(1);
  ASSERT_TRUE(stalled && reader);
  const std::vector<std::uint8_t> big(64 * 1024, 0xAB);
  std::uint32_t sentToReader = 0;
  for (int i = 0; i < 4000; ++i) {
    if (server.transport->send(stalledId, big) == SendStatus::UnknownPeer) break;
    server.transport->send(readerId, numbered(sentToReader++));
    server.handler.waitFor([&] { return server.handler.closed.count(stalledId.value) > 0; }, 1ms);
    reader->poll();
  }
  ASSERT_TRUE(server.handler.waitFor([&] { return server.handler.closed.count(stalledId.value) > 0; }));
  EXPECT_EQ(server.handler.locked([&] { return server.handler.closed[stalledId.value]; }), "send queue limit");
  // The other client still gets everything, in order, and more after the cut-off.
  for (int i = 0; i < 10; ++i) server.transport->send(readerId, numbered(sentToReader++));
  for (std::uint32_t i = 0; i < sentToReader; ++i) {
    const ClientEvent event = reader->receive(5s);
    ASSERT_EQ(event.kind, ClientEvent::Kind::Message) << i << " " << event.closeReason;
    ASSERT_EQ(number(event.message), i);
  }
  EXPECT_TRUE(server.transport->stats(readerId).has_value());
}

TEST(WebSocket, OversizedAndTextFramesCloseWithAReason) {
  TransportOptions options = testOptions();
  options.maxMessageBytes = 1000;
  Server server(options);
  auto big = server.connect();
  ASSERT_TRUE(big);
  (void)big->send(std::vector<std::uint8_t>(3000, 1));
  ClientEvent event = big->receive(5s);
  ASSERT_EQ(event.kind, ClientEvent::Kind::Closed);
  EXPECT_EQ(event.closeReason, "message too large");
  EXPECT_EQ(event.closeCode, 1009);

  auto text = server.connect();
  ASSERT_TRUE(text);
  (void)text->sendText("{\"hello\":1}");
  event = text->receive(5s);
  ASSERT_EQ(event.kind, ClientEvent::Kind::Closed);
  EXPECT_EQ(event.closeReason, "text frame: binary messages only");
  EXPECT_EQ(event.closeCode, 1003);
  EXPECT_TRUE(server.handler.waitFor([&] { return server.handler.closeCount == 2; }));
  EXPECT_EQ(server.transport->send(server.peer(0), std::vector<std::uint8_t>(10)), SendStatus::UnknownPeer);

  auto ok = server.connect();
  ASSERT_TRUE(ok);
  EXPECT_EQ(server.transport->send(server.peer(2), std::vector<std::uint8_t>(1001)), SendStatus::TooLarge);
  EXPECT_EQ(server.transport->send(server.peer(2), std::vector<std::uint8_t>(1000)), SendStatus::Queued);
}

/// A raw TCP connection to the server with the WebSocket upgrade done by hand, to send frames no
/// WebSocket library would.
class RawWebSocket {
 public:
  explicit RawWebSocket(std::uint16_t port) {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in at{};
    at.sin_family = AF_INET;
    at.sin_port = htons(port);
    at.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    connected_ = fd_ >= 0 && ::connect(fd_, reinterpret_cast<sockaddr*>(&at), sizeof at) == 0;
  }
  ~RawWebSocket() {
    if (fd_ >= 0) ::close(fd_);
  }
  /// Sends the upgrade request; true when the answer is 101.
  bool upgrade() {
    const std::string request =
        "GET /ws HTTP/1.1\r\nHost: 127.0.0.1\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
        "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n";
    if (!connected_ || !write(std::vector<std::uint8_t>(request.begin(), request.end()))) return false;
    std::string answer;
    while (answer.find("\r\n\r\n") == std::string::npos) {
      const auto b = read(1, 5s);
      if (b.empty()) return false;
      answer += static_cast<char>(b[0]);
    }
    return answer.rfind("HTTP/1.1 101", 0) == 0;
  }
  void hangUp() {
    ::close(fd_);
    fd_ = -1;
  }
  bool write(const std::vector<std::uint8_t>& b) {
    return ::send(fd_, b.data(), b.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(b.size());
  }
  /// Up to `n` bytes, waiting at most `timeout` for each; fewer at the end of the stream.
  std::vector<std::uint8_t> read(std::size_t n, std::chrono::milliseconds timeout) {
    std::vector<std::uint8_t> out;
    while (out.size() < n) {
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, static_cast<int>(timeout.count())) <= 0) break;
      std::uint8_t c = 0;
      if (::recv(fd_, &c, 1, 0) != 1) break;
      out.push_back(c);
    }
    return out;
  }

 private:
  int fd_ = -1;
  bool connected_ = false;
};

TEST(WebSocket, AFrameDeclaringTooMuchIsRefusedBeforeItsPayload) {
  TransportOptions options = testOptions();
  options.maxMessageBytes = 1000;
  options.wsIdleTimeout = std::chrono::milliseconds(120000);  // no ping or idle close in the way
  Server server(options);
  RawWebSocket raw(server.transport->httpPort());
  ASSERT_TRUE(raw.upgrade());
  const PeerId id = server.peer(0);
  // FIN + binary, masked, 16-bit length 3000, the mask key, then 10 of the 3000 bytes only.
  std::vector<std::uint8_t> frame{0x82, 0xfe, 0x0b, 0xb8, 0x11, 0x22, 0x33, 0x44};
  frame.resize(frame.size() + 10, 0);
  ASSERT_TRUE(raw.write(frame));
  // A close frame at once: code 1009 and the reason.
  const std::string reason = "message too large";
  const auto close = raw.read(4 + reason.size(), 5s);
  ASSERT_EQ(close.size(), 4 + reason.size()) << "no close frame within 5 s: the header was not checked";
  EXPECT_EQ(close[0], 0x88);
  EXPECT_EQ(close[1], 2 + reason.size());
  EXPECT_EQ(close[2], 0x03);
  EXPECT_EQ(close[3], 0xf1);
  EXPECT_EQ(std::string(close.begin() + 4, close.end()), reason);
  ASSERT_TRUE(server.handler.waitFor([&] { return server.handler.closed.count(id.value) > 0; }));
  EXPECT_EQ(server.handler.locked([&] { return server.handler.closed[id.value]; }), reason);
  EXPECT_TRUE(server.handler.locked([&] { return server.handler.messages.empty(); }));
}

TEST(WebSocket, AFrameDeclaringAHugeLengthIsClosedAtItsHeader) {
  TransportOptions options = testOptions();
  options.wsIdleTimeout = std::chrono::milliseconds(120000);  // no ping or idle close in the way
  Server server(options);
  RawWebSocket raw(server.transport->httpPort());
  ASSERT_TRUE(raw.upgrade());
  const PeerId id = server.peer(0);
  // FIN + binary, masked, 64-bit length 2^63 - 1, the mask key; and no payload at all.
  ASSERT_TRUE(raw.write({0x82, 0xff, 0x7f, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0x11, 0x22, 0x33, 0x44}));
  // The answer is a close frame: FIN + close, 2 bytes, code 1009 (message too big).
  const auto close = raw.read(4, 5s);
  ASSERT_EQ(close.size(), 4u) << "no close frame within 5 s: the header was not checked";
  EXPECT_EQ(close, (std::vector<std::uint8_t>{0x88, 0x02, 0x03, 0xf1}));
  EXPECT_TRUE(raw.read(1, 5s).empty());  // then the server ends its side of the stream
  raw.hangUp();  // as a client does after a close frame
  ASSERT_TRUE(server.handler.waitFor([&] { return server.handler.closed.count(id.value) > 0; }));
  EXPECT_EQ(server.handler.locked([&] { return server.handler.closed[id.value]; }), "message too large");
  EXPECT_TRUE(server.handler.locked([&] { return server.handler.messages.empty(); }));
}

TEST(WebSocket, RateLimitClosesTheFloodingPeer) {
  TransportOptions options = testOptions();
  options.messagesPerSecond = 1.0;
  options.burstMessages = 5.0;
  Server server(options);
  auto client = server.connect();
  ASSERT_TRUE(client);
  const PeerId id = server.peer(0);
  for (int i = 0; i < 50; ++i)
    if (!client->send(numbered(i)).ok()) break;
  ClientEvent event;
  do event = client->receive(5s);
  while (event.kind == ClientEvent::Kind::Message);
  ASSERT_EQ(event.kind, ClientEvent::Kind::Closed);
  EXPECT_EQ(event.closeReason, "rate limit");
  ASSERT_TRUE(server.handler.waitFor([&] { return server.handler.closed.count(id.value) > 0; }));
  EXPECT_EQ(server.handler.locked([&] { return server.handler.closed[id.value]; }), "rate limit");
  EXPECT_LE(server.handler.locked([&] { return server.handler.messages[id.value].size(); }), 6u);
}

TEST(WebSocket, ServerCloseFlushesThenSendsTheReason) {
  Server server;
  auto client = server.connect();
  ASSERT_TRUE(client);
  const PeerId id = server.peer(0);
  server.transport->send(id, bytes("last words"));
  server.transport->close(id, std::string(300, 'x'));  // truncated to 123 bytes
  ClientEvent event = client->receive(5s);
  ASSERT_EQ(event.kind, ClientEvent::Kind::Message);
  EXPECT_EQ(event.message, bytes("last words"));
  event = client->receive(5s);
  ASSERT_EQ(event.kind, ClientEvent::Kind::Closed);
  EXPECT_EQ(event.closeReason, std::string(123, 'x'));
  EXPECT_EQ(event.closeCode, 1000);
}

TEST(WebSocket, ShutdownSendsTheReasonToEveryClient) {
  Server server;
  std::vector<std::unique_ptr<WsClient>> clients;
  for (int i = 0; i < 3; ++i) clients.push_back(server.connect());
  server.peer(2);
  std::thread stopper([&] { server.transport->shutdown("maintenance"); });
  for (auto& client : clients) {
    ASSERT_TRUE(client);
    const ClientEvent event = client->receive(5s);
    ASSERT_EQ(event.kind, ClientEvent::Kind::Closed);
    EXPECT_EQ(event.closeReason, "maintenance");
    EXPECT_EQ(event.closeCode, 1001);
  }
  stopper.join();
  EXPECT_EQ(server.handler.closeCount, 3u);
  for (const auto& [id, reason] : server.handler.closed) EXPECT_EQ(reason, "maintenance");
  EXPECT_EQ(server.transport->totals().livePeers, 0u);
  EXPECT_EQ(server.transport->send(PeerId{1}, bytes("x")), SendStatus::ShuttingDown);
  server.transport->shutdown("again");  // idempotent
}

TEST(WebSocket, PeerLimitAnswers503) {
  TransportOptions options = testOptions();
  options.maxPeers = 2;
  Server server(options);
  auto a = server.connect();
  auto b = server.connect();
  ASSERT_TRUE(a && b);
  WsClientOptions o;
  o.port = server.transport->httpPort();
  auto c = WsClient::connect(o);
  EXPECT_FALSE(c.ok());
  a->close();
  ASSERT_TRUE(server.handler.waitFor([&] { return server.handler.closeCount == 1; }));
  for (int i = 0; i < 500 && server.transport->totals().livePeers != 1; ++i) std::this_thread::sleep_for(10ms);
  ASSERT_EQ(server.transport->totals().livePeers, 1u);
  EXPECT_TRUE(WsClient::connect(o).ok());
}

TEST(WebSocket, ThousandsOfConnectDisconnectCyclesLeaveNothingBehind) {
  Server server;
  server.handler.echo = true;
  constexpr int kCycles = 2000;
  WsClientOptions o;
  o.port = server.transport->httpPort();
  for (int i = 0; i < kCycles; ++i) {
    auto client = WsClient::connect(o);
    ASSERT_TRUE(client.ok()) << i;
    if (i % 3 == 0) {
      ASSERT_TRUE(client.value()->send(numbered(i)).ok());
      ASSERT_EQ(client.value()->receive(5s).kind, ClientEvent::Kind::Message);
    }
    if (i % 4 != 0) client.value()->close("cycle");  // every 4th just drops the socket
    if (i % 10 == 0) (void)httpRequest("127.0.0.1", o.port, "GET", "/health");
  }
  ASSERT_TRUE(server.waitDrained());
  ASSERT_TRUE(server.handler.waitFor([&] { return server.handler.closeCount == kCycles; }));
  const TransportTotals totals = server.transport->totals();
  EXPECT_EQ(totals.livePeers, 0u);
  EXPECT_EQ(totals.liveHttpConnections, 0u);
  EXPECT_EQ(totals.peersOpened, static_cast<std::uint64_t>(kCycles));
  EXPECT_EQ(totals.peersClosed, static_cast<std::uint64_t>(kCycles));
  EXPECT_EQ(server.handler.opened.size(), static_cast<std::size_t>(kCycles));
  // Ids are never reused.
  std::set<std::uint64_t> ids;
  for (const auto& o2 : server.handler.opened) ids.insert(o2.peer.value);
  EXPECT_EQ(ids.size(), static_cast<std::size_t>(kCycles));
}

}  // namespace
}  // namespace throng::transport::test
