// Fragment (type 24): its decoder's validation, splitMessage's sizes, and the Reassembler's rules
// (in order, out of order, duplicates, a lost piece dropped when a newer message completes, at
// most 4 in progress, bad count / index, oversize, a Fragment inside a Fragment).
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "throng/protocol/fragments.hpp"

namespace throng::protocol {
namespace {

Bytes sampleMessage(std::size_t bytes) {
  CrowdResult r;
  r.requestId = 9;
  r.ok = true;
  r.text = std::string(bytes, 'x');  // clamped to kMaxTextLength by the encoder
  Bytes out = encode(r);
  // Longer than one text allows: pad with a Welcome carrying a raw JSON world instead.
  if (bytes > kMaxTextLength) {
    Welcome w;
    w.worldEncoding = WorldEncoding::Json;
    const std::string world(bytes, ' ');
    w.world.assign(world.begin(), world.end());
    w.worldSize = static_cast<std::uint32_t>(world.size());
    out = encode(w);
  }
  return out;
}

std::vector<Fragment> fragmentsOf(const Bytes& message, std::uint64_t id, std::size_t datagram) {
  std::vector<Fragment> out;
  for (const Bytes& d : splitMessage(message, id, datagram)) {
    EXPECT_LE(d.size(), datagram);
    auto m = decodeAny(d);
    EXPECT_TRUE(m.ok()) << core::formatAll(m.errors());
    out.push_back(std::get<Fragment>(m.value()));
  }
  return out;
}

TEST(ProtocolFragment, DecoderValidates) {
  auto bad = [](Bytes b, const char* pointer) {
    auto m = decodeAny(b);
    ASSERT_FALSE(m.ok());
    EXPECT_EQ(m.errors().front().pointer, pointer) << m.errors().front().format();
  };
  bad({0x54, 24, 0, 0, 1, 9}, "/Fragment/count");                 // count 1
  bad({0x54, 24, 0, 0, 0x81, 0x40, 9}, "/Fragment/count");        // count 8193
  bad({0x54, 24, 0, 3, 3, 9}, "/Fragment/index");                 // index == count
  bad({0x54, 24, 0, 0, 2}, "/Fragment/payload");                  // no payload
  bad({0x54, 24, 0, 0}, "/Fragment/count");                       // truncated
  auto ok = decodeAny(Bytes{0x54, 24, 0xac, 0x02, 1, 3, 9, 8});
  ASSERT_TRUE(ok.ok());
  const auto& f = std::get<Fragment>(ok.value());
  EXPECT_EQ(f.messageId, 300u);
  EXPECT_EQ(f.index, 1u);
  EXPECT_EQ(f.count, 3u);
  EXPECT_EQ(f.payload, (Bytes{9, 8}));
  EXPECT_EQ(messageType(ok.value()), MessageType::Fragment);
  EXPECT_STREQ(messageTypeName(MessageType::Fragment), "Fragment");
}

TEST(ProtocolFragment, SplitSizes) {
  const Bytes small = sampleMessage(100);
  EXPECT_TRUE(splitMessage(small, 0, 1200).empty());  // fits: sent whole
  const Bytes big = sampleMessage(5000);
  const auto pieces = splitMessage(big, 1u << 20, 300);
  ASSERT_GE(pieces.size(), 17u);
  for (const Bytes& p : pieces) EXPECT_LE(p.size(), 300u);
  EXPECT_TRUE(splitMessage(big, 0, 63).empty());  // below kMinFragmentDatagram
  EXPECT_EQ(maxFragmentedSize(1200), kMaxMessageSize);
  EXPECT_EQ(maxFragmentedSize(200), kMaxFragments * (200 - kMaxFragmentHeader));
  EXPECT_TRUE(splitMessage(Bytes(maxFragmentedSize(200) + 1, 0x54), 0, 200).empty());
  EXPECT_EQ(splitMessage(Bytes(maxFragmentedSize(200), 0x54), ~std::uint64_t{0}, 200).size(), kMaxFragments);
}

TEST(ProtocolFragment, InOrderAndOutOfOrder) {
  const Bytes big = sampleMessage(3000);
  for (const bool reversed : {false, true}) {
    auto pieces = fragmentsOf(big, 5, 400);
    ASSERT_GT(pieces.size(), 2u);
    if (reversed) std::reverse(pieces.begin(), pieces.end());
    Reassembler r;
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      auto got = r.add(pieces[i]);
      ASSERT_TRUE(got.ok());
      if (i + 1 < pieces.size()) {
        EXPECT_FALSE(got.value());
      } else {
        ASSERT_TRUE(got.value());
        EXPECT_EQ(*got.value(), big);
        ASSERT_TRUE(decodeAny(*got.value()).ok());
      }
    }
    EXPECT_EQ(r.inProgress(), 0u);
    EXPECT_EQ(r.droppedMessages(), 0u);
    // A late duplicate of a completed message is ignored.
    auto late = r.add(pieces[0]);
    ASSERT_TRUE(late.ok());
    EXPECT_FALSE(late.value());
    EXPECT_EQ(r.inProgress(), 0u);
  }
}

TEST(ProtocolFragment, DuplicatesIgnored) {
  const Bytes big = sampleMessage(2000);
  const auto pieces = fragmentsOf(big, 1, 500);
  Reassembler r;
  std::optional<Bytes> whole;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    for (int twice = 0; twice < 2 && !whole; ++twice) {
      auto got = r.add(pieces[i]);
      ASSERT_TRUE(got.ok());
      if (got.value()) whole = got.value();
    }
  }
  ASSERT_TRUE(whole);
  EXPECT_EQ(*whole, big);
}

