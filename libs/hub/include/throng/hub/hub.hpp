// throng::hub::Hub — the shared world's server logic (docs/server.md): client sessions (hello,
// welcome, join, leave, heartbeats, timeouts), participants and their tokens, participant state
// relayed to the others (VLNET's Move, Joints, HandJoints, FaceExpression: stateless, the latest
// wins), groups guided by a participant's avatar, and the crowd: one aggregated, delta-coded,
// compressed crowd frame per client per tick, with interest management, detail tiers and an
// animation granularity regulated from the client's measured link (Musse et al. §4).
//
// No sockets, no clock: a transport delivers messages (onOpen/onMessage/onClose, on its thread)
// and takes what the hub sends through an Outbox; the simulation thread calls applyToWorld before
// a tick, and publish follows each tick (on the simulation thread or a publisher thread of its
// own). Times are passed in [s]. Thread-safe: the sessions under one mutex, what the simulation
// needs (guidance requests, avatars) under a second, so a tick never waits for crowd encoding.
#pragma once
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "throng/core/parallel.hpp"
#include "throng/hub/crowd_requests.hpp"
#include "throng/hub/granularity.hpp"
#include "throng/hub/interest.hpp"
#include "throng/hub/motion_library.hpp"
#include "throng/protocol/crowd_encoder.hpp"
#include "throng/protocol/messages.hpp"
#include "throng/sim/frame.hpp"
#include "throng/sim/world.hpp"

namespace throng::hub {

/// A connection's identity, as the transport names it (never reused, never 0).
using PeerKey = std::uint64_t;

/// What the hub knows of one peer's link, as measured by the transport.
struct LinkCounters {
  std::uint64_t bytesSent = 0;
  std::uint64_t droppedLatest = 0;  ///< crowd frames replaced before they were sent
  std::uint64_t queueBytes = 0;     ///< unsent bytes now
};

/// Where the hub's messages go (the transport, or a test's recorder). Called with the hub's mutex
/// held: implementations must not call back into the hub.
class Outbox {
 public:
  virtual ~Outbox() = default;
  /// `latest`: droppable state — replaces an unsent message to the same peer with the same slot.
  virtual void send(PeerKey peer, std::vector<std::uint8_t> message, bool latest, std::uint32_t slot) = 0;
  /// Sends what is queued, then closes the connection with `reason`.
  virtual void close(PeerKey peer, std::string reason) = 0;
  [[nodiscard]] virtual std::optional<LinkCounters> link(PeerKey peer) const = 0;
};

struct HubOptions {
  std::string serverName = "throng";
  std::size_t maxClients = 100;            ///< more are refused ("server full")
  InterestOptions interest;
  GranularityOptions granularity;
  protocol::CrowdEncoderOptions encoder;
  double heartbeatEverySeconds = 1.0;      ///< the server's heartbeats to each client [s]
  double timeoutSeconds = 10.0;            ///< a client silent this long is closed ("timeout") [s]
  /// A client to which nothing could be sent for this long while data waits for it (it does not
  /// read) is closed ("slow client"); until then its stale crowd frames are simply replaced [s].
  double stallSeconds = 10.0;
  double stateMessagesPerSecond = 60.0;    ///< participant state messages per client [1/s]
  double stateBurst = 120.0;               ///< token bucket size [messages]
  std::size_t maxGuidedGroups = 16;        ///< groups one participant may guide at once
  /// InsertCrowd: crowds one participant may insert per minute (sliding 60 s window); more are
  /// answered with a CrowdResult "rate limited" (the session stays open).
  std::size_t crowdInsertsPerMinute = 4;
  /// InsertCrowd: most agents one inserted crowd may spawn (groups × largest group size, summed);
  /// the World's own limits (sim::kMaxInsertAgents per insertion, kMaxInsertedAgents in all) apply too.
  std::uint64_t maxInsertAgents = sim::kMaxInsertAgents;
  /// InsertCrowd: bounds on one request's text (size, nesting, keys, values, polygon vertices),
  /// checked in one pass before it is parsed; over one, a CrowdResult names the limit and where.
  CrowdLimits crowdLimits;
  /// InsertCrowd: most insertions waiting for the crowd thread at once, all participants together;
  /// more are answered with a CrowdResult "busy" (bounds the memory and the thread's backlog).
  std::size_t maxPendingCrowdInserts = 16;
  /// The world is a recording played back (`throng serve FILE.sqlite`): clients drive it with
  /// ReplayControl (takeReplayControls); there are no groups to guide.
  bool replay = false;
};

/// One client as the server's status output shows it.
struct ClientStatus {
  PeerKey peer = 0;
  std::string name;                 ///< from Hello (and Join)
  bool participant = false;
  std::uint32_t participantId = 0;
  std::uint32_t granularity = 1;    ///< X: animation every X frames
  std::string granularityReason;    ///< why X last changed
  double kbitPerSecond = 0.0;       ///< over the last second
  double roundTripMs = 0.0;
  std::uint64_t framesSent = 0;
  std::uint64_t keyFrames = 0;
  std::uint32_t agentsInView = 0;
  std::vector<std::uint32_t> guiding;  ///< stable group ids
};

struct HubStatus {
  std::size_t clients = 0;
  std::size_t participants = 0;
  std::uint64_t crowdBytes = 0;        ///< crowd frame bytes handed to the transport, all clients
  std::uint64_t crowdFrames = 0;
  std::uint64_t closedForErrors = 0;   ///< connections closed for a bad, unexpected or unauthorised message
  std::vector<ClientStatus> perClient;
};

class Hub {
 public:
  /// `worldJson` is the world description (describeWorld); `motions` samples near-tier poses and
  /// must outlive the hub.
  Hub(HubOptions options, const std::string& worldJson, float tickRateHz, const MotionLibrary& motions,
      Outbox& outbox);
  ~Hub();
  Hub(const Hub&) = delete;
  Hub& operator=(const Hub&) = delete;

