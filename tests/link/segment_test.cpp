// throng::link::Segment (libs/link/src/segment.cpp) and the reader helpers of throng_link.h: the
// seqlock / double-buffer frame reader never returns a torn frame while a writer thread rewrites
// the frames as fast as it can; the host input's seqlock likewise; the request / reply rings; a
// second segment of the same name is refused.
#include <gtest/gtest.h>

#include <atomic>
#include <limits>
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

TEST(LinkSegment, ADamagedHeaderIsNamedAndNeverFollowed) {
  auto segment = makeSegment("damaged");
  ASSERT_TRUE(segment);
  EXPECT_FALSE(segment->damaged());
  throng_link_header& h = segment->header();
  // Input past the capacities and not finite: cut and marked, never read beyond the region.
  throng_link_input* in = throng_link_input_of(&h);
  throng_link_input_avatars(&h)[0] = {1, std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f, 0.0f};
  throng_link_input_avatars(&h)[1] = {2, 3.0f, 4.0f, 0.0f, 0.5f};
  in->avatar_count = 0xffffffffu;
  in->guide_count = 5;
  in->detail_count = 0xffffffffu;
  h.max_avatars = 0xffffffffu;  // the old reader cut counts to these
  h.max_detailed = 0xffffffffu;
  auto input = segment->readInput();
  ASSERT_TRUE(input);
  EXPECT_EQ(input->avatars.size(), 4u);
  EXPECT_EQ(input->guides.size(), 4u);
  EXPECT_EQ(input->detailIds.size(), 2u);
  ASSERT_EQ(input->avatarUsable.size(), 4u);
  EXPECT_FALSE(input->avatarUsable[0]);
  EXPECT_TRUE(input->avatarUsable[1]);
  ASSERT_GE(input->problems.size(), 4u);
  EXPECT_EQ(input->problems[0], "avatar_count 4294967295 is more than max_avatars 4: only the first 4 are read");
  EXPECT_EQ(input->problems[1], "guide_count 5 is more than max_guides 4: only the first 4 are read");
  EXPECT_EQ(input->problems[3], "avatar 0 (id 1) has a position or heading that is not a finite number within 1000000 m: ignored");
  const auto why = segment->damaged();
  ASSERT_TRUE(why);
  EXPECT_EQ(*why, "max_detailed is 4294967295, this crowd process wrote 2");  // the first field that differs
  // Frames are written where the crowd put them, whatever the header says now.
  h.max_avatars = 4;
  h.max_detailed = 2;
  const std::uint64_t frame1 = h.frame_offset[1];
  h.frame_offset[1] = std::uint64_t{1} << 40;
  writeFrame(*segment, 1);  // the test's writer reads the header: the same capacities as the segment
  writeFrame(*segment, 2);
  EXPECT_EQ(*segment->damaged(), "frame_offset[1] is 1099511627776, this crowd process wrote " + std::to_string(frame1));
  h.frame_offset[1] = frame1;
  EXPECT_EQ(reinterpret_cast<throng_link_frame*>(reinterpret_cast<unsigned char*>(&h) + frame1)->tick, 2u);
  // A request ring the host ran past its size is not read.
  h.requests_written = 1000;
  EXPECT_FALSE(segment->takeRequest());
  EXPECT_EQ(*segment->damaged(), "requests_written is 1000 but 0 requests were taken and the ring holds 4");
  h.requests_written = 0;
  h.magic = 0;
  EXPECT_EQ(*segment->damaged(), "the magic is 0, this crowd process wrote " + std::to_string(THRONG_LINK_MAGIC));
}

}  // namespace
}  // namespace throng::link
