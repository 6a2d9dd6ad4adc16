// `throng link --shm NAME SCENARIO.json` — runs the crowd as an external process that a host
// application drives over POSIX shared memory (Musse et al. §5; include/throng/throng_link.h,
// docs/integration.md). Each tick: read the host's input (avatars → World::setViewers, guides →
// World::guide / release), answer its requests, step the World, write the frame (and the joint
// angles of the agents the host asked for) into the idle frame buffer, bump the heartbeat, post
// frame_ready. Optionally tells hosts the segment's name over a UNIX socket (--socket). Ends at
// --duration, on Ctrl-C, when the host detaches or when its heartbeat stops; then removes the
// segment. Reads the scenario and its clips; writes the segment, the socket, lines on stdout and
// problems on stderr.
//
// The parts: FrameWriter (a frame into the segment), HostInputApplier (avatars and guides into the
// World), answerRequests (crowd insertion and removal), HostWatch (attach, detach, heartbeat) and
// LinkLoop (the real-time loop).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <thread>

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "commands.hpp"
#include "live_world.hpp"
#include "output.hpp"
#include "signal.hpp"
#include "validators.hpp"
#include "throng/core/parallel.hpp"
#include "throng/hub/motion_library.hpp"
#include "throng/hub/crowd_requests.hpp"
#include "throng/io/crowd_loader.hpp"
#include "throng/io/scenario_loader.hpp"
#include "throng/link/handshake_server.hpp"
#include "throng/link/segment.hpp"
#include "throng/sim/animation.hpp"
#include "throng/sim/world.hpp"

namespace throng::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

void copyName(char* dst, std::size_t size, const std::string& text) {
  const std::size_t n = std::min(size - 1, text.size());
  std::memcpy(dst, text.data(), n);
  dst[n] = '\0';
}

/// Writes one frame of the World into the segment's idle buffer.
class FrameWriter {
 public:
  FrameWriter(link::Segment& segment, const hub::MotionLibrary& motions) : segment_(segment), motions_(motions) {}

  void write(const sim::Frame& frame, const sim::World& world, const std::vector<std::uint32_t>& detailIds) {
    // Capacities from the segment's own copy of the layout, never from the shared header.
    const std::uint32_t maxAgents = segment_.maxAgents(), maxDetailed = segment_.maxDetailed();
    const std::uint32_t joints = segment_.jointCount();
    // Stable group of each agent (ids are spawn order, groups 0 .. groupCount - 1).
    const std::size_t groups = world.groupCount();
    groupOf_.assign(world.stats().spawned, 0xffffffffu);
    for (std::uint32_t g = 0; g < groups; ++g) {
      if (auto info = world.groupInfo(world.groupById(g))) {
        for (std::uint32_t m : info->members) {
          if (m < groupOf_.size()) groupOf_[m] = g;
        }
      }
    }
    throng_link_frame& f = segment_.beginFrame();
    const std::uint32_t n = static_cast<std::uint32_t>(std::min<std::size_t>(frame.size(), maxAgents));
    throng_link_agent* agents = segment_.agents(f);
    for (std::uint32_t i = 0; i < n; ++i) {
      throng_link_agent& a = agents[i];
      a.id = frame.ids[i];
      a.group = a.id < groupOf_.size() ? groupOf_[a.id] : 0xffffffffu;
      a.x = frame.posX[i];
      a.y = frame.posY[i];
      a.z = frame.height(i);  // 0 on flat worlds
      a.yaw = std::atan2(frame.oriY[i], frame.oriX[i]);
      a.phase = frame.phase[i];
      a.clip = frame.clip[i];
      a.mode = static_cast<std::uint8_t>(frame.mode[i]);
      a.reserved = 0;
    }
    // Joint angles of the agents the host wants in full detail (present ones, in its order).
    std::uint32_t detailed = 0;
    for (std::uint32_t id : detailIds) {
      if (detailed >= maxDetailed) break;
      const auto it = std::lower_bound(frame.ids.begin(), frame.ids.end(), id);
      if (it == frame.ids.end() || *it != id) continue;
      const std::size_t row = static_cast<std::size_t>(it - frame.ids.begin());
      throng_link_detailed* d = segment_.detailed(f, detailed++);
      d->id = id;
      d->joint_count = joints;
      d->clip = frame.clip[row];
      d->reserved0 = 0;
      d->phase = frame.phase[row];
      if (joints > 0) {
        motions_.sample(frame.clip[row], frame.phase[row],
                        std::span<float>(throng_link_detailed_angles(d), std::size_t{3} * joints));
      }
    }
    f.tick = frame.tick;
    f.time = frame.time;
    f.agent_count = n;
    f.total_agents = static_cast<std::uint32_t>(frame.size());
    f.detailed_count = detailed;
    f.group_count = static_cast<std::uint32_t>(groups);
    f.flags = frame.size() > maxAgents ? THRONG_LINK_FRAME_TRUNCATED : 0u;
    segment_.publishFrame();
  }