  // Transport side (any thread).
  void onOpen(PeerKey peer, std::string remote, double now);
  void onMessage(PeerKey peer, std::span<const std::uint8_t> message, double now);
  void onClose(PeerKey peer, std::string_view reason);

  // Simulation side, between ticks.
  /// Carries out guide and release requests and crowd insertions / removals (InsertCrowd,
  /// RemoveCrowd, answered with a CrowdResult; an inserted crowd's agents appear from the next
  /// tick), moves the guided groups' dynamic goals to their guides' avatars, and gives the world
  /// the avatars as viewers (multiresolution steering). InsertCrowd is parsed and validated on the
  /// hub's own crowd thread against a copy of the world's description, never here: applyToWorld
  /// queues the crowds validated since the last call (World::insertCrowd, cheap) and refreshes
  /// that copy when the world changed. A crowd is removed only by the participant that inserted
  /// it. Always the same World, which must outlive the hub (the crowd thread reads its navmesh).
  void applyToWorld(sim::World& world);
  /// Blocks until every crowd request received so far is validated against `world` and waits for
  /// applyToWorld (tests and tools that want a request carried out at a known tick; a server
  /// never waits). Simulation thread, between ticks.
  void awaitCrowdValidation(const sim::World& world);
  /// Crowd id → the participant that inserted it (crowds of the scenario are not listed).
  [[nodiscard]] std::map<std::string, std::uint32_t> crowdOwners() const;
  /// Sends every welcomed client its crowd frame for `frame`, the server heartbeats, and closes
  /// clients that timed out or stalled. Clients' frames are encoded in parallel on `tasks` when
  /// given. May run on its own thread, beside the simulation: applyToWorld never waits for it.
  void publish(const sim::Frame& frame, double now, const core::TaskSystem* tasks = nullptr);

  /// Replay: the ReplayControl messages received since the last call, in order.
  [[nodiscard]] std::vector<protocol::ReplayControl> takeReplayControls();
  /// Sends `message` to every welcomed client (reliable), e.g. a ReplayStatus.
  void broadcast(const std::vector<std::uint8_t>& message);

  /// Keeps the Common Ground action-script entries of `frame` (the simulation thread calls it for
  /// every frame, so none is missed when the publisher skips one).
  void observe(const sim::Frame& frame);
  /// The action-script entries agent `id` carried out in its latest coordination (oldest first).
  [[nodiscard]] std::vector<sim::ScriptRecord> agentScript(std::uint32_t id) const;

  /// Tells every client why the server stops (Bye) and closes them.
  void shutdown(const std::string& reason);

  [[nodiscard]] HubStatus status() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace throng::hub
