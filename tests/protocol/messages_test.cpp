// Decoding errors of throng::protocol's messages: every truncation of every golden message, bad
// magic, unknown type, over-long strings, trailing bytes, out-of-range enums — each a diagnostic
// naming the field and byte offset, never a crash.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "protocol_test_util.hpp"

namespace throng::protocol {
namespace {

std::vector<std::vector<std::uint8_t>> allGoldenBytes() {
  std::vector<std::vector<std::uint8_t>> out;
  for (const auto& [name, m] : test::goldenMessages()) out.push_back(encode(m));
  for (const bool c : {false, true}) {
    auto [k, d] = test::goldenCrowdFrames(c);
    out.push_back(k);
    out.push_back(d);
  }
  return out;
}

TEST(ProtocolMessages, EveryTruncationIsAnError) {
  for (const auto& bytes : allGoldenBytes()) {
    // A Fragment's payload is the rest of the datagram (a datagram arrives whole or not at all):
    // only cuts into its header or leaving no payload are errors.
    const bool fragment = bytes.size() > 1 && bytes[1] == static_cast<std::uint8_t>(MessageType::Fragment);
    const std::size_t cuts = fragment ? 7 : bytes.size();  // the golden Fragment's header is 6 bytes
    // A Presence's look (version 2) is optional: without its 2 bytes it is a version-1 Presence.
    const bool look = bytes.size() > 1 && bytes[1] == static_cast<std::uint8_t>(MessageType::Presence) &&
                      std::get<Presence>(decodeAny(bytes).value()).avatar.has_value();
    for (std::size_t n = 0; n < cuts; ++n) {
      auto r = decodeAny(std::span(bytes.data(), n));
      if (look && n == bytes.size() - 2) {
        ASSERT_TRUE(r) << core::formatAll(r.errors());
        EXPECT_FALSE(std::get<Presence>(r.value()).avatar.has_value());
        continue;
      }
      ASSERT_FALSE(r) << "prefix of " << n << " of " << bytes.size() << " bytes decoded";
      EXPECT_FALSE(r.errors().front().what.empty());
    }
  }
}

TEST(ProtocolMessages, TrailingBytesAreAnError) {
  auto bytes = encode(Ack{1, 2});
  bytes.push_back(0);
  auto r = decodeAny(bytes);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.errors()[0].pointer, "/Ack/end");
  EXPECT_NE(r.errors()[0].what.find("1 trailing bytes"), std::string::npos) << r.errors()[0].what;
}

TEST(ProtocolMessages, BadMagicAndUnknownType) {
  auto r = decodeAny(std::vector<std::uint8_t>{0x55, 1});
  ASSERT_FALSE(r);
  EXPECT_NE(r.errors()[0].what.find("bad magic"), std::string::npos);
  r = decodeAny(std::vector<std::uint8_t>{kMagic, 200});
  ASSERT_FALSE(r);
  EXPECT_NE(r.errors()[0].what.find("unknown message type 200"), std::string::npos);
  EXPECT_EQ(r.errors()[0].column, 2);  // 1-based byte offset
}

TEST(ProtocolMessages, OverlongNameNamesFieldAndOffset) {
  std::vector<std::uint8_t> b{kMagic, static_cast<std::uint8_t>(MessageType::Hello), 1, 0, 0, 200, 1};
  auto r = decodeAny(b);
  ASSERT_FALSE(r);
  const core::Diagnostic& d = r.errors()[0];
  EXPECT_EQ(d.pointer, "/Hello/clientName");
  EXPECT_EQ(d.column, 6);
  EXPECT_NE(d.what.find("string of 200 bytes too long at byte 5"), std::string::npos) << d.format();
  EXPECT_NE(d.expected.find("at most 64"), std::string::npos);
}

TEST(ProtocolMessages, OutOfRangeEnumsAreErrors) {
  auto bye = encode(Bye{ReasonCode::None, ""});
  bye[2] = 250;
  EXPECT_FALSE(decodeAny(bye));
  auto hello = encode(Hello{});
  hello[4] = 9;
  EXPECT_FALSE(decodeAny(hello));
}

TEST(ProtocolMessages, EncoderClampsStringsToTheLimits) {
  Hello h;
  h.clientName = std::string(500, 'x');
  auto r = decodeAny(encode(h));
  ASSERT_TRUE(r);
  EXPECT_EQ(std::get<Hello>(r.value()).clientName.size(), kMaxNameLength);
}

TEST(ProtocolMessages, MoveQuantizesToCentimetresAndTurns) {
  Move m{{Subject::Kind::Participant, 12}, 9, 1.234f, -0.006f, 100.0f, 3.5f};
  auto r = decodeAny(encode(m));
  ASSERT_TRUE(r);
  const Move& d = std::get<Move>(r.value());
  EXPECT_EQ(d.subject, m.subject);
  EXPECT_FLOAT_EQ(d.x, 1.23f);
  EXPECT_FLOAT_EQ(d.y, -0.01f);
  EXPECT_NEAR(d.yaw, 3.5f - 2.0f * 3.14159265f, 1e-3f);  // wrapped into [-π, π)
}

TEST(ProtocolMessages, WelcomeWorldRoundTrips) {
  const std::string world(5000, 'a');
  auto r = decodeAny(encode(makeWelcome("s", 25.0f, world)));
  ASSERT_TRUE(r);
  const Welcome& w = std::get<Welcome>(r.value());
  EXPECT_LT(w.world.size(), 100u);
  auto text = worldJson(w);
  ASSERT_TRUE(text);
  EXPECT_EQ(text.value(), world);
  Welcome bad = w;
  bad.world[bad.world.size() / 2] ^= 0xff;
  bad.worldSize += 1;
  EXPECT_FALSE(worldJson(bad));
}

TEST(ProtocolMessages, PeekTypeAndNames) {
  auto t = peekType(encode(Guide{1, 2}));
  ASSERT_TRUE(t);
  EXPECT_EQ(t.value(), MessageType::Guide);
  EXPECT_STREQ(messageTypeName(MessageType::CrowdFrame), "CrowdFrame");
  EXPECT_EQ(messageType(Message{Ack{}}), MessageType::Ack);
  EXPECT_STREQ(messageTypeName(MessageType::Presence), "Presence");
  EXPECT_STREQ(messageTypeName(MessageType::ReplayControl), "ReplayControl");
  EXPECT_STREQ(messageTypeName(MessageType::ReplayStatus), "ReplayStatus");
  EXPECT_STREQ(messageTypeName(static_cast<MessageType>(kMaxMessageType + 1)), "?");
  EXPECT_EQ(messageType(Message{Presence{}}), MessageType::Presence);
  EXPECT_EQ(messageType(Message{ReplayControl{}}), MessageType::ReplayControl);
  EXPECT_EQ(messageType(Message{ReplayStatus{}}), MessageType::ReplayStatus);
}

/// Sets the f64 at byte `at` of `bytes`.
void putF64(std::vector<std::uint8_t>& bytes, std::size_t at, double v) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &v, 8);
  for (int i = 0; i < 8; ++i) bytes[at + i] = static_cast<std::uint8_t>(bits >> (8 * i));
}

