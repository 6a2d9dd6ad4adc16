// The hub without sockets: sessions, refusals, tokens, relays, guidance moving a real group, crowd
// frames a client decodes and acknowledges, timeouts and rate limits.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "throng/core/parallel.hpp"
#include "throng/hub/hub.hpp"
#include "throng/hub/text.hpp"
#include "throng/io/crowd_loader.hpp"
#include "throng/hub/world_description.hpp"
#include "throng/io/scenario_loader.hpp"
#include "throng/protocol/crowd_decoder.hpp"
#include "throng/protocol/messages.hpp"

namespace throng::hub {
namespace {

using namespace protocol;

/// Records what the hub sends; `latest` messages of one slot replace each other until drained.
class RecordingOutbox : public Outbox {
 public:
  struct Sent {
    std::vector<std::uint8_t> bytes;
    bool latest;
    std::uint32_t slot;
  };
  void send(PeerKey peer, std::vector<std::uint8_t> message, bool latest, std::uint32_t slot) override {
    bytesSent[peer] += message.size();
    queues[peer].push_back({std::move(message), latest, slot});
  }
  void close(PeerKey peer, std::string reason) override { closed[peer] = std::move(reason); }
  std::optional<LinkCounters> link(PeerKey peer) const override {
    if (stalled.count(peer)) return LinkCounters{1, 50, 100'000};  // nothing leaves, data waits
    auto it = bytesSent.find(peer);
    return LinkCounters{it == bytesSent.end() ? 0 : it->second, 0, 0};
  }
  std::set<PeerKey> stalled;
  /// Decoded messages sent to `peer` since the last call.
  std::vector<Message> drain(PeerKey peer) {
    std::vector<Message> out;
    for (Sent& s : queues[peer]) {
      auto m = decodeAny(s.bytes);
      EXPECT_TRUE(m.ok()) << (m.ok() ? "" : m.errors().front().format());
      if (m.ok()) out.push_back(std::move(m).value());
    }
    raw[peer] = std::move(queues[peer]);
    queues[peer].clear();
    return out;
  }
  std::map<PeerKey, std::vector<Sent>> queues, raw;
  std::map<PeerKey, std::uint64_t> bytesSent;
  std::map<PeerKey, std::string> closed;
};

template <class T>
const T* find(const std::vector<Message>& messages) {
  for (const Message& m : messages) {
    if (const T* t = std::get_if<T>(&m)) return t;
  }
  return nullptr;
}

struct HubFixture : ::testing::Test {
  void SetUp() override {
    auto loaded = io::loadScenarioFile(std::string(THRONG_SOURCE_DIR) + "/scenarios/museum.json");
    ASSERT_TRUE(loaded.ok()) << io_errors(loaded);
    scenario = std::make_unique<io::LoadedScenario>(std::move(loaded).value());
    auto w = sim::World::create(scenario->desc, scenario->navmesh);
    ASSERT_TRUE(w.ok());
    world = std::move(w).value();
    std::vector<std::string> warnings;
    motions = std::make_unique<MotionLibrary>(
        MotionLibrary::load(*scenario, std::string(THRONG_SOURCE_DIR) + "/scenarios", warnings));
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    HubOptions options;
    options.maxClients = 2;
    hub = std::make_unique<Hub>(options, describeWorld(*scenario, *motions, *world, 20.0), 20.0f, *motions, outbox);
  }
  static std::string io_errors(const core::Result<io::LoadedScenario>& r) {
    return r.ok() ? "" : core::formatAll(r.errors());
  }
  void say(PeerKey peer, const std::vector<std::uint8_t>& bytes) { hub->onMessage(peer, bytes, now); }
  /// Opens a client and says Hello; returns the Welcome's world JSON.
  std::string connect(PeerKey peer) {
    hub->onOpen(peer, "test:" + std::to_string(peer), now);
    say(peer, encode(Hello{kProtocolVersion, ClientKind::Native, "client"}));
    auto got = outbox.drain(peer);
    const Welcome* w = find<Welcome>(got);
    if (w == nullptr) return {};
    auto json = worldJson(*w);
    return json.ok() ? json.value() : std::string();
  }
  /// A browser of this protocol version connecting now as `peer`: what it hears first.
  auto arrive(PeerKey peer) {
    hub->onOpen(peer, "late", now);
    say(peer, encode(Hello{kProtocolVersion, ClientKind::Browser, "late"}));
    return outbox.drain(peer);
  }
  Joined join(PeerKey peer, const std::string& name) {
    say(peer, encode(Join{name, 0}));
    auto got = outbox.drain(peer);
    const Joined* j = find<Joined>(got);
    return j ? *j : Joined{};
  }
  void tick() {
    hub->awaitCrowdValidation(*world);  // crowd requests are validated on the hub's own thread
    hub->applyToWorld(*world);
    world->step(tasks);
    now += world->desc().dt;
    hub->publish(*world->takeFrame(), now);
  }

  std::unique_ptr<io::LoadedScenario> scenario;
  std::unique_ptr<sim::World> world;
  std::unique_ptr<MotionLibrary> motions;
  RecordingOutbox outbox;
  std::unique_ptr<Hub> hub;
  core::TaskSystem tasks{1};
  double now = 0.0;
};

TEST_F(HubFixture, WelcomeCarriesTheWorldDescription) {
  const std::string json = connect(1);
  EXPECT_NE(json.find("\"skeleton\""), std::string::npos);
  EXPECT_NE(json.find("\"clips\""), std::string::npos);
  EXPECT_NE(json.find("\"walkable\""), std::string::npos);
  EXPECT_TRUE(outbox.closed.empty());
}

TEST_F(HubFixture, RefusesAVersionMismatchAFullServerAndAnythingBeforeHello) {
  hub->onOpen(1, "a", now);
  say(1, encode(Hello{kProtocolVersion + 1, ClientKind::Native, "future"}));
  auto got = outbox.drain(1);
  const Refuse* r = find<Refuse>(got);
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->reason, ReasonCode::VersionMismatch);
  EXPECT_NE(r->text.find("versions 1 to 2"), std::string::npos) << r->text;
  EXPECT_TRUE(outbox.closed.count(1));

