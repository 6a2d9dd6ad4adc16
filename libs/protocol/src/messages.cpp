// throng::protocol messages — encode and decode the session, participant-state, guidance and ack
// messages (layouts in docs/protocol.md), and decodeAny's dispatch on the type byte. Reads bytes,
// writes bytes; every read is bounds-checked (ByteReader) and every length checked against the
// limits in protocol.hpp before anything is allocated.
#include "throng/protocol/messages.hpp"

#include <algorithm>
#include <cmath>

#include "byte_io.hpp"
#include "crowd_frame_codec.hpp"
#include "zstd_codec.hpp"

namespace throng::protocol {
namespace {

using detail::ByteReader;
using detail::ByteWriter;

Bytes start(MessageType type) {
  Bytes out;
  out.push_back(kMagic);
  out.push_back(static_cast<std::uint8_t>(type));
  return out;
}

std::string clampString(const std::string& s, std::size_t max) { return s.size() <= max ? s : s.substr(0, max); }

void writeSubject(ByteWriter& w, const Subject& s) {
  w.u8(static_cast<std::uint8_t>(s.kind));
  if (s.kind == Subject::Kind::Token) {
    w.u64(s.value);
  } else {
    w.varint(s.value & 0xffffffffu);
  }
}

Subject readSubject(ByteReader& r) {
  Subject s;
  const std::size_t at = r.offset();
  const std::uint8_t kind = r.u8("subject");
  if (kind > 1) {
    r.fail("subject", at, "unknown subject kind " + std::to_string(kind), "0 (token) or 1 (participant id)");
    return s;
  }
  s.kind = static_cast<Subject::Kind>(kind);
  s.value = s.kind == Subject::Kind::Token ? r.u64("subject") : r.varint("subject", 0xffffffffu);
  return s;
}

ReasonCode readReason(ByteReader& r) {
  const std::size_t at = r.offset();
  const std::uint8_t v = r.u8("reason");
  if (v > kMaxReasonCode) {
    r.fail("reason", at, "unknown reason code " + std::to_string(v), "0.." + std::to_string(kMaxReasonCode));
    return ReasonCode::None;
  }
  return static_cast<ReasonCode>(v);
}

void writeAngles(ByteWriter& w, const std::vector<float>& angles) {
  const std::size_t joints = std::min(angles.size() / 3, kMaxJoints);
  w.u8(static_cast<std::uint8_t>(joints));
  for (std::size_t i = 0; i < joints * 3; ++i) w.u16(quantizeAngle16(angles[i]));
}

std::vector<float> readAngles(ByteReader& r) {
  const std::size_t at = r.offset();
  const std::uint8_t joints = r.u8("jointCount");
  if (joints > kMaxJoints) {
    r.fail("jointCount", at, std::to_string(joints) + " joints", "at most " + std::to_string(kMaxJoints));
    return {};
  }
  if (r.remaining() < joints * 6u) {
    r.fail("angles", "truncated: " + std::to_string(r.remaining()) + " bytes left",
           std::to_string(joints * 6) + " bytes (3 int16 per joint)");
    return {};
  }
  std::vector<float> angles(joints * 3u);
  for (auto& a : angles) a = dequantizeAngle16(r.u16("angles"));
  return angles;
}

Bytes encodeAngles(MessageType type, const JointAngles& m) {
  Bytes out = start(type);
  ByteWriter w(out);
  writeSubject(w, m.subject);
  w.varint(m.seq);
  writeAngles(w, m.angles);
  return out;
}

template <class T>
T readJointAngles(ByteReader& r) {
  T m;
  m.subject = readSubject(r);
  m.seq = static_cast<std::uint32_t>(r.varint("seq", 0xffffffffu));
  m.angles = readAngles(r);
  return m;
}

std::uint8_t quantizeWeight(float w) {
  if (!(w > 0.0f)) return 0;
  if (w >= 1.0f) return 255;
  return static_cast<std::uint8_t>(std::lround(w * 255.0f));
}

}  // namespace

Bytes encode(const Hello& m) {
  Bytes out = start(MessageType::Hello);
  ByteWriter w(out);
  w.u16(m.protocolVersion);
  w.u8(static_cast<std::uint8_t>(m.clientKind));
  w.string(clampString(m.clientName, kMaxNameLength));
  return out;
}

Bytes encode(const Refuse& m) {
  Bytes out = start(MessageType::Refuse);
  ByteWriter w(out);
  w.u16(m.protocolVersion);
  w.u8(static_cast<std::uint8_t>(m.reason));
  w.string(clampString(m.text, kMaxTextLength));
  return out;
}

Bytes encode(const Welcome& m) {
  Bytes out = start(MessageType::Welcome);
  ByteWriter w(out);
  w.u16(m.protocolVersion);
  w.string(clampString(m.serverName, kMaxNameLength));
  w.f32(m.tickRateHz);
  w.u8(static_cast<std::uint8_t>(m.worldEncoding));
  w.varint(m.worldSize);
  w.varint(m.world.size());
  w.bytes(m.world);
  return out;
}

Bytes encode(const Join& m) {
  Bytes out = start(MessageType::Join);
  ByteWriter w(out);
  w.string(clampString(m.name, kMaxNameLength));
  w.u16(m.avatar);
  return out;
}

Bytes encode(const Joined& m) {
  Bytes out = start(MessageType::Joined);
  ByteWriter w(out);
  w.u32(m.participantId);
  w.u64(m.token);
  return out;
}

Bytes encode(const Leave& m) {
  Bytes out = start(MessageType::Leave);
  ByteWriter(out).u64(m.token);
  return out;
}

Bytes encode(const Heartbeat& m) {
  Bytes out = start(MessageType::Heartbeat);
  ByteWriter w(out);
  w.u64(m.token);
  w.u64(m.timeUs);
  w.u64(m.echoUs);
  return out;
}

Bytes encode(const Bye& m) {
  Bytes out = start(MessageType::Bye);
  ByteWriter w(out);
  w.u8(static_cast<std::uint8_t>(m.reason));
  w.string(clampString(m.text, kMaxTextLength));
  return out;
}

Bytes encode(const Move& m) {
  Bytes out = start(MessageType::Move);
  ByteWriter w(out);
  writeSubject(w, m.subject);
  w.varint(m.seq);
  w.i32(quantizePosition(m.x));
  w.i32(quantizePosition(m.y));
  w.i32(quantizePosition(m.z));
  w.u16(quantizeAngle16(m.yaw));
  return out;
}

Bytes encode(const Joints& m) { return encodeAngles(MessageType::Joints, m); }
Bytes encode(const HandJoints& m) { return encodeAngles(MessageType::HandJoints, m); }

Bytes encode(const FaceExpression& m) {
  Bytes out = start(MessageType::FaceExpression);
  ByteWriter w(out);
  writeSubject(w, m.subject);
  w.varint(m.seq);
  w.u16(m.expression);
  const std::size_t n = std::min(m.weights.size(), kMaxExpressionWeights);
  w.u8(static_cast<std::uint8_t>(n));
  for (std::size_t i = 0; i < n; ++i) w.u8(quantizeWeight(m.weights[i]));
  return out;
}

Bytes encode(const Guide& m) {
  Bytes out = start(MessageType::Guide);
  ByteWriter w(out);
  w.u64(m.token);
  w.varint(m.groupId);
  return out;
}

Bytes encode(const Release& m) {
  Bytes out = start(MessageType::Release);
  ByteWriter w(out);
  w.u64(m.token);
  w.varint(m.groupId);
  return out;
}

Bytes encode(const GuideResult& m) {
  Bytes out = start(MessageType::GuideResult);
  ByteWriter w(out);
  w.varint(m.groupId);
  w.u8(static_cast<std::uint8_t>((m.ok ? 1 : 0) | (m.guiding ? 2 : 0)));
  w.u8(static_cast<std::uint8_t>(m.reason));
  return out;
}

Bytes encode(const Ack& m) {
  Bytes out = start(MessageType::Ack);
  ByteWriter w(out);
  w.u64(m.token);
  w.varint(m.frameNumber);
  return out;
}

Bytes encode(const CrowdFrame& m) { return detail::encodeCrowdFrame(m); }

Bytes encode(const Presence& m) {
  Bytes out = start(MessageType::Presence);
  ByteWriter w(out);
  w.varint(m.participantId);
  w.u8(m.present ? 1 : 0);
  w.string(clampString(m.name, kMaxNameLength));
  if (m.avatar) w.u16(*m.avatar);  // version 2; a version-1 Presence ends with the name
  return out;
}

Bytes encode(const ReplayControl& m) {
  Bytes out = start(MessageType::ReplayControl);
  ByteWriter w(out);
  w.u64(m.token);
  w.u8(static_cast<std::uint8_t>(m.command));
  w.f64(m.value);
  return out;
}

Bytes encode(const ReplayStatus& m) {
  Bytes out = start(MessageType::ReplayStatus);
  ByteWriter w(out);
  w.f64(m.time);
  w.f64(m.duration);
  w.u8(m.playing ? 1 : 0);
  w.f32(m.speed);
  return out;
}

Bytes encode(const InsertCrowd& m) {
  Bytes out = start(MessageType::InsertCrowd);
  ByteWriter w(out);
  w.u64(m.token);
  w.varint(m.requestId);
  w.string(clampString(m.crowdJson, kMaxCrowdJson));
  return out;
}

Bytes encode(const RemoveCrowd& m) {
  Bytes out = start(MessageType::RemoveCrowd);
  ByteWriter w(out);
  w.u64(m.token);
  w.varint(m.requestId);
  w.string(clampString(m.crowdId, kMaxNameLength));
  return out;
}

Bytes encode(const CrowdResult& m) {
  Bytes out = start(MessageType::CrowdResult);
  ByteWriter w(out);
  w.varint(m.requestId);
  w.u8(m.ok ? 1 : 0);
  w.varint(m.crowdIndex);
  w.string(clampString(m.crowdId, kMaxNameLength));
  w.string(clampString(m.text, kMaxTextLength));
  return out;
}

Bytes encode(const Fragment& m) {
  Bytes out = start(MessageType::Fragment);
  ByteWriter w(out);
  w.varint(m.messageId);
  w.varint(m.index);
  w.varint(m.count);
  w.bytes(m.payload);
  return out;
}

Bytes encode(const Cookie& m) {
  Bytes out = start(MessageType::Cookie);
  ByteWriter(out).bytes(m.cookie);
  return out;
}

Bytes encode(const UdpHello& m) {
  Bytes out = start(MessageType::UdpHello);
  ByteWriter w(out);
  w.bytes(m.cookie);
  w.bytes(encode(m.hello));
  return out;
}

Bytes encode(const Message& m) {
  return std::visit([](const auto& v) { return encode(v); }, m);
}

MessageType messageType(const Message& m) {
  return static_cast<MessageType>(m.index() + 1);  // the variant lists the types in enum order
}

const char* messageTypeName(MessageType type) {
  static constexpr const char* kNames[] = {"?", "Hello", "Refuse", "Welcome", "Join", "Joined", "Leave",
                                           "Heartbeat", "Bye", "Move", "Joints", "HandJoints",
                                           "FaceExpression", "Guide", "Release", "GuideResult", "Ack",
                                           "CrowdFrame", "Presence", "ReplayControl", "ReplayStatus",
                                           "InsertCrowd", "RemoveCrowd", "CrowdResult", "Fragment",
                                           "Cookie", "UdpHello"};
  const auto i = static_cast<std::uint8_t>(type);
  return i <= kMaxMessageType ? kNames[i] : "?";
}

Direction messageDirection(MessageType type) {
  switch (type) {
    case MessageType::Hello:
    case MessageType::Join:
    case MessageType::Leave:
    case MessageType::Guide:
    case MessageType::Release:
    case MessageType::Ack:
    case MessageType::ReplayControl:
    case MessageType::InsertCrowd:
    case MessageType::RemoveCrowd:
    case MessageType::UdpHello: return Direction::ClientToServer;
    case MessageType::Heartbeat:
    case MessageType::Bye:
    case MessageType::Move:
    case MessageType::Joints:
    case MessageType::HandJoints:
    case MessageType::FaceExpression: return Direction::Both;
    case MessageType::Refuse:
    case MessageType::Welcome:
    case MessageType::Joined:
    case MessageType::GuideResult:
    case MessageType::CrowdFrame:
    case MessageType::Presence:
    case MessageType::ReplayStatus:
    case MessageType::CrowdResult:
    case MessageType::Fragment:
    case MessageType::Cookie: return Direction::ServerToClient;
  }
  return Direction::ServerToClient;
}

std::size_t maxClientMessageSize(MessageType type) {
  if (messageDirection(type) == Direction::ServerToClient) return 0;
  // InsertCrowd: header 2, token 8, requestId ≤ 5, string length ≤ 3, then the crowd file.
  if (type == MessageType::InsertCrowd) return kMaxCrowdJson + 32;
  return kMaxClientMessageSize;
}

core::Result<MessageType> peekType(std::span<const std::uint8_t> bytes) {
  ByteReader r(bytes, "message");
  if (bytes.size() > kMaxMessageSize) {
    r.fail("size", 0, "message of " + std::to_string(bytes.size()) + " bytes too large",
           "at most " + std::to_string(kMaxMessageSize) + " bytes");
    return r.error();
  }
  const std::uint8_t magic = r.u8("magic");
  if (r.ok() && magic != kMagic) r.fail("magic", 0, "bad magic byte " + std::to_string(magic), "0x54 ('T')");
  const std::uint8_t type = r.u8("type");
  if (r.ok() && (type == 0 || type > kMaxMessageType)) {
    r.fail("type", 1, "unknown message type " + std::to_string(type), "1.." + std::to_string(kMaxMessageType));
  }
  if (!r.ok()) return r.error();
  return static_cast<MessageType>(type);
}

namespace {

/// A u8 that must be 0 or 1.
bool readFlag(ByteReader& r, const char* field, const char* expected) {
  const std::size_t at = r.offset();
  const std::uint8_t v = r.u8(field);
  if (v > 1) r.fail(field, at, "value " + std::to_string(v), expected);
  return v == 1;
}

/// An f64 time [s] that must be finite and ≥ 0.
double readSeconds(ByteReader& r, const char* field) {
  const std::size_t at = r.offset();
  const double v = r.f64(field);
  if (r.ok() && !(std::isfinite(v) && v >= 0.0)) {
    r.fail(field, at, std::string(field) + " " + std::to_string(v) + " s", "a finite time >= 0 s");
  }
  return v;
}

/// ReplayControl::value, checked against its command.
void readReplayValue(ByteReader& r, ReplayControl& m) {
  const std::size_t at = r.offset();
  m.value = r.f64("value");
  if (!r.ok()) return;
  const std::string got = "value " + std::to_string(m.value);
  switch (m.command) {
    case ReplayCommand::Play:
    case ReplayCommand::Pause:
      if (m.value != 0.0) r.fail("value", at, got + " for play/pause", "0");
      break;
    case ReplayCommand::Seek:
      if (!(std::isfinite(m.value) && m.value >= 0.0)) r.fail("value", at, got + " for seek", "a finite time >= 0 s");
      break;
    case ReplayCommand::Speed:
      if (!(std::isfinite(m.value) && m.value > 0.0 && m.value <= kMaxReplaySpeed)) {
        r.fail("value", at, got + " for speed", "a finite factor in (0, 64]");
      }
      break;
  }
}

Message decodeBody(MessageType type, ByteReader& r) {
  switch (type) {
    case MessageType::Hello: {
      Hello m;
      m.protocolVersion = r.u16("protocolVersion");
      const std::size_t at = r.offset();
      const std::uint8_t kind = r.u8("clientKind");
      if (kind > 2) r.fail("clientKind", at, "unknown client kind " + std::to_string(kind), "0 (browser), 1 (native) or 2 (loadgen)");
      m.clientKind = static_cast<ClientKind>(kind);
      m.clientName = r.string("clientName", kMaxNameLength);
      return m;
    }
    case MessageType::Refuse: {
      Refuse m;
      m.protocolVersion = r.u16("protocolVersion");
      m.reason = readReason(r);
      m.text = r.string("text", kMaxTextLength);
      return m;
    }
    case MessageType::Welcome: {
      Welcome m;
      m.protocolVersion = r.u16("protocolVersion");
      m.serverName = r.string("serverName", kMaxNameLength);
      std::size_t at = r.offset();
      m.tickRateHz = r.f32("tickRateHz");
      if (r.ok() && !(std::isfinite(m.tickRateHz) && m.tickRateHz > 0.0f)) {
        r.fail("tickRateHz", at, "tick rate " + std::to_string(m.tickRateHz), "a finite rate > 0 Hz");
      }
      at = r.offset();
      const std::uint8_t enc = r.u8("worldEncoding");
      if (enc > 1) r.fail("worldEncoding", at, "unknown world encoding " + std::to_string(enc), "0 (JSON) or 1 (zstd JSON)");
      m.worldEncoding = static_cast<WorldEncoding>(enc);
      m.worldSize = static_cast<std::uint32_t>(r.varint("worldSize", kMaxWorldSize));
      at = r.offset();
      const std::uint64_t n = r.varint("worldLength", kMaxMessageSize);
      if (r.ok() && m.worldEncoding == WorldEncoding::Json && n != m.worldSize) {
        r.fail("worldLength", at, "raw JSON world of " + std::to_string(n) + " bytes",
               "worldSize (" + std::to_string(m.worldSize) + ") bytes");
      }
      const auto b = r.bytes("world", static_cast<std::size_t>(n));
      m.world.assign(b.begin(), b.end());
      return m;
    }
    case MessageType::Join: {
      Join m;
      m.name = r.string("name", kMaxNameLength);
      m.avatar = r.u16("avatar");
      return m;
    }
    case MessageType::Joined: {
      Joined m;
      m.participantId = r.u32("participantId");
      m.token = r.u64("token");
      return m;
    }
    case MessageType::Leave: return Leave{r.u64("token")};
    case MessageType::Heartbeat: {
      Heartbeat m;
      m.token = r.u64("token");
      m.timeUs = r.u64("timeUs");
      m.echoUs = r.u64("echoUs");
      return m;
    }
    case MessageType::Bye: {
      Bye m;
      m.reason = readReason(r);
      m.text = r.string("text", kMaxTextLength);
      return m;
    }
    case MessageType::Move: {
      Move m;
      m.subject = readSubject(r);
      m.seq = static_cast<std::uint32_t>(r.varint("seq", 0xffffffffu));
      m.x = dequantizePosition(r.i32("x"));
      m.y = dequantizePosition(r.i32("y"));
      m.z = dequantizePosition(r.i32("z"));
      m.yaw = dequantizeAngle16(r.u16("yaw"));
      return m;
    }
    case MessageType::Joints: return readJointAngles<Joints>(r);
    case MessageType::HandJoints: return readJointAngles<HandJoints>(r);
    case MessageType::FaceExpression: {
      FaceExpression m;
      m.subject = readSubject(r);
      m.seq = static_cast<std::uint32_t>(r.varint("seq", 0xffffffffu));
      m.expression = r.u16("expression");
      const std::size_t at = r.offset();
      const std::uint8_t n = r.u8("weightCount");
      if (n > kMaxExpressionWeights) {
        r.fail("weightCount", at, std::to_string(n) + " weights", "at most " + std::to_string(kMaxExpressionWeights));
      }
      const auto b = r.bytes("weights", r.ok() ? n : 0);
      for (const std::uint8_t v : b) m.weights.push_back(static_cast<float>(v) / 255.0f);
      return m;
    }
    case MessageType::Guide: {
      Guide m;
      m.token = r.u64("token");
      m.groupId = static_cast<std::uint32_t>(r.varint("groupId", 0xffffffffu));
      return m;
    }
    case MessageType::Release: {
      Release m;
      m.token = r.u64("token");
      m.groupId = static_cast<std::uint32_t>(r.varint("groupId", 0xffffffffu));
      return m;
    }
    case MessageType::GuideResult: {
      GuideResult m;
      m.groupId = static_cast<std::uint32_t>(r.varint("groupId", 0xffffffffu));
      const std::size_t at = r.offset();
      const std::uint8_t flags = r.u8("flags");
      if (flags > 3) r.fail("flags", at, "unknown flag bits " + std::to_string(flags), "bit 0 (ok) and bit 1 (guiding) only");
      m.ok = (flags & 1) != 0;
      m.guiding = (flags & 2) != 0;
      m.reason = readReason(r);
      return m;
    }
    case MessageType::Ack: {
      Ack m;
      m.token = r.u64("token");
      m.frameNumber = static_cast<std::uint32_t>(r.varint("frameNumber", 0xffffffffu));
      return m;
    }
    case MessageType::CrowdFrame: return detail::decodeCrowdFrame(r);
    case MessageType::Presence: {
      Presence m;
      m.participantId = static_cast<std::uint32_t>(r.varint("participantId", 0xffffffffu));
      m.present = readFlag(r, "present", "1 (present) or 0 (left)");
      m.name = r.string("name", kMaxNameLength);
      if (r.ok() && r.remaining() > 0) m.avatar = r.u16("avatar");  // version 2: optional trailing look
      return m;
    }
    case MessageType::ReplayControl: {
      ReplayControl m;
      m.token = r.u64("token");
      const std::size_t at = r.offset();
      const std::uint8_t command = r.u8("command");
      if (command > kMaxReplayCommand) {
        r.fail("command", at, "unknown replay command " + std::to_string(command),
               "0 (play), 1 (pause), 2 (seek) or 3 (speed)");
      }
      m.command = static_cast<ReplayCommand>(command);
      readReplayValue(r, m);
      return m;
    }
    case MessageType::ReplayStatus: {
      ReplayStatus m;
      m.time = readSeconds(r, "time");
      m.duration = readSeconds(r, "duration");
      m.playing = readFlag(r, "playing", "1 (playing) or 0 (paused)");
      const std::size_t at = r.offset();
      m.speed = r.f32("speed");
      if (r.ok() && !(std::isfinite(m.speed) && m.speed > 0.0f)) {
        r.fail("speed", at, "speed " + std::to_string(m.speed), "a finite factor > 0");
      }
      return m;
    }
    case MessageType::InsertCrowd: {
      InsertCrowd m;
      m.token = r.u64("token");
      m.requestId = static_cast<std::uint32_t>(r.varint("requestId", 0xffffffffu));
      m.crowdJson = r.string("crowdJson", kMaxCrowdJson);
      return m;
    }
    case MessageType::RemoveCrowd: {
      RemoveCrowd m;
      m.token = r.u64("token");
      m.requestId = static_cast<std::uint32_t>(r.varint("requestId", 0xffffffffu));
      m.crowdId = r.string("crowdId", kMaxNameLength);
      return m;
    }
    case MessageType::CrowdResult: {
      CrowdResult m;
      m.requestId = static_cast<std::uint32_t>(r.varint("requestId", 0xffffffffu));
      m.ok = readFlag(r, "ok", "1 (carried out) or 0 (refused)");
      m.crowdIndex = static_cast<std::uint32_t>(r.varint("crowdIndex", 0xffffffffu));
      m.crowdId = r.string("crowdId", kMaxNameLength);
      m.text = r.string("text", kMaxTextLength);
      return m;
    }
    case MessageType::Fragment: {
      Fragment m;
      m.messageId = r.varint("messageId");
      const std::size_t indexAt = r.offset();
      m.index = static_cast<std::uint32_t>(r.varint("index", 0xffffffffu));
      std::size_t at = r.offset();
      m.count = static_cast<std::uint32_t>(r.varint("count", 0xffffffffu));
      if (r.ok() && (m.count < kMinFragments || m.count > kMaxFragments)) {
        r.fail("count", at, "count " + std::to_string(m.count),
               std::to_string(kMinFragments) + ".." + std::to_string(kMaxFragments) + " fragments");
      } else if (r.ok() && m.index >= m.count) {
        r.fail("index", indexAt, "index " + std::to_string(m.index) + " of " + std::to_string(m.count) + " fragments",
               "an index below count (" + std::to_string(m.count) + ")");
      }
      at = r.offset();
      if (r.ok() && r.remaining() == 0) r.fail("payload", at, "an empty payload", "at least 1 payload byte");
      const auto b = r.bytes("payload", r.ok() ? r.remaining() : 0);
      m.payload.assign(b.begin(), b.end());
      return m;
    }
    case MessageType::Cookie: {
      Cookie m;
      const auto b = r.bytes("cookie", kCookieSize);
      if (r.ok()) std::copy(b.begin(), b.end(), m.cookie.begin());
      return m;
    }
    case MessageType::UdpHello: {
      UdpHello m;
      const auto b = r.bytes("cookie", kCookieSize);
      if (r.ok()) std::copy(b.begin(), b.end(), m.cookie.begin());
      // Then a whole Hello message, magic and type included.
      std::size_t at = r.offset();
      const std::uint8_t magic = r.u8("hello");
      if (r.ok() && magic != kMagic) r.fail("hello", at, "bad magic byte " + std::to_string(magic) + " of the Hello", "0x54 ('T')");
      at = r.offset();
      const std::uint8_t type = r.u8("hello");
      if (r.ok() && type != static_cast<std::uint8_t>(MessageType::Hello)) {
        r.fail("hello", at, "a message of type " + std::to_string(type) + " after the cookie", "a Hello (type 1)");
      }
      if (!r.ok()) return m;
      m.hello = std::get<Hello>(decodeBody(MessageType::Hello, r));
      return m;
    }
  }
  return Hello{};  // unreachable: peekType checked the type
}

}  // namespace

core::Result<Message> decodeAny(std::span<const std::uint8_t> bytes) {
  auto type = peekType(bytes);
  if (!type) return std::move(type).takeErrors();
  ByteReader r(bytes, messageTypeName(type.value()));
  r.bytes("header", 2);
  Message m = decodeBody(type.value(), r);
  r.expectEnd();
  if (!r.ok()) return r.error();
  return m;
}

core::Result<Message> decodeFromClient(std::span<const std::uint8_t> bytes) {
  auto type = peekType(bytes);
  if (!type) return std::move(type).takeErrors();
  ByteReader r(bytes, "message");
  const char* name = messageTypeName(type.value());
  if (messageDirection(type.value()) == Direction::ServerToClient) {
    r.fail("type", 1,
           std::string(name) + " (type " + std::to_string(static_cast<int>(type.value())) +
               ") is a server → client message; not decoded",
           "a client → server message type");
    return r.error();
  }
  if (const std::size_t max = maxClientMessageSize(type.value()); bytes.size() > max) {
    r.fail("size", 0, std::string(name) + " of " + std::to_string(bytes.size()) + " bytes",
           "at most " + std::to_string(max) + " bytes for a " + name);
    return r.error();
  }
  return decodeAny(bytes);
}

Welcome makeWelcome(std::string serverName, float tickRateHz, const std::string& worldJson) {
  Welcome w;
  w.serverName = std::move(serverName);
  w.tickRateHz = tickRateHz;
  w.worldEncoding = WorldEncoding::ZstdJson;
  w.worldSize = static_cast<std::uint32_t>(worldJson.size());
  w.world = detail::zstdCompress(
      std::span(reinterpret_cast<const std::uint8_t*>(worldJson.data()), worldJson.size()), 19);
  return w;
}

core::Result<std::string> worldJson(const Welcome& welcome) {
  core::Diagnostic d;
  d.pointer = "/Welcome/world";
  if (welcome.worldEncoding == WorldEncoding::Json) return std::string(welcome.world.begin(), welcome.world.end());
  if (welcome.worldSize > kMaxWorldSize) {
    d.what = "world of " + std::to_string(welcome.worldSize) + " bytes too large";
    d.expected = "at most " + std::to_string(kMaxWorldSize) + " bytes";
    return d;
  }
  std::string why;
  auto raw = detail::zstdDecompress(welcome.world, welcome.worldSize, why);
  if (!raw) {
    d.what = why;
    d.expected = "a zstd frame of worldSize bytes";
    return d;
  }
  return std::string(raw->begin(), raw->end());
}

}  // namespace throng::protocol
