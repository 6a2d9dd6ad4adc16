// throng::link::Segment — creates, fills and removes the shared-memory segment of the link
// (include/throng/throng_link.h); the seqlock writer of the frame buffers and the reader of the
// host's input. Reads and writes only the segment.
#include "throng/link/segment.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <new>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

namespace throng::link {
namespace {

constexpr std::uint64_t kAlign = 64;  // every region starts on a cache line

std::uint64_t alignUp(std::uint64_t v) { return (v + kAlign - 1) / kAlign * kAlign; }

core::Diagnostic problem(const std::string& name, std::string what, std::string expected = {}) {
  core::Diagnostic d;
  d.source = name;
  d.what = std::move(what);
  d.expected = std::move(expected);
  return d;
}

void copyText(char* dst, std::size_t size, std::string_view text) {
  const std::size_t n = std::min(size - 1, text.size());
  std::memcpy(dst, text.data(), n);
  dst[n] = '\0';
}

}  // namespace

Layout computeLayout(const SegmentOptions& o) {
  Layout l;
  l.detailedSize = static_cast<std::uint32_t>(sizeof(throng_link_detailed) + 12u * o.maxJoints);
  l.frameSize = alignUp(sizeof(throng_link_frame) + std::uint64_t{o.maxAgents} * sizeof(throng_link_agent) +
                        std::uint64_t{o.maxDetailed} * l.detailedSize);
  std::uint64_t at = alignUp(sizeof(throng_link_header));
  l.frameOffset[0] = at;
  l.frameOffset[1] = at + l.frameSize;
  at += 2 * l.frameSize;
  l.skeletonOffset = at;
  at = alignUp(at + std::uint64_t{o.maxJoints} * sizeof(throng_link_joint));
  l.clipsOffset = at;
  at = alignUp(at + std::uint64_t{o.maxClips} * sizeof(throng_link_clip));
  l.hostOffset = at;
  l.hostSize = alignUp(sizeof(throng_link_input) + std::uint64_t{o.maxAvatars} * sizeof(throng_link_avatar) +
                       std::uint64_t{o.maxGuides} * sizeof(throng_link_guide) + std::uint64_t{o.maxDetailed} * 4u);
  at += l.hostSize;
  l.requestsOffset = at;
  at = alignUp(at + std::uint64_t{o.maxRequests} * sizeof(throng_link_request));
  l.repliesOffset = at;
  at = alignUp(at + std::uint64_t{o.maxRequests} * sizeof(throng_link_reply));
  l.totalSize = at;
  return l;
}

void initHeader(throng_link_header& h, const SegmentOptions& o, const Layout& l) {
  h.magic = THRONG_LINK_MAGIC;
  h.version = THRONG_LINK_VERSION;
  h.header_size = sizeof(throng_link_header);
  h.flags = o.lockstep ? THRONG_LINK_FLAG_LOCKSTEP : 0u;
  h.total_size = l.totalSize;
  h.max_agents = o.maxAgents;
  h.max_detailed = o.maxDetailed;
  h.max_joints = o.maxJoints;
  h.max_avatars = o.maxAvatars;
  h.max_guides = o.maxGuides;
  h.max_requests = o.maxRequests;
  h.max_clips = o.maxClips;
  h.request_size = sizeof(throng_link_request);
  h.frame_offset[0] = l.frameOffset[0];
  h.frame_offset[1] = l.frameOffset[1];
  h.frame_size = l.frameSize;
  h.agent_size = sizeof(throng_link_agent);
  h.detailed_size = l.detailedSize;
  h.skeleton_offset = l.skeletonOffset;
  h.clips_offset = l.clipsOffset;
  h.host_offset = l.hostOffset;
  h.host_size = l.hostSize;
  h.requests_offset = l.requestsOffset;
  h.replies_offset = l.repliesOffset;
  h.dt = o.dt;
  h.tick_rate = o.tickRate;
  h.heartbeat_timeout_ms = o.heartbeatTimeoutMs;
  h.crowd_pid = static_cast<std::int32_t>(getpid());
  h.latest_frame = THRONG_LINK_NO_FRAME;
  h.crowd_state = THRONG_LINK_CROWD_STARTING;
  copyText(h.scenario, sizeof h.scenario, o.scenario);
}

core::Result<std::unique_ptr<Segment>> Segment::create(const std::string& name, const SegmentOptions& o) {
  if (name.size() < 2 || name[0] != '/' || name.find('/', 1) != std::string::npos || name.size() > 255) {
    return problem(name, "not a shared-memory name", "\"/\" followed by 1 to 254 characters without \"/\" (\"/throng-1\")");
  }
  if (o.maxAgents < 1 || o.maxDetailed < 1 || o.maxAvatars < 1 || o.maxGuides < 1 || o.maxRequests < 1) {
    return problem(name, "a capacity is 0", "at least 1 agent, detailed agent, avatar, guide and request slot");
  }
  const Layout layout = computeLayout(o);
  int flags = O_RDWR | O_CREAT | O_EXCL;
  int fd = shm_open(name.c_str(), flags, 0600);
  if (fd < 0 && errno == EEXIST && o.force) {
    shm_unlink(name.c_str());
    fd = shm_open(name.c_str(), flags, 0600);
  }
  if (fd < 0) {
    if (errno == EEXIST) {
      return problem(name, "a shared-memory segment of this name exists already (another throng link, or one "
                           "that crashed)",
                     "a new name, or --force to replace it");
    }
    return problem(name, std::string("cannot create the shared-memory segment: ") + std::strerror(errno));
  }
  if (ftruncate(fd, static_cast<off_t>(layout.totalSize)) != 0) {
    const int e = errno;
    close(fd);
    shm_unlink(name.c_str());
    return problem(name, std::string("cannot size the segment: ") + std::strerror(e));
  }
  void* memory = mmap(nullptr, layout.totalSize, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  close(fd);
  if (memory == MAP_FAILED) {
    const int e = errno;
    shm_unlink(name.c_str());
    return problem(name, std::string("cannot map the segment: ") + std::strerror(e));
  }
  std::memset(memory, 0, layout.totalSize);
  auto segment = std::unique_ptr<Segment>(new Segment());
  segment->name_ = name;
  segment->size_ = layout.totalSize;
  segment->options_ = o;
  segment->layout_ = layout;
  segment->header_ = static_cast<throng_link_header*>(memory);
  throng_link_header& h = *segment->header_;
  initHeader(h, o, layout);
  if (sem_init(&h.frame_ready.sem, 1, 0) != 0 || sem_init(&h.input_written.sem, 1, 0) != 0) {
    return problem(name, std::string("cannot create the process-shared semaphores: ") + std::strerror(errno));
  }
  return segment;
}

Segment::~Segment() {
  if (!header_) return;
  shm_unlink(name_.c_str());
  // The semaphores stay valid for hosts that still map the segment (sem_destroy would not be).
  munmap(header_, size_);
}

void Segment::setCounts(std::uint32_t joints, std::uint32_t clips) {
  jointCount_ = std::min(joints, options_.maxJoints);
  clipCount_ = std::min(clips, options_.maxClips);
  header_->joint_count = jointCount_;
  header_->clip_count = clipCount_;
}

throng_link_agent* Segment::agents(throng_link_frame& f) const {
  return reinterpret_cast<throng_link_agent*>(reinterpret_cast<unsigned char*>(&f) + sizeof(throng_link_frame));
}

throng_link_detailed* Segment::detailed(throng_link_frame& f, std::uint32_t i) const {
  return reinterpret_cast<throng_link_detailed*>(reinterpret_cast<unsigned char*>(&f) + sizeof(throng_link_frame) +
                                                 std::size_t{options_.maxAgents} * sizeof(throng_link_agent) +
                                                 std::size_t{std::min(i, options_.maxDetailed - 1)} * layout_.detailedSize);
}

std::optional<std::string> Segment::damaged() const {
  const throng_link_header& h = *header_;
  auto load32 = [](const std::uint32_t& v) { return __atomic_load_n(&v, __ATOMIC_RELAXED); };
  auto load64 = [](const std::uint64_t& v) { return __atomic_load_n(&v, __ATOMIC_RELAXED); };
  auto changed = [](const char* field, std::uint64_t now, std::uint64_t was) {
    return std::string(field) + " is " + std::to_string(now) + ", this crowd process wrote " + std::to_string(was);
  };
  if (const std::uint32_t m = load32(h.magic); m != THRONG_LINK_MAGIC) return changed("the magic", m, THRONG_LINK_MAGIC);
  if (const std::uint32_t v = load32(h.version); v != THRONG_LINK_VERSION) return changed("the layout version", v, THRONG_LINK_VERSION);
  const struct {
    const char* field;
    std::uint64_t now, was;
  } fields[] = {
      {"header_size", load32(h.header_size), sizeof(throng_link_header)},
      {"flags", load32(h.flags), options_.lockstep ? THRONG_LINK_FLAG_LOCKSTEP : 0u},
      {"total_size", load64(h.total_size), layout_.totalSize},
      {"max_agents", load32(h.max_agents), options_.maxAgents},
      {"max_detailed", load32(h.max_detailed), options_.maxDetailed},
      {"max_joints", load32(h.max_joints), options_.maxJoints},
      {"max_avatars", load32(h.max_avatars), options_.maxAvatars},
      {"max_guides", load32(h.max_guides), options_.maxGuides},
      {"max_requests", load32(h.max_requests), options_.maxRequests},
      {"max_clips", load32(h.max_clips), options_.maxClips},
      {"request_size", load32(h.request_size), sizeof(throng_link_request)},
      {"frame_offset[0]", load64(h.frame_offset[0]), layout_.frameOffset[0]},
      {"frame_offset[1]", load64(h.frame_offset[1]), layout_.frameOffset[1]},
      {"frame_size", load64(h.frame_size), layout_.frameSize},
      {"agent_size", load32(h.agent_size), sizeof(throng_link_agent)},
      {"detailed_size", load32(h.detailed_size), layout_.detailedSize},
      {"skeleton_offset", load64(h.skeleton_offset), layout_.skeletonOffset},
      {"clips_offset", load64(h.clips_offset), layout_.clipsOffset},
      {"host_offset", load64(h.host_offset), layout_.hostOffset},
      {"host_size", load64(h.host_size), layout_.hostSize},
      {"requests_offset", load64(h.requests_offset), layout_.requestsOffset},
      {"replies_offset", load64(h.replies_offset), layout_.repliesOffset},
      {"joint_count", load32(h.joint_count), jointCount_},
      {"clip_count", load32(h.clip_count), clipCount_},
  };
  for (const auto& f : fields) {
    if (f.now != f.was) return changed(f.field, f.now, f.was);
  }
  const std::uint64_t requests = __atomic_load_n(&h.requests_written, __ATOMIC_ACQUIRE);
  if (requests < requestsRead_ || requests - requestsRead_ > options_.maxRequests) {
    return "requests_written is " + std::to_string(requests) + " but " + std::to_string(requestsRead_) +
           " requests were taken and the ring holds " + std::to_string(options_.maxRequests);
  }
  if (const std::uint64_t read = __atomic_load_n(&h.replies_read, __ATOMIC_ACQUIRE); read > repliesWritten_) {
    return "replies_read is " + std::to_string(read) + " but only " + std::to_string(repliesWritten_) + " replies were written";
  }
  return std::nullopt;
}

void Segment::start() { __atomic_store_n(&header_->crowd_state, THRONG_LINK_CROWD_RUNNING, __ATOMIC_RELEASE); }

void Segment::stop(std::string_view why) {
  copyText(header_->message, sizeof header_->message, why);
  __atomic_store_n(&header_->crowd_state, THRONG_LINK_CROWD_STOPPED, __ATOMIC_RELEASE);
  sem_post(&header_->frame_ready.sem);
}

throng_link_frame& Segment::beginFrame() {
  writing_ = latest_ == THRONG_LINK_NO_FRAME ? 0u : (latest_ ^ 1u);
  throng_link_frame& f = *at<throng_link_frame>(layout_.frameOffset[writing_]);
  const std::uint64_t seq = __atomic_load_n(&f.seq, __ATOMIC_RELAXED);
  __atomic_store_n(&f.seq, (seq | 1u) == seq ? seq + 2 : seq + 1, __ATOMIC_RELAXED);  // odd: readers retry
  __atomic_thread_fence(__ATOMIC_RELEASE);               // ... before any byte of the frame changes
  return f;
}

void Segment::publishFrame() {
  throng_link_frame& f = *at<throng_link_frame>(layout_.frameOffset[writing_]);
  const std::uint64_t seq = __atomic_load_n(&f.seq, __ATOMIC_RELAXED);
  __atomic_store_n(&f.seq, (seq | 1u) + 1, __ATOMIC_RELEASE);  // even: consistent
  latest_ = writing_;
  __atomic_store_n(&header_->latest_frame, writing_, __ATOMIC_RELEASE);
  beat();
  throng_link_sem_post_once(&header_->frame_ready);
}

void Segment::beat() { __atomic_add_fetch(&header_->crowd_heartbeat, 1, __ATOMIC_RELEASE); }

namespace {

bool usable(const throng_link_avatar& a) {
  for (const float v : {a.x, a.y, a.z, a.yaw}) {
    if (!std::isfinite(v) || std::fabs(static_cast<double>(v)) > kMaxCoordinate) return false;
  }
  return true;
}

}  // namespace

std::optional<HostInput> Segment::readInput() const {
  auto* in = at<throng_link_input>(layout_.hostOffset);
  const auto* avatars = reinterpret_cast<const throng_link_avatar*>(reinterpret_cast<const unsigned char*>(in) + sizeof(throng_link_input));
  const auto* guides = reinterpret_cast<const throng_link_guide*>(avatars + options_.maxAvatars);
  const auto* ids = reinterpret_cast<const std::uint32_t*>(guides + options_.maxGuides);
  HostInput out;
  for (int attempt = 0; attempt < 1000; ++attempt) {
    const std::uint64_t before = __atomic_load_n(&in->seq, __ATOMIC_ACQUIRE);
    if (before & 1u) continue;
    // Counts are read once each (the host may change them meanwhile) and cut to the capacities.
    const std::uint32_t avatarCount = __atomic_load_n(&in->avatar_count, __ATOMIC_RELAXED);
    const std::uint32_t guideCount = __atomic_load_n(&in->guide_count, __ATOMIC_RELAXED);
    const std::uint32_t detailCount = __atomic_load_n(&in->detail_count, __ATOMIC_RELAXED);
    const std::uint32_t na = std::min(avatarCount, options_.maxAvatars);
    const std::uint32_t ng = std::min(guideCount, options_.maxGuides);
    const std::uint32_t nd = std::min(detailCount, options_.maxDetailed);
    out.avatars.assign(avatars, avatars + na);
    out.guides.assign(guides, guides + ng);
    out.detailIds.assign(ids, ids + nd);
    __atomic_thread_fence(__ATOMIC_ACQUIRE);
    if (__atomic_load_n(&in->seq, __ATOMIC_RELAXED) != before) continue;
    out.seq = before;
    out.problems.clear();
    auto over = [&](const char* count, std::uint32_t n, const char* cap, std::uint32_t max) {
      if (n > max) {
        out.problems.push_back(std::string(count) + " " + std::to_string(n) + " is more than " + cap + " " +
                               std::to_string(max) + ": only the first " + std::to_string(max) + " are read");
      }
    };
    over("avatar_count", avatarCount, "max_avatars", options_.maxAvatars);
    over("guide_count", guideCount, "max_guides", options_.maxGuides);
    over("detail_count", detailCount, "max_detailed", options_.maxDetailed);
    out.avatarUsable.assign(out.avatars.size(), true);
    for (std::size_t i = 0; i < out.avatars.size(); ++i) {
      if (usable(out.avatars[i])) continue;
      out.avatarUsable[i] = false;
      out.problems.push_back("avatar " + std::to_string(i) + " (id " + std::to_string(out.avatars[i].id) +
                             ") has a position or heading that is not a finite number within " +
                             std::to_string(static_cast<long long>(kMaxCoordinate)) + " m: ignored");
    }
    return out;
  }
  return std::nullopt;
}

bool Segment::waitInput(std::uint32_t ms) { return throng_link_sem_wait(&header_->input_written, ms) == 1; }

std::optional<throng_link_request> Segment::takeRequest() {
  throng_link_header& h = *header_;
  const std::uint64_t written = __atomic_load_n(&h.requests_written, __ATOMIC_ACQUIRE);
  // A ring the host overran (or wound back) is damaged(): nothing is taken from it.
  if (written <= requestsRead_ || written - requestsRead_ > options_.maxRequests) return std::nullopt;
  // A reply slot must be free before a request is taken (the host reads replies at its pace).
  const std::uint64_t repliesRead = __atomic_load_n(&h.replies_read, __ATOMIC_ACQUIRE);
  if (repliesRead > repliesWritten_ || repliesWritten_ - repliesRead >= options_.maxRequests) return std::nullopt;
  throng_link_request r;
  std::memcpy(&r, at<throng_link_request>(layout_.requestsOffset) + requestsRead_ % options_.maxRequests, sizeof r);
  r.payload[THRONG_LINK_REQUEST_PAYLOAD - 1] = '\0';
  r.payload_size = std::min<std::uint32_t>(r.payload_size, THRONG_LINK_REQUEST_PAYLOAD - 1);
  ++requestsRead_;
  __atomic_store_n(&h.requests_read, requestsRead_, __ATOMIC_RELEASE);
  return r;
}

void Segment::putReply(const throng_link_reply& reply) {
  std::memcpy(at<throng_link_reply>(layout_.repliesOffset) + repliesWritten_ % options_.maxRequests, &reply, sizeof reply);
  ++repliesWritten_;
  __atomic_store_n(&header_->replies_written, repliesWritten_, __ATOMIC_RELEASE);
}

}  // namespace throng::link