 private:
  link::Segment& segment_;
  const hub::MotionLibrary& motions_;
  std::vector<std::uint32_t> groupOf_;
};

/// Applies the host's avatars and guides to the World; remembers which groups it guides. What the
/// host wrote was checked by Segment::readInput: unusable avatars are left out and said once.
class HostInputApplier {
 public:
  void apply(const link::HostInput& in, sim::World& world) {
    for (const std::string& problem : in.problems) warn(problem);
    std::vector<core::Vec2> viewers;
    viewers.reserve(in.avatars.size());
    for (std::size_t i = 0; i < in.avatars.size(); ++i) {
      if (in.avatarUsable[i]) viewers.push_back({in.avatars[i].x, in.avatars[i].y});
    }
    world.setViewers(std::move(viewers));
    std::set<std::uint32_t> now;
    for (const throng_link_guide& g : in.guides) {
      if (!g.active) continue;
      const sim::GroupId handle = world.groupById(g.group);
      if (handle.isNull() || g.avatar >= in.avatars.size() || !in.avatarUsable[g.avatar]) {
        warn(fmt::format("guide record for group {} ignored: {}", g.group,
                         handle.isNull()                      ? "no such group"
                         : g.avatar >= in.avatars.size() ? "its avatar index is past the avatar count"
                                                              : "its avatar's position is not usable"));
        continue;
      }
      world.guide(handle, {in.avatars[g.avatar].x, in.avatars[g.avatar].y}, in.avatars[g.avatar].z);
      now.insert(g.group);
    }
    for (std::uint32_t g : guided_) {
      if (!now.contains(g)) world.release(world.groupById(g));
    }
    guided_ = std::move(now);
  }
  /// The host left: every group it guided goes back to its own goals, no viewers.
  void releaseAll(sim::World& world) {
    for (std::uint32_t g : guided_) world.release(world.groupById(g));
    guided_.clear();
    world.setViewers({});
  }

 private:
  /// Each distinct warning once, at most kMaxWarnings in all (a host writing garbage every tick
  /// must not flood the terminal).
  void warn(const std::string& text) {
    static constexpr std::size_t kMaxWarnings = 20;
    if (warned_.size() > kMaxWarnings || !warned_.insert(text).second) return;
    printLine(stderr, "throng link: warning: " + (warned_.size() > kMaxWarnings ? std::string("further warnings about the host's input are not shown") : text));
  }
  std::set<std::uint32_t> guided_;
  std::set<std::string> warned_;
};

/// A crowd file's text (at most 4 MiB), or nothing when it cannot be read.
std::optional<std::string> readCrowdFile(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec) || std::filesystem::file_size(path, ec) > (4u << 20) || ec) return std::nullopt;
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) return std::nullopt;
  std::string text;
  char buffer[65536];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, f)) > 0;) text.append(buffer, n);
  const bool failed = std::ferror(f) != 0;
  std::fclose(f);
  if (failed) return std::nullopt;
  return text;
}

