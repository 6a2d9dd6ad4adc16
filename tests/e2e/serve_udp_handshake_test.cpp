// `throng serve` against hostile UDP sources (issue 15, item 7): empty datagrams, bare Hellos and
// junk from many source ports open no session, get no more bytes than they sent (a Welcome once went
// to any 7-byte Hello, a Bye to any junk, spoofable), and leave every /ws slot free; a native UDP client still connects
// (the cookie round trip of docs/protocol.md "Opening a UDP session").
#include <gtest/gtest.h>

#include <csignal>
#include <chrono>
#include <regex>
#include <thread>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "throng/client/session.hpp"
#include "throng/client/http_client.hpp"
#include "throng/client/udp_client.hpp"

namespace throng::e2e {
namespace {

using namespace std::chrono_literals;

TEST(ServeUdpHandshake, RawSourcesOpenNothingAndGetNoMoreThanTheySent) {
  ScratchDir dir("serve-udp-handshake");
  // --max-clients 2: 18 WebSocket slots (and 18 UDP ones); 60 sources once filled them all.
  CliProcess server({"serve", std::string(THRONG_SOURCE_DIR) + "/scenarios/museum.json", "--port", "0", "--udp-port", "0",
                     "--max-clients", "2"},
                    dir.path());
  const std::regex ws(R"(ws://127\.0\.0\.1:(\d+)/ws)"), udp(R"(udp +127\.0\.0\.1:(\d+))");
  std::uint16_t port = 0, udpPort = 0;
  for (int i = 0; i < 500 && (port == 0 || udpPort == 0); ++i) {
    std::this_thread::sleep_for(20ms);
    const std::string out = server.outSoFar();
    std::smatch m;
    if (std::regex_search(out, m, ws)) port = static_cast<std::uint16_t>(std::stoi(m[1]));
    if (std::regex_search(out, m, udp)) udpPort = static_cast<std::uint16_t>(std::stoi(m[1]));
  }
  ASSERT_NE(port, 0) << server.outSoFar();
  ASSERT_NE(udpPort, 0) << server.outSoFar();

  const protocol::Bytes bareHello = protocol::encode(protocol::Hello{protocol::kProtocolVersion, protocol::ClientKind::Native, "x"});
  ASSERT_EQ(bareHello.size(), 7u);
  std::vector<std::unique_ptr<client::UdpClient>> sources;
  for (int i = 0; i < 60; ++i) {
    auto c = client::UdpClient::connect("127.0.0.1", udpPort);
    ASSERT_TRUE(c.ok());
    sources.push_back(std::move(c).value());
    ASSERT_TRUE(sources.back()->send({}).ok());
    ASSERT_TRUE(sources.back()->send(bareHello).ok());
  }
  // And 20 that send 2 bytes of junk (an unknown type): once each was answered with a Bye.
  for (int i = 0; i < 20; ++i) {
    auto c = client::UdpClient::connect("127.0.0.1", udpPort);
    ASSERT_TRUE(c.ok());
    sources.push_back(std::move(c).value());
    ASSERT_TRUE(sources.back()->send(protocol::Bytes{0x54, 0xee}).ok());
  }
  // A WebSocket client gets in (no 503), and so does a native UDP client.
  client::SessionOptions o;
  o.port = port;
  o.udpPort = udpPort;
  o.name = "ws";
  auto wsSession = client::Session::open(o);
  ASSERT_TRUE(wsSession.ok()) << wsSession.errors().front().format();
  o.udp = true;
  o.name = "udp";
  auto udpSession = client::Session::open(o);
  ASSERT_TRUE(udpSession.ok()) << udpSession.errors().front().format();
  const auto end = std::chrono::steady_clock::now() + 1s;
  while (std::chrono::steady_clock::now() < end && (*udpSession)->pump(5ms)) {
  }
  EXPECT_GT((*udpSession)->stats().crowdFrames, 3u);
  // The sources sent at most 7 bytes each: nothing came back to any of them (no Welcome, no Bye).
  std::size_t received = 0;
  for (auto& s : sources) {
    while (auto d = s->receive(10ms)) received += d->size();
  }
  EXPECT_EQ(received, 0u) << "bytes sent to unproven UDP sources";
  // The server saw two clients, not 62.
  auto status = client::httpRequest("127.0.0.1", port, "GET", "/api/status");
  ASSERT_TRUE(status.ok());
  ASSERT_EQ(status->status, 200u) << status->body;
  const auto json = nlohmann::json::parse(status->body, nullptr, false);
  ASSERT_TRUE(json.is_object()) << status->body;
  EXPECT_EQ(json.value("clients", -1), 2) << status->body;

  (*wsSession)->close();
  (*udpSession)->close();
  server.signal(SIGINT);
  EXPECT_EQ(server.wait().exitCode, 130);
}

}  // namespace
}  // namespace throng::e2e
