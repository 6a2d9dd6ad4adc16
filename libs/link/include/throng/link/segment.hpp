// throng::link::Segment — the crowd process's end of the shared-memory link: it creates the POSIX
// segment laid out as include/throng/throng_link.h says, writes each crowd frame into the idle one
// of the two frame buffers under its seqlock, reads the host's input consistently, takes insert /
// remove requests and puts replies, and removes the segment when it is destroyed. Reads and writes
// only the segment; the World is the app's business.
#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "throng/core/result.hpp"
#include "throng/throng_link.h"

namespace throng::link {

/// Capacities of a new segment (header fields of the same names).
struct SegmentOptions {
  std::uint32_t maxAgents = 10000;  ///< agent records per frame [1, 10^7]
  std::uint32_t maxDetailed = 16;   ///< agents with joint angles per frame [1, 1024]
  std::uint32_t maxJoints = 0;      ///< joints per detailed record (the skeleton's count) [0, 1024]
  std::uint32_t maxAvatars = 16;    ///< [1, 1024]
  std::uint32_t maxGuides = 16;     ///< [1, 1024]
  std::uint32_t maxRequests = 8;    ///< request and reply ring slots [1, 256]
  std::uint32_t maxClips = 0;       ///< clip records [0, 65535]
  double dt = 0.05;                 ///< [s]
  double tickRate = 20.0;           ///< [Hz]
  std::uint32_t heartbeatTimeoutMs = 2000;  ///< [ms]
  bool lockstep = false;            ///< THRONG_LINK_FLAG_LOCKSTEP
  bool force = false;               ///< replace a segment of the same name instead of refusing
  std::string scenario;             ///< name shown to hosts (truncated to 127 bytes)
};

/// A consistent copy of the host's input.
struct HostInput {
  std::uint64_t seq = 0;
  std::vector<throng_link_avatar> avatars;
  std::vector<throng_link_guide> guides;
  std::vector<std::uint32_t> detailIds;
};

/// Offsets and sizes for given capacities (also what the tests use to build a segment by hand).
struct Layout {
  std::uint64_t frameOffset[2] = {0, 0};
  std::uint64_t frameSize = 0;
  std::uint32_t detailedSize = 0;
  std::uint64_t skeletonOffset = 0, clipsOffset = 0, hostOffset = 0, hostSize = 0;
  std::uint64_t requestsOffset = 0, repliesOffset = 0, totalSize = 0;
};
[[nodiscard]] Layout computeLayout(const SegmentOptions& options);
/// Fills a header (in memory of at least layout.totalSize bytes, zeroed) for `options`, state STARTING.
void initHeader(throng_link_header& header, const SegmentOptions& options, const Layout& layout);

class Segment {
 public:
  /// Creates `name` ("/throng-1234": a leading '/', no other '/', at most 255 bytes) with
  /// O_CREAT|O_EXCL; an existing one is refused unless options.force. State STARTING until start().
  static core::Result<std::unique_ptr<Segment>> create(const std::string& name, const SegmentOptions& options);
  /// Removes the segment's name (hosts keep their mapping) and unmaps it.
  ~Segment();
  Segment(const Segment&) = delete;
  Segment& operator=(const Segment&) = delete;

  [[nodiscard]] const std::string& name() const { return name_; }
  [[nodiscard]] throng_link_header& header() { return *header_; }

  /// Fill the skeleton and clip tables (between create and start).
  [[nodiscard]] throng_link_joint* skeleton() { return throng_link_skeleton(header_); }
  [[nodiscard]] throng_link_clip* clips() { return throng_link_clips(header_); }
  void setCounts(std::uint32_t joints, std::uint32_t clips);
  /// crowd_state RUNNING: hosts may read.
  void start();
  /// crowd_state STOPPED with `why` in the header's message; wakes a waiting host.
  void stop(std::string_view why);

  /// The idle frame buffer, its sequence counter made odd. Fill it, then publishFrame().
  [[nodiscard]] throng_link_frame& beginFrame();
  /// Makes the buffer consistent (sequence even), publishes it as the newest, bumps the crowd
  /// heartbeat and posts frame_ready.
  void publishFrame();
  /// Bumps the crowd heartbeat without a frame (idle waits).
  void beat();

  /// A consistent copy of the host's input; nullopt when the host kept it busy for 1000 tries
  /// (a host that died while writing: the heartbeat will tell).
  [[nodiscard]] std::optional<HostInput> readInput() const;
  /// Waits up to `ms` for the host's input_written post; true when posted.
  bool waitInput(std::uint32_t ms);

  /// The oldest request not yet taken, if any (and there is room for its reply).
  [[nodiscard]] std::optional<throng_link_request> takeRequest();
  void putReply(const throng_link_reply& reply);

 private:
  Segment() = default;
  std::string name_;
  throng_link_header* header_ = nullptr;
  std::size_t size_ = 0;
  std::uint32_t writing_ = 0;  ///< buffer index between beginFrame and publishFrame
};

}  // namespace throng::link
