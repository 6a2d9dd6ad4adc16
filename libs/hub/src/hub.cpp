// The shared world's server logic (see hub.hpp): sessions, participants, guidance, crowd frames.
#include "throng/hub/hub.hpp"

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <map>
#include <mutex>
#include <random>
#include <thread>
#include <utility>

#include "throng/core/parallel.hpp"
#include "throng/hub/crowd_requests.hpp"
#include "throng/hub/text.hpp"
#include "throng/protocol/messages.hpp"

namespace throng::hub {
namespace {

using protocol::Bytes;
using protocol::ReasonCode;

/// Transport slots of droppable messages: the crowd frame, and per participant and kind the
/// relayed state (so a burst of Moves from one participant collapses to the newest).
constexpr std::uint32_t kCrowdSlot = 1;
std::uint32_t relaySlot(std::uint32_t participant, protocol::MessageType type) {
  return 0x100u + participant * 8u + (static_cast<std::uint32_t>(type) - static_cast<std::uint32_t>(protocol::MessageType::Move));
}

constexpr double kPi = 3.14159265358979323846;

struct Client {
  PeerKey peer = 0;
  std::string remote;
  std::string name;
  bool welcomed = false;
  bool closing = false;  ///< a Bye was sent; everything else it sends is ignored
  std::uint16_t protocolVersion = protocol::kProtocolVersion;  ///< its Hello's: what it is sent
  // Participant.
  bool participant = false;
  std::uint32_t participantId = 0;
  std::uint64_t token = 0;
  std::uint16_t look = 0;  ///< Join's avatar: the look other viewers draw it in (Presence, version 2)
  std::optional<core::Vec2> avatar;
  float avatarZ = 0.0f;
  std::uint32_t moveSeq = 0;
  // Messages last relayed, sent to clients that arrive later.
  std::map<protocol::MessageType, Bytes> lastState;
  // Link.
  double lastHeard = 0.0;
  double lastHeartbeatSent = -1e300;
  std::uint64_t peerTimeUs = 0;  ///< newest clock the client sent (echoed back)
  double roundTripMs = 0.0;
  std::uint64_t lastBytesSent = 0;
  double lastProgress = 0.0;     ///< when bytes last left for this client
  double tokens = 0.0;           ///< rate limit bucket
  double tokensAt = 0.0;
  std::deque<double> crowdInserts;  ///< when its InsertCrowds were accepted for the queue, last minute [s]
  // Crowd.
  protocol::CrowdEncoder encoder;
  std::uint32_t acked = 0;
  GranularityController granularity;
  std::uint64_t framesSent = 0;
  std::uint64_t keyFrames = 0;
  std::uint32_t agentsInView = 0;
};

struct GuideRequest {
  PeerKey peer = 0;
  std::uint32_t participantId = 0;
  std::uint32_t group = 0;
  bool guide = true;
  bool answer = true;  ///< false: the participant left; nobody to answer
};

/// An InsertCrowd or RemoveCrowd, in the order they came: validated on the crowd worker, then
/// carried out by applyToWorld.
struct CrowdRequest {
  PeerKey peer = 0;
  std::uint32_t participantId = 0;
  std::string name;     ///< the participant's name (the crowd's owner, in refusals)
  std::uint32_t requestId = 0;
  bool insert = true;
  std::string payload;  ///< the crowd file's JSON (insert) or the crowd id (remove)
};

/// A request the worker is done with: an insertion parsed and validated (or refused).
struct CrowdDone {
  CrowdRequest request;
  ParsedCrowd parsed;
};

/// What the worker validates insertions against: a copy of the world's description, its navmesh
/// and the ids of its crowds, refreshed by the simulation thread between ticks when they changed.
struct CrowdContext {
  sim::ScenarioDesc desc;
  io::CrowdOptions options;
};

constexpr double kCrowdInsertWindowSeconds = 60.0;

}  // namespace

struct Hub::Impl {
  HubOptions options;
  const MotionLibrary& motions;
  Outbox& outbox;
  Bytes welcome;
  float tickRate = 10.0f;
  mutable std::mutex mutex;
  std::map<PeerKey, Client> clients;
  std::uint32_t nextParticipantId = 1;
  std::mt19937_64 tokenSource{std::random_device{}()};
  HubStatus totals;
  /// What the simulation thread needs (applyToWorld), under its own small lock so a tick never
  /// waits for the crowd frames being encoded (publish holds `mutex`).
  struct WorldInput {
    std::mutex mutex;
    std::vector<GuideRequest> requests;
    std::map<std::uint32_t, std::uint32_t> guideOf;    ///< group → participant guiding it
    std::map<std::uint32_t, core::Vec2> avatars;       ///< participant → avatar position
    std::map<std::uint32_t, float> avatarHeights;      ///< participant → avatar height [m] (multi-level worlds)
    std::map<std::uint32_t, PeerKey> participants;     ///< participants present → their peer
    std::vector<protocol::ReplayControl> replayControls;
    CrowdOwners owners;                                ///< who inserted each crowd (removal rule)
    std::size_t crowdsQueued = 0;                      ///< insertions queued into the World by the hub
  } input;
  /// Crowd requests: parsed and validated on their own thread, never on the simulation's, so a
  /// large or hostile crowd file cannot stall the tick (docs/server.md).
  struct CrowdWork {
    std::mutex mutex;
    std::condition_variable changed;
    std::deque<CrowdRequest> queue;   ///< waiting for the worker, in arrival order
    std::vector<CrowdDone> done;      ///< waiting for applyToWorld, in arrival order
    std::shared_ptr<const CrowdContext> context;
    bool stale = true;                ///< the world changed since `context` was taken
    bool busy = false;                ///< the worker holds a request
    bool stop = false;
    std::size_t points = 0, populations = 0, queued = 0;  ///< what `context` was taken at
  } work;
  std::thread worker;
  void crowdWorker();
  /// A fresh validation context when the world changed since the last and requests wait for it
  /// (or always with `force`). Simulation thread, between ticks.
  void refreshCrowdContext(const sim::World& world, bool force);
  static float heightOf(const WorldInput& in, std::uint32_t participant) {
    const auto h = in.avatarHeights.find(participant);
    return h == in.avatarHeights.end() ? 0.0f : h->second;
  }
  /// Latest coordination's script entries per agent (observe / agentScript).
  mutable std::mutex scriptMutex;
  std::map<std::uint32_t, std::vector<sim::ScriptRecord>> scripts;

