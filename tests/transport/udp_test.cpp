// Tests for libs/transport/src/udp_endpoint.cpp: the cookie round trip that opens a peer (and what an
// unproven endpoint gets: never more bytes than it sent, never a peer), echo, size limits,
// keep-alives, idle timeout, rate limit, peers back to zero, UDP and WebSocket limits kept apart,
// and large messages going out as protocol Fragments (reassembled here with protocol::Reassembler).
#include <gtest/gtest.h>

#include <thread>

#include "test_handler.hpp"
#include "throng/protocol/fragments.hpp"
#include "throng/client/udp_client.hpp"
#include "throng/client/ws_client.hpp"

namespace throng::transport::test {
using client::UdpClient;
using client::WsClient;
using client::WsClientOptions;
namespace {
using namespace std::chrono_literals;

/// A Hello as a throng client's first message (any bytes do for the transport; ≥ 6 of them).
std::vector<std::uint8_t> hello(const std::string& name) {
  return protocol::encode(protocol::Hello{protocol::kProtocolVersion, protocol::ClientKind::Native, name});
}

struct UdpServer {
  explicit UdpServer(TransportOptions options = testOptions()) {
    auto started = Transport::start(std::move(options), handler);
    EXPECT_TRUE(started.ok()) << core::formatAll(started.errors());
    transport = std::move(started.value());
    handler.transport = transport.get();
  }
  /// A socket that has not opened a session.
  std::unique_ptr<UdpClient> raw() {
    auto client = UdpClient::connect("127.0.0.1", transport->udpPort());
    EXPECT_TRUE(client.ok());
    return client.ok() ? std::move(client.value()) : nullptr;
  }
  /// A client that went through the cookie round trip with `first` as its first message.
  std::unique_ptr<UdpClient> connect(const std::vector<std::uint8_t>& first = hello("client")) {
    auto client = raw();
    if (!client) return nullptr;
    const auto opened = client->open(first, 5s);
    EXPECT_TRUE(opened.ok()) << core::formatAll(opened.errors());
    return client;
  }
  /// Waits until the transport has answered, ignored (or opened a peer for) `n` datagrams of
  /// unproven endpoints.
  bool waitHandshakeDatagrams(std::uint64_t n) {
    for (int i = 0; i < 500; ++i) {
      const auto t = transport->totals();
      if (t.udpIgnored + t.udpCookiesSent + t.peersOpened >= n) return true;
      std::this_thread::sleep_for(10ms);
    }
    return false;
  }
  TestHandler handler;
  std::unique_ptr<Transport> transport;
};

/// Every byte `client` receives until nothing more comes for 200 ms.
std::size_t drain(UdpClient& client, std::size_t* datagrams = nullptr) {
  std::size_t total = 0;
  while (auto d = client.receive(200ms)) {
    total += d->size();
    if (datagrams) ++*datagrams;
  }
  return total;
}

TEST(Udp, CookieRoundTripOpensPeerAndEchoes) {
  UdpServer server;
  server.handler.echo = true;
  auto client = server.connect(hello("first"));
  ASSERT_TRUE(client);
  // The message inside the UdpHello is the peer's first message (and echoed).
  const auto first = client->receive(5s);
  ASSERT_TRUE(first);
  EXPECT_EQ(*first, hello("first"));
  ASSERT_EQ(server.handler.opened.size(), 1u);
  const auto opened = server.handler.locked([&] { return server.handler.opened[0]; });
  EXPECT_EQ(opened.kind, PeerKind::Udp);
  EXPECT_EQ(opened.remote, "127.0.0.1:" + std::to_string(client->localPort()));
  EXPECT_GE(server.transport->totals().udpCookiesSent, 1u);  // more if a Cookie was slow and the UdpHello resent
  // A repeated UdpHello (its answer was lost, the client thinks) is only a keep-alive now.
  ASSERT_TRUE(client->reopen().ok());
  ASSERT_TRUE(client->send(bytes("ping")).ok());
  const auto reply = client->receive(5s);
  ASSERT_TRUE(reply);
  EXPECT_EQ(*reply, bytes("ping"));
  // Same endpoint, same peer; a second client is a second peer.
  ASSERT_TRUE(client->send(bytes("again")).ok());
  ASSERT_TRUE(client->receive(5s));
  auto other = server.connect();
  ASSERT_TRUE(other->receive(5s));
  EXPECT_EQ(server.handler.locked([&] { return server.handler.opened.size(); }), 2u);
  const auto stats = server.transport->stats(opened.peer);
  ASSERT_TRUE(stats);
  EXPECT_EQ(stats->kind, PeerKind::Udp);
  EXPECT_EQ(stats->messagesReceived, 3u);  // first, ping, again: not the repeated UdpHello
  EXPECT_EQ(server.handler.locked([&] { return server.handler.messages[opened.peer.value].size(); }), 3u);
  EXPECT_EQ(server.transport->totals().liveUdpPeers, 2u);
}

TEST(Udp, UnprovenEndpointsOpenNothingAndGetNoMoreBytesThanTheySent) {
  UdpServer server;
  // What a throng server does on open: answer with something large (its Welcome).
  server.handler.openHook = [&](PeerId peer) { server.transport->send(peer, std::vector<std::uint8_t>(5000, 1)); };
  struct Probe {
    std::vector<std::uint8_t> datagram;
    std::size_t cookies;  // Cookie datagrams expected back
  };
  auto forged = protocol::encode(protocol::UdpHello{protocol::CookieBytes{1, 2, 3}, protocol::Hello{}});
  const std::vector<Probe> probes{
      {{}, 0},                                                            // empty datagram
      {hello("x"), 0},                                                    // a bare 7-byte Hello
      {bytes("garbage that is long enough to be anything at all"), 0},
      {protocol::encode(protocol::UdpHello{{}, protocol::Hello{}}), 1},   // no cookie yet: one Cookie
      {forged, 1},                                                        // a forged cookie: a new one
      {std::vector<std::uint8_t>(forged.begin(), forged.begin() + 23), 0},  // shorter than a UdpHello
  };
  std::vector<std::unique_ptr<UdpClient>> sockets;
  for (const Probe& p : probes) {
    sockets.push_back(server.raw());
    ASSERT_TRUE(sockets.back()->send(p.datagram).ok());
  }
  EXPECT_TRUE(server.waitHandshakeDatagrams(probes.size()));
  for (std::size_t i = 0; i < probes.size(); ++i) {
    SCOPED_TRACE(i);
    std::size_t datagrams = 0;
    const std::size_t got = drain(*sockets[i], &datagrams);
    EXPECT_LE(got, probes[i].datagram.size());
    EXPECT_EQ(datagrams, probes[i].cookies);
    EXPECT_EQ(got, probes[i].cookies * protocol::kCookieMessageSize);
  }
  const auto totals = server.transport->totals();
  EXPECT_EQ(totals.udpCookiesSent, 2u);
  EXPECT_EQ(totals.udpIgnored, 4u);
  EXPECT_EQ(totals.peersOpened, 0u);
  EXPECT_EQ(totals.liveUdpPeers, 0u);
  EXPECT_EQ(totals.bytesSent, 0u);
  EXPECT_TRUE(server.handler.locked([&] { return server.handler.opened.empty(); }));

  // A cookie is good for the endpoint it was issued to only.
  auto a = server.raw();
  ASSERT_TRUE(a->send(protocol::encode(protocol::UdpHello{{}, protocol::Hello{}})).ok());
  const auto cookieBytes = a->receive(5s);
  ASSERT_TRUE(cookieBytes);
  auto cookie = protocol::decodeAny(*cookieBytes);
  ASSERT_TRUE(cookie.ok());
  const protocol::CookieBytes aCookie = std::get<protocol::Cookie>(cookie.value()).cookie;
  auto b = server.raw();
  ASSERT_TRUE(b->send(protocol::encode(protocol::UdpHello{aCookie, protocol::Hello{}})).ok());
  const auto bAnswer = b->receive(5s);
  ASSERT_TRUE(bAnswer);
  EXPECT_EQ(bAnswer->size(), protocol::kCookieMessageSize);  // b gets its own cookie, no peer
  EXPECT_TRUE(server.handler.locked([&] { return server.handler.opened.empty(); }));
  // With it, a opens a peer.
  ASSERT_TRUE(a->send(protocol::encode(protocol::UdpHello{aCookie, protocol::Hello{}})).ok());
  ASSERT_TRUE(server.handler.waitFor([&] { return server.handler.opened.size() == 1; }));
  EXPECT_EQ(server.handler.locked([&] { return server.handler.opened[0].remote; }),
            "127.0.0.1:" + std::to_string(a->localPort()));
}

TEST(Udp, RawSourcesNeverTakeWebSocketSlotsAndUdpHasItsOwnLimit) {
  TransportOptions options = testOptions();
  options.maxPeers = 3;
  options.maxUdpPeers = 2;
  UdpServer server(options);
  // 40 source ports, each an empty datagram and a bare Hello: once all opened peers.
  std::vector<std::unique_ptr<UdpClient>> sources;
  for (int i = 0; i < 40; ++i) {
    sources.push_back(server.raw());
    ASSERT_TRUE(sources.back()->send({}).ok());
    ASSERT_TRUE(sources.back()->send(hello("x")).ok());
  }
  EXPECT_TRUE(server.waitHandshakeDatagrams(80));
  EXPECT_EQ(server.transport->totals().liveUdpPeers, 0u);
  // Proven UDP clients up to their own limit; one more is ignored.
  auto u1 = server.connect(), u2 = server.connect();
  ASSERT_TRUE(server.handler.waitFor([&] { return server.handler.opened.size() == 2; }));
  const auto ignoredBefore = server.transport->totals().udpIgnored;
  auto u3 = server.connect();
  for (int i = 0; i < 500 && server.transport->totals().udpIgnored == ignoredBefore; ++i) std::this_thread::sleep_for(10ms);
  EXPECT_GE(server.transport->totals().udpIgnored, ignoredBefore + 1);
  EXPECT_EQ(server.transport->totals().liveUdpPeers, 2u);
  // Every /ws slot is still free.
  WsClientOptions o;
  o.port = server.transport->httpPort();
  std::vector<std::unique_ptr<WsClient>> ws;
  for (int i = 0; i < 3; ++i) {
    auto c = WsClient::connect(o);
    ASSERT_TRUE(c.ok()) << "WebSocket " << i << ": " << core::formatAll(c.errors());
    ws.push_back(std::move(c).value());
  }
  EXPECT_FALSE(WsClient::connect(o).ok());  // the fourth: 503, the WebSocket limit
  EXPECT_EQ(server.transport->totals().liveWebSocketPeers, 3u);
}

TEST(Udp, SizeLimitsBothWays) {
  TransportOptions options = testOptions();
  options.maxDatagramBytes = 1200;
  options.udpFragmentBytes = 0;  // never fragment: over maxDatagramBytes is TooLarge
  UdpServer server(options);
  auto client = server.connect();
  ASSERT_TRUE(server.handler.waitFor([&] { return server.handler.opened.size() == 1; }));
  ASSERT_TRUE(client->send(std::vector<std::uint8_t>(1200, 7)).ok());
  ASSERT_TRUE(server.handler.waitFor([&] { return server.handler.messages.begin()->second.size() == 2; }));
  const PeerId id = server.handler.locked([&] { return server.handler.opened[0].peer; });
  EXPECT_EQ(server.transport->send(id, std::vector<std::uint8_t>(1201)), SendStatus::TooLarge);
  EXPECT_EQ(server.transport->send(id, std::vector<std::uint8_t>(1200)), SendStatus::Queued);
  ASSERT_TRUE(client->receive(5s));
  ASSERT_TRUE(client->send(std::vector<std::uint8_t>(1300, 7)).ok());
  ASSERT_TRUE(server.handler.waitFor([&] { return server.handler.closed.count(id.value) > 0; }));
  EXPECT_EQ(server.handler.locked([&] { return server.handler.closed[id.value]; }), "message too large");
  // A UdpHello over the limit opens nothing and gets nothing.
  const auto cookies = server.transport->totals().udpCookiesSent;
  auto big = server.raw();
  EXPECT_FALSE(big->open(std::vector<std::uint8_t>(1200, 0x54), 600ms).ok());
  EXPECT_EQ(server.transport->totals().udpCookiesSent, cookies);
}

TEST(Udp, LargeMessagesGoAsFragments) {
  TransportOptions options = testOptions();
  options.udpFragmentBytes = 300;
  UdpServer server(options);
  auto client = server.connect();
  ASSERT_TRUE(server.handler.waitFor([&] { return server.handler.opened.size() == 1; }));
  const PeerId id = server.handler.locked([&] { return server.handler.opened[0].peer; });
  // At or under the fragment size: one datagram, unchanged.
  const std::vector<std::uint8_t> small(300, 7);
  ASSERT_EQ(server.transport->send(id, small), SendStatus::Queued);
  const auto whole = client->receive(5s);
  ASSERT_TRUE(whole);
  EXPECT_EQ(*whole, small);
  // Over it: Fragment datagrams of at most 300 bytes that reassemble to the message, twice
  // (message ids 0 and 1).
  protocol::Reassembler reassembler;
  for (int round = 0; round < 2; ++round) {
    std::vector<std::uint8_t> big(5000);
    for (std::size_t i = 0; i < big.size(); ++i) big[i] = static_cast<std::uint8_t>(i * 7 + round);
    ASSERT_EQ(server.transport->send(id, big, SendClass::Latest, 1), SendStatus::Queued);
    std::optional<std::vector<std::uint8_t>> done;
    std::size_t datagrams = 0;
    while (!done) {
      const auto d = client->receive(5s);
      ASSERT_TRUE(d) << "fragment " << datagrams << " missing";
      ++datagrams;
      EXPECT_LE(d->size(), 300u);
      auto m = protocol::decodeAny(*d);
      ASSERT_TRUE(m.ok()) << core::formatAll(m.errors());
      const auto& f = std::get<protocol::Fragment>(m.value());
      EXPECT_EQ(f.messageId, static_cast<std::uint64_t>(round));
      auto got = reassembler.add(f);
      ASSERT_TRUE(got.ok()) << core::formatAll(got.errors());
      done = got.value();
    }
    EXPECT_EQ(*done, big);
    EXPECT_EQ(datagrams, (5000 + 292) / 293u);  // a 7-byte header: magic, type, id, 2-byte index and count
  }
  // Counted as messages, with the bytes of all their datagrams.
  for (int i = 0; i < 500 && server.transport->stats(id)->messagesSent < 3; ++i) std::this_thread::sleep_for(10ms);
  EXPECT_EQ(server.transport->stats(id)->messagesSent, 3u);
  EXPECT_GT(server.transport->stats(id)->bytesSent, 300u + 2 * 5000u);
  // Beyond what 8192 fragments carry: TooLarge.
  EXPECT_EQ(server.transport->send(id, std::vector<std::uint8_t>(protocol::maxFragmentedSize(300) + 1)), SendStatus::TooLarge);
}

TEST(Udp, IdlePeersTimeOutKeepAlivesKeepThem) {
  TransportOptions options = testOptions();
  options.udpIdleTimeout = 200ms;
  UdpServer server(options);
  auto idle = server.connect();
  ASSERT_TRUE(server.handler.waitFor([&] { return server.handler.opened.size() == 1; }));
  auto alive = server.connect();
  ASSERT_TRUE(server.handler.waitFor([&] { return server.handler.opened.size() == 2; }));
  const PeerId idleId = server.handler.locked([&] { return server.handler.opened[0].peer; });
  const PeerId aliveId = server.handler.locked([&] { return server.handler.opened[1].peer; });
  // The live one sends empty keep-alives until the idle one is gone.
  bool gone = false;
  for (int i = 0; i < 500 && !gone; ++i) {
    ASSERT_TRUE(alive->send({}).ok());
    gone = server.handler.waitFor([&] { return server.handler.closed.count(idleId.value) > 0; }, 20ms);
  }
  ASSERT_TRUE(gone);
  EXPECT_EQ(server.handler.locked([&] { return server.handler.closed[idleId.value]; }), "timeout");
  // (Not asserted: that the live peer is still open; a machine stalled past the timeout may close it too.)
  server.handler.locked([&] {
    EXPECT_EQ(server.handler.messages.size(), 2u);  // keep-alives are not delivered
    EXPECT_EQ(server.handler.messages[aliveId.value].size(), 1u);  // its first message only
    return 0;
  });
  // The forgotten endpoint is unproven again: a message opens nothing, a new round trip does.
  const std::string idleRemote = "127.0.0.1:" + std::to_string(idle->localPort());
  const auto ignored = server.transport->totals().udpIgnored;
  ASSERT_TRUE(idle->send(bytes("back")).ok());
  for (int i = 0; i < 500 && server.transport->totals().udpIgnored == ignored; ++i) std::this_thread::sleep_for(10ms);
  EXPECT_EQ(server.transport->totals().udpIgnored, ignored + 1);
  ASSERT_TRUE(idle->open(hello("back"), 5s).ok());
  ASSERT_TRUE(server.handler.waitFor([&] {
    for (const auto& o : server.handler.opened)
      if (o.remote == idleRemote && o.peer != idleId) return true;
    return false;
  }));
  // Everyone times out in the end.
  ASSERT_TRUE(server.handler.waitFor([&] { return server.handler.closed.size() == server.handler.opened.size(); }));
  EXPECT_EQ(server.transport->totals().livePeers, 0u);
}

TEST(Udp, RateLimitAndShutdown) {
  TransportOptions options = testOptions();
  options.messagesPerSecond = 1.0;
  options.burstMessages = 3.0;
  UdpServer server(options);
  auto flood = server.connect();
  for (int i = 0; i < 20; ++i) ASSERT_TRUE(flood->send(bytes("m")).ok());
  ASSERT_TRUE(server.handler.waitFor([&] { return server.handler.closed.size() >= 1; }));
  EXPECT_EQ(server.handler.locked([&] { return server.handler.closed.begin()->second; }), "rate limit");
  auto quiet = server.connect();
  ASSERT_TRUE(server.handler.waitFor([&] {
    for (const auto& o : server.handler.opened)
      if (!server.handler.closed.count(o.peer.value)) return true;
    return false;
  }));
  server.transport->shutdown("bye");
  EXPECT_EQ(server.transport->totals().livePeers, 0u);
  server.handler.locked([&] {
    EXPECT_EQ(server.handler.closed.size(), server.handler.opened.size());
    return 0;
  });
}

}  // namespace
}  // namespace throng::transport::test
