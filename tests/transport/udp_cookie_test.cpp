// Tests for libs/transport/src/udp_cookie.cpp: SipHash-2-4 against the reference vectors of its paper,
// and the cookies: good for their endpoint for 10 to 20 s, for no other address, port or key.
#include <gtest/gtest.h>

#include <numeric>

#include "udp_cookie.hpp"

namespace throng::transport::detail {
namespace {

TEST(UdpCookie, SipHashReferenceVectors) {
  // Key 00 01 .. 0f; messages 00 01 .. (n-1) (Aumasson and Bernstein, appendix A).
  const std::uint64_t k0 = 0x0706050403020100ULL, k1 = 0x0f0e0d0c0b0a0908ULL;
  std::vector<std::uint8_t> m(64);
  std::iota(m.begin(), m.end(), 0);
  EXPECT_EQ(sipHash24(k0, k1, std::span(m.data(), 0)), 0x726fdb47dd0e0e31ULL);
  EXPECT_EQ(sipHash24(k0, k1, std::span(m.data(), 15)), 0xa129ca6149be45e5ULL);
  EXPECT_EQ(sipHash24(k0, k1, std::span(m.data(), 8)), 0x93f5f5799a932462ULL);
}

TEST(UdpCookie, GoodForItsEndpointForTenToTwentySeconds) {
  const CookieJar jar(std::array<std::uint64_t, 4>{1, 2, 3, 4});
  const udp::endpoint client(asio::ip::make_address("192.0.2.7"), 40000);
  // The start of a 10-second interval, well away from the clock's epoch.
  const CookieJar::Clock::time_point t0{std::chrono::seconds(1'000'000)};
  const auto cookie = jar.issue(client, t0);
  EXPECT_NE(cookie, protocol::CookieBytes{});
  EXPECT_TRUE(jar.check(client, cookie, t0));
  EXPECT_TRUE(jar.check(client, cookie, t0 + std::chrono::milliseconds(19999)));
  EXPECT_FALSE(jar.check(client, cookie, t0 + std::chrono::seconds(20)));
  EXPECT_FALSE(jar.check(client, cookie, t0 - std::chrono::seconds(1)));  // from the future
  // Another port, another address, another family, another key.
  EXPECT_FALSE(jar.check(udp::endpoint(client.address(), 40001), cookie, t0));
  EXPECT_FALSE(jar.check(udp::endpoint(asio::ip::make_address("192.0.2.8"), 40000), cookie, t0));
  EXPECT_FALSE(jar.check(udp::endpoint(asio::ip::make_address("::ffff:192.0.2.7"), 40000), cookie, t0));
  EXPECT_FALSE(CookieJar(std::array<std::uint64_t, 4>{1, 2, 3, 5}).check(client, cookie, t0));
  // Any one bit changed is refused; all zero (no cookie yet) too.
  for (std::size_t bit = 0; bit < cookie.size() * 8; ++bit) {
    auto flipped = cookie;
    flipped[bit / 8] ^= static_cast<std::uint8_t>(1u << (bit % 8));
    EXPECT_FALSE(jar.check(client, flipped, t0)) << "bit " << bit;
  }
  EXPECT_FALSE(jar.check(client, protocol::CookieBytes{}, t0));
  // Two random jars disagree.
  EXPECT_NE(CookieJar().issue(client, t0), CookieJar().issue(client, t0));
}

}  // namespace
}  // namespace throng::transport::detail
