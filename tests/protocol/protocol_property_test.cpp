// Properties (RapidCheck): decode(encode(m)) equals the quantized message; chains of random crowd
// views with random acks and lost frames always decode to what the encoder says the client
// holds (and to the quantized input when every field is refreshed); corrupted bytes give an error
// or a valid message, never a crash.
#include <gtest/gtest.h>
#include <rapidcheck.h>

#include <algorithm>

#include "protocol_test_util.hpp"

namespace throng::protocol {
namespace {

CrowdView randomView(std::uint8_t jointCount) {
  CrowdView v;
  v.jointCount = jointCount;
  v.simTick = *rc::gen::inRange<std::uint64_t>(0, 1u << 20);
  auto ids = *rc::gen::container<std::vector<std::uint32_t>>(*rc::gen::inRange(0, 60), rc::gen::inRange<std::uint32_t>(0, 300));
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  for (const std::uint32_t id : ids) {
    AgentState a;
    a.id = id;
    a.tier = static_cast<Tier>(*rc::gen::inRange(0, 3));
    a.x = static_cast<float>(*rc::gen::inRange(-100000, 100000)) / 97.0f;
    a.y = static_cast<float>(*rc::gen::inRange(-100000, 100000)) / 89.0f;
    a.z = *rc::gen::element(0.0f, 0.0f, 3.5f);
    a.yaw = static_cast<float>(*rc::gen::inRange(-7000, 7000)) / 1000.0f;
    a.clip = static_cast<std::uint16_t>(*rc::gen::inRange(0, 5));
    a.phase = static_cast<float>(*rc::gen::inRange(0, 1000)) / 1000.0f;
    if (a.tier == Tier::Near) {
      for (int j = 0; j < jointCount * 3; ++j) a.joints.push_back(static_cast<float>(*rc::gen::inRange(-3200, 3200)) / 1000.0f);
    }
    v.agents.push_back(a);
  }
  return v;
}

TEST(ProtocolProperties, MoveRoundTripsQuantized) {
  EXPECT_TRUE(rc::check([](std::int32_t xCm, std::uint16_t yaw, std::uint32_t seq, std::uint64_t token) {
    xCm %= 4000000;  // within ±40 km: exact in float metres
    Move m{{Subject::Kind::Token, token}, seq, dequantizePosition(xCm), 0.0f, 0.0f, dequantizeAngle16(yaw)};
    auto r = decodeAny(encode(m));
    RC_ASSERT(r.ok());
    const Move& d = std::get<Move>(r.value());
    RC_ASSERT(quantizePosition(d.x) == xCm);
    RC_ASSERT(quantizeAngle16(d.yaw) == yaw);
    RC_ASSERT(d.seq == seq);
    RC_ASSERT(d.subject.value == token);
  }));
}

TEST(ProtocolProperties, CrowdKeyFrameRoundTripsQuantized) {
  EXPECT_TRUE(rc::check([] {
    const auto J = static_cast<std::uint8_t>(*rc::gen::inRange(0, 5));
    const auto shift = static_cast<std::uint8_t>(*rc::gen::inRange(0, 9));
    const CrowdView v = randomView(J);
    CrowdEncoderOptions o;
    o.jointShift = shift;
    o.compressMinBytes = *rc::gen::element<std::size_t>(0, 1u << 30);
    CrowdEncoder enc(o);
    CrowdDecoder dec;
    auto e = enc.encode(v, 0);
    RC_ASSERT(e.ok());
    auto d = dec.decode(e.value().bytes);
    RC_ASSERT(d.ok());
    RC_ASSERT(d.value().view == quantized(v, shift));
  }));
}

TEST(ProtocolProperties, DeltaChainsWithRandomAcksAndLosses) {
  EXPECT_TRUE(rc::check([] {
    const auto J = static_cast<std::uint8_t>(*rc::gen::inRange(0, 4));
    const bool everyField = *rc::gen::arbitrary<bool>();
    CrowdEncoderOptions o;
    o.historyFrames = static_cast<std::size_t>(*rc::gen::inRange(1, 10));
    o.farInterval = everyField ? 1 : static_cast<std::uint32_t>(*rc::gen::inRange(1, 5));
    o.jointShift = static_cast<std::uint8_t>(*rc::gen::inRange(0, 9));
    CrowdEncoder enc(o);
    CrowdDecoder dec(static_cast<std::size_t>(*rc::gen::inRange(1, 10)));
    std::vector<std::uint32_t> decoded;  // frames the client has, candidates for acks
    const int steps = *rc::gen::inRange(1, 12);
    for (int s = 0; s < steps; ++s) {
      CrowdView v = randomView(J);
      v.animationInterval = everyField ? 1 : static_cast<std::uint8_t>(*rc::gen::inRange(1, 4));
      const std::uint32_t ack = decoded.empty() || *rc::gen::inRange(0, 5) == 0 ? 0 : *rc::gen::elementOf(decoded);
      auto e = enc.encode(v, ack);
      RC_ASSERT(e.ok());
      if (*rc::gen::inRange(0, 4) == 0) continue;  // lost on the way
      auto d = dec.decode(e.value().bytes);
      if (!d.ok()) {  // only an unknown base may fail
        RC_ASSERT(e.value().header.baseFrame != 0);
        RC_ASSERT(!dec.hasFrame(e.value().header.baseFrame));
        continue;
      }
      decoded.push_back(e.value().header.frameNumber);
      RC_ASSERT(d.value().view == *enc.sentView(e.value().header.frameNumber));
      if (everyField) RC_ASSERT(d.value().view == quantized(v, o.jointShift));
    }
  }));
}

TEST(ProtocolProperties, CorruptedBytesNeverCrash) {
  EXPECT_TRUE(rc::check([] {
    CrowdEncoder enc;
    CrowdDecoder dec;
    const CrowdView v0 = randomView(2);
    auto k = enc.encode(v0, 0);
    RC_ASSERT(k.ok());
    RC_ASSERT(dec.decode(k.value().bytes).ok());
    std::vector<std::uint8_t> bytes = enc.encode(randomView(2), 1).value().bytes;
    const int flips = *rc::gen::inRange(1, 6);
    for (int i = 0; i < flips; ++i) {
      const auto at = *rc::gen::inRange<std::size_t>(0, bytes.size());
      bytes[at] = *rc::gen::arbitrary<std::uint8_t>();
    }
    if (*rc::gen::arbitrary<bool>()) bytes.resize(*rc::gen::inRange<std::size_t>(0, bytes.size() + 1));
    auto r = dec.decode(bytes);  // an error or a frame; ASan/UBSan builds check the rest
    if (!r.ok()) RC_ASSERT(!r.errors().front().what.empty());
  }));
}

}  // namespace
}  // namespace throng::protocol
