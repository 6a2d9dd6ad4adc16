// throng::transport::detail::CookieJar (see header): SipHash-2-4 written from the paper's
// description, two independent keys for a 128-bit cookie.
#include "udp_cookie.hpp"

#include <random>

namespace throng::transport::detail {
namespace {

constexpr std::uint64_t rotl(std::uint64_t v, int s) { return (v << s) | (v >> (64 - s)); }

struct SipState {
  std::uint64_t v0, v1, v2, v3;
  void round() {
    v0 += v1;
    v1 = rotl(v1, 13);
    v1 ^= v0;
    v0 = rotl(v0, 32);
    v2 += v3;
    v3 = rotl(v3, 16);
    v3 ^= v2;
    v0 += v3;
    v3 = rotl(v3, 21);
    v3 ^= v0;
    v2 += v1;
    v1 = rotl(v1, 17);
    v1 ^= v2;
    v2 = rotl(v2, 32);
  }
  void absorb(std::uint64_t m) {
    v3 ^= m;
    round();
    round();
    v0 ^= m;
  }
};

std::uint64_t loadLe(const std::uint8_t* p, std::size_t n) {
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < n; ++i) v |= static_cast<std::uint64_t>(p[i]) << (8 * i);
  return v;
}

}  // namespace

std::uint64_t sipHash24(std::uint64_t k0, std::uint64_t k1, std::span<const std::uint8_t> data) {
  SipState s{k0 ^ 0x736f6d6570736575ULL, k1 ^ 0x646f72616e646f6dULL, k0 ^ 0x6c7967656e657261ULL,
             k1 ^ 0x7465646279746573ULL};
  const std::size_t whole = data.size() / 8 * 8;
  for (std::size_t i = 0; i < whole; i += 8) s.absorb(loadLe(data.data() + i, 8));
  s.absorb(loadLe(data.data() + whole, data.size() - whole) | (static_cast<std::uint64_t>(data.size() & 0xff) << 56));
  s.v2 ^= 0xff;
  for (int i = 0; i < 4; ++i) s.round();
  return s.v0 ^ s.v1 ^ s.v2 ^ s.v3;
}

CookieJar::CookieJar() {
  std::random_device device;
  for (auto& k : key_) k = (static_cast<std::uint64_t>(device()) << 32) ^ device();
}

protocol::CookieBytes CookieJar::make(const udp::endpoint& remote, std::int64_t interval) const {
  // family, 16 address bytes (IPv4 in the first 4), port, interval: 27 bytes.
  std::array<std::uint8_t, 27> input{};
  const auto address = remote.address();
  input[0] = address.is_v6() ? 6 : 4;
  if (address.is_v6()) {
    const auto b = address.to_v6().to_bytes();
    std::copy(b.begin(), b.end(), input.begin() + 1);
  } else {
    const auto b = address.to_v4().to_bytes();
    std::copy(b.begin(), b.end(), input.begin() + 1);
  }
  input[17] = static_cast<std::uint8_t>(remote.port());
  input[18] = static_cast<std::uint8_t>(remote.port() >> 8);
  for (int i = 0; i < 8; ++i) input[19 + i] = static_cast<std::uint8_t>(static_cast<std::uint64_t>(interval) >> (8 * i));
  protocol::CookieBytes cookie{};
  const std::uint64_t a = sipHash24(key_[0], key_[1], input), b = sipHash24(key_[2], key_[3], input);
  for (int i = 0; i < 8; ++i) {
    cookie[i] = static_cast<std::uint8_t>(a >> (8 * i));
    cookie[8 + i] = static_cast<std::uint8_t>(b >> (8 * i));
  }
  return cookie;
}

namespace {
std::int64_t intervalOf(CookieJar::Clock::time_point now) {
  return std::chrono::duration_cast<std::chrono::seconds>(now.time_since_epoch()).count() / CookieJar::kInterval.count();
}
}  // namespace

protocol::CookieBytes CookieJar::issue(const udp::endpoint& remote, Clock::time_point now) const {
  return make(remote, intervalOf(now));
}

bool CookieJar::check(const udp::endpoint& remote, const protocol::CookieBytes& cookie, Clock::time_point now) const {
  const std::int64_t interval = intervalOf(now);
  for (const std::int64_t i : {interval, interval - 1}) {
    const protocol::CookieBytes expected = make(remote, i);
    std::uint8_t diff = 0;  // no early exit: the time taken says nothing about the cookie
    for (std::size_t k = 0; k < cookie.size(); ++k) diff |= static_cast<std::uint8_t>(cookie[k] ^ expected[k]);
    if (diff == 0) return true;
  }
  return false;
}

}  // namespace throng::transport::detail