TEST(ProtocolMessages, PresenceFlagMustBeZeroOrOne) {
  auto b = encode(Presence{5, false, "Bo", std::nullopt});
  auto ok = decodeAny(b);
  ASSERT_TRUE(ok);
  EXPECT_FALSE(std::get<Presence>(ok.value()).present);
  EXPECT_EQ(std::get<Presence>(ok.value()).name, "Bo");
  b[3] = 2;  // header 2, varint id 1 byte, then the flag
  auto r = decodeAny(b);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.errors()[0].pointer, "/Presence/present");
  EXPECT_EQ(r.errors()[0].column, 4);
  EXPECT_NE(r.errors()[0].what.find("at byte 3"), std::string::npos) << r.errors()[0].format();
  // Names longer than kMaxNameLength: clamped by the encoder, refused by the decoder.
  auto longName = decodeAny(encode(Presence{1, true, std::string(100, 'n'), std::nullopt}));
  ASSERT_TRUE(longName);
  EXPECT_EQ(std::get<Presence>(longName.value()).name.size(), kMaxNameLength);
  std::vector<std::uint8_t> tooLong{kMagic, static_cast<std::uint8_t>(MessageType::Presence), 1, 1, 65};
  tooLong.resize(tooLong.size() + 65, 'x');
  auto t = decodeAny(tooLong);
  ASSERT_FALSE(t);
  EXPECT_EQ(t.errors()[0].pointer, "/Presence/name");
}

