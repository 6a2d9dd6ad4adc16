// A native participant of a shared world (see session.hpp).
#include "throng/client/session.hpp"

#include "throng/protocol/fragments.hpp"

#include <algorithm>

#include "throng/client/udp_client.hpp"
#include "throng/client/ws_client.hpp"

namespace throng::client {
namespace {

using Clock = std::chrono::steady_clock;
using protocol::Bytes;

/// One message from the link, or the end of the connection.
struct Received {
  bool closed = false;
  bool timeout = false;
  Bytes message;
  std::string reason;
};

class Link {
 public:
  virtual ~Link() = default;
  virtual core::Status send(const Bytes& bytes) = 0;
  /// Sends the session's first message, the Hello (over UDP after the cookie round trip).
  virtual core::Status start(const Bytes& hello, std::chrono::milliseconds timeout) = 0;
  /// Repeats the start when no answer came (UDP may have lost it); nothing over WebSocket.
  virtual void restart() {}
  virtual Received receive(std::chrono::milliseconds wait) = 0;
  virtual void close(const std::string& reason) = 0;
};

class WsLink final : public Link {
 public:
  explicit WsLink(std::unique_ptr<WsClient> c) : c_(std::move(c)) {}
  core::Status send(const Bytes& bytes) override { return c_->send(bytes); }
  core::Status start(const Bytes& hello, std::chrono::milliseconds) override { return c_->send(hello); }
  Received receive(std::chrono::milliseconds wait) override {
    ClientEvent e = c_->receive(wait);
    switch (e.kind) {
      case ClientEvent::Kind::Message: return {false, false, std::move(e.message), {}};
      case ClientEvent::Kind::Closed: return {true, false, {}, e.closeReason};
      case ClientEvent::Kind::Timeout: break;
    }
    return {false, true, {}, {}};
  }
  void close(const std::string& reason) override { c_->close(reason); }

 private:
  std::unique_ptr<WsClient> c_;
};

class UdpLink final : public Link {
 public:
  explicit UdpLink(std::unique_ptr<UdpClient> c) : c_(std::move(c)) {}
  core::Status send(const Bytes& bytes) override { return c_->send(bytes); }
  core::Status start(const Bytes& hello, std::chrono::milliseconds timeout) override { return c_->open(hello, timeout); }
  void restart() override { (void)c_->reopen(); }
  Received receive(std::chrono::milliseconds wait) override {
    auto d = c_->receive(wait);
    if (!d) return {false, true, {}, {}};
    return {false, false, std::move(*d), {}};
  }
  void close(const std::string&) override {}

 private:
  std::unique_ptr<UdpClient> c_;
};

core::Diagnostic problem(const std::string& source, const std::string& what, const std::string& expected = {}) {
  core::Diagnostic d;
  d.source = source;
  d.what = what;
  d.expected = expected;
  return d;
}

}  // namespace

struct Session::Impl {
  SessionOptions options;
  std::string source;  ///< "ws://host:port/ws" or "udp://host:port", for messages
  std::unique_ptr<Link> link;
  protocol::Welcome welcome;
  std::string world;
  std::uint64_t token = 0;
  std::uint32_t participantId = 0;
  std::uint32_t moveSeq = 0;
  Clock::time_point start = Clock::now();
  Clock::time_point lastHeartbeat = Clock::now();
  protocol::CrowdDecoder decoder;
  protocol::Reassembler fragments;  ///< UDP: Fragment datagrams back into whole messages
  std::optional<protocol::DecodedCrowdFrame> crowd;
  std::vector<protocol::GuideResult> guideResults;
  std::vector<protocol::CrowdResult> crowdResults;
  std::uint32_t nextRequestId = 1;
  std::vector<std::pair<std::uint32_t, protocol::Move>> others;
  std::optional<protocol::Joined> joined;
  std::optional<protocol::ReplayStatus> replayStatus;
  std::vector<std::pair<std::uint32_t, std::string>> participants;
  std::vector<Participant> present;  ///< the same, with their looks
  SessionStats stats;
  bool isOpen = true;
  std::string closeReason;
  std::uint32_t lastFrame = 0;
  // Tick schedule for frame delays: the earliest-arriving frame fixes the origin.
  bool haveOrigin = false;
  double originSeconds = 0.0;  ///< arrival time minus simTick / tickRate, minimised over frames

