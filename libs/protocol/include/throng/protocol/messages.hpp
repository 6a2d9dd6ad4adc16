// throng::protocol messages — the session, participant-state, guidance and ack messages as plain
// structs, `encode(msg)` → bytes for each, and `decodeAny(bytes)` → one of them (or a
// diagnostic saying what was wrong at which byte). The crowd frame's structs live in
// crowd_frame.hpp; its delta state in CrowdEncoder / CrowdDecoder. Layouts: docs/protocol.md.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "throng/core/result.hpp"
#include "throng/protocol/crowd_frame.hpp"
#include "throng/protocol/protocol.hpp"

namespace throng::protocol {

using Bytes = std::vector<std::uint8_t>;

struct Hello {
  std::uint16_t protocolVersion = kProtocolVersion;
  ClientKind clientKind = ClientKind::Native;
  std::string clientName;  ///< ≤ kMaxNameLength bytes
};

struct Refuse {
  std::uint16_t protocolVersion = kProtocolVersion;  ///< the server's version
  ReasonCode reason = ReasonCode::None;
  std::string text;  ///< ≤ kMaxTextLength bytes
};

/// How Welcome::world is stored.
enum class WorldEncoding : std::uint8_t { Json = 0, ZstdJson = 1 };

struct Welcome {
  std::uint16_t protocolVersion = kProtocolVersion;
  std::string serverName;   ///< ≤ kMaxNameLength bytes
  float tickRateHz = 10.0f; ///< simulation ticks per second (> 0)
  WorldEncoding worldEncoding = WorldEncoding::ZstdJson;
  std::uint32_t worldSize = 0;  ///< size of the JSON once decompressed [bytes], ≤ kMaxWorldSize
  Bytes world;  ///< the world description JSON (compressWorld / decompressWorld)
};

struct Join {
  std::string name;          ///< participant name, ≤ kMaxNameLength bytes
  std::uint16_t avatar = 0;  ///< index into the world description's avatar list
};

struct Joined {
  std::uint32_t participantId = 0;
  std::uint64_t token = 0;  ///< secret of the participant: proves who controls the avatar
};

struct Leave {
  std::uint64_t token = 0;
};

/// Round-trip time: each side sends its clock and echoes the last clock it received;
/// RTT = now − echoUs on the receiver of an echo.
struct Heartbeat {
  std::uint64_t token = 0;   ///< sender's token (client → server over UDP); 0 from the server
  std::uint64_t timeUs = 0;  ///< sender's clock [µs]
  std::uint64_t echoUs = 0;  ///< last timeUs received from the peer [µs]; 0 when none
};

struct Bye {
  ReasonCode reason = ReasonCode::None;
  std::string text;  ///< ≤ kMaxTextLength bytes
};

/// Who a participant-state message is about: client → server carries the token (UDP has no
/// connection to say who sends), server → client relays carry the participant id.
struct Subject {
  enum class Kind : std::uint8_t { Token = 0, Participant = 1 };
  Kind kind = Kind::Token;
  std::uint64_t value = 0;  ///< the token, or the participant id (≤ 0xffffffff)
  bool operator==(const Subject&) const = default;
};

/// Participant state messages are stateless (the latest overrides); `seq` grows by one per
/// message of that kind from that participant, so a receiver drops reordered older ones.
struct Move {
  Subject subject;
  std::uint32_t seq = 0;
  float x = 0, y = 0, z = 0;  ///< [m], quantized to 1 cm, |v| < 2^31 cm
  float yaw = 0;              ///< [rad], quantized to 1/65536 turn, decoded in [-π, π)
};

/// Body joint angles (Joints) or hand joint angles (HandJoints): three angles per joint [rad],
/// each quantized to an int16 in 1/65536 turn, in the skeleton's joint order.
struct JointAngles {
  Subject subject;
  std::uint32_t seq = 0;
  std::vector<float> angles;  ///< 3 × joints, joints ≤ kMaxJoints
};
struct Joints : JointAngles {};
struct HandJoints : JointAngles {};

struct FaceExpression {
  Subject subject;
  std::uint32_t seq = 0;
  std::uint16_t expression = 0;  ///< expression id
  std::vector<float> weights;    ///< [0, 1], quantized to 1/255; ≤ kMaxExpressionWeights
};

struct Guide {
  std::uint64_t token = 0;
  std::uint32_t groupId = 0;  ///< stable group id
};
struct Release {
  std::uint64_t token = 0;
  std::uint32_t groupId = 0;
};
struct GuideResult {
  std::uint32_t groupId = 0;
  bool guiding = false;  ///< true: the sender now guides the group; false: it does not
  bool ok = false;       ///< the request was carried out
  ReasonCode reason = ReasonCode::None;
};

/// The client decoded crowd frame `frameNumber`; the server deltas against the newest acked.
struct Ack {
  std::uint64_t token = 0;
  std::uint32_t frameNumber = 0;
};

/// A participant joined or left. The server sends it to every client when a participant joins or
/// leaves, and to a newcomer once for each participant already present.
struct Presence {
  std::uint32_t participantId = 0;
  bool present = false;  ///< true: present (joined); false: left
  std::string name;      ///< participant name, ≤ kMaxNameLength bytes
  /// The participant's look: Join's `avatar` (version 2; a trailing u16 on the wire, absent in
  /// version-1 messages, which still decode). Sent only to clients that said version 2 in Hello.
  std::optional<std::uint16_t> avatar;
};

/// Drives the replay of a server started on a recording. A viewer need not join to send it.
struct ReplayControl {
  std::uint64_t token = 0;  ///< sender's token; 0 when the sender has not joined
  ReplayCommand command = ReplayCommand::Play;
  /// Seek: recording time [s], finite, ≥ 0; Speed: factor, finite, in (0, kMaxReplaySpeed];
  /// Play / Pause: 0.
  double value = 0.0;
};

/// Where a replay stands: sent on every change and once a second.
struct ReplayStatus {
  double time = 0.0;      ///< recording time shown [s], finite, ≥ 0
  double duration = 0.0;  ///< recording length [s], finite, ≥ 0
  bool playing = false;
  float speed = 1.0f;     ///< playback speed factor, finite, > 0
};

/// A participant asks the server to add a crowd (a "throng-crowd/1" file's text, docs/scenario-format.md
/// "Crowd files") to the running world. Answered by a CrowdResult with the same requestId.
struct InsertCrowd {
  std::uint64_t token = 0;       ///< the participant's token
  std::uint32_t requestId = 0;   ///< chosen by the client, echoed in the CrowdResult
  std::string crowdJson;         ///< ≤ kMaxCrowdJson bytes
};

/// A participant asks the server to remove a crowd inserted earlier (its agents leave).
struct RemoveCrowd {
  std::uint64_t token = 0;       ///< the participant's token
  std::uint32_t requestId = 0;   ///< chosen by the client, echoed in the CrowdResult
  std::string crowdId;           ///< the crowd's id (its file's "id"), ≤ kMaxNameLength bytes
};

/// The answer to an InsertCrowd or RemoveCrowd, sent to the requesting client only.
struct CrowdResult {
  std::uint32_t requestId = 0;
  bool ok = false;               ///< carried out (the agents appear / leave at the next tick)
  std::uint32_t crowdIndex = 0;  ///< the crowd's index in insertion order (when ok)
  std::string crowdId;           ///< the crowd's id, ≤ kMaxNameLength bytes (empty when unknown)
  /// What happened, or the diagnostics one per line (file:line:column, JSON pointer, what was
  /// expected), truncated with "(and N more)"; ≤ kMaxTextLength bytes.
  std::string text;
};

/// One piece of a larger server → client message over UDP (docs/protocol.md "Fragment"): the
/// payloads of fragments 0..count-1 with the same messageId, concatenated, are one whole encoded
/// message (never itself a Fragment) of at most kMaxMessageSize bytes. See fragments.hpp.
struct Fragment {
  std::uint64_t messageId = 0;  ///< per peer, increasing by one per fragmented message
  std::uint32_t index = 0;      ///< < count
  std::uint32_t count = 0;      ///< kMinFragments..kMaxFragments
  Bytes payload;                ///< the rest of the datagram
};

/// A cookie: the server's keyed hash of the client's address, port and a time interval
/// (docs/protocol.md "Opening a UDP session"). All zero = none yet.
using CookieBytes = std::array<std::uint8_t, kCookieSize>;

/// The server's answer to a UdpHello from an address it has not seen prove itself: the cookie to
/// send back. Never larger than the UdpHello it answers (18 bytes against at least 24).
struct Cookie {
  CookieBytes cookie{};
};

/// The first datagram of a UDP session: a cookie (zeros when the client has none yet) and the
/// session's Hello. The server opens a UDP session only for a UdpHello whose cookie it issued to
/// that address and port within the last 10 to 20 s, and then treats `hello` as the first message.
struct UdpHello {
  CookieBytes cookie{};
  Hello hello;
};

using Message = std::variant<Hello, Refuse, Welcome, Join, Joined, Leave, Heartbeat, Bye, Move, Joints,
                             HandJoints, FaceExpression, Guide, Release, GuideResult, Ack, CrowdFrame,
                             Presence, ReplayControl, ReplayStatus, InsertCrowd, RemoveCrowd, CrowdResult,
                             Fragment, Cookie, UdpHello>;

[[nodiscard]] Bytes encode(const Hello& m);
[[nodiscard]] Bytes encode(const Refuse& m);
[[nodiscard]] Bytes encode(const Welcome& m);
[[nodiscard]] Bytes encode(const Join& m);
[[nodiscard]] Bytes encode(const Joined& m);
[[nodiscard]] Bytes encode(const Leave& m);
[[nodiscard]] Bytes encode(const Heartbeat& m);
[[nodiscard]] Bytes encode(const Bye& m);
[[nodiscard]] Bytes encode(const Move& m);
[[nodiscard]] Bytes encode(const Joints& m);
[[nodiscard]] Bytes encode(const HandJoints& m);
[[nodiscard]] Bytes encode(const FaceExpression& m);
[[nodiscard]] Bytes encode(const Guide& m);
[[nodiscard]] Bytes encode(const Release& m);
[[nodiscard]] Bytes encode(const GuideResult& m);
[[nodiscard]] Bytes encode(const Ack& m);
[[nodiscard]] Bytes encode(const CrowdFrame& m);  ///< compresses the payload when m.compressed
[[nodiscard]] Bytes encode(const Presence& m);
[[nodiscard]] Bytes encode(const ReplayControl& m);
[[nodiscard]] Bytes encode(const ReplayStatus& m);
[[nodiscard]] Bytes encode(const InsertCrowd& m);  ///< crowdJson over kMaxCrowdJson is cut (the server then refuses it)
[[nodiscard]] Bytes encode(const RemoveCrowd& m);
[[nodiscard]] Bytes encode(const CrowdResult& m);
[[nodiscard]] Bytes encode(const Fragment& m);
[[nodiscard]] Bytes encode(const Cookie& m);
[[nodiscard]] Bytes encode(const UdpHello& m);
[[nodiscard]] Bytes encode(const Message& m);

/// The type byte of a message without decoding it; an error when too short, a bad magic or an
/// unknown type.
[[nodiscard]] core::Result<MessageType> peekType(std::span<const std::uint8_t> bytes);

/// Decodes one message. Never reads out of bounds, never allocates beyond the limits in
/// protocol.hpp; errors name the field, the byte offset and what was expected
/// (Diagnostic::column = 1-based byte offset, Diagnostic::pointer = "/Type/field").
/// Strings are bytes (UTF-8 by convention; not validated). A CrowdFrame comes back with its
/// payload decompressed but not applied: hand it to CrowdDecoder.
[[nodiscard]] core::Result<Message> decodeAny(std::span<const std::uint8_t> bytes);

/// Decodes a message a client sent (what a server calls): the type is checked before anything
/// else, so a server → client type (a CrowdFrame, a Welcome: the ones with compressed parts) is
/// refused from its first two bytes without its body being read or decompressed
/// (pointer "/message/type"), and the size against that type's bound (kMaxCrowdJson + 32 for
/// InsertCrowd, kMaxClientMessageSize for the others; pointer "/message/size"). Then decodeAny.
[[nodiscard]] core::Result<Message> decodeFromClient(std::span<const std::uint8_t> bytes);
/// The most bytes a client → server message of `type` may have (0 for server → client types).
[[nodiscard]] std::size_t maxClientMessageSize(MessageType type);

[[nodiscard]] MessageType messageType(const Message& m);

/// zstd-compresses a world description JSON for Welcome (level 19: sent once per client).
[[nodiscard]] Welcome makeWelcome(std::string serverName, float tickRateHz, const std::string& worldJson);
/// The JSON of Welcome::world, decompressed when needed; an error when corrupt or over kMaxWorldSize.
[[nodiscard]] core::Result<std::string> worldJson(const Welcome& welcome);

}  // namespace throng::protocol