/// The host's crowd requests: an insertion is parsed and validated against the running world (a
/// bad file changes nothing and the reply says why, file:line:col and all); a valid one is queued
/// and its agents appear at the next tick. A removal names the crowd id an insertion replied.
void answerRequests(link::Segment& segment, sim::World& world) {
  while (auto r = segment.takeRequest()) {
    throng_link_reply reply{};
    reply.request_id = r->request_id;
    std::string message;
    if (r->kind == THRONG_LINK_REQUEST_INSERT) {
      const std::string payload(r->payload, std::min<std::size_t>(r->payload_size, THRONG_LINK_REQUEST_PAYLOAD - 1));
      // Parsing, validation and the queueing are the server's too (hub/crowd_requests.hpp).
      std::optional<hub::CrowdOutcome> outcome;
      if (r->payload_kind == THRONG_LINK_PAYLOAD_PATH) {
        if (auto text = readCrowdFile(payload)) {
          outcome = hub::insertCrowdJson(world, *text, payload);
        } else {
          reply.status = THRONG_LINK_STATUS_INVALID;
          message = fmt::format("{}: cannot read the crowd file (missing, unreadable or over 4 MiB)", payload);
        }
      } else if (r->payload_kind == THRONG_LINK_PAYLOAD_JSON) {
        outcome = hub::insertCrowdJson(world, payload, fmt::format("host request {}", r->request_id));
      } else {
        reply.status = THRONG_LINK_STATUS_INVALID;
        message = fmt::format("insert: payload_kind {}; expected 1 (a path) or 2 (the crowd JSON)", r->payload_kind);
      }
      if (outcome) {
        reply.status = outcome->ok         ? THRONG_LINK_STATUS_OK
                       : outcome->tooLarge ? THRONG_LINK_STATUS_TOO_LARGE
                                           : THRONG_LINK_STATUS_INVALID;
        if (outcome->ok) reply.crowd = outcome->index;
        message = outcome->text;
      }
    } else if (r->kind == THRONG_LINK_REQUEST_REMOVE) {
      const std::vector<sim::CrowdInfo> crowds = world.crowds();
      if (r->target < crowds.size() && !crowds[r->target].removed && world.removeCrowd(crowds[r->target].id)) {
        reply.status = THRONG_LINK_STATUS_OK;
        reply.crowd = r->target;
        message = fmt::format("crowd '{}' ({}) removed: its agents leave at the next tick", crowds[r->target].id, r->target);
      } else {
        reply.status = THRONG_LINK_STATUS_UNKNOWN;
        message = fmt::format("remove: no crowd {} present; {} crowds were inserted", r->target, crowds.size());
      }
    } else {
      reply.status = THRONG_LINK_STATUS_INVALID;
      message = fmt::format("unknown request kind {}; expected 1 (insert) or 2 (remove)", r->kind);
    }
    copyName(reply.message, sizeof reply.message, message);
    segment.putReply(reply);
  }
}


/// The segment's name: --shm with a leading '/', else /throng-<pid> (with --socket); empty when
/// neither flag was given.
std::string segmentName(const LinkOptions& options) {
  std::string name = options.shm;
  if (name.empty() && options.socket.empty()) return {};
  if (name.empty()) name = fmt::format("/throng-{}", getpid());
  if (name[0] != '/') name.insert(name.begin(), '/');
  return name;
}

link::SegmentOptions segmentOptions(const LinkOptions& options, const sim::ScenarioDesc& desc,
                                    const hub::MotionLibrary& motions, double tickRate) {
  link::SegmentOptions so;
  so.maxAgents = static_cast<std::uint32_t>(options.maxAgents);
  so.maxDetailed = static_cast<std::uint32_t>(options.maxDetailed);
  so.maxJoints = static_cast<std::uint32_t>(motions.jointCount());
  so.maxAvatars = static_cast<std::uint32_t>(options.maxAvatars);
  so.maxGuides = static_cast<std::uint32_t>(options.maxGuides);
  so.maxClips = static_cast<std::uint32_t>(motions.clips().size());
  so.dt = desc.dt;
  so.tickRate = tickRate;
  so.heartbeatTimeoutMs = static_cast<std::uint32_t>(std::lround(options.hostTimeout * 1000.0));
  so.lockstep = options.lockstep;
  so.force = options.force;
  so.scenario = desc.name.empty() ? fs::path(options.scenario).stem().string() : desc.name;
  return so;
}

/// Skeleton and clips, written once before hosts may read.
void writeSkeletonAndClips(link::Segment& segment, const hub::MotionLibrary& motions) {
  const hub::Skeleton& skeleton = motions.skeleton();
  for (std::size_t j = 0; j < skeleton.names.size(); ++j) {
    throng_link_joint& out = segment.skeleton()[j];
    copyName(out.name, sizeof out.name, skeleton.names[j]);
    out.parent = skeleton.parents[j];
    std::copy(skeleton.offsets[j].begin(), skeleton.offsets[j].end(), out.offset);
  }
  for (std::size_t c = 0; c < motions.clips().size(); ++c) {
    throng_link_clip& out = segment.clips()[c];
    copyName(out.name, sizeof out.name, motions.clips()[c].name);
    out.duration = motions.clips()[c].duration;
    out.loops = motions.clips()[c].loops ? 1u : 0u;
  }
  segment.setCounts(static_cast<std::uint32_t>(skeleton.names.size()), static_cast<std::uint32_t>(motions.clips().size()));
}

