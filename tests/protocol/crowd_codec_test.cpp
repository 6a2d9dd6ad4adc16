// CrowdEncoder / CrowdDecoder: key and delta frames, fallback to a key frame when the ack is
// unknown, a clean error for an unknown base, far agents refreshed at their lower rate,
// animation every X frames, shared poses, removals, and payload corruption caught.
#include <gtest/gtest.h>

#include "protocol_test_util.hpp"

namespace throng::protocol {
namespace {

CrowdView walkers(int n, int tick, std::uint8_t jointCount = 3) {
  CrowdView v;
  v.simTick = static_cast<std::uint64_t>(tick);
  v.jointCount = jointCount;
  for (int i = 0; i < n; ++i) {
    AgentState a;
    a.id = static_cast<std::uint32_t>(i * 2 + 1);
    a.tier = i < 4 ? Tier::Near : i < n / 2 ? Tier::Middle : Tier::Far;
    a.x = 0.1f * i + 0.067f * tick;
    a.y = 0.05f * i;
    a.yaw = 0.01f * i;
    a.clip = static_cast<std::uint16_t>(i % 3);
    a.phase = 0.05f * tick + 0.01f * i;
    if (a.tier == Tier::Near) a.joints.assign(jointCount * 3u, 0.02f * tick);
    v.agents.push_back(a);
  }
  return v;
}

TEST(CrowdCodec, DeltaFramesReconstructTheView) {
  CrowdEncoderOptions o;
  o.farInterval = 1;
  CrowdEncoder enc(o);
  CrowdDecoder dec;
  for (int t = 0; t < 10; ++t) {
    auto e = enc.encode(walkers(40, t), dec.newestFrame());
    ASSERT_TRUE(e);
    EXPECT_EQ(e.value().keyFrame(), t == 0);
    auto d = dec.decode(e.value().bytes);
    ASSERT_TRUE(d) << core::formatAll(d.errors());
    EXPECT_EQ(d.value().view, quantized(walkers(40, t), o.jointShift));
  }
}

TEST(CrowdCodec, DeltaIsSmallerThanKey) {
  CrowdEncoder enc;
  auto k = enc.encode(walkers(200, 0), 0);
  auto d = enc.encode(walkers(200, 1), 1);
  ASSERT_TRUE(k && d);
  EXPECT_LT(d.value().bytes.size(), k.value().bytes.size());
}

TEST(CrowdCodec, UnknownBaseIsACleanErrorAndKeyFrameRecovers) {
  CrowdEncoder enc;
  CrowdDecoder dec;
  auto k = enc.encode(walkers(10, 0), 0);
  auto d = enc.encode(walkers(10, 1), 1);  // the client never saw frame 1
  ASSERT_TRUE(k && d);
  auto r = dec.decode(d.value().bytes);
  ASSERT_FALSE(r);
  EXPECT_NE(r.errors()[0].what.find("base frame 1 unknown"), std::string::npos) << r.errors()[0].format();
  EXPECT_EQ(dec.newestFrame(), 0u);
  auto again = enc.encode(walkers(10, 2), 0);  // no ack → key frame
  ASSERT_TRUE(again);
  EXPECT_TRUE(again.value().keyFrame());
  ASSERT_TRUE(dec.decode(again.value().bytes));
}

TEST(CrowdCodec, AckOlderThanHistoryFallsBackToKey) {
  CrowdEncoderOptions o;
  o.historyFrames = 2;
  CrowdEncoder enc(o);
  for (int t = 0; t < 4; ++t) ASSERT_TRUE(enc.encode(walkers(5, t), 0));
  auto e = enc.encode(walkers(5, 4), 1);  // frame 1 dropped from the history
  ASSERT_TRUE(e);
  EXPECT_TRUE(e.value().keyFrame());
  EXPECT_FALSE(enc.sentView(1).has_value());
}

TEST(CrowdCodec, FarAgentsKeepTheirLastStateBetweenRefreshes) {
  CrowdEncoderOptions o;
  o.farInterval = 3;
  CrowdEncoder enc(o);
  CrowdDecoder dec;
  ASSERT_TRUE(dec.decode(enc.encode(walkers(20, 0), 0).value().bytes));
  auto e = enc.encode(walkers(20, 1), 1);  // frame 2: far not refreshed
  ASSERT_TRUE(e);
  EXPECT_FALSE(e.value().header.farIncluded);
  auto d = dec.decode(e.value().bytes);
  ASSERT_TRUE(d);
  const auto fresh = quantized(walkers(20, 1), o.jointShift);
  const auto stale = quantized(walkers(20, 0), o.jointShift);
  for (std::size_t i = 0; i < fresh.agents.size(); ++i) {
    EXPECT_EQ(d.value().view.agents[i], fresh.agents[i].tier == Tier::Far ? stale.agents[i] : fresh.agents[i]);
  }
  EXPECT_EQ(d.value().view, enc.sentView(2).value());
  auto f = enc.encode(walkers(20, 2), 2);  // frame 3: refreshed
  ASSERT_TRUE(f);
  EXPECT_TRUE(f.value().header.farIncluded);
  EXPECT_EQ(dec.decode(f.value().bytes).value().view, quantized(walkers(20, 2), o.jointShift));
}

TEST(CrowdCodec, AnimationIntervalHoldsClipPhaseAndJoints) {
  CrowdEncoder enc;
  CrowdDecoder dec;
  CrowdView v0 = walkers(8, 0);
  ASSERT_TRUE(dec.decode(enc.encode(v0, 0).value().bytes));
  CrowdView v1 = walkers(8, 1);
  v1.animationInterval = 4;  // frame 2: not an animation frame
  auto d = dec.decode(enc.encode(v1, 1).value().bytes);
  ASSERT_TRUE(d);
  EXPECT_EQ(d.value().header.animationInterval, 4);
  const auto q0 = quantized(v0, 4), q1 = quantized(v1, 4);
  EXPECT_EQ(d.value().view.agents[0].x, q1.agents[0].x);
  EXPECT_EQ(d.value().view.agents[0].phase, q0.agents[0].phase);
  EXPECT_EQ(d.value().view.agents[0].joints, q0.agents[0].joints);
}

TEST(CrowdCodec, IdenticalPosesAreSentOnce) {
  CrowdEncoder enc;
  CrowdView v = walkers(30, 0, 20);
  for (auto& a : v.agents) {
    if (a.tier == Tier::Near) a.joints.assign(60, 0.5f);
  }
  auto e = enc.encode(v, 0);
  ASSERT_TRUE(e);
  EXPECT_EQ(e.value().poses, 1u);
}

TEST(CrowdCodec, EncoderRejectsDuplicateIds) {
  CrowdEncoder enc;
  CrowdView v = walkers(3, 0);
  v.agents[1].id = v.agents[0].id;
  auto e = enc.encode(v, 0);
  ASSERT_FALSE(e);
  EXPECT_NE(e.errors()[0].what.find("duplicate agent id"), std::string::npos);
  EXPECT_EQ(enc.nextFrameNumber(), 1u);
}

TEST(CrowdCodec, ContradictoryPayloadsAreErrors) {
  CrowdEncoder enc;
  CrowdDecoder dec;
  auto k = enc.encode(walkers(6, 0), 0);
  ASSERT_TRUE(dec.decode(k.value().bytes));
  auto m = decodeAny(enc.encode(walkers(6, 1), 1).value().bytes);
  ASSERT_TRUE(m);
  CrowdFrame f = std::get<CrowdFrame>(m.value());
  CrowdFrame wrongCounts = f;
  wrongCounts.header.nearCount += 1;
  auto r = dec.apply(wrongCounts);
  ASSERT_FALSE(r);
  EXPECT_NE(r.errors()[0].what.find("tier counts"), std::string::npos);
  CrowdFrame removal = f;  // remove agent 999, absent from the base
  removal.payload[0] = 1;
  removal.payload.insert(removal.payload.begin() + 1, {0xe7, 0x07});
  r = dec.apply(removal);
  ASSERT_FALSE(r);
  EXPECT_NE(r.errors()[0].what.find("removal of agent 999"), std::string::npos) << r.errors()[0].format();
  ASSERT_TRUE(dec.apply(f));  // the decoder's state was not touched by the failures
}

}  // namespace
}  // namespace throng::protocol