TEST(ProtocolMessages, PresenceCarriesTheLookInVersionTwoAndDecodesVersionOneMessages) {
  // Version 2: the look (Join's avatar) trails the name and survives the round trip.
  const Bytes withLook = encode(Presence{300, true, "Ada", 7});
  EXPECT_EQ(withLook, (Bytes{kMagic, 18, 0xac, 0x02, 1, 3, 'A', 'd', 'a', 7, 0}));
  auto look = decodeAny(withLook);
  ASSERT_TRUE(look) << core::formatAll(look.errors());
  EXPECT_EQ(std::get<Presence>(look.value()).avatar, std::optional<std::uint16_t>(7));
  EXPECT_EQ(std::get<Presence>(look.value()).name, "Ada");
  EXPECT_EQ(encode(look.value()), withLook);
  // A version-1 Presence (what a version-1 server sends, and this one sends version-1 clients):
  // the name ends the message, and it still decodes, without a look.
  const Bytes old{kMagic, 18, 0xac, 0x02, 0, 3, 'A', 'd', 'a'};
  auto v1 = decodeAny(old);
  ASSERT_TRUE(v1) << core::formatAll(v1.errors());
  EXPECT_FALSE(std::get<Presence>(v1.value()).avatar.has_value());
  EXPECT_FALSE(std::get<Presence>(v1.value()).present);
  EXPECT_EQ(encode(Presence{300, false, "Ada", std::nullopt}), old);
  // One byte of a look is not a look; a byte after it is one too many.
  Bytes half = old;
  half.push_back(7);
  auto h = decodeAny(half);
  ASSERT_FALSE(h);
  EXPECT_EQ(h.errors()[0].pointer, "/Presence/avatar");
  Bytes extra = withLook;
  extra.push_back(0);
  EXPECT_FALSE(decodeAny(extra));
}