/// The UNIX-socket handshake (--socket), or nullptr without it; false when it failed (printed).
bool startHandshake(const LinkOptions& options, const std::string& name, std::unique_ptr<link::HandshakeServer>& out) {
  if (options.socket.empty()) return true;
  const bool quiet = options.quiet;
  auto started = link::HandshakeServer::start(options.socket, name, options.force,
                                              [quiet](bool refused, const std::string& message) {
                                                if (refused) printLine(stderr, "throng link: " + message);
                                                else if (!quiet) printLine(stdout, "throng link: " + message);
                                              });
  if (!started) {
    printDiagnostics(started.errors());
    return false;
  }
  out = std::move(started).value();
  return true;
}

/// Why the link ended (or a host left) and the exit code that goes with it.
struct LinkEnd {
  std::string reason;
  int exitCode = kExitOk;
};

/// The host's side of the header: it attaches (version check), leaves, or falls silent.
class HostWatch {
 public:
  HostWatch(throng_link_header& h, const LinkOptions& options) : h_(h), options_(options) {}

  [[nodiscard]] bool attached() const { return attached_; }

  /// Reads the host's state: attaches a host of the right version (refuses another), and says
  /// when an attached host detached or its heartbeat stopped for --host-timeout (then detached).
  std::optional<LinkEnd> poll() {
    const std::uint32_t hostState = __atomic_load_n(&h_.host_state, __ATOMIC_ACQUIRE);
    if (!attached_ && hostState == THRONG_LINK_HOST_ATTACHED) attach();
    if (!attached_) return std::nullopt;
    const std::uint64_t beat = __atomic_load_n(&h_.host_heartbeat, __ATOMIC_ACQUIRE);
    std::optional<LinkEnd> gone;
    if (hostState == THRONG_LINK_HOST_DETACHED) {
      gone = LinkEnd{"host detached", kExitOk};
    } else if (beat != lastBeat_) {
      lastBeat_ = beat;
      lastChange_ = Clock::now();
    } else if (secondsSince(lastChange_) >= options_.hostTimeout) {
      gone = LinkEnd{fmt::format("host stopped: no heartbeat for {:.1f} s", secondsSince(lastChange_)), kExitFailure};
    }
    if (gone) attached_ = false;
    return gone;
  }
  /// Ready for the next host (--keep-alive).
  void reset() { __atomic_store_n(&h_.host_state, THRONG_LINK_HOST_NONE, __ATOMIC_RELEASE); }

 private:
  void attach() {
    if (h_.host_version != THRONG_LINK_VERSION) {
      const std::string why = fmt::format("host (pid {}) speaks link version {}, this crowd speaks version {}: refused",
                                          h_.host_pid, h_.host_version, THRONG_LINK_VERSION);
      copyName(h_.message, sizeof h_.message, why);
      __atomic_store_n(&h_.host_state, THRONG_LINK_HOST_REFUSED, __ATOMIC_RELEASE);
      printLine(stderr, "throng link: " + why);
      return;
    }
    attached_ = true;
    lastBeat_ = __atomic_load_n(&h_.host_heartbeat, __ATOMIC_ACQUIRE);
    lastChange_ = Clock::now();
    if (!options_.quiet) printLine(stdout, fmt::format("throng link: host attached (pid {})", h_.host_pid));
  }

  throng_link_header& h_;
  const LinkOptions& options_;
  bool attached_ = false;
  std::uint64_t lastBeat_ = 0;
  Clock::time_point lastChange_ = Clock::now();
};

/// The real-time loop: the host's state, its input and requests, one World step and one frame per
/// period (or per input_written with --lockstep), until --duration, Ctrl-C, a damaged header or
/// the host leaving (unless --keep-alive).
class LinkLoop {
 public:
  LinkLoop(const LinkOptions& options, link::Segment& segment, sim::World& world, const hub::MotionLibrary& motions)
      : options_(options), segment_(segment), world_(world), tasks_(options.threads), writer_(segment, motions),
        host_(segment.header(), options) {}

