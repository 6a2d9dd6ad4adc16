// throng::client::Session — a native participant of a shared world (docs/server.md): connects over
// WebSocket or UDP, says Hello, receives the world description, joins with a name, moves its
// avatar (in a look of its choice), guides groups, and decodes the crowd frames (acknowledging
// each, so the server delta-codes against them), answering heartbeats; it keeps who else is
// present, with each participant's name and look (Presence), for the embedding code to draw. Blocking calls with timeouts; no threads of its
// own, so one thread can drive many sessions (throng loadgen). Reads and writes a socket.
#pragma once
#include <array>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "throng/core/result.hpp"
#include "throng/protocol/crowd_decoder.hpp"
#include "throng/protocol/messages.hpp"

namespace throng::client {

struct SessionOptions {
  std::string host = "127.0.0.1";
  std::uint16_t port = 8080;      ///< HTTP/WebSocket port
  std::string path = "/ws";
  bool udp = false;               ///< speak UDP to udpPort instead of WebSocket
  std::uint16_t udpPort = 8081;
  std::string name = "native";
  protocol::ClientKind kind = protocol::ClientKind::Native;
  std::chrono::milliseconds timeout{5000};
};

/// A participant present in the world, as its latest Presence announced it.
struct Participant {
  std::uint32_t id = 0;
  std::string name;
  /// Its look: the `avatar` it joined with (Join; docs/protocol.md), an index into the looks the
  /// viewers offer (the browser viewer's: web/viewer/src/crowd/avatar_looks.js; an index past the
  /// list is drawn in the first look). nullopt when the server speaks protocol version 1, which
  /// does not relay looks.
  std::optional<std::uint16_t> avatar;
};

/// Counters a load generator reports.
struct SessionStats {
  std::uint64_t bytesReceived = 0;
  std::uint64_t messagesReceived = 0;
  std::uint64_t crowdFrames = 0;
  std::uint64_t keyFrames = 0;
  std::uint64_t lostFrames = 0;     ///< gaps in the crowd frame numbers (replaced by newer ones, or lost)
  std::uint64_t undecodable = 0;    ///< delta frames whose base this client did not have
  /// UDP: fragmented messages dropped incomplete (a piece lost, or overtaken by newer ones); a
  /// crowd frame among them also shows in lostFrames as a gap.
  std::uint64_t incompleteMessages = 0;
  std::vector<double> frameDelayMs; ///< per crowd frame: arrival minus its slot in the tick schedule [ms]
  double roundTripMs = 0.0;         ///< latest heartbeat round trip
  std::uint32_t agentsInView = 0;   ///< agents in the newest decoded frame
  /// Agents per detail tier (near, middle, far; docs/protocol.md "Tiers") in the newest decoded frame.
  std::array<std::uint32_t, 3> tiersInView{};
  /// Per tier, agents summed over every decoded frame (÷ crowdFrames: the mean per frame).
  std::array<std::uint64_t, 3> tierSums{};
  std::uint32_t farMax = 0;         ///< most far-tier agents in any decoded frame
  std::uint32_t animationInterval = 1;  ///< X of the newest frame
};

class Session {
 public:
  /// Connects, says Hello and waits for the Welcome. A Refuse comes back as a diagnostic with the
  /// server's reason.
  static core::Result<std::unique_ptr<Session>> open(const SessionOptions& options);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  [[nodiscard]] const protocol::Welcome& welcome() const;
  [[nodiscard]] const std::string& worldJson() const;

  /// Joins as a participant in look `avatar` (Join's avatar: what other clients are told in
  /// Presence, see Participant::avatar); waits for Joined. Called again while joined, it changes
  /// the participant's name (unless empty) and look for everyone, keeping its id and token.
  core::Result<protocol::Joined> join(const std::string& name, std::uint16_t avatar = 0);
  core::Status move(float x, float y, float yaw);
  core::Status guide(std::uint32_t group);
  core::Status release(std::uint32_t group);
  core::Status leave();
  /// Drives a replay (a server playing a recording): play, pause, seek [s], speed (factor).
  core::Status replayControl(protocol::ReplayCommand command, double value = 0.0);
  /// The newest ReplayStatus heard (replays only).
  [[nodiscard]] const std::optional<protocol::ReplayStatus>& replayStatus() const;
  /// Asks the server to insert a crowd (a "throng-crowd/1" file's text, ≤ protocol::kMaxCrowdJson
  /// bytes; WebSocket only, it does not fit a datagram). Returns the request id that the answer
  /// (crowdResults) carries. Needs join() first.
  core::Result<std::uint32_t> insertCrowd(const std::string& crowdJson);
  /// Asks the server to remove the crowd with id `crowdId`; returns the request id.
  core::Result<std::uint32_t> removeCrowd(const std::string& crowdId);
  /// Participants present, by id, with their names (Presence messages).
  [[nodiscard]] const std::vector<std::pair<std::uint32_t, std::string>>& participants() const;
  /// The other participants present, with their names and looks, in the order they were announced
  /// (Presence messages: to a newcomer, those already present; then each that joins or leaves).
  /// Updated by pump().
  [[nodiscard]] const std::vector<Participant>& present() const;
  /// The look of participant `participantId`: nullopt when it is not present, or the server did not
  /// say (protocol version 1).
  [[nodiscard]] std::optional<std::uint16_t> avatarOf(std::uint32_t participantId) const;

  /// Handles every message waiting (or the next within `wait`): crowd frames are decoded and
  /// acknowledged, heartbeats answered, relays and guide results kept. Returns false once the
  /// server closed the session (closeReason() says why).
  bool pump(std::chrono::milliseconds wait = std::chrono::milliseconds(0));

  /// The crowd as last decoded (ascending id).
  [[nodiscard]] const std::optional<protocol::DecodedCrowdFrame>& crowd() const;
  /// Guide results received, oldest first (cleared by the caller).
  [[nodiscard]] std::vector<protocol::GuideResult>& guideResults();
  /// Answers to insertCrowd / removeCrowd received, oldest first (cleared by the caller).
  [[nodiscard]] std::vector<protocol::CrowdResult>& crowdResults();
  /// Latest Move of each other participant, by participant id.
  [[nodiscard]] const std::vector<std::pair<std::uint32_t, protocol::Move>>& others() const;
  [[nodiscard]] const SessionStats& stats() const;
  [[nodiscard]] bool open() const;
  [[nodiscard]] const std::string& closeReason() const;
  /// Says Bye and closes.
  void close(const std::string& reason = "client quit");

 private:
  struct Impl;
  explicit Session(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace throng::client