  Impl(HubOptions o, const MotionLibrary& m, Outbox& out) : options(std::move(o)), motions(m), outbox(out) {}

  void fail(Client& c, ReasonCode code, const std::string& text) {
    if (c.closing) return;
    c.closing = true;
    ++totals.closedForErrors;
    outbox.send(c.peer, protocol::encode(protocol::Bye{code, std::string(cutUtf8(text, protocol::kMaxTextLength))}), false, 0);
    outbox.close(c.peer, std::string(cutUtf8(text, 120)));
  }

  void refuse(Client& c, ReasonCode code, const std::string& text) {
    c.closing = true;
    outbox.send(c.peer,
                protocol::encode(protocol::Refuse{protocol::kProtocolVersion, code, std::string(cutUtf8(text, protocol::kMaxTextLength))}),
                false, 0);
    outbox.close(c.peer, std::string(cutUtf8(text, 120)));
  }

  /// Participant state and guidance requests must carry the sender's own token.
  bool owns(Client& c, std::uint64_t token, const char* what) {
    if (!c.participant) {
      fail(c, ReasonCode::UnexpectedMessage, std::string(what) + " before Join: join as a participant first");
      return false;
    }
    if (token != c.token) {
      fail(c, ReasonCode::BadToken, std::string(what) + " with a token that is not this participant's");
      return false;
    }
    return true;
  }

  bool allowState(Client& c, double now) {
    c.tokens = std::min(options.stateBurst, c.tokens + (now - c.tokensAt) * options.stateMessagesPerSecond);
    c.tokensAt = now;
    if (c.tokens < 1.0) {
      fail(c, ReasonCode::RateLimited,
           "more than " + std::to_string(static_cast<int>(options.stateMessagesPerSecond)) +
               " participant messages per second");
      return false;
    }
    c.tokens -= 1.0;
    return true;
  }

  /// Relays a participant's state message to every other welcomed client, as the participant.
  template <class M>
  void relay(Client& from, M message) {
    message.subject = protocol::Subject{protocol::Subject::Kind::Participant, from.participantId};
    Bytes bytes = protocol::encode(message);
    const protocol::MessageType type = protocol::messageType(protocol::Message{message});
    for (auto& [peer, c] : clients) {
      if (peer == from.peer || !c.welcomed || c.closing) continue;
      outbox.send(peer, bytes, true, relaySlot(from.participantId, type));
    }
    from.lastState[type] = std::move(bytes);
  }

  /// `who`'s Presence as a client of protocol `version` reads it: with the look from version 2.
  static Bytes presence(const Client& who, bool present, std::uint16_t version) {
    protocol::Presence m{who.participantId, present, who.name, std::nullopt};
    if (version >= 2) m.avatar = who.look;
    return protocol::encode(m);
  }

  /// Tells every welcomed client (but `except`) that a participant came or went.
  void announce(const Client& who, bool present, PeerKey except) {
    const Bytes bytes = presence(who, present, protocol::kProtocolVersion), v1 = presence(who, present, 1);
    for (auto& [peer, c] : clients) {
      if (peer == except || !c.welcomed || c.closing) continue;
      outbox.send(peer, c.protocolVersion >= 2 ? bytes : v1, false, 0);
    }
  }

  /// The Welcome for a client of protocol `version`: the shared one, its version field set to it.
  Bytes welcomeFor(std::uint16_t version) const {
    Bytes w = welcome;
    w[2] = static_cast<std::uint8_t>(version & 0xff);  // u16 protocolVersion right after the header
    w[3] = static_cast<std::uint8_t>(version >> 8);
    return w;
  }

  /// The participant is gone (Leave, closed): its groups go back to their own goals.
  void dropParticipant(Client& c) {
    announce(c, false, c.peer);
    std::lock_guard lock(input.mutex);
    for (const auto& [group, participant] : input.guideOf) {
      if (participant == c.participantId) input.requests.push_back({c.peer, c.participantId, group, false, false});
    }
    input.avatars.erase(c.participantId);
    input.avatarHeights.erase(c.participantId);
    input.participants.erase(c.participantId);
  }