  LinkEnd run(double tickRate, Clock::time_point start) {
    const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / tickRate));
    auto next = Clock::now();
    while (true) {
      if (InterruptGuard::requested()) return {"interrupted (Ctrl-C)", kExitInterrupted};
      // The layout is this process's own copy, so a damaged header cannot make it crash; but hosts
      // address the segment through the header, so a damaged one ends the link.
      if (const auto why = segment_.damaged()) return {"the segment's header was overwritten (" + *why + "): stopped", kExitFailure};
      if (options_.duration && secondsSince(start) >= *options_.duration) return {"duration reached", kExitOk};
      if (auto gone = host_.poll()) {
        if (auto end = hostLeft(*gone)) return *end;
      }
      // Lockstep: the host sets the pace; beat while waiting so it knows we are alive.
      if (options_.lockstep && !segment_.waitInput(100)) {
        segment_.beat();
        continue;
      }
      tick();
      next += period;
      const auto now = Clock::now();
      if (now > next) {
        next = now;  // late: never catch up in a burst
      } else {
        std::this_thread::sleep_until(next);
      }
    }
  }
  [[nodiscard]] std::uint64_t ticks() const { return ticks_; }

 private:
  /// The host left: its groups go back to their goals; the link ends, or waits for the next host.
  std::optional<LinkEnd> hostLeft(const LinkEnd& gone) {
    applier_.releaseAll(world_);
    detailIds_.clear();
    if (!options_.keepAlive) {
      if (gone.exitCode != kExitOk) printLine(stderr, "throng link: " + gone.reason);
      return gone;
    }
    printLine(gone.exitCode == kExitOk ? stdout : stderr, "throng link: " + gone.reason + "; waiting for the next host");
    host_.reset();
    return std::nullopt;
  }

  /// The host's input and requests, one step, one frame.
  void tick() {
    if (host_.attached()) {
      if (auto in = segment_.readInput()) {
        applier_.apply(*in, world_);
        detailIds_ = std::move(in->detailIds);
      }
    }
    answerRequests(segment_, world_);
    world_.step(tasks_);
    const sim::FramePtr frame = world_.takeFrame();
    writer_.write(*frame, world_, detailIds_);
    ++ticks_;
  }

  const LinkOptions& options_;
  link::Segment& segment_;
  sim::World& world_;
  core::TaskSystem tasks_;
  FrameWriter writer_;
  HostInputApplier applier_;
  HostWatch host_;
  std::vector<std::uint32_t> detailIds_;
  std::uint64_t ticks_ = 0;
};

}  // namespace