TEST(ProtocolMessages, ReplayControlChecksCommandAndValue) {
  constexpr std::size_t kCommandAt = 2 + 8, kValueAt = kCommandAt + 1;
  auto check = [](ReplayCommand c, double v) { return decodeAny(encode(ReplayControl{0, c, v})); };
  EXPECT_TRUE(check(ReplayCommand::Play, 0.0));
  EXPECT_TRUE(check(ReplayCommand::Pause, 0.0));
  EXPECT_TRUE(check(ReplayCommand::Seek, 0.0));
  EXPECT_TRUE(check(ReplayCommand::Seek, 1e6));
  EXPECT_TRUE(check(ReplayCommand::Speed, 0.25));
  EXPECT_TRUE(check(ReplayCommand::Speed, 64.0));
  for (const auto& [c, v] : std::vector<std::pair<ReplayCommand, double>>{
           {ReplayCommand::Play, 1.0}, {ReplayCommand::Pause, -0.5},
           {ReplayCommand::Seek, -1.0}, {ReplayCommand::Seek, std::nan("")},
           {ReplayCommand::Seek, HUGE_VAL}, {ReplayCommand::Speed, 0.0},
           {ReplayCommand::Speed, -1.0}, {ReplayCommand::Speed, 64.5},
           {ReplayCommand::Speed, std::nan("")}}) {
    auto r = check(c, v);
    ASSERT_FALSE(r) << static_cast<int>(c) << " " << v;
    EXPECT_EQ(r.errors()[0].pointer, "/ReplayControl/value");
    EXPECT_EQ(r.errors()[0].column, static_cast<int>(kValueAt + 1));
    EXPECT_FALSE(r.errors()[0].expected.empty());
  }
  auto b = encode(ReplayControl{7, ReplayCommand::Play, 0.0});
  b[kCommandAt] = 4;
  auto r = decodeAny(b);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.errors()[0].pointer, "/ReplayControl/command");
  EXPECT_NE(r.errors()[0].what.find("unknown replay command 4 at byte 10"), std::string::npos) << r.errors()[0].format();
  auto ok = check(ReplayCommand::Seek, 3.25);
  ASSERT_TRUE(ok);
  EXPECT_EQ(std::get<ReplayControl>(ok.value()).value, 3.25);
  EXPECT_EQ(std::get<ReplayControl>(ok.value()).command, ReplayCommand::Seek);
}

TEST(ProtocolMessages, ReplayStatusChecksTimesFlagAndSpeed) {
  const ReplayStatus good{1.5, 10.0, false, 0.5f};
  auto ok = decodeAny(encode(good));
  ASSERT_TRUE(ok);
  const auto& s = std::get<ReplayStatus>(ok.value());
  EXPECT_EQ(s.time, 1.5);
  EXPECT_EQ(s.duration, 10.0);
  EXPECT_FALSE(s.playing);
  EXPECT_EQ(s.speed, 0.5f);
  auto expectError = [](const std::vector<std::uint8_t>& b, const char* pointer, int column) {
    auto r = decodeAny(b);
    ASSERT_FALSE(r) << pointer;
    EXPECT_EQ(r.errors()[0].pointer, pointer);
    EXPECT_EQ(r.errors()[0].column, column);
  };
  auto b = encode(good);
  putF64(b, 2, -0.1);
  expectError(b, "/ReplayStatus/time", 3);
  b = encode(good);
  putF64(b, 10, std::nan(""));
  expectError(b, "/ReplayStatus/duration", 11);
  b = encode(good);
  b[18] = 2;
  expectError(b, "/ReplayStatus/playing", 19);
  expectError(encode(ReplayStatus{0, 0, true, 0.0f}), "/ReplayStatus/speed", 20);
  expectError(encode(ReplayStatus{0, 0, true, -1.0f}), "/ReplayStatus/speed", 20);
  expectError(encode(ReplayStatus{0, 0, true, HUGE_VALF}), "/ReplayStatus/speed", 20);
}