  [[nodiscard]] std::uint64_t nowUs() const {
    return static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - start).count()) + 1;
  }

  core::Status send(const Bytes& bytes) {
    if (!isOpen) return problem(source, "the session is closed: " + closeReason);
    return link->send(bytes);
  }

  void handle(const Bytes& bytes) {
    ++stats.messagesReceived;
    stats.bytesReceived += bytes.size();
    auto decoded = reassemble(protocol::decodeAny(bytes));
    if (!decoded) return;  // malformed (ignored, like any bad message) or a message still in pieces
    protocol::Message& m = *decoded;
    if (auto* frame = std::get_if<protocol::CrowdFrame>(&m)) {
      const double arrival = static_cast<double>(nowUs()) / 1e6;
      auto applied = decoder.apply(*frame);
      if (!applied.ok()) {
        ++stats.undecodable;
        return;
      }
      ++stats.crowdFrames;
      if (applied->header.baseFrame == 0) ++stats.keyFrames;
      if (lastFrame != 0 && applied->header.frameNumber > lastFrame + 1) stats.lostFrames += applied->header.frameNumber - lastFrame - 1;
      lastFrame = std::max(lastFrame, applied->header.frameNumber);
      const double slot = static_cast<double>(applied->header.simTick) / std::max(1e-3, static_cast<double>(welcome.tickRateHz));
      const double offset = arrival - slot;
      if (!haveOrigin || offset < originSeconds) {
        haveOrigin = true;
        originSeconds = offset;
      }
      stats.frameDelayMs.push_back((offset - originSeconds) * 1000.0);
      stats.agentsInView = static_cast<std::uint32_t>(applied->view.agents.size());
      stats.tiersInView = {applied->header.nearCount, applied->header.middleCount, applied->header.farCount};
      for (std::size_t t = 0; t < 3; ++t) stats.tierSums[t] += stats.tiersInView[t];
      stats.farMax = std::max(stats.farMax, applied->header.farCount);
      stats.animationInterval = applied->header.animationInterval;
      const std::uint32_t number = applied->header.frameNumber;
      crowd = std::move(applied).value();
      (void)send(protocol::encode(protocol::Ack{token, number}));
    } else if (auto* hb = std::get_if<protocol::Heartbeat>(&m)) {
      if (hb->echoUs == 0) {
        // The server's ping: answer at once (its round trip measures the link, not our pace).
        (void)send(protocol::encode(protocol::Heartbeat{token, nowUs(), hb->timeUs}));
      } else {
        stats.roundTripMs = static_cast<double>(nowUs() - std::min(nowUs(), hb->echoUs)) / 1000.0;
      }
    } else if (auto* g = std::get_if<protocol::GuideResult>(&m)) {
      guideResults.push_back(*g);
    } else if (auto* cr = std::get_if<protocol::CrowdResult>(&m)) {
      crowdResults.push_back(std::move(*cr));
    } else if (auto* j = std::get_if<protocol::Joined>(&m)) {
      joined = *j;
    } else if (auto* mv = std::get_if<protocol::Move>(&m)) {
      const auto id = static_cast<std::uint32_t>(mv->subject.value);
      auto it = std::find_if(others.begin(), others.end(), [&](const auto& e) { return e.first == id; });
      if (it == others.end()) others.emplace_back(id, *mv);
      else it->second = *mv;
    } else if (auto* rs = std::get_if<protocol::ReplayStatus>(&m)) {
      replayStatus = *rs;
    } else if (auto* p = std::get_if<protocol::Presence>(&m)) {
      std::erase_if(participants, [&](const auto& e) { return e.first == p->participantId; });
      std::erase_if(present, [&](const Participant& e) { return e.id == p->participantId; });
      if (p->present) {
        participants.emplace_back(p->participantId, p->name);
        present.push_back(Participant{p->participantId, p->name, p->avatar});
      }
    } else if (auto* bye = std::get_if<protocol::Bye>(&m)) {
      isOpen = false;
      closeReason = bye->text;
    } else if (auto* refuse = std::get_if<protocol::Refuse>(&m)) {
      isOpen = false;
      closeReason = refuse->text;
    }
  }

  /// A decoded datagram as a whole message: a Fragment goes to the reassembler and comes back as
  /// the message it completes (nullopt while incomplete); bad ones come back as nullopt.
  std::optional<protocol::Message> reassemble(core::Result<protocol::Message> decoded) {
    if (!decoded.ok()) return std::nullopt;
    auto* fragment = std::get_if<protocol::Fragment>(&decoded.value());
    if (!fragment) return std::move(decoded).value();
    auto whole = fragments.add(*fragment);
    stats.incompleteMessages = fragments.droppedMessages();
    if (!whole.ok() || !whole.value()) return std::nullopt;
    auto m = protocol::decodeAny(*whole.value());
    if (!m.ok()) return std::nullopt;
    return std::move(m).value();
  }

  bool pump(std::chrono::milliseconds wait) {
    if (!isOpen) return false;
    // Our heartbeat, once a second: keeps the session alive and measures the round trip.
    if (Clock::now() - lastHeartbeat >= std::chrono::seconds(1)) {
      lastHeartbeat = Clock::now();
      (void)send(protocol::encode(protocol::Heartbeat{token, nowUs(), 0}));  // a ping
    }
    Received r = link->receive(wait);
    while (isOpen) {
      if (r.closed) {
        isOpen = false;
        if (closeReason.empty()) closeReason = r.reason.empty() ? "connection closed" : r.reason;
        break;
      }
      if (r.timeout) break;
      handle(r.message);
      r = link->receive(std::chrono::milliseconds(0));
    }
    return isOpen;
  }
};