  hub->onOpen(2, "b", now);
  say(2, encode(Join{"me", 0}));
  const auto got1 = outbox.drain(2);
  const Bye* bye = find<Bye>(got1);
  ASSERT_NE(bye, nullptr);
  EXPECT_EQ(bye->reason, ReasonCode::UnexpectedMessage);
  EXPECT_NE(bye->text.find("expected Hello"), std::string::npos) << bye->text;

  connect(3);
  connect(4);
  EXPECT_TRUE(connect(5).empty());
  ASSERT_FALSE(outbox.raw[5].empty());
  auto m = decodeAny(outbox.raw[5].front().bytes);
  ASSERT_TRUE(m.ok());
  ASSERT_TRUE(std::holds_alternative<Refuse>(m.value()));
  EXPECT_EQ(std::get<Refuse>(m.value()).reason, ReasonCode::ServerFull);
}

TEST_F(HubFixture, GarbageClosesOnlyThatClientWithAReason) {
  connect(1);
  connect(2);
  say(1, {0x54, 0xee, 0x01});
  const auto got2 = outbox.drain(1);
  const Bye* bye = find<Bye>(got2);
  ASSERT_NE(bye, nullptr);
  EXPECT_EQ(bye->reason, ReasonCode::BadMessage);
  EXPECT_TRUE(outbox.closed.count(1));
  EXPECT_FALSE(outbox.closed.count(2));
  tick();
  EXPECT_NE(find<CrowdFrame>(outbox.drain(2)), nullptr);
}

TEST_F(HubFixture, OnlyTheTokenHolderMovesItsAvatarAndOthersSeeTheMove) {
  connect(1);
  connect(2);
  const Joined a = join(1, "alice");
  ASSERT_NE(a.token, 0u);
  Move move;
  move.subject = {Subject::Kind::Token, a.token};
  move.seq = 1;
  move.x = 10.0f;
  move.y = 5.0f;
  say(1, encode(move));
  auto got = outbox.drain(2);
  const Move* relayed = find<Move>(got);
  ASSERT_NE(relayed, nullptr);
  EXPECT_EQ(relayed->subject.kind, Subject::Kind::Participant);
  EXPECT_EQ(relayed->subject.value, a.participantId);
  EXPECT_NEAR(relayed->x, 10.0f, 0.01f);
  // Client 2 tries to move alice's avatar with a made-up token.
  move.subject.value = a.token ^ 1;
  say(2, encode(move));
  const auto got3 = outbox.drain(2);
  const Bye* bye = find<Bye>(got3);
  ASSERT_NE(bye, nullptr);
  EXPECT_EQ(bye->reason, ReasonCode::UnexpectedMessage);  // it never joined
  EXPECT_TRUE(outbox.closed.count(2));
}

TEST_F(HubFixture, AGuidedGroupFollowsTheAvatarAndAnotherClientSeesIt) {
  connect(1);
  connect(2);
  const Joined a = join(1, "guide");
  for (int i = 0; i < 20; ++i) tick();  // the museum's groups are in
  // Group 0's members, and a spot 8 m away from them where the avatar stands.
  const auto info = world->groupInfo(world->groupById(0));
  ASSERT_TRUE(info && !info->members.empty());
  auto frame = world->takeFrame();
  auto centroid = [&](const sim::Frame& f) {
    core::Vec2 c{};
    int n = 0;
    for (std::size_t r = 0; r < f.size(); ++r) {
      if (std::find(info->members.begin(), info->members.end(), f.ids[r]) != info->members.end()) {
        c += core::Vec2{f.posX[r], f.posY[r]};
        ++n;
      }
    }
    return n ? c * (1.0f / static_cast<float>(n)) : c;
  };
  const core::Vec2 start = centroid(*frame);
  Move move;
  move.subject = {Subject::Kind::Token, a.token};
  move.seq = 1;
  move.x = start.x + 6.0f;
  move.y = start.y;
  say(1, encode(move));
  say(1, encode(Guide{a.token, 0}));
  tick();
  const auto got4 = outbox.drain(1);
  const GuideResult* result = find<GuideResult>(got4);
  ASSERT_NE(result, nullptr);
  EXPECT_TRUE(result->ok && result->guiding);
  // Client 2 decodes its crowd frames and acknowledges them; the group walks toward the avatar.
  CrowdDecoder decoder;
  std::optional<DecodedCrowdFrame> last;
  for (int i = 0; i < 120; ++i) {
    tick();
    for (const auto& sent : outbox.queues[2]) {
      auto d = decoder.decode(sent.bytes);
      if (d.ok()) last = std::move(d).value();
    }
    outbox.queues[2].clear();
    if (last) say(2, encode(Ack{0, last->header.frameNumber}));
    outbox.drain(1);
  }
  const core::Vec2 end = centroid(*world->takeFrame());
  const core::Vec2 avatar{move.x, move.y};
  EXPECT_LT(core::length(end - avatar), core::length(start - avatar) - 2.0f)
      << "group went from " << start.x << "," << start.y << " to " << end.x << "," << end.y;
  ASSERT_TRUE(last.has_value());
  EXPECT_NE(last->header.baseFrame, 0u);  // acknowledged: delta frames
  // What client 2 decoded is where the world has the agents (1 cm quantization).
  auto snap = world->takeFrame();
  std::size_t matched = 0;
  for (const AgentState& s : last->view.agents) {
    for (std::size_t r = 0; r < snap->size(); ++r) {
      if (snap->ids[r] == s.id && std::fabs(snap->posX[r] - s.x) < 0.011f && std::fabs(snap->posY[r] - s.y) < 0.011f) ++matched;
    }
  }
  EXPECT_EQ(matched, last->view.agents.size());
  EXPECT_EQ(last->view.agents.size(), snap->size());  // no avatar: an overview of everyone
  // Releasing gives the group back; a second release is refused.
  say(1, encode(Release{a.token, 0}));
  tick();
  const auto got5 = outbox.drain(1);
  const GuideResult* released = find<GuideResult>(got5);
  ASSERT_NE(released, nullptr);
  EXPECT_TRUE(released->ok);
  EXPECT_FALSE(released->guiding);
  say(1, encode(Release{a.token, 0}));
  tick();
  const auto got6 = outbox.drain(1);
  const GuideResult* again = find<GuideResult>(got6);
  ASSERT_NE(again, nullptr);
  EXPECT_FALSE(again->ok);
  EXPECT_EQ(again->reason, ReasonCode::NotGuiding);
}

TEST_F(HubFixture, NearAgentsCarryJointPoses) {
  connect(1);
  const Joined a = join(1, "near");
  for (int i = 0; i < 20; ++i) tick();
  auto snap = world->takeFrame();
  ASSERT_GT(snap->size(), 0u);
  Move move;
  move.subject = {Subject::Kind::Token, a.token};
  move.seq = 1;
  move.x = snap->posX[0];
  move.y = snap->posY[0];
  say(1, encode(move));
  outbox.drain(1);
  tick();
  CrowdDecoder decoder;
  bool sawJoints = false;
  for (const auto& sent : outbox.queues[1]) {
    auto d = decoder.decode(sent.bytes);
    if (!d.ok()) continue;
    for (const AgentState& s : d->view.agents) {
      if (s.tier == Tier::Near) {
        EXPECT_EQ(s.joints.size(), 3 * motions->jointCount());
        sawJoints = sawJoints || !s.joints.empty();
      }
    }
  }
  EXPECT_TRUE(sawJoints);
}

TEST_F(HubFixture, SilentClientsTimeOutAndFloodsAreCut) {
  connect(1);
  connect(2);
  const Joined b = join(2, "flood");
  now += 11.0;  // client 1 says nothing for 11 s; client 2 keeps talking
  say(2, encode(Heartbeat{b.token, 1, 0}));
  hub->publish(*world->takeFrame(), now);
  EXPECT_TRUE(outbox.closed.count(1));
  const auto got7 = outbox.drain(1);
  const Bye* bye = find<Bye>(got7);
  ASSERT_NE(bye, nullptr);
  EXPECT_EQ(bye->reason, ReasonCode::Timeout);
  EXPECT_FALSE(outbox.closed.count(2));
  Move move;
  move.subject = {Subject::Kind::Token, b.token};
  for (std::uint32_t i = 1; i < 400 && !outbox.closed.count(2); ++i) {
    move.seq = i;
    say(2, encode(move));
  }
  ASSERT_TRUE(outbox.closed.count(2));
  const auto got = outbox.drain(2);
  const Bye* limited = find<Bye>(got);
  ASSERT_NE(limited, nullptr);
  EXPECT_EQ(limited->reason, ReasonCode::RateLimited);
}

TEST_F(HubFixture, EveryoneHearsWhoJoinsAndWhoLeaves) {
  connect(1);
  connect(2);
  const Joined a = join(1, "alice");
  auto heard = outbox.drain(2);
  const Presence* came = find<Presence>(heard);
  ASSERT_NE(came, nullptr);
  EXPECT_EQ(came->participantId, a.participantId);
  EXPECT_TRUE(came->present);
  EXPECT_EQ(came->name, "alice");
  // A newcomer learns who is already there (client 2 leaves first: the fixture serves two).
  hub->onClose(2, "done");
  const auto late = arrive(3);
  const Presence* there = find<Presence>(late);
  ASSERT_NE(there, nullptr);
  EXPECT_EQ(there->name, "alice");
  hub->onClose(1, "gone");
  const auto left = outbox.drain(3);
  const Presence* gone = find<Presence>(left);
  ASSERT_NE(gone, nullptr);
  EXPECT_FALSE(gone->present);
  EXPECT_EQ(gone->participantId, a.participantId);
}

TEST_F(HubFixture, VersionTwoClientsHearEachParticipantsLookVersionOneClientsGetVersionOneMessages) {
  connect(1);  // version 2
  hub->onOpen(2, "old", now);
  say(2, encode(Hello{1, ClientKind::Browser, "old viewer"}));
  auto welcomed = outbox.drain(2);
  const Welcome* w = find<Welcome>(welcomed);
  ASSERT_NE(w, nullptr);
  EXPECT_EQ(w->protocolVersion, 1);  // spoken to in its own version
  EXPECT_TRUE(worldJson(*w).ok());
  say(1, encode(Join{"alice", 5}));
  outbox.drain(1);
  auto heardByOld = outbox.drain(2);
  const Presence* plain = find<Presence>(heardByOld);
  ASSERT_NE(plain, nullptr);
  EXPECT_EQ(plain->name, "alice");
  EXPECT_FALSE(plain->avatar.has_value());  // the version-1 layout: ends with the name
  say(2, encode(Join{"bob", 3}));
  auto heardByNew = outbox.drain(1);
  const Presence* bob = find<Presence>(heardByNew);
  ASSERT_NE(bob, nullptr);
  EXPECT_EQ(bob->name, "bob");
  EXPECT_EQ(bob->avatar, std::optional<std::uint16_t>(3));
  // A version-2 newcomer learns the look of each participant already there.
  hub->onClose(2, "done");
  auto late = arrive(3);
  const Presence* there = find<Presence>(late);
  ASSERT_NE(there, nullptr);
  EXPECT_EQ(there->name, "alice");
  EXPECT_EQ(there->avatar, std::optional<std::uint16_t>(5));
  EXPECT_EQ(find<Welcome>(late)->protocolVersion, kProtocolVersion);
}

TEST_F(HubFixture, JoiningAgainChangesTheParticipantsNameAndLookForEveryoneKeepingItsIdAndToken) {
  connect(1);
  connect(2);
  say(1, encode(Join{"alice", 2}));
  const auto first = outbox.drain(1);
  const Joined* joined = find<Joined>(first);
  ASSERT_NE(joined, nullptr);
  const Joined a = *joined;
  outbox.drain(2);
  say(1, encode(Join{"alice in green", 3}));  // a new look (and name) while joined
  const auto again = outbox.drain(1);
  const Joined* same = find<Joined>(again);
  ASSERT_NE(same, nullptr) << "a second Join is answered, not refused";
  EXPECT_EQ(same->participantId, a.participantId);
  EXPECT_EQ(same->token, a.token);
  EXPECT_EQ(find<Bye>(again), nullptr);
  const auto heard = outbox.drain(2);
  const Presence* changed = find<Presence>(heard);
  ASSERT_NE(changed, nullptr);
  EXPECT_EQ(changed->participantId, a.participantId);
  EXPECT_TRUE(changed->present);
  EXPECT_EQ(changed->name, "alice in green");
  EXPECT_EQ(changed->avatar, std::optional<std::uint16_t>(3));
  // An empty name keeps the name; the look still changes. A newcomer learns the latest.
  say(1, encode(Join{"", 4}));
  outbox.drain(1);
  outbox.drain(2);
  hub->onClose(2, "done");
  const auto late = arrive(3);
  const Presence* there = find<Presence>(late);
  ASSERT_NE(there, nullptr);
  EXPECT_EQ(there->name, "alice in green");
  EXPECT_EQ(there->avatar, std::optional<std::uint16_t>(4));
  // A bad name is still refused, joined or not.
  say(1, encode(Join{"\xc3\x28", 0}));
  const auto bad = outbox.drain(1);
  ASSERT_NE(find<Bye>(bad), nullptr);
  EXPECT_EQ(find<Bye>(bad)->reason, ReasonCode::BadMessage);
}

TEST_F(HubFixture, JoiningAgainAndAgainIsRateLimitedLikeOtherParticipantMessages) {
  connect(1);
  const Joined a = join(1, "flood");
  ASSERT_NE(a.token, 0u);
  bool limited = false;
  for (int i = 0; i < 1000 && !limited; ++i) {
    say(1, encode(Join{"flood", static_cast<std::uint16_t>(i % 5)}));
    const auto got = outbox.drain(1);
    if (const Bye* bye = find<Bye>(got)) limited = bye->reason == ReasonCode::RateLimited;
  }
  EXPECT_TRUE(limited) << "a thousand Joins within the same instant are cut off";
}

TEST_F(HubFixture, ReplayControlIsRefusedByALiveWorldAndQueuedByAReplay) {
  connect(1);
  say(1, encode(ReplayControl{0, ReplayCommand::Pause, 0.0}));
  const auto got = outbox.drain(1);
  const Bye* bye = find<Bye>(got);
  ASSERT_NE(bye, nullptr);
  EXPECT_EQ(bye->reason, ReasonCode::UnexpectedMessage);
  HubOptions options;
  options.replay = true;
  Hub replay(options, "{}", 10.0f, *motions, outbox);
  replay.onOpen(7, "viewer", now);
  replay.onMessage(7, encode(Hello{kProtocolVersion, ClientKind::Browser, "viewer"}), now);
  replay.onMessage(7, encode(ReplayControl{0, ReplayCommand::Seek, 12.5}), now);
  replay.onMessage(7, encode(ReplayControl{0, ReplayCommand::Speed, 4.0}), now);
  const auto controls = replay.takeReplayControls();
  ASSERT_EQ(controls.size(), 2u);
  EXPECT_EQ(controls[0].command, ReplayCommand::Seek);
  EXPECT_DOUBLE_EQ(controls[0].value, 12.5);
  EXPECT_TRUE(replay.takeReplayControls().empty());
  EXPECT_FALSE(outbox.closed.count(7));
}

TEST_F(HubFixture, AClientThatNeverReadsIsCutOffAndTheOthersGoOn) {
  connect(1);
  connect(2);
  outbox.stalled.insert(1);
  for (int second = 1; second <= 12; ++second) {
    now += 1.0;
    say(1, encode(Heartbeat{0, 1, 0}));  // it talks, but never reads
    say(2, encode(Heartbeat{0, 1, 0}));
    hub->publish(*world->takeFrame(), now);
  }
  ASSERT_TRUE(outbox.closed.count(1));
  EXPECT_NE(outbox.closed[1].find("slow client"), std::string::npos) << outbox.closed[1];
  EXPECT_FALSE(outbox.closed.count(2));
  const auto got = outbox.drain(2);
  EXPECT_NE(find<CrowdFrame>(got), nullptr);
}

// ---- Crowds inserted at run time (InsertCrowd / RemoveCrowd → CrowdResult) ----

namespace crowds {

/// A valid crowd for scenarios/museum.json: 2 groups of 3 starting at the hall, at once.
std::string visitors(const std::string& id = "late-visitors", int groups = 2, int size = 3) {
  return R"({"format": "throng-crowd/1", "id": ")" + id + R"(",
  "populations": [
    {"id": ")" + id + R"(-pop", "groups": )" + std::to_string(groups) + R"(, "size": )" + std::to_string(size) + R"(,
     "spawn": {"point": "hall"}, "goals": ["door-a", "a1-sunflowers", "exit"], "speed": 1.1, "radius": 0.2}
  ]
})";
}

/// Agents of the world's snapshot whose population index is at least `firstPopulation`.
std::size_t agentsFrom(sim::World& world, std::uint32_t firstPopulation) {
  auto snap = world.takeFrame();
  std::size_t n = 0;
  for (std::size_t r = 0; r < snap->size(); ++r) {
    auto info = world.agentInfo(snap->ids[r]);
    if (info && info->population >= firstPopulation) ++n;
  }
  return n;
}

const CrowdResult* result(const std::vector<Message>& got) { return find<CrowdResult>(got); }

}  // namespace crowds

