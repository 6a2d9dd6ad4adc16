// `throng serve --udp-fragment 300` on scenarios/square.json (1000 agents): every crowd frame and
// the world description are larger than 300 bytes, so a native UDP client (throng::client::Session)
// only sees the crowd if the server's Fragment datagrams reassemble (docs/protocol.md "Fragment").
#include <gtest/gtest.h>

#include <csignal>
#include <chrono>
#include <regex>
#include <thread>

#include "cli_runner.hpp"
#include "throng/client/session.hpp"

namespace throng::e2e {
namespace {

using namespace std::chrono_literals;

TEST(ServeUdpFragment, AUdpClientGetsLargeCrowdFramesInFragments) {
  ScratchDir dir("serve-fragment");
  CliProcess server({"serve", std::string(THRONG_SOURCE_DIR) + "/scenarios/square.json", "--port", "0", "--udp-port", "0",
                     "--udp-fragment", "300"},
                    dir.path());
  const std::regex udp(R"(udp +127\.0\.0\.1:(\d+))");
  std::uint16_t udpPort = 0;
  for (int i = 0; i < 500 && udpPort == 0; ++i) {
    std::this_thread::sleep_for(20ms);
    const std::string out = server.outSoFar();
    std::smatch m;
    if (std::regex_search(out, m, udp)) udpPort = static_cast<std::uint16_t>(std::stoi(m[1]));
  }
  ASSERT_NE(udpPort, 0) << server.outSoFar();

  client::SessionOptions o;
  o.udp = true;
  o.udpPort = udpPort;
  o.name = "fragments";
  auto opened = client::Session::open(o);  // the Welcome itself comes in fragments
  ASSERT_TRUE(opened.ok()) << opened.errors().front().format();
  auto session = std::move(opened).value();
  EXPECT_GT(session->worldJson().size(), 300u);
  const auto end = std::chrono::steady_clock::now() + 1500ms;
  while (std::chrono::steady_clock::now() < end && session->pump(5ms)) {
  }
  const client::SessionStats& stats = session->stats();
  EXPECT_GT(stats.crowdFrames, 3u);
  EXPECT_GT(stats.keyFrames, 0u);
  EXPECT_GT(stats.agentsInView, 100u);  // far more than one 300-byte datagram could carry
  // Every datagram was at most 300 bytes, so the frames came in many of them.
  EXPECT_GT(stats.messagesReceived, 3 * stats.crowdFrames);
  EXPECT_LE(stats.bytesReceived, 300u * stats.messagesReceived);
  ASSERT_TRUE(session->crowd());
  EXPECT_EQ(session->crowd()->view.agents.size(), stats.agentsInView);

  session->close();
  server.signal(SIGINT);
  EXPECT_EQ(server.wait().exitCode, 130);
}

}  // namespace
}  // namespace throng::e2e