TEST(ProtocolMessages, CrowdRequestsCheckLimitsAndFlag) {
  EXPECT_STREQ(messageTypeName(MessageType::InsertCrowd), "InsertCrowd");
  EXPECT_STREQ(messageTypeName(MessageType::RemoveCrowd), "RemoveCrowd");
  EXPECT_STREQ(messageTypeName(MessageType::CrowdResult), "CrowdResult");
  EXPECT_EQ(messageType(Message{InsertCrowd{}}), MessageType::InsertCrowd);
  EXPECT_EQ(messageType(Message{CrowdResult{}}), MessageType::CrowdResult);
  // A crowd file of exactly kMaxCrowdJson bytes passes; the encoder cuts a longer one.
  const std::string big(kMaxCrowdJson, 'x');
  auto ok = decodeAny(encode(InsertCrowd{5, 9, big}));
  ASSERT_TRUE(ok) << core::formatAll(ok.errors());
  EXPECT_EQ(std::get<InsertCrowd>(ok.value()).crowdJson.size(), kMaxCrowdJson);
  EXPECT_EQ(std::get<InsertCrowd>(ok.value()).requestId, 9u);
  EXPECT_EQ(std::get<InsertCrowd>(decodeAny(encode(InsertCrowd{5, 9, big + "y"})).value()).crowdJson.size(), kMaxCrowdJson);
  // Hand-made: a length prefix one over the limit is refused before anything is read.
  std::vector<std::uint8_t> tooLong{kMagic, static_cast<std::uint8_t>(MessageType::InsertCrowd), 0, 0, 0, 0, 0, 0, 0, 0, 1};
  for (std::uint64_t n = kMaxCrowdJson + 1; ; n >>= 7) {
    tooLong.push_back(static_cast<std::uint8_t>((n & 0x7f) | (n >= 0x80 ? 0x80 : 0)));
    if (n < 0x80) break;
  }
  auto t = decodeAny(tooLong);
  ASSERT_FALSE(t);
  EXPECT_EQ(t.errors()[0].pointer, "/InsertCrowd/crowdJson");
  EXPECT_EQ(t.errors()[0].column, 12);
  // RemoveCrowd: the id is a name.
  std::vector<std::uint8_t> longId = encode(RemoveCrowd{1, 2, "a"});
  longId[longId.size() - 2] = static_cast<std::uint8_t>(kMaxNameLength + 1);
  auto r = decodeAny(longId);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.errors()[0].pointer, "/RemoveCrowd/crowdId");
  // CrowdResult: ok is 0 or 1.
  auto c = encode(CrowdResult{3, true, 1, "a", "b"});
  c[3] = 2;
  auto bad = decodeAny(c);
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.errors()[0].pointer, "/CrowdResult/ok");
  EXPECT_EQ(bad.errors()[0].column, 4);
  auto round = decodeAny(encode(CrowdResult{3, false, 0, "", std::string(2000, 't')}));
  ASSERT_TRUE(round);
  EXPECT_EQ(std::get<CrowdResult>(round.value()).text.size(), kMaxTextLength);
}

}  // namespace
}  // namespace throng::protocol