TEST_F(HubFixture, AnInsertedCrowdsAgentsAppearForEveryClient) {
  connect(1);
  connect(2);
  const Joined a = join(1, "curator");
  for (int i = 0; i < 5; ++i) tick();
  outbox.drain(1);
  outbox.drain(2);
  const auto firstPopulation = static_cast<std::uint32_t>(world->desc().populations.size());
  say(1, encode(InsertCrowd{a.token, 7, crowds::visitors()}));
  EXPECT_TRUE(outbox.drain(1).empty());  // answered by applyToWorld, between ticks
  tick();
  const auto got = outbox.drain(1);
  const CrowdResult* r = crowds::result(got);
  ASSERT_NE(r, nullptr);
  EXPECT_TRUE(r->ok) << r->text;
  EXPECT_EQ(r->requestId, 7u);
  EXPECT_EQ(r->crowdIndex, 0u);
  EXPECT_EQ(r->crowdId, "late-visitors");
  EXPECT_NE(r->text.find("inserted"), std::string::npos) << r->text;
  ASSERT_EQ(world->crowds().size(), 1u);
  EXPECT_TRUE(world->crowds()[0].applied);
  EXPECT_EQ(crowds::agentsFrom(*world, firstPopulation), 6u);
  EXPECT_EQ(find<CrowdResult>(outbox.drain(2)), nullptr);  // only the sender hears the answer
  // Client 2 (no avatar: an overview of everyone) decodes the new agents in its crowd frames.
  tick();
  CrowdDecoder decoder;
  std::set<std::uint32_t> seen;
  for (const auto& sent : outbox.queues[2]) {
    auto d = decoder.decode(sent.bytes);
    if (!d.ok()) continue;
    seen.clear();
    for (const AgentState& s : d->view.agents) seen.insert(s.id);
  }
  auto snap = world->takeFrame();
  std::size_t inserted = 0;
  for (std::size_t i = 0; i < snap->size(); ++i) {
    auto info = world->agentInfo(snap->ids[i]);
    if (info && info->population >= firstPopulation) {
      ++inserted;
      EXPECT_TRUE(seen.count(snap->ids[i])) << "agent " << snap->ids[i];
    }
  }
  EXPECT_EQ(inserted, 6u);
  EXPECT_TRUE(outbox.closed.empty());
}