CLI::App* addLinkCommand(CLI::App& app, LinkOptions& options) {
  CLI::App* cmd = app.add_subcommand("link", "Run the crowd for a host application over shared memory");
  cmd->footer(
      "Runs the scenario in real time in a POSIX shared-memory segment that a host application (a game\n"
      "engine, a virtual-world client, a robot simulator) opens by name: the crowd's frames go in, the host's\n"
      "avatars and the groups they guide come out. Layout: include/throng/throng_link.h; protocol and the\n"
      "three ways of starting: docs/integration.md. With --socket PATH, hosts can also connect to a UNIX\n"
      "socket to learn the segment's name. Ends at --duration, on Ctrl-C, when the host detaches (exit 0)\n"
      "or when its heartbeat stops (exit 1; with --keep-alive it waits for the next host instead).\n"
      "Crowd insertion/removal requests from the host (a crowd file's path or its JSON) are validated\n"
      "against the running world and carried out at the next tick (docs/integration.md).");
  cmd->add_option("scenario", options.scenario, "Scenario JSON file")->required()->type_name("SCENARIO.json");
  cmd->add_option("--shm", options.shm, "Name of the shared-memory segment (\"/throng-1\"; a missing leading / is "
                                        "added). Default with --socket: /throng-<pid>")
      ->type_name("NAME");
  cmd->add_option("--socket", options.socket, "Also listen on this UNIX socket path and tell each host the segment's "
                                              "name and the layout version")
      ->type_name("PATH");
  cmd->add_option("--tick", options.tick, "Ticks per second in real time; default 1/dt of the scenario")
      ->type_name("HZ")
      ->check(positiveNumber("Hz"));
  cmd->add_option("--duration", options.duration, "Stop after this many seconds of wall-clock time (default: "
                                                  "until Ctrl-C or the host leaves)")
      ->type_name("S")
      ->check(positiveNumber("s"));
  cmd->add_option("--max-agents", options.maxAgents, "Agent records per frame; more agents are left out and the "
                                                     "frame is flagged truncated")
      ->check(integerRange(1, 10000000))
      ->capture_default_str();
  cmd->add_option("--max-detailed", options.maxDetailed, "Agents whose joint angles a host may ask for per frame")
      ->check(integerRange(1, 1024))
      ->capture_default_str();
  cmd->add_option("--max-avatars", options.maxAvatars, "Avatar records the host may write")
      ->check(integerRange(1, 1024))
      ->capture_default_str();
  cmd->add_option("--max-guides", options.maxGuides, "Guide records the host may write")
      ->check(integerRange(1, 1024))
      ->capture_default_str();
  cmd->add_option("--host-timeout", options.hostTimeout, "A host whose heartbeat stays still this long is gone [s]")
      ->check(positiveNumber("s"))
      ->capture_default_str();
  cmd->add_flag("--keep-alive", options.keepAlive, "When the host leaves or stops, release its groups and wait "
                                                   "for the next host instead of exiting");
  cmd->add_flag("--lockstep", options.lockstep, "Step only after the host posts input_written (the host sets the "
                                                "pace; --tick is then a maximum)");
  cmd->add_flag("--force", options.force, "Replace an existing segment or socket file of the same name");
  cmd->add_option("--threads", options.threads, "Simulation worker threads; 0 = all hardware threads")
      ->check(integerRange(0, 1024))
      ->capture_default_str();
  cmd->add_option("--seed", options.seed, "Random seed; overrides the scenario's \"seed\"")->type_name("N");
  cmd->add_flag("--quiet", options.quiet, "Only errors and the lines a host's launcher waits for");
  return cmd;
}

int runLink(const LinkOptions& options) {
  InterruptGuard interrupts;
  const std::string name = segmentName(options);
  if (name.empty()) {
    printLine(stderr, "throng link: give --shm NAME (the segment's name), --socket PATH, or both");
    return kExitUsage;
  }
  if (auto missing = checkInputFile(options.scenario, "scenario"); !missing.empty()) {
    printDiagnostics(missing);
    return kExitFailure;
  }
  auto live = makeLiveWorld(io::loadScenarioFile(options.scenario), options.seed,
                            fs::path(options.scenario).parent_path(), "link", options.quiet);
  if (!live) return kExitFailure;
  const double tickRate = options.tick ? *options.tick : 1.0 / live->scenario.desc.dt;
  const link::SegmentOptions so = segmentOptions(options, live->scenario.desc, live->motions, tickRate);
  auto made = link::Segment::create(name, so);
  if (!made) {
    printDiagnostics(made.errors());
    return kExitFailure;
  }
  std::unique_ptr<link::Segment> segment = std::move(made).value();
  writeSkeletonAndClips(*segment, live->motions);
  std::unique_ptr<link::HandshakeServer> handshake;
  if (!startHandshake(options, name, handshake)) return kExitFailure;
  segment->start();
  // Launchers and tests wait for these lines (printed even with --quiet).
  printLine(stdout, fmt::format("throng link: {} — segment {} (layout version {}), {:.4g} ticks/s{}", so.scenario, name,
                                THRONG_LINK_VERSION, tickRate, options.lockstep ? ", lockstep" : ""));
  if (handshake) printLine(stdout, fmt::format("  socket     {}", options.socket));
  printLine(stdout, "  waiting for a host (Ctrl-C to stop)");

  LinkLoop loop(options, *segment, *live->world, live->motions);
  const auto start = Clock::now();
  const LinkEnd end = loop.run(tickRate, start);
  segment->stop(end.reason);
  handshake.reset();
  segment.reset();  // removes the segment's name; hosts still mapping it read STOPPED and the reason
  if (!options.quiet || end.exitCode != kExitOk) {
    printLine(end.exitCode == kExitOk ? stdout : stderr,
              fmt::format("throng link: {} after {}: {} ticks; segment {} removed", end.reason,
                          formatSeconds(secondsSince(start)), loop.ticks(), name));
  }
  return end.exitCode;
}

}  // namespace throng::cli