  // applyToWorld's steps, on the simulation thread with input.mutex held.
  /// Guide and Release requests in order, each answered with a GuideResult (unless its
  /// participant left).
  void applyGuideRequests(sim::World& world);
  /// One Guide or Release; nullopt when the participant asking to guide left meanwhile.
  std::optional<protocol::GuideResult> applyGuideRequest(sim::World& world, const GuideRequest& r);
  /// The crowd worker's finished requests: insertions queued into the World, removals carried
  /// out, each answered with a CrowdResult.
  void applyCrowdRequests(sim::World& world);
  /// Each guided group heads for its guide's avatar; the avatars become the World's viewers.
  void followAvatars(sim::World& world);
  /// One message from a client: Hello first (greet), then one handler per client → server type.
  void handle(Client& c, const protocol::Message& message, double now);
  /// The first message: a Hello of this protocol version, room on the server and a UTF-8 name;
  /// answered with the Welcome, who is here and what the participants said last.
  void greet(Client& c, const protocol::Message& message);
  void on(Client& c, const protocol::Join& m, double now);
  void on(Client& c, const protocol::Leave& m, double now);
  void on(Client& c, const protocol::Heartbeat& m, double now);  ///< a ping answered, or a round trip measured
  void on(Client& c, const protocol::Bye& m, double now);
  void on(Client& c, const protocol::Move& m, double now);
  void on(Client& c, const protocol::Joints& m, double now);
  void on(Client& c, const protocol::HandJoints& m, double now);
  void on(Client& c, const protocol::FaceExpression& m, double now);
  void on(Client& c, const protocol::ReplayControl& m, double now);
  void on(Client& c, const protocol::Guide& m, double now);
  void on(Client& c, const protocol::Release& m, double now);
  void on(Client& c, const protocol::InsertCrowd& m, double now);  ///< rate limits, then the crowd worker's queue
  void on(Client& c, const protocol::RemoveCrowd& m, double now);
  void on(Client& c, const protocol::Ack& m, double now);
  void on(Client& c, const protocol::Hello& m, double now);  ///< a second Hello
  /// Any server → client type: the client is closed.
  template <class M>
  void on(Client& c, const M& m, double now);
  /// Joints, HandJoints, FaceExpression: checked (token, rate) and relayed.
  template <class M>
  void relayState(Client& c, const M& m, double now);
  /// Guide or Release of `group`, for applyToWorld (refused at once on a recording).
  void requestGuidance(Client& c, std::uint64_t token, std::uint32_t group, bool guide, double now);
  /// A CrowdResult refusing request `requestId` with `text`.
  void answerCrowd(const Client& c, std::uint32_t requestId, const std::string& id, std::string text);
  /// Builds and encodes client `c`'s crowd frame (no sending: parallel over clients).
  core::Result<protocol::EncodedCrowdFrame> encodeCrowd(Client& c, const sim::Frame& frame);
};

Hub::Hub(HubOptions options, const std::string& worldJson, float tickRateHz, const MotionLibrary& motions, Outbox& outbox)
    : impl_(std::make_unique<Impl>(std::move(options), motions, outbox)) {
  impl_->tickRate = tickRateHz;
  impl_->welcome = protocol::encode(protocol::makeWelcome(impl_->options.serverName, tickRateHz, worldJson));
  impl_->worker = std::thread([h = impl_.get()] { h->crowdWorker(); });
}

Hub::~Hub() {
  {
    std::lock_guard lock(impl_->work.mutex);
    impl_->work.stop = true;
  }
  impl_->work.changed.notify_all();
  impl_->worker.join();
}

void Hub::Impl::crowdWorker() {
  std::unique_lock lock(work.mutex);
  while (true) {
    // Removals pass in order; an insertion waits for a context taken since the world last changed.
    work.changed.wait(lock, [&] {
      return work.stop || (!work.queue.empty() && (!work.queue.front().insert || (work.context && !work.stale)));
    });
    if (work.stop) return;
    CrowdDone d{std::move(work.queue.front()), {}};
    work.queue.pop_front();
    const std::shared_ptr<const CrowdContext> context = work.context;
    work.busy = true;
    lock.unlock();
    if (d.request.insert) {
      const std::string source = "participant " + std::to_string(d.request.participantId) + " request " +
                                 std::to_string(d.request.requestId);
      try {
        d.parsed = parseCrowdRequest(d.request.payload, source, context->desc, context->options, options.maxInsertAgents,
                                     options.crowdLimits);
      } catch (const std::exception& e) {
        d.parsed.refusal.text = "the server could not validate the crowd: " + std::string(e.what());
        d.parsed.refusal.diagnostics = {{source, 0, 0, "", d.parsed.refusal.text, "", ""}};
      }
      d.request.payload.clear();
      d.request.payload.shrink_to_fit();
    }
    lock.lock();
    work.done.push_back(std::move(d));
    work.busy = false;
    work.changed.notify_all();
  }
}

void Hub::Impl::refreshCrowdContext(const sim::World& world, bool force) {
  const sim::ScenarioDesc& desc = world.desc();
  std::size_t queued = 0;
  {
    std::lock_guard lock(input.mutex);
    queued = input.crowdsQueued;
  }
  {
    std::lock_guard lock(work.mutex);
    const bool stale = !work.context || work.points != desc.points.size() || work.populations != desc.populations.size() ||
                       work.queued != queued;
    if (stale) work.stale = true;
    if (!work.stale || (work.queue.empty() && !force)) return;
  }
  auto context = std::make_shared<CrowdContext>();
  context->desc = desc;
  // The World outlives the hub (hub.hpp): a non-owning pointer to its navmesh.
  context->options.navmesh = std::shared_ptr<const nav::NavMesh>(std::shared_ptr<const nav::NavMesh>(), &world.navMesh());
  for (const sim::CrowdInfo& c : world.crowds()) context->options.takenCrowdIds.push_back(c.id);
  {
    std::lock_guard lock(work.mutex);
    work.context = std::move(context);
    work.stale = false;
    work.points = desc.points.size();
    work.populations = desc.populations.size();
    work.queued = queued;
  }
  work.changed.notify_all();
}

void Hub::awaitCrowdValidation(const sim::World& world) {
  impl_->refreshCrowdContext(world, true);
  std::unique_lock lock(impl_->work.mutex);
  impl_->work.changed.wait(lock, [&] { return impl_->work.queue.empty() && !impl_->work.busy; });
}

std::map<std::string, std::uint32_t> Hub::crowdOwners() const {
  std::lock_guard lock(impl_->input.mutex);
  std::map<std::string, std::uint32_t> out;
  for (const auto& [id, owner] : impl_->input.owners.all()) out.emplace(id, owner.first);
  return out;
}

void Hub::onOpen(PeerKey peer, std::string remote, double now) {
  std::lock_guard lock(impl_->mutex);
  Client c{.peer = peer,
           .remote = std::move(remote),
           .encoder = protocol::CrowdEncoder(impl_->options.encoder),
           .granularity = GranularityController(impl_->options.granularity)};
  c.lastHeard = now;
  c.lastProgress = now;
  c.tokens = impl_->options.stateBurst;
  c.tokensAt = now;
  impl_->clients.emplace(peer, std::move(c));
}

void Hub::onClose(PeerKey peer, std::string_view) {
  std::lock_guard lock(impl_->mutex);
  auto it = impl_->clients.find(peer);
  if (it == impl_->clients.end()) return;
  Client& c = it->second;
  if (c.participant) impl_->dropParticipant(c);
  impl_->clients.erase(it);
}

void Hub::onMessage(PeerKey peer, std::span<const std::uint8_t> bytes, double now) {
  std::lock_guard lock(impl_->mutex);
  auto it = impl_->clients.find(peer);
  if (it == impl_->clients.end() || it->second.closing) return;
  Client& c = it->second;
  c.lastHeard = now;
  auto decoded = protocol::decodeFromClient(bytes);  // the type first: nothing server → client is decoded
  if (!decoded.ok()) {
    impl_->fail(c, ReasonCode::BadMessage, decoded.errors().front().format());
    return;
  }
  impl_->handle(c, decoded.value(), now);
}

void Hub::Impl::handle(Client& c, const protocol::Message& message, double now) {
  if (!c.welcomed) {
    greet(c, message);
    return;
  }
  std::visit([&](const auto& m) { on(c, m, now); }, message);
}

void Hub::Impl::greet(Client& c, const protocol::Message& message) {
  using namespace protocol;
  const auto* hello = std::get_if<Hello>(&message);
  if (hello == nullptr) {
    fail(c, ReasonCode::UnexpectedMessage,
         std::string("expected Hello as the first message, got ") + messageTypeName(messageType(message)));
    return;
  }
  if (hello->protocolVersion < kMinProtocolVersion || hello->protocolVersion > kProtocolVersion) {
    refuse(c, ReasonCode::VersionMismatch,
           "this server speaks protocol versions " + std::to_string(kMinProtocolVersion) + " to " +
               std::to_string(kProtocolVersion) + ", the client " + std::to_string(hello->protocolVersion));
    return;
  }
  const auto welcomed = static_cast<std::size_t>(std::count_if(
      clients.begin(), clients.end(), [](const auto& e) { return e.second.welcomed && !e.second.closing; }));
  if (welcomed >= options.maxClients) {
    refuse(c, ReasonCode::ServerFull, "server full: " + std::to_string(options.maxClients) + " clients (--max-clients)");
    return;
  }
  if (const auto bad = invalidUtf8At(hello->clientName)) {
    refuse(c, ReasonCode::BadMessage,
           "Hello: clientName is not UTF-8 at " + describeByte(hello->clientName, *bad) + "; expected a UTF-8 name");
    return;
  }
  c.welcomed = true;
  c.name = hello->clientName;
  c.protocolVersion = hello->protocolVersion;
  outbox.send(c.peer, welcomeFor(c.protocolVersion), false, 0);
  // Who is here, and everything participants said last, so the newcomer sees their avatars at once.
  for (auto& [peer, other] : clients) {
    if (peer == c.peer) continue;
    if (other.participant && !other.closing) {
      outbox.send(c.peer, presence(other, true, c.protocolVersion), false, 0);
    }
    for (const auto& [type, state] : other.lastState) outbox.send(c.peer, state, true, relaySlot(other.participantId, type));
  }
}

void Hub::Impl::on(Client& c, const protocol::Join& m, double now) {
  if (const auto bad = invalidUtf8At(m.name)) {
    fail(c, ReasonCode::BadMessage, "Join: name is not UTF-8 at " + describeByte(m.name, *bad) + "; expected a UTF-8 name");
    return;
  }
  if (c.participant) {
    // Joined already: a new name or look for the same participant (same id and token), told to
    // everyone as a Presence, within the participant messages' rate (each one reaches every client).
    if (!allowState(c, now)) return;
    if (!m.name.empty()) c.name = m.name;
    c.look = m.avatar;
    outbox.send(c.peer, protocol::encode(protocol::Joined{c.participantId, c.token}), false, 0);
    announce(c, true, 0);
    return;
  }
  c.participant = true;
  c.participantId = nextParticipantId++;
  do c.token = tokenSource(); while (c.token == 0);
  if (!m.name.empty()) c.name = m.name;
  c.look = m.avatar;
  {
    std::lock_guard lock(input.mutex);
    input.participants[c.participantId] = c.peer;
  }
  outbox.send(c.peer, protocol::encode(protocol::Joined{c.participantId, c.token}), false, 0);
  announce(c, true, 0);
}

void Hub::Impl::on(Client& c, const protocol::Leave& m, double) {
  if (!owns(c, m.token, "Leave")) return;
  dropParticipant(c);
  c.participant = false;
  c.avatar.reset();
  c.lastState.clear();
}

void Hub::Impl::on(Client& c, const protocol::Heartbeat& m, double now) {
  if (m.token != 0 && c.participant && m.token != c.token) {
    fail(c, ReasonCode::BadToken, "Heartbeat with a token that is not this participant's");
    return;
  }
  c.peerTimeUs = m.timeUs;
  if (m.echoUs == 0) {
    // A ping: answer at once, so the client's round trip holds no waiting.
    outbox.send(c.peer, protocol::encode(protocol::Heartbeat{0, static_cast<std::uint64_t>(now * 1e6), m.timeUs}), false, 0);
  } else {
    const double rtt = now * 1e3 - static_cast<double>(m.echoUs) / 1e3;
    if (rtt >= 0.0 && rtt < 1e7) c.roundTripMs = rtt;
  }
}

void Hub::Impl::on(Client& c, const protocol::Bye&, double) {
  c.closing = true;
  outbox.close(c.peer, "client quit");
}

void Hub::Impl::on(Client& c, const protocol::Move& m, double now) {
  if (!owns(c, m.subject.value, "Move") || m.subject.kind != protocol::Subject::Kind::Token || !allowState(c, now)) return;
  if (m.seq < c.moveSeq && c.moveSeq - m.seq < 0x80000000u) return;  // reordered (UDP): older than the last
  if (!std::isfinite(m.x) || !std::isfinite(m.y) || !std::isfinite(m.z) || !std::isfinite(m.yaw)) {
    fail(c, ReasonCode::BadMessage, "Move: position and yaw must be finite numbers");
    return;
  }
  c.moveSeq = m.seq;
  c.avatar = core::Vec2{m.x, m.y};
  c.avatarZ = m.z;
  {
    std::lock_guard lock(input.mutex);
    input.avatars[c.participantId] = *c.avatar;
    input.avatarHeights[c.participantId] = m.z;
  }
  relay(c, m);
}

template <class M>
void Hub::Impl::relayState(Client& c, const M& m, double now) {
  if (!owns(c, m.subject.value, protocol::messageTypeName(protocol::messageType(protocol::Message{m}))) ||
      m.subject.kind != protocol::Subject::Kind::Token || !allowState(c, now)) {
    return;
  }
  relay(c, m);
}

void Hub::Impl::on(Client& c, const protocol::Joints& m, double now) { relayState(c, m, now); }
void Hub::Impl::on(Client& c, const protocol::HandJoints& m, double now) { relayState(c, m, now); }
void Hub::Impl::on(Client& c, const protocol::FaceExpression& m, double now) { relayState(c, m, now); }

void Hub::Impl::on(Client& c, const protocol::ReplayControl& m, double now) {
  if (!options.replay) {
    fail(c, ReasonCode::UnexpectedMessage, "ReplayControl: this server runs a live world, not a recording");
    return;
  }
  if (m.token != 0 && (!c.participant || m.token != c.token)) {
    fail(c, ReasonCode::BadToken, "ReplayControl with a token that is not this client's");
    return;
  }
  if (!allowState(c, now)) return;
  std::lock_guard lock(input.mutex);
  input.replayControls.push_back(m);
}

void Hub::Impl::requestGuidance(Client& c, std::uint64_t token, std::uint32_t group, bool guide, double now) {
  if (!owns(c, token, guide ? "Guide" : "Release") || !allowState(c, now)) return;
  if (options.replay) {
    // A recording cannot be steered: say so, keep the session.
    outbox.send(c.peer, protocol::encode(protocol::GuideResult{group, false, false, ReasonCode::UnknownGroup}), false, 0);
    return;
  }
  std::lock_guard lock(input.mutex);
  input.requests.push_back({c.peer, c.participantId, group, guide, true});
}

void Hub::Impl::on(Client& c, const protocol::Guide& m, double now) { requestGuidance(c, m.token, m.groupId, true, now); }
void Hub::Impl::on(Client& c, const protocol::Release& m, double now) { requestGuidance(c, m.token, m.groupId, false, now); }

void Hub::Impl::answerCrowd(const Client& c, std::uint32_t requestId, const std::string& id, std::string text) {
  outbox.send(c.peer, protocol::encode(protocol::CrowdResult{requestId, false, 0, id, std::move(text)}), false, 0);
}

void Hub::Impl::on(Client& c, const protocol::InsertCrowd& m, double now) {
  if (!owns(c, m.token, "InsertCrowd") || !allowState(c, now)) return;
  if (options.replay) {
    answerCrowd(c, m.requestId, "", "this server plays a recording: crowds cannot be inserted");
    return;
  }
  while (!c.crowdInserts.empty() && now - c.crowdInserts.front() >= kCrowdInsertWindowSeconds) c.crowdInserts.pop_front();
  if (c.crowdInserts.size() >= options.crowdInsertsPerMinute) {
    const double wait = kCrowdInsertWindowSeconds - (now - c.crowdInserts.front());
    answerCrowd(c, m.requestId, "",
                "rate limited: at most " + std::to_string(options.crowdInsertsPerMinute) +
                    " crowd insertions per participant per minute; try again in " +
                    std::to_string(static_cast<int>(std::ceil(wait))) + " s");
    return;
  }
  {
    std::lock_guard lock(work.mutex);
    const auto pending = static_cast<std::size_t>(
        std::count_if(work.queue.begin(), work.queue.end(), [](const CrowdRequest& r) { return r.insert; }));
    if (pending >= options.maxPendingCrowdInserts) {
      answerCrowd(c, m.requestId, "",
                  "busy: " + std::to_string(pending) +
                      " crowd insertions are waiting to be validated; try again in a few seconds");
      return;
    }
    c.crowdInserts.push_back(now);
    work.queue.push_back({c.peer, c.participantId, c.name, m.requestId, true, m.crowdJson});
  }
  work.changed.notify_all();
}

void Hub::Impl::on(Client& c, const protocol::RemoveCrowd& m, double now) {
  if (!owns(c, m.token, "RemoveCrowd") || !allowState(c, now)) return;
  if (options.replay) {
    answerCrowd(c, m.requestId,
                std::string(cutUtf8(printable(m.crowdId, protocol::kMaxNameLength), protocol::kMaxNameLength)),
                "this server plays a recording: crowds cannot be removed");
    return;
  }
  if (const auto bad = invalidUtf8At(m.crowdId)) {
    answerCrowd(c, m.requestId, "", "remove /crowdId: not UTF-8 at " + describeByte(m.crowdId, *bad) + "; expected the id of a crowd");
    return;
  }
  {
    std::lock_guard lock(work.mutex);
    work.queue.push_back({c.peer, c.participantId, c.name, m.requestId, false, m.crowdId});
  }
  work.changed.notify_all();
}

void Hub::Impl::on(Client& c, const protocol::Ack& m, double) {
  if (m.token != 0 && c.participant && m.token != c.token) {
    fail(c, ReasonCode::BadToken, "Ack with a token that is not this participant's");
    return;
  }
  if (m.frameNumber >= c.encoder.nextFrameNumber()) {
    fail(c, ReasonCode::BadMessage, "Ack of frame " + std::to_string(m.frameNumber) + " which was never sent");
    return;
  }
  c.acked = std::max(c.acked, m.frameNumber);
}

void Hub::Impl::on(Client& c, const protocol::Hello&, double) {
  fail(c, ReasonCode::UnexpectedMessage, "Hello: the session is already open");
}

template <class M>
void Hub::Impl::on(Client& c, const M& m, double) {
  fail(c, ReasonCode::UnexpectedMessage,
       std::string(protocol::messageTypeName(protocol::messageType(protocol::Message{m}))) +
           " is sent by the server, not by clients");
}

std::optional<protocol::GuideResult> Hub::Impl::applyGuideRequest(sim::World& world, const GuideRequest& r) {
  auto& in = input;
  const sim::GroupId handle = world.groupById(r.group);
  protocol::GuideResult result{r.group, false, false, ReasonCode::None};
  const bool present = in.participants.count(r.participantId) != 0;
  auto owner = in.guideOf.find(r.group);
  if (handle.isNull()) {
    result.reason = ReasonCode::UnknownGroup;
  } else if (r.guide) {
    const auto count = static_cast<std::size_t>(std::count_if(
        in.guideOf.begin(), in.guideOf.end(), [&](const auto& e) { return e.second == r.participantId; }));
    if (owner != in.guideOf.end() && owner->second != r.participantId) {
      result.reason = ReasonCode::GroupTaken;
    } else if (owner == in.guideOf.end() && count >= options.maxGuidedGroups) {
      result.reason = ReasonCode::RateLimited;
    } else if (!present) {
      return std::nullopt;  // left meanwhile
    } else {
      in.guideOf[r.group] = r.participantId;
      if (auto a = in.avatars.find(r.participantId); a != in.avatars.end()) world.guide(handle, a->second, heightOf(in, r.participantId));
      result.guiding = result.ok = true;
    }
  } else {
    if (owner == in.guideOf.end() || owner->second != r.participantId) {
      result.reason = ReasonCode::NotGuiding;
    } else {
      in.guideOf.erase(owner);
      world.release(handle);
      result.ok = true;
    }
  }
  return result;
}

void Hub::Impl::applyGuideRequests(sim::World& world) {
  for (const GuideRequest& r : input.requests) {
    const auto result = applyGuideRequest(world, r);
    if (result && r.answer && input.participants.count(r.participantId) != 0) {
      outbox.send(r.peer, protocol::encode(*result), false, 0);
    }
  }
  input.requests.clear();
}

void Hub::Impl::applyCrowdRequests(sim::World& world) {
  std::vector<CrowdDone> done;
  {
    std::lock_guard workLock(work.mutex);
    done.swap(work.done);
  }
  for (CrowdDone& d : done) {
    const CrowdRequest& r = d.request;
    if (input.participants.count(r.participantId) == 0) continue;  // left meanwhile: nobody asks any more
    CrowdOutcome outcome;
    if (!r.insert) {
      outcome = removeCrowdById(world, r.payload, &input.owners, r.participantId);
    } else if (d.parsed.crowd) {
      outcome = queueCrowd(world, *d.parsed.crowd);
      if (outcome.ok) {
        input.owners.add(outcome.id, r.participantId, r.name);
        ++input.crowdsQueued;
      }
    } else {
      outcome = std::move(d.parsed.refusal);
    }
    protocol::CrowdResult result{r.requestId, outcome.ok, outcome.index,
                                 std::string(cutUtf8(outcome.id, protocol::kMaxNameLength)), std::move(outcome.text)};
    if (!outcome.ok) result.text = diagnosticsText(outcome.diagnostics, protocol::kMaxTextLength);
    outbox.send(r.peer, protocol::encode(result), false, 0);
  }
}

void Hub::Impl::followAvatars(sim::World& world) {
  std::vector<core::Vec2> viewers;
  viewers.reserve(input.avatars.size());
  for (const auto& [participant, position] : input.avatars) viewers.push_back(position);
  for (const auto& [group, participant] : input.guideOf) {
    if (auto a = input.avatars.find(participant); a != input.avatars.end()) {
      world.guide(world.groupById(group), a->second, heightOf(input, participant));
    }
  }
  world.setViewers(std::move(viewers));
}

void Hub::applyToWorld(sim::World& world) {
  Impl& h = *impl_;
  std::unique_lock lock(h.input.mutex);  // never the main mutex: publish may be encoding meanwhile
  h.applyGuideRequests(world);
  // Crowds inserted and removed at the participants' request, in the order they came. Insertions
  // were parsed and validated on the crowd worker; here they are only queued into the World
  // (World::insertCrowd checks their ids against the crowds queued since), so they take effect at
  // the next tick boundary. A crowd belongs to whoever inserted it: only they remove it.
  h.applyCrowdRequests(world);
  // Dynamic goals: each guided group walks to its guide's avatar (the World replans only when it
  // moved far enough); the avatars are the viewers of multiresolution steering.
  h.followAvatars(world);
  lock.unlock();
  h.refreshCrowdContext(world, false);
}

core::Result<protocol::EncodedCrowdFrame> Hub::Impl::encodeCrowd(Client& c, const sim::Frame& frame) {
  // Per-thread scratch: clients are encoded in parallel.
  thread_local std::vector<Interested> interested;
  thread_local std::vector<std::pair<float, std::uint32_t>> nearScratch;
  thread_local std::vector<float> pose;
  const core::Vec2* viewpoint = c.avatar ? &*c.avatar : nullptr;
  selectInterest(frame, viewpoint, options.interest, interested, nearScratch);
  protocol::CrowdView view;
  view.simTick = frame.tick;
  view.animationInterval = static_cast<std::uint8_t>(std::min<std::uint32_t>(255, c.granularity.factor()));
  view.jointCount = static_cast<std::uint8_t>(std::min(motions.jointCount(), protocol::kMaxJoints));
  view.agents.reserve(interested.size());
  pose.resize(3 * motions.jointCount());
  for (const Interested& it : interested) {
    const std::uint32_t r = it.row;
    protocol::AgentState a;
    a.id = frame.ids[r];
    a.tier = it.tier;
    a.x = frame.posX[r];
    a.y = frame.posY[r];
    a.z = frame.height(r);
    a.yaw = r < frame.oriX.size() ? static_cast<float>(std::atan2(frame.oriY[r], frame.oriX[r])) : 0.0f;
    a.clip = r < frame.clip.size() ? frame.clip[r] : 0;
    a.phase = r < frame.phase.size() ? frame.phase[r] : 0.0f;
    if (it.tier == Tier::Near && view.jointCount > 0) {
      motions.sample(a.clip, a.phase, pose);
      a.joints.resize(3u * view.jointCount);
      for (std::size_t k = 0; k < a.joints.size(); ++k) a.joints[k] = static_cast<float>(pose[k] * kPi / 180.0);
    }
    view.agents.push_back(std::move(a));
  }
  c.agentsInView = static_cast<std::uint32_t>(view.agents.size());
  return c.encoder.encode(view, c.acked);
}

void Hub::publish(const sim::Frame& frame, double now, const core::TaskSystem* tasks) {
  std::lock_guard lock(impl_->mutex);
  Impl& h = *impl_;
  std::vector<Client*> due;
  for (auto& [peer, c] : h.clients) {
    if (c.closing) continue;
    if (now - c.lastHeard > h.options.timeoutSeconds) {
      h.fail(c, ReasonCode::Timeout,
             "no message for " + std::to_string(static_cast<int>(h.options.timeoutSeconds)) + " s (heartbeat timeout)");
      continue;
    }
    if (!c.welcomed) continue;
    if (now - c.lastHeartbeatSent >= h.options.heartbeatEverySeconds) {
      c.lastHeartbeatSent = now;
      h.outbox.send(peer, protocol::encode(protocol::Heartbeat{0, static_cast<std::uint64_t>(now * 1e6), 0}), false, 0);  // a ping
    }
    if (auto link = h.outbox.link(peer)) {
      if (link->bytesSent != c.lastBytesSent || link->queueBytes == 0) {
        c.lastBytesSent = link->bytesSent;
        c.lastProgress = now;
      } else if (now - c.lastProgress > h.options.stallSeconds) {
        h.fail(c, ReasonCode::SlowClient,
               "slow client: nothing could be sent for " + std::to_string(static_cast<int>(h.options.stallSeconds)) +
                   " s (send queue limit)");
        continue;
      }
      c.granularity.update({now, link->bytesSent, link->droppedLatest, link->queueBytes, c.roundTripMs});
    }
    due.push_back(&c);
  }
  // Each client's frame is its own work (its encoder, its view): encode them in parallel, then
  // hand them to the transport in client order.
  std::vector<std::optional<core::Result<protocol::EncodedCrowdFrame>>> encoded(due.size());
  auto encodeRange = [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) encoded[i].emplace(h.encodeCrowd(*due[i], frame));
  };
  if (tasks != nullptr && tasks->threads() > 1 && due.size() > 1) tasks->parallelFor(due.size(), 1, encodeRange);
  else encodeRange(0, due.size());
  for (std::size_t i = 0; i < due.size(); ++i) {
    Client& c = *due[i];
    auto& e = *encoded[i];
    if (!e.ok()) {
      h.fail(c, ReasonCode::BadMessage, "server could not encode the crowd: " + e.errors().front().format());
      continue;
    }
    ++c.framesSent;
    if (e->keyFrame()) ++c.keyFrames;
    ++h.totals.crowdFrames;
    h.totals.crowdBytes += e->bytes.size();
    h.outbox.send(c.peer, std::move(e->bytes), true, kCrowdSlot);
  }
}