Session::Session(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Session::~Session() = default;

core::Result<std::unique_ptr<Session>> Session::open(const SessionOptions& options) {
  auto impl = std::make_unique<Impl>();
  impl->options = options;
  if (options.udp) {
    impl->source = "udp://" + options.host + ":" + std::to_string(options.udpPort);
    auto c = UdpClient::connect(options.host, options.udpPort);
    if (!c.ok()) return std::move(c).takeErrors();
    impl->link = std::make_unique<UdpLink>(std::move(c).value());
  } else {
    impl->source = "ws://" + options.host + ":" + std::to_string(options.port) + options.path;
    WsClientOptions w;
    w.host = options.host;
    w.port = options.port;
    w.path = options.path;
    w.timeout = options.timeout;
    auto c = WsClient::connect(w);
    if (!c.ok()) return std::move(c).takeErrors();
    impl->link = std::make_unique<WsLink>(std::move(c).value());
  }
  const auto deadline = Clock::now() + options.timeout;
  const Bytes hello = protocol::encode(protocol::Hello{protocol::kProtocolVersion, options.kind, options.name});
  if (auto s = impl->link->start(hello, options.timeout); !s.ok()) return std::move(s).takeErrors();
  // Over UDP the UdpHello that opens the session may be lost: repeat it after a second of silence.
  constexpr auto kRetry = std::chrono::milliseconds(1000);
  while (Clock::now() < deadline) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
    Received r = impl->link->receive(options.udp ? std::min(left, kRetry) : left);
    if (r.closed) return problem(impl->source, "the server closed the connection before its Welcome: " + r.reason);
    if (r.timeout) {
      if (!options.udp) break;
      impl->link->restart();
      continue;
    }
    auto decoded = protocol::decodeAny(r.message);
    if (!decoded.ok()) return problem(impl->source, "the server's first message does not decode: " + decoded.errors().front().format());
    // Over UDP a large Welcome arrives in Fragments: wait for the whole of it.
    auto m = impl->reassemble(std::move(decoded));
    if (!m) continue;
    if (auto* refuse = std::get_if<protocol::Refuse>(&*m)) {
      return problem(impl->source, "the server refused the session: " + refuse->text);
    }
    if (auto* welcome = std::get_if<protocol::Welcome>(&*m)) {
      auto json = protocol::worldJson(*welcome);
      if (!json.ok()) return std::move(json).takeErrors();
      impl->welcome = *welcome;
      impl->world = std::move(json).value();
      return std::unique_ptr<Session>(new Session(std::move(impl)));
    }
  }
  return problem(impl->source, "no Welcome within " + std::to_string(options.timeout.count()) + " ms",
                 "a throng server (throng serve) at this address");
}

const protocol::Welcome& Session::welcome() const { return impl_->welcome; }
const std::string& Session::worldJson() const { return impl_->world; }