TEST(ProtocolFragment, LostPieceDroppedWhenNewerCompletes) {
  const Bytes a = sampleMessage(2000), b = sampleMessage(2500);
  auto pa = fragmentsOf(a, 10, 500), pb = fragmentsOf(b, 11, 500);
  Reassembler r;
  for (std::size_t i = 1; i < pa.size(); ++i) ASSERT_TRUE(r.add(pa[i]).ok());  // piece 0 lost
  EXPECT_EQ(r.inProgress(), 1u);
  std::optional<Bytes> whole;
  for (const auto& f : pb) {
    auto got = r.add(f);
    ASSERT_TRUE(got.ok());
    if (got.value()) whole = got.value();
  }
  ASSERT_TRUE(whole);
  EXPECT_EQ(*whole, b);
  EXPECT_EQ(r.inProgress(), 0u);
  EXPECT_EQ(r.droppedMessages(), 1u);
  // The lost piece arriving now is stale: ignored, nothing restarts.
  auto late = r.add(pa[0]);
  ASSERT_TRUE(late.ok());
  EXPECT_FALSE(late.value());
  EXPECT_EQ(r.inProgress(), 0u);
}

TEST(ProtocolFragment, AtMostFourInProgress) {
  const Bytes m = sampleMessage(2000);
  Reassembler r;
  for (std::uint64_t id = 1; id <= 5; ++id) ASSERT_TRUE(r.add(fragmentsOf(m, id, 500).front()).ok());
  EXPECT_EQ(r.inProgress(), 4u);
  EXPECT_EQ(r.droppedMessages(), 1u);  // message 1, the oldest
  auto stale = r.add(fragmentsOf(m, 1, 500).back());
  ASSERT_TRUE(stale.ok());
  EXPECT_FALSE(stale.value());
  EXPECT_EQ(r.inProgress(), 4u);
  // Message 2 still completes.
  std::optional<Bytes> whole;
  for (const auto& f : fragmentsOf(m, 2, 500)) {
    auto got = r.add(f);
    ASSERT_TRUE(got.ok());
    if (got.value()) whole = got.value();
  }
  ASSERT_TRUE(whole);
  EXPECT_EQ(*whole, m);
}

TEST(ProtocolFragment, BadFragmentsAreErrors) {
  Reassembler r;
  EXPECT_FALSE(r.add(Fragment{1, 0, 1, {1}}).ok());      // count below 2
  EXPECT_FALSE(r.add(Fragment{1, 3, 3, {1}}).ok());      // index == count
  EXPECT_FALSE(r.add(Fragment{1, 0, 8193, {1}}).ok());   // count over 8192
  ASSERT_TRUE(r.add(Fragment{2, 0, 3, {1}}).ok());
  auto inconsistent = r.add(Fragment{2, 1, 4, {2}});
  ASSERT_FALSE(inconsistent.ok());
  EXPECT_EQ(inconsistent.errors().front().pointer, "/Fragment/messageId");
  EXPECT_EQ(r.droppedMessages(), 1u);
  EXPECT_EQ(r.inProgress(), 0u);
  // Oversize: pieces adding up to more than kMaxMessageSize.
  const Bytes half(kMaxMessageSize / 2 + 1, 0x54);
  ASSERT_TRUE(r.add(Fragment{3, 0, 2, half}).ok());
  EXPECT_FALSE(r.add(Fragment{3, 1, 2, half}).ok());
  EXPECT_EQ(r.droppedMessages(), 2u);
  // A Fragment inside a Fragment.
  ASSERT_TRUE(r.add(Fragment{4, 0, 2, {0x54}}).ok());
  EXPECT_FALSE(r.add(Fragment{4, 1, 2, {24, 0, 0, 2, 1}}).ok());
  EXPECT_EQ(r.inProgress(), 0u);
}

}  // namespace
}  // namespace throng::protocol
