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

/// A consistent copy of the host's input, checked: counts are cut to the capacities, and an avatar
/// whose position or heading is not finite (or beyond kMaxCoordinate) is marked unusable.
struct HostInput {
  std::uint64_t seq = 0;
  std::vector<throng_link_avatar> avatars;
  std::vector<bool> avatarUsable;  ///< parallel to avatars (guides index avatars, so none is dropped)
  std::vector<throng_link_guide> guides;
  std::vector<std::uint32_t> detailIds;
  std::vector<std::string> problems;  ///< what was wrong with the host's input, one sentence each
};

/// The largest |coordinate| an avatar may have [m]; beyond it (or NaN, infinite) it is ignored.
inline constexpr double kMaxCoordinate = 1e6;

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
  /// The header, for the fields the host owns (host_state, host_version, host_pid, heartbeat) and
  /// the message. Offsets and capacities are never taken from it: a host may have overwritten
  /// them; the segment keeps its own copy of the layout (and damaged() compares).
  [[nodiscard]] throng_link_header& header() { return *header_; }

  /// Capacities and counts as created (never re-read from the shared header).
  [[nodiscard]] std::uint32_t maxAgents() const { return options_.maxAgents; }
  [[nodiscard]] std::uint32_t maxDetailed() const { return options_.maxDetailed; }
  [[nodiscard]] std::uint32_t jointCount() const { return jointCount_; }

  /// Fill the skeleton and clip tables (between create and start): maxJoints and maxClips records.
  [[nodiscard]] throng_link_joint* skeleton() { return at<throng_link_joint>(layout_.skeletonOffset); }
  [[nodiscard]] throng_link_clip* clips() { return at<throng_link_clip>(layout_.clipsOffset); }
  void setCounts(std::uint32_t joints, std::uint32_t clips);

  /// The agent records (maxAgents) and detailed record `i` (< maxDetailed) of a frame from beginFrame().
  [[nodiscard]] throng_link_agent* agents(throng_link_frame& f) const;
  [[nodiscard]] throng_link_detailed* detailed(throng_link_frame& f, std::uint32_t i) const;

  /// Why the segment can no longer be trusted, or nothing: the magic, the version or a layout
  /// field (offsets, sizes, capacities, counts) differs from what this process wrote, or the host
  /// moved a ring counter impossibly. The run should stop (the header names no valid layout for hosts).
  [[nodiscard]] std::optional<std::string> damaged() const;
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

  /// A consistent, checked copy of the host's input (see HostInput); nullopt when the host kept it
  /// busy for 1000 tries (a host that died while writing: the heartbeat will tell).
  [[nodiscard]] std::optional<HostInput> readInput() const;
  /// Waits up to `ms` for the host's input_written post; true when posted.
  bool waitInput(std::uint32_t ms);

  /// The oldest request not yet taken, if any (and there is room for its reply).
  [[nodiscard]] std::optional<throng_link_request> takeRequest();
  void putReply(const throng_link_reply& reply);

 private:
  Segment() = default;
  template <typename T>
  [[nodiscard]] T* at(std::uint64_t offset) const {
    return reinterpret_cast<T*>(reinterpret_cast<unsigned char*>(header_) + offset);
  }
  std::string name_;
  throng_link_header* header_ = nullptr;
  std::size_t size_ = 0;
  // This process's own copy of what it wrote into the header: every address is computed from it.
  SegmentOptions options_;
  Layout layout_;
  std::uint32_t jointCount_ = 0, clipCount_ = 0;
  std::uint32_t latest_ = THRONG_LINK_NO_FRAME;  ///< newest published buffer
  std::uint64_t requestsRead_ = 0;               ///< requests taken
  std::uint64_t repliesWritten_ = 0;             ///< replies put
  std::uint32_t writing_ = 0;  ///< buffer index between beginFrame and publishFrame
};

}  // namespace throng::link