std::vector<protocol::ReplayControl> Hub::takeReplayControls() {
  std::lock_guard lock(impl_->input.mutex);
  return std::exchange(impl_->input.replayControls, {});
}

void Hub::broadcast(const std::vector<std::uint8_t>& message) {
  std::lock_guard lock(impl_->mutex);
  for (auto& [peer, c] : impl_->clients) {
    if (c.welcomed && !c.closing) impl_->outbox.send(peer, message, false, 0);
  }
}

void Hub::observe(const sim::Frame& frame) {
  if (frame.script.empty()) return;
  std::lock_guard lock(impl_->scriptMutex);
  for (const sim::ScriptRecord& r : frame.script) {
    std::vector<sim::ScriptRecord>& entries = impl_->scripts[r.agent];
    if (!entries.empty() && entries.back().coordination != r.coordination) entries.clear();  // a new coordination
    if (entries.size() < 64) entries.push_back(r);
  }
}

std::vector<sim::ScriptRecord> Hub::agentScript(std::uint32_t id) const {
  std::lock_guard lock(impl_->scriptMutex);
  auto it = impl_->scripts.find(id);
  return it == impl_->scripts.end() ? std::vector<sim::ScriptRecord>{} : it->second;
}

void Hub::shutdown(const std::string& reason) {
  std::lock_guard lock(impl_->mutex);
  for (auto& [peer, c] : impl_->clients) {
    if (c.closing) continue;
    c.closing = true;
    impl_->outbox.send(peer, protocol::encode(protocol::Bye{ReasonCode::ShuttingDown, reason}), false, 0);
    impl_->outbox.close(peer, reason);
  }
}

HubStatus Hub::status() const {
  std::lock_guard lock(impl_->mutex);
  HubStatus s = impl_->totals;
  s.perClient.clear();
  for (const auto& [peer, c] : impl_->clients) {
    if (!c.welcomed) continue;
    ++s.clients;
    if (c.participant) ++s.participants;
    ClientStatus cs{peer, c.name, c.participant, c.participantId, c.granularity.factor(), c.granularity.reason(), c.granularity.kbitPerSecond(),
                    c.roundTripMs, c.framesSent, c.keyFrames, c.agentsInView, {}};
    {
      std::lock_guard inputLock(impl_->input.mutex);
      for (const auto& [group, participant] : impl_->input.guideOf) {
        if (c.participant && participant == c.participantId) cs.guiding.push_back(group);
      }
    }
    s.perClient.push_back(std::move(cs));
  }
  return s;
}

}  // namespace throng::hub