TEST_F(HubFixture, ABadCrowdIsRefusedWithDiagnosticsAndTheWorldIsUntouched) {
  auto control = sim::World::create(scenario->desc, scenario->navmesh);
  ASSERT_TRUE(control.ok());
  std::unique_ptr<sim::World> twin = std::move(control).value();
  connect(1);
  const Joined a = join(1, "curator");
  const std::string bad = R"({"format": "throng-crowd/1", "id": "oops",
  "populations": [
    {"id": "p", "groups": 1, "size": 2, "spawn": {"point": "hal"}, "goals": ["door-a"]}
  ]
})";
  for (int i = 0; i < 30; ++i) {
    if (i == 3) say(1, encode(InsertCrowd{a.token, 9, bad}));
    tick();
    twin->setViewers({});
    twin->step(tasks);
  }
  const auto got = outbox.drain(1);
  const CrowdResult* r = crowds::result(got);
  ASSERT_NE(r, nullptr);
  EXPECT_FALSE(r->ok);
  EXPECT_EQ(r->requestId, 9u);
  // file:line:column, JSON pointer, what was expected, did you mean.
  EXPECT_NE(r->text.find("participant " + std::to_string(a.participantId) + " request 9:3:"), std::string::npos) << r->text;
  EXPECT_NE(r->text.find("/populations/0/spawn"), std::string::npos) << r->text;
  EXPECT_NE(r->text.find("hall"), std::string::npos) << r->text;
  EXPECT_TRUE(world->crowds().empty());
  EXPECT_EQ(world->takeFrame()->size(), twin->takeFrame()->size());
  EXPECT_EQ(world->stateHash(), twin->stateHash());
  EXPECT_TRUE(outbox.closed.empty());  // a bad crowd file is no protocol error: the session stays
}