namespace throng::protocol {
namespace {

// The UDP handshake messages (types 25 and 26): sizes, the Hello inside a UdpHello, errors.
TEST(ProtocolMessages, CookieAndUdpHello) {
  CookieBytes cookie{};
  for (std::size_t i = 0; i < cookie.size(); ++i) cookie[i] = static_cast<std::uint8_t>(0xa0 + i);
  const Bytes c = encode(Cookie{cookie});
  EXPECT_EQ(c.size(), kCookieMessageSize);
  const Bytes smallest = encode(UdpHello{CookieBytes{}, Hello{kProtocolVersion, ClientKind::Native, ""}});
  EXPECT_EQ(smallest.size(), kMinUdpHelloSize);
  EXPECT_GT(kMinUdpHelloSize, kCookieMessageSize);  // the server's answer never amplifies
  const Bytes u = encode(UdpHello{cookie, Hello{kProtocolVersion, ClientKind::Loadgen, "lg"}});
  // The Hello inside is a whole Hello message, byte for byte.
  const Bytes inner = encode(Hello{kProtocolVersion, ClientKind::Loadgen, "lg"});
  ASSERT_EQ(u.size(), 2 + kCookieSize + inner.size());
  EXPECT_TRUE(std::equal(inner.begin(), inner.end(), u.begin() + 2 + kCookieSize));
  auto d = decodeAny(u);
  ASSERT_TRUE(d) << core::formatAll(d.errors());
  const auto& m = std::get<UdpHello>(d.value());
  EXPECT_EQ(m.cookie, cookie);
  EXPECT_EQ(m.hello.clientName, "lg");
  EXPECT_EQ(m.hello.clientKind, ClientKind::Loadgen);
  EXPECT_EQ(messageDirection(MessageType::UdpHello), Direction::ClientToServer);
  EXPECT_EQ(messageDirection(MessageType::Cookie), Direction::ServerToClient);
  EXPECT_STREQ(messageTypeName(MessageType::Cookie), "Cookie");
  EXPECT_STREQ(messageTypeName(MessageType::UdpHello), "UdpHello");

  auto bad = [](Bytes b, const char* pointer) {
    auto r = decodeAny(b);
    ASSERT_FALSE(r);
    EXPECT_EQ(r.errors().front().pointer, pointer) << r.errors().front().format();
  };
  Bytes notHello = u;
  notHello[2 + kCookieSize + 1] = static_cast<std::uint8_t>(MessageType::Join);
  bad(notHello, "/UdpHello/hello");
  Bytes badMagic = u;
  badMagic[2 + kCookieSize] = 0x55;
  bad(badMagic, "/UdpHello/hello");
  Bytes longer = c;
  longer.push_back(0);
  bad(longer, "/Cookie/end");
}

// A compressed CrowdFrame whose payload inflates to 16 MiB from about 530 bytes.
Bytes inflatingCrowdFrame() {
  CrowdFrame f;
  f.header.compressed = true;
  f.header.frameNumber = 1;
  f.header.animationInterval = 1;
  f.payload.assign(kMaxCrowdPayload, 0);
  return encode(f);
}

TEST(ProtocolMessages, ClientMessagesAreTypeCheckedBeforeTheirBody) {
  const Bytes bomb = inflatingCrowdFrame();
  EXPECT_LT(bomb.size(), 1000u);
  // decodeAny (what a client uses) inflates it; decodeFromClient refuses it from its type byte.
  auto inflated = decodeAny(bomb);
  ASSERT_TRUE(inflated) << core::formatAll(inflated.errors());
  EXPECT_EQ(std::get<CrowdFrame>(inflated.value()).payload.size(), kMaxCrowdPayload);
  auto refused = decodeFromClient(bomb);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.errors().front().pointer, "/message/type");
  EXPECT_NE(refused.errors().front().what.find("CrowdFrame (type 17) is a server → client message"), std::string::npos)
      << refused.errors().front().format();
  // Not even read: a corrupt body gives the same answer (decodeAny reports the payload).
  Bytes corrupt = bomb;
  corrupt.pop_back();
  EXPECT_EQ(decodeAny(corrupt).errors().front().pointer, "/CrowdFrame/payload");
  EXPECT_EQ(decodeFromClient(corrupt).errors().front().pointer, "/message/type");

  // Every golden message: server → client types refused at the type, the others decode as usual.
  for (const auto& [name, message] : test::goldenMessages()) {
    SCOPED_TRACE(name);
    const Bytes bytes = encode(message);
    auto r = decodeFromClient(bytes);
    if (messageDirection(messageType(message)) == Direction::ServerToClient) {
      ASSERT_FALSE(r);
      EXPECT_EQ(r.errors().front().pointer, "/message/type");
    } else {
      ASSERT_TRUE(r) << core::formatAll(r.errors());
      EXPECT_EQ(encode(r.value()), bytes);
    }
  }
  // Size per type: a Move padded past the client bound, before its fields are read; an
  // InsertCrowd may be up to its crowd file's limit.
  Bytes longMove = encode(Move{});
  longMove.resize(kMaxClientMessageSize + 1);
  auto tooLong = decodeFromClient(longMove);
  ASSERT_FALSE(tooLong);
  EXPECT_EQ(tooLong.errors().front().pointer, "/message/size");
  EXPECT_EQ(maxClientMessageSize(MessageType::CrowdFrame), 0u);
  const Bytes bigCrowd = encode(InsertCrowd{1, 2, std::string(kMaxCrowdJson, ' ')});
  EXPECT_TRUE(decodeFromClient(bigCrowd));
}

}  // namespace
}  // namespace throng::protocol
