// throng::protocol — the shared-world wire protocol, version 2 (docs/protocol.md): message types,
// enums shared by several messages, and the limits every decoder enforces. Pure data: no sockets,
// no I/O. One message = one WebSocket binary frame or one UDP datagram; every message starts with
// the magic byte kMagic and a MessageType byte; integers are little-endian, varints are LEB128.
#pragma once
#include <cstddef>
#include <cstdint>

namespace throng::protocol {

/// The version this code speaks. Version 2 added Presence's trailing `avatar` (a participant's look).
inline constexpr std::uint16_t kProtocolVersion = 2;
/// The oldest version a server still serves: a version-1 client gets version-1 messages (Presence
/// without `avatar`), so clients built before version 2 keep working.
inline constexpr std::uint16_t kMinProtocolVersion = 1;
inline constexpr std::uint8_t kMagic = 0x54;  ///< 'T', byte 0 of every message

// Limits (a decoder refuses anything beyond them; allocations never exceed them).
inline constexpr std::size_t kMaxMessageSize = 8u << 20;     ///< one encoded message [bytes]
inline constexpr std::size_t kMaxDatagramSize = 65507;       ///< what fits one UDP datagram [bytes]
inline constexpr std::size_t kMaxCrowdPayload = 16u << 20;   ///< decompressed crowd payload [bytes]
inline constexpr std::size_t kMaxWorldSize = 64u << 20;      ///< decompressed world description [bytes]
inline constexpr std::size_t kMaxNameLength = 64;            ///< client, server, participant names [bytes, UTF-8]
inline constexpr std::size_t kMaxTextLength = 1024;          ///< reason texts [bytes, UTF-8]
inline constexpr std::size_t kMaxAgents = 65536;             ///< agents in one crowd view
inline constexpr std::size_t kMaxJoints = 128;               ///< joints of a skeleton (3 angles each)
inline constexpr std::size_t kMaxExpressionWeights = 64;     ///< FaceExpression weights
inline constexpr std::size_t kMaxCrowdJson = 1u << 20;       ///< InsertCrowd's crowd file text [bytes, UTF-8]
inline constexpr std::size_t kMinFragments = 2;              ///< Fragment::count, at least
inline constexpr std::size_t kMaxFragments = 8192;           ///< Fragment::count, at most
inline constexpr std::size_t kCookieSize = 16;               ///< Cookie / UdpHello cookie [bytes]
inline constexpr std::size_t kCookieMessageSize = 2 + kCookieSize;      ///< an encoded Cookie [bytes]
/// The smallest encoded UdpHello [bytes]: header, cookie and a Hello with an empty name (6 bytes).
/// Larger than a Cookie, so the server's answer never amplifies what it answers.
inline constexpr std::size_t kMinUdpHelloSize = 2 + kCookieSize + 6;
/// Largest client → server message other than InsertCrowd [bytes] (a Joints of 128 joints is 785).
inline constexpr std::size_t kMaxClientMessageSize = 4096;

enum class MessageType : std::uint8_t {
  Hello = 1,           ///< client → server: first message
  Refuse = 2,          ///< server → client: Hello refused, connection closes
  Welcome = 3,         ///< server → client: Hello accepted, world description
  Join = 4,            ///< client → server: become a participant
  Joined = 5,          ///< server → client: participant id and token
  Leave = 6,           ///< client → server: stop being a participant
  Heartbeat = 7,       ///< both ways: keep-alive and round-trip time
  Bye = 8,             ///< both ways: the sender closes, with a reason
  Move = 9,            ///< participant state: position and yaw
  Joints = 10,         ///< participant state: body joint angles
  HandJoints = 11,     ///< participant state: hand joint angles
  FaceExpression = 12, ///< participant state: expression id and weights
  Guide = 13,          ///< client → server: take control of a group
  Release = 14,        ///< client → server: give a group back
  GuideResult = 15,    ///< server → client: answer to Guide / Release
  Ack = 16,            ///< client → server: newest crowd frame decoded
  CrowdFrame = 17,     ///< server → client: the aggregated crowd of one tick
  Presence = 18,       ///< server → client: a participant joined (or is present) or left
  ReplayControl = 19,  ///< client → server: play, pause, seek or change the speed of a replay
  ReplayStatus = 20,   ///< server → client: the replay's time, duration, playing and speed
  InsertCrowd = 21,    ///< client → server: add a crowd (a crowd file's JSON) to the running world
  RemoveCrowd = 22,    ///< client → server: remove a crowd inserted earlier, by its id
  CrowdResult = 23,    ///< server → client: answer to InsertCrowd / RemoveCrowd
  Fragment = 24,       ///< server → client (UDP only): one piece of a message too large for a datagram
  Cookie = 25,         ///< server → client (UDP only): proof-of-address cookie answering a UdpHello
  UdpHello = 26,       ///< client → server (UDP only): a cookie and a Hello; opens a UDP session
};
inline constexpr std::uint8_t kMaxMessageType = 26;

/// Who may send a message type.
enum class Direction : std::uint8_t { ClientToServer, ServerToClient, Both };
/// The direction of a type (docs/protocol.md "Messages"); ServerToClient for an unknown value.
[[nodiscard]] Direction messageDirection(MessageType type);

/// Name of a message type ("Hello"); "?" for an unknown value.
[[nodiscard]] const char* messageTypeName(MessageType type);

enum class ClientKind : std::uint8_t { Browser = 0, Native = 1, Loadgen = 2 };

/// Why a Hello is refused, a connection closed or a Guide answered no.
enum class ReasonCode : std::uint8_t {
  None = 0,             ///< normal close / success
  VersionMismatch = 1,  ///< Hello's protocolVersion is not the server's
  ServerFull = 2,       ///< --max-clients reached
  BadMessage = 3,       ///< a message failed to decode (the text says where and why)
  UnexpectedMessage = 4,///< a valid message at the wrong time (Join before Hello…)
  BadToken = 5,         ///< a token that is not the sender's
  RateLimited = 6,      ///< too many participant messages
  Timeout = 7,          ///< no heartbeat for too long
  SlowClient = 8,       ///< send queue over its limit
  ShuttingDown = 9,     ///< the server stops (Ctrl-C)
  UnknownGroup = 10,    ///< Guide / Release: no such group
  GroupTaken = 11,      ///< Guide: another participant guides it
  NotGuiding = 12,      ///< Release: the sender does not guide it
  ClientQuit = 13,      ///< the client leaves
};
inline constexpr std::uint8_t kMaxReasonCode = 13;

/// What a ReplayControl asks of a server playing a recording.
enum class ReplayCommand : std::uint8_t {
  Play = 0,   ///< value must be 0
  Pause = 1,  ///< value must be 0
  Seek = 2,   ///< value = recording time [s], finite, ≥ 0 (clamped to the duration by the server)
  Speed = 3,  ///< value = playback speed factor, finite, in (0, kMaxReplaySpeed]
};
inline constexpr std::uint8_t kMaxReplayCommand = 3;
inline constexpr double kMaxReplaySpeed = 64.0;  ///< fastest replay speed factor

/// Detail tier of an agent in a crowd frame, chosen per client by the server.
enum class Tier : std::uint8_t {
  Near = 0,    ///< position, yaw (16 bits), clip, phase and the full joint pose
  Middle = 1,  ///< position, yaw (8 bits), clip and phase
  Far = 2,     ///< position only, at a lower rate
};

}  // namespace throng::protocol