TEST_F(HubFixture, TooManyAgentsAreRefused) {
  HubOptions options;
  options.maxInsertAgents = 4;
  hub = std::make_unique<Hub>(options, describeWorld(*scenario, *motions, *world, 20.0), 20.0f, *motions, outbox);
  connect(1);
  const Joined a = join(1, "curator");
  say(1, encode(InsertCrowd{a.token, 1, crowds::visitors("six", 2, 3)}));  // 6 > 4 on this server
  say(1, encode(InsertCrowd{a.token, 2, crowds::visitors("huge", 100, 200)}));  // 20000 > the World's 10000
  tick();
  const auto got = outbox.drain(1);
  std::vector<CrowdResult> results;
  for (const Message& m : got) {
    if (auto* c = std::get_if<CrowdResult>(&m)) results.push_back(*c);
  }
  ASSERT_EQ(results.size(), 2u);
  EXPECT_FALSE(results[0].ok);
  EXPECT_NE(results[0].text.find("at most 4 agents per crowd insertion"), std::string::npos) << results[0].text;
  EXPECT_EQ(results[0].crowdId, "six");
  EXPECT_FALSE(results[1].ok);
  EXPECT_NE(results[1].text.find("agents per crowd insertion"), std::string::npos) << results[1].text;
  EXPECT_LE(results[1].text.size(), kMaxTextLength);
  EXPECT_TRUE(world->crowds().empty());
}

