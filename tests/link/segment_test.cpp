// throng::link::Segment (libs/link/src/segment.cpp) and the reader helpers of throng_link.h: the
// seqlock / double-buffer frame reader never returns a torn frame while a writer thread rewrites
// the frames as fast as it can; the host input's seqlock likewise; the request / reply rings; a
// second segment of the same name is refused.
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include <unistd.h>

#include "throng/link/segment.hpp"
#include "throng/throng_link.h"

namespace throng::link {
namespace {

std::string uniqueName(const char* tag) { return "/throng-test-" + std::to_string(getpid()) + "-" + tag; }

std::unique_ptr<Segment> makeSegment(const char* tag, std::uint32_t maxAgents = 64) {
  SegmentOptions o;
  o.maxAgents = maxAgents;
  o.maxDetailed = 2;
  o.maxJoints = 3;
  o.maxAvatars = 4;
  o.maxGuides = 4;
  o.maxRequests = 4;
  o.force = true;
  auto s = Segment::create(uniqueName(tag), o);
  EXPECT_TRUE(s.ok()) << (s.ok() ? "" : s.errors().front().format());
  if (!s.ok()) return nullptr;
  auto segment = std::move(s).value();
  segment->setCounts(3, 0);
  segment->start();
  return segment;
}

/// Every field of every record carries the tick it was written in (agent count varies too).
void writeFrame(Segment& s, std::uint64_t tick) {
  throng_link_header& h = s.header();
  throng_link_frame& f = s.beginFrame();
  const std::uint32_t n = 1 + static_cast<std::uint32_t>(tick % h.max_agents);
  throng_link_agent* agents = throng_link_frame_agents(&h, &f);
  for (std::uint32_t i = 0; i < n; ++i) {
    agents[i].id = static_cast<std::uint32_t>(tick);
    agents[i].group = i;
    agents[i].x = static_cast<float>(tick % 100000);
    agents[i].y = -static_cast<float>(tick % 100000);
    agents[i].phase = static_cast<float>(tick % 1000) / 1000.0f;
  }
  throng_link_detailed* d = throng_link_frame_detailed(&h, &f, 0);
  d->id = static_cast<std::uint32_t>(tick);
  d->joint_count = 3;
  for (int k = 0; k < 9; ++k) throng_link_detailed_angles(d)[k] = static_cast<float>(tick % 100000);
  f.tick = tick;
  f.time = static_cast<double>(tick) * 0.05;
  f.agent_count = n;
  f.total_agents = n;
  f.detailed_count = 1;
  s.publishFrame();
}

TEST(LinkSegment, ReaderNeverSeesATornFrame) {
  auto segment = makeSegment("torn");
  ASSERT_TRUE(segment);
  throng_link link{};
  link.header = &segment->header();
  std::vector<unsigned char> buffer(segment->header().frame_size);
  auto* copy = reinterpret_cast<throng_link_frame*>(buffer.data());
  EXPECT_EQ(throng_link_read_frame(&link, copy), -1) << "no frame yet";

  std::atomic<bool> stop{false};
  std::thread writer([&] {
    for (std::uint64_t tick = 1; !stop.load(std::memory_order_relaxed); ++tick) writeFrame(*segment, tick);
  });
  std::uint64_t reads = 0, lastTick = 0, torn = 0;
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(700);
  while (std::chrono::steady_clock::now() < end || reads < 1000) {
    if (throng_link_read_frame(&link, copy) != 0) continue;
    ++reads;
    const std::uint64_t tick = copy->tick;
    EXPECT_GE(tick, lastTick) << "frames go forwards";
    lastTick = tick;
    const throng_link_header& h = segment->header();
    bool ok = copy->agent_count == 1 + tick % h.max_agents && copy->time == static_cast<double>(tick) * 0.05;
    const throng_link_agent* agents = throng_link_frame_agents(&h, copy);
    for (std::uint32_t i = 0; ok && i < copy->agent_count; ++i) {
      ok = agents[i].id == static_cast<std::uint32_t>(tick) && agents[i].group == i &&
           agents[i].x == static_cast<float>(tick % 100000) && agents[i].y == -static_cast<float>(tick % 100000);
    }
    throng_link_detailed* d = throng_link_frame_detailed(&h, copy, 0);
    for (int k = 0; ok && k < 9; ++k) ok = throng_link_detailed_angles(d)[k] == static_cast<float>(tick % 100000);
    if (!ok) ++torn;
    if (reads > 2000000) break;
  }
  stop = true;
  writer.join();
  EXPECT_EQ(torn, 0u) << "of " << reads << " reads";
  EXPECT_GT(lastTick, 1u);
}

TEST(LinkSegment, HostInputIsReadConsistently) {
  auto segment = makeSegment("input");
  ASSERT_TRUE(segment);
  throng_link link{};
  link.header = &segment->header();
  std::atomic<bool> stop{false};
  std::thread host([&] {
    for (std::uint32_t k = 1; !stop.load(std::memory_order_relaxed); ++k) {
      const std::uint32_t n = 1 + k % 4;
      throng_link_avatar avatars[4];
      throng_link_guide guides[4];
      std::uint32_t ids[2] = {k, k};
      for (std::uint32_t i = 0; i < 4; ++i) {
        avatars[i] = {k, static_cast<float>(k), static_cast<float>(k), 0.0f, 0.0f};
        guides[i] = {k, i, 1, 0};
      }
      throng_link_write_input(&link, avatars, n, guides, n, ids, 2);
    }
  });
  std::uint64_t reads = 0, torn = 0;
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(500);
  while (std::chrono::steady_clock::now() < end) {
    auto in = segment->readInput();
    if (!in || in->avatars.empty()) continue;
    ++reads;
    const std::uint32_t k = in->avatars[0].id;
    bool ok = in->avatars.size() == 1 + k % 4 && in->guides.size() == in->avatars.size() && in->detailIds.size() == 2;
    for (const auto& a : in->avatars) ok = ok && a.id == k && a.x == static_cast<float>(k);
    for (const auto& g : in->guides) ok = ok && g.group == k;
    for (std::uint32_t id : in->detailIds) ok = ok && id == k;
    if (!ok) ++torn;
  }
  stop = true;
  host.join();
  EXPECT_GT(reads, 0u);
  EXPECT_EQ(torn, 0u) << "of " << reads << " reads";
}

TEST(LinkSegment, RequestsAndRepliesGoRoundTheRings) {
  auto segment = makeSegment("rings");
  ASSERT_TRUE(segment);
  throng_link link{};
  link.header = &segment->header();
  for (std::uint32_t round = 0; round < 3; ++round) {
    for (std::uint32_t i = 0; i < 4; ++i) {
      EXPECT_EQ(throng_link_send_request(&link, THRONG_LINK_REQUEST_INSERT, round * 10 + i, THRONG_LINK_PAYLOAD_JSON,
                                         "{\"populations\": []}", 0),
                0);
    }
    EXPECT_EQ(throng_link_send_request(&link, THRONG_LINK_REQUEST_REMOVE, 99, THRONG_LINK_PAYLOAD_NONE, nullptr, 1), -1)
        << "ring full";
    for (std::uint32_t i = 0; i < 4; ++i) {
      auto r = segment->takeRequest();
      ASSERT_TRUE(r);
      EXPECT_EQ(r->request_id, round * 10 + i);
      EXPECT_STREQ(r->payload, "{\"populations\": []}");
      throng_link_reply reply{};
      reply.request_id = r->request_id;
      reply.status = THRONG_LINK_STATUS_NOT_SUPPORTED;
      std::snprintf(reply.message, sizeof reply.message, "no %u", r->request_id);
      segment->putReply(reply);
    }
    EXPECT_FALSE(segment->takeRequest());
    throng_link_reply out{};
    for (std::uint32_t i = 0; i < 4; ++i) {
      ASSERT_EQ(throng_link_take_reply(&link, &out), 1);
      EXPECT_EQ(out.request_id, round * 10 + i);
      EXPECT_EQ(out.status, THRONG_LINK_STATUS_NOT_SUPPORTED);
    }
    EXPECT_EQ(throng_link_take_reply(&link, &out), 0);
  }
  const std::string long_payload(THRONG_LINK_REQUEST_PAYLOAD, 'x');
  EXPECT_EQ(throng_link_send_request(&link, THRONG_LINK_REQUEST_INSERT, 1, THRONG_LINK_PAYLOAD_JSON,
                                     long_payload.c_str(), 0),
            -1)
      << "payload too large";
}

TEST(LinkSegment, AnExistingNameIsRefusedUnlessForced) {
  SegmentOptions o;
  o.maxJoints = 0;
  auto first = Segment::create(uniqueName("twice"), o);
  ASSERT_TRUE(first.ok());
  auto second = Segment::create(uniqueName("twice"), o);
  ASSERT_FALSE(second.ok());
  EXPECT_NE(second.errors().front().format().find("exists already"), std::string::npos)
      << second.errors().front().format();
  auto bad = Segment::create("no-slash", o);
  EXPECT_FALSE(bad.ok());
  // Opened by a host, the segment checks out; after the owner goes, the name is gone.
  first.value()->start();
  throng_link link{};
  char error[512];
  ASSERT_EQ(throng_link_open(&link, uniqueName("twice").c_str(), 100, error, sizeof error), 0) << error;
  EXPECT_EQ(link.header->max_agents, o.maxAgents);
  throng_link_close(&link);
  first.value().reset();
  EXPECT_NE(throng_link_open(&link, uniqueName("twice").c_str(), 50, error, sizeof error), 0);
  EXPECT_NE(std::string(error).find("no throng link segment"), std::string::npos) << error;
}

}  // namespace
}  // namespace throng::link
