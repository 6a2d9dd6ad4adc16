// throng::link::Segment — creates, fills and removes the shared-memory segment of the link
// (include/throng/throng_link.h); the seqlock writer of the frame buffers and the reader of the
// host's input. Reads and writes only the segment.
#include "throng/link/segment.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
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
  header_->joint_count = std::min(joints, header_->max_joints);
  header_->clip_count = std::min(clips, header_->max_clips);
}

void Segment::start() { __atomic_store_n(&header_->crowd_state, THRONG_LINK_CROWD_RUNNING, __ATOMIC_RELEASE); }

void Segment::stop(std::string_view why) {
  copyText(header_->message, sizeof header_->message, why);
  __atomic_store_n(&header_->crowd_state, THRONG_LINK_CROWD_STOPPED, __ATOMIC_RELEASE);
  sem_post(&header_->frame_ready.sem);
}

throng_link_frame& Segment::beginFrame() {
  const std::uint32_t latest = __atomic_load_n(&header_->latest_frame, __ATOMIC_ACQUIRE);
  writing_ = latest == THRONG_LINK_NO_FRAME ? 0u : (latest ^ 1u);
  throng_link_frame& f = *throng_link_frame_at(header_, writing_);
  const std::uint64_t seq = __atomic_load_n(&f.seq, __ATOMIC_RELAXED);
  __atomic_store_n(&f.seq, seq + 1, __ATOMIC_RELAXED);  // odd: readers retry
  __atomic_thread_fence(__ATOMIC_RELEASE);               // ... before any byte of the frame changes
  return f;
}

void Segment::publishFrame() {
  throng_link_frame& f = *throng_link_frame_at(header_, writing_);
  const std::uint64_t seq = __atomic_load_n(&f.seq, __ATOMIC_RELAXED);
  __atomic_store_n(&f.seq, seq + 1, __ATOMIC_RELEASE);  // even: consistent
  __atomic_store_n(&header_->latest_frame, writing_, __ATOMIC_RELEASE);
  beat();
  throng_link_sem_post_once(&header_->frame_ready);
}

void Segment::beat() { __atomic_add_fetch(&header_->crowd_heartbeat, 1, __ATOMIC_RELEASE); }

std::optional<HostInput> Segment::readInput() const {
  throng_link_input* in = throng_link_input_of(header_);
  HostInput out;
  for (int attempt = 0; attempt < 1000; ++attempt) {
    const std::uint64_t before = __atomic_load_n(&in->seq, __ATOMIC_ACQUIRE);
    if (before & 1u) continue;
    const std::uint32_t na = std::min(in->avatar_count, header_->max_avatars);
    const std::uint32_t ng = std::min(in->guide_count, header_->max_guides);
    const std::uint32_t nd = std::min(in->detail_count, header_->max_detailed);
    out.avatars.assign(throng_link_input_avatars(header_), throng_link_input_avatars(header_) + na);
    out.guides.assign(throng_link_input_guides(header_), throng_link_input_guides(header_) + ng);
    out.detailIds.assign(throng_link_input_detail_ids(header_), throng_link_input_detail_ids(header_) + nd);
    __atomic_thread_fence(__ATOMIC_ACQUIRE);
    if (__atomic_load_n(&in->seq, __ATOMIC_RELAXED) == before) {
      out.seq = before;
      return out;
    }
  }
  return std::nullopt;
}

bool Segment::waitInput(std::uint32_t ms) { return throng_link_sem_wait(&header_->input_written, ms) == 1; }

std::optional<throng_link_request> Segment::takeRequest() {
  throng_link_header& h = *header_;
  const std::uint64_t read = __atomic_load_n(&h.requests_read, __ATOMIC_RELAXED);
  if (read == __atomic_load_n(&h.requests_written, __ATOMIC_ACQUIRE)) return std::nullopt;
  // A reply slot must be free before a request is taken (the host reads replies at its pace).
  if (__atomic_load_n(&h.replies_written, __ATOMIC_RELAXED) - __atomic_load_n(&h.replies_read, __ATOMIC_ACQUIRE) >=
      h.max_requests) {
    return std::nullopt;
  }
  throng_link_request r;
  std::memcpy(&r, throng_link_requests(header_) + read % h.max_requests, sizeof r);
  r.payload[THRONG_LINK_REQUEST_PAYLOAD - 1] = '\0';
  r.payload_size = std::min<std::uint32_t>(r.payload_size, THRONG_LINK_REQUEST_PAYLOAD - 1);
  __atomic_store_n(&h.requests_read, read + 1, __ATOMIC_RELEASE);
  return r;
}

void Segment::putReply(const throng_link_reply& reply) {
  throng_link_header& h = *header_;
  const std::uint64_t written = __atomic_load_n(&h.replies_written, __ATOMIC_RELAXED);
  std::memcpy(throng_link_replies(header_) + written % h.max_requests, &reply, sizeof reply);
  __atomic_store_n(&h.replies_written, written + 1, __ATOMIC_RELEASE);
}

}  // namespace throng::link