TEST_F(HubFixture, ARemovedCrowdsAgentsLeave) {
  connect(1);
  const Joined a = join(1, "curator");
  const auto firstPopulation = static_cast<std::uint32_t>(world->desc().populations.size());
  say(1, encode(InsertCrowd{a.token, 1, crowds::visitors()}));
  for (int i = 0; i < 5; ++i) tick();
  ASSERT_EQ(crowds::agentsFrom(*world, firstPopulation), 6u);
  outbox.drain(1);
  say(1, encode(RemoveCrowd{a.token, 2, "late-visitors"}));
  tick();
  auto got = outbox.drain(1);
  const CrowdResult* r = crowds::result(got);
  ASSERT_NE(r, nullptr);
  EXPECT_TRUE(r->ok) << r->text;
  EXPECT_EQ(r->requestId, 2u);
  EXPECT_EQ(r->crowdIndex, 0u);
  EXPECT_EQ(r->crowdId, "late-visitors");
  EXPECT_EQ(crowds::agentsFrom(*world, firstPopulation), 0u);
  ASSERT_EQ(world->crowds().size(), 1u);
  EXPECT_TRUE(world->crowds()[0].removed);
  // Removing it again, or a crowd that never was, is refused (the session stays).
  say(1, encode(RemoveCrowd{a.token, 3, "late-visitors"}));
  say(1, encode(RemoveCrowd{a.token, 4, "late-visitor"}));
  tick();
  got = outbox.drain(1);
  std::vector<CrowdResult> results;
  for (const Message& m : got) {
    if (auto* c = std::get_if<CrowdResult>(&m)) results.push_back(*c);
  }
  ASSERT_EQ(results.size(), 2u);
  EXPECT_FALSE(results[0].ok);
  EXPECT_NE(results[0].text.find("removed already"), std::string::npos) << results[0].text;
  EXPECT_FALSE(results[1].ok);
  EXPECT_NE(results[1].text.find("no crowd 'late-visitor'"), std::string::npos) << results[1].text;
  EXPECT_TRUE(outbox.closed.empty());
}

TEST_F(HubFixture, OnlyParticipantsInsertCrowdsAndAtMostFourAMinute) {
  connect(1);
  connect(2);
  // A viewer that never joined: refused like a Guide, and closed.
  say(2, encode(InsertCrowd{0, 1, crowds::visitors()}));
  const auto got2 = outbox.drain(2);
  const Bye* bye = find<Bye>(got2);
  ASSERT_NE(bye, nullptr);
  EXPECT_EQ(bye->reason, ReasonCode::UnexpectedMessage);
  EXPECT_TRUE(outbox.closed.count(2));
  // A participant with someone else's token: closed too.
  const Joined a = join(1, "curator");
  tick();
  EXPECT_TRUE(world->crowds().empty());
  // Four insertions a minute; the fifth is answered "rate limited" at once, the session stays.
  for (std::uint32_t i = 0; i < 5; ++i) say(1, encode(InsertCrowd{a.token, 10 + i, crowds::visitors("c" + std::to_string(i), 1, 1)}));
  auto got = outbox.drain(1);
  const CrowdResult* limited = crowds::result(got);
  ASSERT_NE(limited, nullptr);
  EXPECT_FALSE(limited->ok);
  EXPECT_EQ(limited->requestId, 14u);
  EXPECT_NE(limited->text.find("rate limited"), std::string::npos) << limited->text;
  tick();
  EXPECT_EQ(world->crowds().size(), 4u);
  now += 61.0;
  hub->onMessage(1, encode(Heartbeat{a.token, 1, 0}), now);  // keeps it from timing out
  say(1, encode(InsertCrowd{a.token, 20, crowds::visitors("c5", 1, 1)}));
  tick();
  got = outbox.drain(1);
  const CrowdResult* later = crowds::result(got);
  ASSERT_NE(later, nullptr);
  EXPECT_TRUE(later->ok) << later->text;
  EXPECT_EQ(world->crowds().size(), 5u);
  say(1, encode(InsertCrowd{a.token ^ 1, 21, crowds::visitors("c6", 1, 1)}));
  const auto got3 = outbox.drain(1);
  const Bye* bad = find<Bye>(got3);
  ASSERT_NE(bad, nullptr);
  EXPECT_EQ(bad->reason, ReasonCode::BadToken);
}

TEST_F(HubFixture, AReplayServerRefusesCrowdInsertion) {
  HubOptions options;
  options.replay = true;
  hub = std::make_unique<Hub>(options, describeWorld(*scenario, *motions, *world, 20.0), 20.0f, *motions, outbox);
  connect(1);
  const Joined a = join(1, "viewer");
  say(1, encode(InsertCrowd{a.token, 3, crowds::visitors()}));
  const auto got = outbox.drain(1);
  const CrowdResult* r = crowds::result(got);
  ASSERT_NE(r, nullptr);
  EXPECT_FALSE(r->ok);
  EXPECT_NE(r->text.find("this server plays a recording"), std::string::npos) << r->text;
  EXPECT_TRUE(outbox.closed.empty());
}