core::Result<protocol::Joined> Session::join(const std::string& name, std::uint16_t avatar) {
  impl_->joined.reset();  // joined already: wait for the answer to this Join (same id and token)
  if (auto s = impl_->send(protocol::encode(protocol::Join{name, avatar})); !s.ok()) return std::move(s).takeErrors();
  const auto deadline = Clock::now() + impl_->options.timeout;
  while (!impl_->joined && impl_->isOpen && Clock::now() < deadline) impl_->pump(std::chrono::milliseconds(20));
  if (!impl_->joined) {
    return problem(impl_->source, impl_->isOpen ? "no Joined within the timeout" : "closed while joining: " + impl_->closeReason);
  }
  impl_->token = impl_->joined->token;
  impl_->participantId = impl_->joined->participantId;
  return *impl_->joined;
}

core::Status Session::move(float x, float y, float yaw) {
  protocol::Move m;
  m.subject = {protocol::Subject::Kind::Token, impl_->token};
  m.seq = ++impl_->moveSeq;
  m.x = x;
  m.y = y;
  m.yaw = yaw;
  return impl_->send(protocol::encode(m));
}

core::Status Session::guide(std::uint32_t group) { return impl_->send(protocol::encode(protocol::Guide{impl_->token, group})); }
core::Status Session::release(std::uint32_t group) { return impl_->send(protocol::encode(protocol::Release{impl_->token, group})); }
core::Status Session::leave() { return impl_->send(protocol::encode(protocol::Leave{impl_->token})); }

core::Status Session::replayControl(protocol::ReplayCommand command, double value) {
  return impl_->send(protocol::encode(protocol::ReplayControl{impl_->token, command, value}));
}
core::Result<std::uint32_t> Session::insertCrowd(const std::string& crowdJson) {
  if (crowdJson.size() > protocol::kMaxCrowdJson) {
    return problem(impl_->source, "crowd file of " + std::to_string(crowdJson.size()) + " bytes",
                   "at most " + std::to_string(protocol::kMaxCrowdJson) + " bytes");
  }
  const Bytes bytes = protocol::encode(protocol::InsertCrowd{impl_->token, impl_->nextRequestId, crowdJson});
  if (impl_->options.udp && bytes.size() > protocol::kMaxDatagramSize) {
    return problem(impl_->source, "crowd file of " + std::to_string(crowdJson.size()) + " bytes does not fit a UDP datagram",
                   "a WebSocket session, or a file under 64 KB");
  }
  if (auto s = impl_->send(bytes); !s.ok()) return std::move(s).takeErrors();
  return impl_->nextRequestId++;
}

core::Result<std::uint32_t> Session::removeCrowd(const std::string& crowdId) {
  if (auto s = impl_->send(protocol::encode(protocol::RemoveCrowd{impl_->token, impl_->nextRequestId, crowdId})); !s.ok()) {
    return std::move(s).takeErrors();
  }
  return impl_->nextRequestId++;
}

std::vector<protocol::CrowdResult>& Session::crowdResults() { return impl_->crowdResults; }

const std::optional<protocol::ReplayStatus>& Session::replayStatus() const { return impl_->replayStatus; }
const std::vector<std::pair<std::uint32_t, std::string>>& Session::participants() const { return impl_->participants; }
const std::vector<Participant>& Session::present() const { return impl_->present; }
std::optional<std::uint16_t> Session::avatarOf(std::uint32_t participantId) const {
  for (const Participant& p : impl_->present) {
    if (p.id == participantId) return p.avatar;
  }
  return std::nullopt;
}

bool Session::pump(std::chrono::milliseconds wait) { return impl_->pump(wait); }
const std::optional<protocol::DecodedCrowdFrame>& Session::crowd() const { return impl_->crowd; }
std::vector<protocol::GuideResult>& Session::guideResults() { return impl_->guideResults; }
const std::vector<std::pair<std::uint32_t, protocol::Move>>& Session::others() const { return impl_->others; }
const SessionStats& Session::stats() const { return impl_->stats; }
bool Session::open() const { return impl_->isOpen; }
const std::string& Session::closeReason() const { return impl_->closeReason; }

void Session::close(const std::string& reason) {
  if (!impl_->isOpen) return;
  (void)impl_->send(protocol::encode(protocol::Bye{protocol::ReasonCode::ClientQuit, reason}));
  impl_->link->close(reason);
  impl_->isOpen = false;
  impl_->closeReason = reason;
}

}  // namespace throng::client
