// Tests for libs/transport/src/send_queue.cpp and token_bucket.hpp: Latest replacement keeps send
// order; the token bucket refills at its rate.
#include "send_queue.hpp"

#include <gtest/gtest.h>

#include "token_bucket.hpp"

namespace throng::transport::detail {
namespace {

QueuedMessage msg(std::uint8_t tag, SendClass cls, std::uint32_t slot = 0) { return {{tag, tag}, cls, slot}; }

std::vector<std::uint8_t> drainTags(SendQueue& q) {
  std::vector<std::uint8_t> tags;
  while (!q.empty()) tags.push_back(q.pop().data.front());
  return tags;
}

TEST(SendQueue, ReliableKeepsOrder) {
  SendQueue q;
  for (std::uint8_t i = 1; i <= 5; ++i) EXPECT_EQ(q.push(msg(i, SendClass::Reliable)), 0u);
  EXPECT_EQ(q.messages(), 5u);
  EXPECT_EQ(q.bytes(), 10u);
  EXPECT_EQ(drainTags(q), (std::vector<std::uint8_t>{1, 2, 3, 4, 5}));
  EXPECT_EQ(q.bytes(), 0u);
}

TEST(SendQueue, LatestReplacesSameSlotAndMovesToBack) {
  SendQueue q;
  q.push(msg(1, SendClass::Latest, 7));
  q.push(msg(2, SendClass::Reliable));
  q.push(msg(3, SendClass::Latest, 8));
  EXPECT_EQ(q.push(msg(4, SendClass::Latest, 7)), 1u);  // replaces 1, goes after 2 and 3
  EXPECT_EQ(q.push(msg(5, SendClass::Reliable, 7)), 0u);  // Reliable never replaces
  EXPECT_EQ(q.messages(), 4u);
  EXPECT_EQ(q.bytes(), 8u);
  EXPECT_EQ(drainTags(q), (std::vector<std::uint8_t>{2, 3, 4, 5}));
}

TEST(SendQueue, ClearEmpties) {
  SendQueue q;
  q.push(msg(1, SendClass::Latest));
  q.clear();
  EXPECT_TRUE(q.empty());
  EXPECT_EQ(q.bytes(), 0u);
}

TEST(TokenBucket, BurstThenRate) {
  const auto t0 = TokenBucket::Clock::time_point{};
  TokenBucket bucket(10.0, 3.0, t0);
  EXPECT_TRUE(bucket.take(t0));
  EXPECT_TRUE(bucket.take(t0));
  EXPECT_TRUE(bucket.take(t0));
  EXPECT_FALSE(bucket.take(t0));
  EXPECT_TRUE(bucket.take(t0 + std::chrono::milliseconds(100)));  // one token back after 0.1 s at 10/s
  EXPECT_FALSE(bucket.take(t0 + std::chrono::milliseconds(100)));
  TokenBucket unlimited(0.0, 1.0, t0);
  for (int i = 0; i < 1000; ++i) EXPECT_TRUE(unlimited.take(t0));
}

}  // namespace
}  // namespace throng::transport::detail