// ---- Per-request limits, ownership, names (issue 15 items 6, 8, 10) ----

/// All CrowdResults in `got`, in order.
std::vector<CrowdResult> crowdResults(const std::vector<Message>& got) {
  std::vector<CrowdResult> out;
  for (const Message& m : got) {
    if (auto* c = std::get_if<CrowdResult>(&m)) out.push_back(*c);
  }
  return out;
}

/// `i` as 4 base-36 digits: 96,312 distinct short keys fit 1 MiB.
std::string base36(int i) {
  std::string s(4, '0');
  for (int k = 3; k >= 0; --k, i /= 36) s[static_cast<std::size_t>(k)] = "0123456789abcdefghijklmnopqrstuvwxyz"[i % 36];
  return s;
}

TEST_F(HubFixture, ACrowdOverALimitIsRefusedNamingTheLimitAndWhereItWasCrossed) {
  connect(1);
  const Joined a = join(1, "curator");
  // A spawn polygon of 95,280 vertices (it stalled the world for 30 s), and a population of
  // 96,312 keys (14.6 s): each refused at the vertex or key that crossed the limit.
  std::string polygon;
  for (int i = 0; i < 95280; ++i) polygon += std::string(i ? "," : "") + "[" + std::to_string(1 + i % 7) + "," + std::to_string(2 + i % 5) + "]";
  const std::string vertices = R"({"format": "throng-crowd/1", "id": "big", "populations": [{"id": "p", "groups": 1, "size": 1,
    "spawn": {"polygon": [)" + polygon + R"(]}, "goals": ["exit"]}]})";
  std::string keys;
  for (int i = 0; i < 96312; ++i) keys += ",\"" + base36(i) + "\":0";  // about 1 MiB
  const std::string manyKeys = R"({"format": "throng-crowd/1", "id": "keys", "populations": [{"id": "p", "groups": 1,
    "size": 1, "spawn": {"point": "hall"}, "goals": ["exit"])" + keys + "}]}";
  std::string deep = R"({"format": "throng-crowd/1", "id": "deep", "populations": )";
  for (int i = 0; i < 40; ++i) deep += "[";
  for (int i = 0; i < 40; ++i) deep += "]";
  deep += "}";
  say(1, encode(InsertCrowd{a.token, 1, vertices}));
  say(1, encode(InsertCrowd{a.token, 2, manyKeys}));
  say(1, encode(InsertCrowd{a.token, 3, deep}));
  tick();
  const std::vector<CrowdResult> results = crowdResults(outbox.drain(1));
  ASSERT_EQ(results.size(), 3u);
  for (const CrowdResult& r : results) {
    EXPECT_FALSE(r.ok);
    EXPECT_NE(r.text.find("(server limit)"), std::string::npos) << r.text;
    EXPECT_LE(r.text.size(), kMaxTextLength);
  }
  const std::string who = "participant " + std::to_string(a.participantId) + " request ";
  EXPECT_NE(results[0].text.find(who + "1:2:"), std::string::npos) << results[0].text;
  EXPECT_NE(results[0].text.find("/populations/0/spawn/polygon/1000: a polygon of more than 1000 vertices"),
            std::string::npos) << results[0].text;
  EXPECT_NE(results[1].text.find("/populations/0/" + base36(9991) + ": more than 10000 object keys"), std::string::npos) << results[1].text;
  EXPECT_NE(results[2].text.find("/populations/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0: nesting deeper than 16 levels"),
            std::string::npos) << results[2].text;
  EXPECT_TRUE(world->crowds().empty());
  EXPECT_TRUE(outbox.closed.empty());  // the session stays
}

TEST_F(HubFixture, ACrowdBelongsToWhoeverInsertedItOthersAreRefused) {
  connect(1);
  connect(2);
  const Joined a = join(1, "alice");
  const Joined b = join(2, "bob");
  say(1, encode(InsertCrowd{a.token, 1, crowds::visitors("alices")}));
  tick();
  ASSERT_TRUE(crowds::result(outbox.drain(1))->ok);
  // The scenario's own crowd (its timeline does this): nobody's.
  {
    auto parsed = io::parseCrowd(crowds::visitors("scenarios"), "timeline", *world);
    ASSERT_TRUE(parsed.ok()) << core::formatAll(parsed.errors());
    ASSERT_TRUE(world->insertCrowd(parsed.value()).ok());
  }
  tick();
  outbox.drain(2);
  // Bob may remove neither Alice's crowd nor the scenario's: refused with a reason, session kept.
  say(2, encode(RemoveCrowd{b.token, 5, "alices"}));
  say(2, encode(RemoveCrowd{b.token, 6, "scenarios"}));
  tick();
  std::vector<CrowdResult> refused = crowdResults(outbox.drain(2));
  ASSERT_EQ(refused.size(), 2u);
  EXPECT_FALSE(refused[0].ok);
  EXPECT_EQ(refused[0].crowdId, "alices");
  EXPECT_NE(refused[0].text.find("crowd 'alices' belongs to participant " + std::to_string(a.participantId) + " ('alice')"),
            std::string::npos) << refused[0].text;
  EXPECT_FALSE(refused[1].ok);
  EXPECT_NE(refused[1].text.find("crowd 'scenarios' belongs to the scenario"), std::string::npos) << refused[1].text;
  for (const sim::CrowdInfo& c : world->crowds()) EXPECT_FALSE(c.removed) << c.id;
  EXPECT_TRUE(outbox.closed.empty());
  EXPECT_EQ(hub->crowdOwners(), (std::map<std::string, std::uint32_t>{{"alices", a.participantId}}));
  // Alice removes her own.
  say(1, encode(RemoveCrowd{a.token, 7, "alices"}));
  tick();
  const std::vector<CrowdResult> removed = crowdResults(outbox.drain(1));
  ASSERT_EQ(removed.size(), 1u);
  EXPECT_TRUE(removed[0].ok) << removed[0].text;
  EXPECT_TRUE(world->crowds()[0].removed);
  EXPECT_FALSE(world->crowds()[1].removed);
}

