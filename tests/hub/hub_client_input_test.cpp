// What the hub does with a message of a server → client type from a client (issue 15, item 9): it
// is refused from its type byte, before its body is read — a 534-byte CrowdFrame whose payload
// inflates to 16 MiB is never decompressed — and the client is closed with Bye "bad message".
#include <gtest/gtest.h>

#include <map>

#include "throng/hub/hub.hpp"
#include "throng/protocol/messages.hpp"

namespace throng::hub {
namespace {

using namespace protocol;

class Recorder : public Outbox {
 public:
  void send(PeerKey peer, std::vector<std::uint8_t> message, bool, std::uint32_t) override {
    sent[peer].push_back(std::move(message));
  }
  void close(PeerKey peer, std::string reason) override { closed[peer] = std::move(reason); }
  std::optional<LinkCounters> link(PeerKey) const override { return LinkCounters{}; }
  std::map<PeerKey, std::vector<Bytes>> sent;
  std::map<PeerKey, std::string> closed;
};

/// The Bye the hub sent to `peer` (fails the test when there is none).
Bye byeTo(const Recorder& out, PeerKey peer) {
  const auto it = out.sent.find(peer);
  if (it == out.sent.end()) {
    ADD_FAILURE() << "nothing sent to " << peer;
    return {};
  }
  for (const Bytes& b : it->second) {
    auto m = decodeAny(b);
    if (m.ok() && std::holds_alternative<Bye>(m.value())) return std::get<Bye>(m.value());
  }
  ADD_FAILURE() << "no Bye to " << peer;
  return {};
}

TEST(HubClientInput, ServerToClientTypesAreRefusedBeforeTheirBodyIsRead) {
  Recorder out;
  const MotionLibrary motions;
  Hub hub(HubOptions{}, R"({"name":"empty"})", 20.0f, motions, out);
  CrowdFrame bomb;
  bomb.header.compressed = true;
  bomb.header.frameNumber = 1;
  bomb.header.animationInterval = 1;
  bomb.payload.assign(kMaxCrowdPayload, 0);  // 16 MiB of zeros: about 530 bytes once compressed
  const Bytes bytes = encode(bomb);
  ASSERT_LT(bytes.size(), 1000u);
  Bytes corruptBytes = bytes;  // the same with its zstd frame cut short: decoding it fails at the payload
  corruptBytes.pop_back();
  ASSERT_EQ(decodeAny(corruptBytes).errors().front().pointer, "/CrowdFrame/payload");
  const Bytes& corrupt = corruptBytes;

  for (const Bytes* message : {&bytes, &corrupt}) {
    const PeerKey peer = message == &bytes ? 1 : 2;
    hub.onOpen(peer, "test", 0.0);
    hub.onMessage(peer, encode(Hello{kProtocolVersion, ClientKind::Native, "client"}), 0.0);
    hub.onMessage(peer, *message, 0.0);
    const Bye bye = byeTo(out, peer);
    EXPECT_EQ(bye.reason, ReasonCode::BadMessage);
    // The diagnostic is about the type byte (pointer /message/type), not about the payload.
    EXPECT_NE(bye.text.find("/message/type"), std::string::npos) << bye.text;
    EXPECT_NE(bye.text.find("CrowdFrame (type 17) is a server → client message"), std::string::npos) << bye.text;
    EXPECT_TRUE(out.closed.count(peer));
  }
  // A Welcome from a client likewise; a client → server message over its size bound too.
  hub.onOpen(3, "test", 0.0);
  hub.onMessage(3, encode(makeWelcome("evil", 20.0f, std::string(100000, ' '))), 0.0);
  EXPECT_NE(byeTo(out, 3).text.find("/message/type"), std::string::npos);
  hub.onOpen(4, "test", 0.0);
  Bytes longHello = encode(Hello{kProtocolVersion, ClientKind::Native, "x"});
  longHello.resize(kMaxClientMessageSize + 1);
  hub.onMessage(4, longHello, 0.0);
  EXPECT_NE(byeTo(out, 4).text.find("/message/size"), std::string::npos) << byeTo(out, 4).text;
}

}  // namespace
}  // namespace throng::hub