TEST_F(HubFixture, NamesThatAreNotUtf8AreRefusedAtEntry) {
  hub->onOpen(1, "test:1", now);
  say(1, encode(Hello{kProtocolVersion, ClientKind::Native, "bad\xff\xfe" "name"}));
  const auto got = outbox.drain(1);
  const Refuse* refused = find<Refuse>(got);
  ASSERT_NE(refused, nullptr);
  EXPECT_EQ(refused->reason, ReasonCode::BadMessage);
  EXPECT_NE(refused->text.find("clientName is not UTF-8 at byte 3 (0xFF)"), std::string::npos) << refused->text;
  EXPECT_TRUE(outbox.closed.count(1));
  EXPECT_EQ(find<Welcome>(got), nullptr);
  // A participant name: the session is closed with the reason; nobody hears of it.
  connect(2);
  hub->onOpen(3, "test:3", now);
  say(3, encode(Hello{kProtocolVersion, ClientKind::Native, "watcher"}));
  outbox.drain(3);
  say(2, encode(Join{"\xc3\x28", 0}));  // a lead byte followed by no continuation byte
  const auto got2 = outbox.drain(2);
  const Bye* bye = find<Bye>(got2);
  ASSERT_NE(bye, nullptr);
  EXPECT_EQ(bye->reason, ReasonCode::BadMessage);
  EXPECT_NE(bye->text.find("Join: name is not UTF-8 at byte 0 (0xC3)"), std::string::npos) << bye->text;
  EXPECT_EQ(find<Joined>(got2), nullptr);
  EXPECT_EQ(find<Presence>(outbox.drain(3)), nullptr);
  for (const ClientStatus& c : hub->status().perClient) EXPECT_FALSE(c.participant) << c.name;
  // A UTF-8 name with a control character is kept as sent (JSON and the viewer escape it).
  hub->onOpen(4, "test:4", now);
  say(4, encode(Hello{kProtocolVersion, ClientKind::Native, "Zo\xc3\xab\x07"}));
  EXPECT_NE(find<Welcome>(outbox.drain(4)), nullptr);
}

TEST_F(HubFixture, ACrowdIdThatIsNotUtf8IsRefusedAndRepliesStayUtf8) {
  connect(1);
  const Joined a = join(1, "curator");
  say(1, encode(RemoveCrowd{a.token, 4, "x\xff"}));
  tick();
  std::vector<CrowdResult> results = crowdResults(outbox.drain(1));
  ASSERT_EQ(results.size(), 1u);
  EXPECT_FALSE(results[0].ok);
  EXPECT_NE(results[0].text.find("not UTF-8 at byte 1 (0xFF)"), std::string::npos) << results[0].text;
  EXPECT_FALSE(invalidUtf8At(results[0].crowdId).has_value());
  // A crowd file that is not UTF-8: refused at its line and column, before it is parsed.
  say(1, encode(InsertCrowd{a.token, 5, "{\"format\": \"throng-crowd/1\",\n \"id\": \"\xfe\"}"}));
  // An unknown id quoting control characters: echoed escaped.
  say(1, encode(RemoveCrowd{a.token, 6, "a\x1b[2Jb"}));
  tick();
  results = crowdResults(outbox.drain(1));
  ASSERT_EQ(results.size(), 2u);
  EXPECT_NE(results[0].text.find(":2:9: not UTF-8: byte 37 (0xFE)"), std::string::npos) << results[0].text;
  EXPECT_NE(results[1].text.find("no crowd 'a\\x1B[2Jb' present"), std::string::npos) << results[1].text;
  EXPECT_EQ(results[1].text.find('\x1b'), std::string::npos);
}


TEST_F(HubFixture, AtMostSoManyInsertionsWaitForValidationMoreAreAnsweredBusy) {
  HubOptions options;
  options.crowdInsertsPerMinute = 100;
  options.maxPendingCrowdInserts = 3;
  hub = std::make_unique<Hub>(options, describeWorld(*scenario, *motions, *world, 20.0), 20.0f, *motions, outbox);
  connect(1);
  const Joined a = join(1, "curator");
  // No tick yet: the crowd thread has no copy of the world to validate against, so they wait.
  for (std::uint32_t i = 0; i < 5; ++i) say(1, encode(InsertCrowd{a.token, i, crowds::visitors("c" + std::to_string(i), 1, 1)}));
  std::vector<CrowdResult> busy = crowdResults(outbox.drain(1));
  ASSERT_EQ(busy.size(), 2u);
  for (const CrowdResult& r : busy) {
    EXPECT_FALSE(r.ok);
    EXPECT_NE(r.text.find("busy: 3 crowd insertions are waiting"), std::string::npos) << r.text;
  }
  EXPECT_EQ(busy[0].requestId, 3u);
  EXPECT_EQ(busy[1].requestId, 4u);
  tick();
  const std::vector<CrowdResult> done = crowdResults(outbox.drain(1));
  ASSERT_EQ(done.size(), 3u);
  for (const CrowdResult& r : done) EXPECT_TRUE(r.ok) << r.text;
  EXPECT_EQ(world->crowds().size(), 3u);
}

}  // namespace
}  // namespace throng::hub
