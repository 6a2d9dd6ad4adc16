// Shared by the protocol tests: the fixed sample of every message (the golden set's inputs) and
// the JSON form of a decoded message — wire units (cm, 1/65536 turn, 1/256 phase, int16 joint
// angles), 64-bit values as decimal strings — which web/protocol/decode.js produces too.
#pragma once
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "throng/protocol/crowd_decoder.hpp"
#include "throng/protocol/crowd_encoder.hpp"
#include "throng/protocol/messages.hpp"

namespace throng::protocol::test {

inline nlohmann::json subjectJson(const Subject& s) {
  return {{"kind", static_cast<int>(s.kind)}, {"value", std::to_string(s.value)}};
}

inline nlohmann::json anglesJson(const std::vector<float>& angles) {
  nlohmann::json a = nlohmann::json::array();
  for (const float v : angles) a.push_back(static_cast<std::int16_t>(quantizeAngle16(v)));
  return a;
}

inline nlohmann::json agentJson(const AgentState& a) {
  return {{"id", a.id},
          {"tier", static_cast<int>(a.tier)},
          {"x", quantizePosition(a.x)},
          {"y", quantizePosition(a.y)},
          {"z", quantizePosition(a.z)},
          {"yaw", quantizeAngle16(a.yaw)},
          {"clip", a.clip},
          {"phase", quantizePhase(a.phase)},
          {"joints", anglesJson(a.joints)}};
}

inline nlohmann::json headerJson(const CrowdFrameHeader& h) {
  return {{"compressed", h.compressed},   {"farIncluded", h.farIncluded},
          {"frameNumber", h.frameNumber}, {"baseFrame", h.baseFrame},
          {"simTick", std::to_string(h.simTick)}, {"animationInterval", h.animationInterval},
          {"jointCount", h.jointCount},   {"jointShift", h.jointShift},
          {"nearCount", h.nearCount},     {"middleCount", h.middleCount},
          {"farCount", h.farCount},       {"payloadSize", h.payloadSize}};
}

inline nlohmann::json crowdJson(const DecodedCrowdFrame& f) {
  nlohmann::json agents = nlohmann::json::array();
  for (const AgentState& a : f.view.agents) agents.push_back(agentJson(a));
  return {{"type", "CrowdFrame"}, {"header", headerJson(f.header)}, {"agents", agents}};
}

/// Lower-case hex of a cookie, as decode.js writes it.
inline std::string hex(const CookieBytes& b) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out;
  for (const std::uint8_t v : b) {
    out += kDigits[v >> 4];
    out += kDigits[v & 15];
  }
  return out;
}

/// JSON of a decoded non-crowd message.
inline nlohmann::json messageJson(const Message& m) {
  using nlohmann::json;
  json j = {{"type", messageTypeName(messageType(m))}};
  std::visit(
      [&](const auto& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, Hello>) {
          j["protocolVersion"] = v.protocolVersion;
          j["clientKind"] = static_cast<int>(v.clientKind);
          j["clientName"] = v.clientName;
        } else if constexpr (std::is_same_v<T, Refuse>) {
          j["protocolVersion"] = v.protocolVersion;
          j["reason"] = static_cast<int>(v.reason);
          j["text"] = v.text;
        } else if constexpr (std::is_same_v<T, Welcome>) {
          j["protocolVersion"] = v.protocolVersion;
          j["serverName"] = v.serverName;
          j["tickRateHz"] = v.tickRateHz;
          j["worldEncoding"] = static_cast<int>(v.worldEncoding);
          j["worldSize"] = v.worldSize;
          auto text = worldJson(v);
          j["world"] = text ? text.value() : std::string("<corrupt>");
        } else if constexpr (std::is_same_v<T, Join>) {
          j["name"] = v.name;
          j["avatar"] = v.avatar;
        } else if constexpr (std::is_same_v<T, Joined>) {
          j["participantId"] = v.participantId;
          j["token"] = std::to_string(v.token);
        } else if constexpr (std::is_same_v<T, Leave>) {
          j["token"] = std::to_string(v.token);
        } else if constexpr (std::is_same_v<T, Heartbeat>) {
          j["token"] = std::to_string(v.token);
          j["timeUs"] = std::to_string(v.timeUs);
          j["echoUs"] = std::to_string(v.echoUs);
        } else if constexpr (std::is_same_v<T, Bye>) {
          j["reason"] = static_cast<int>(v.reason);
          j["text"] = v.text;
        } else if constexpr (std::is_same_v<T, Move>) {
          j["subject"] = subjectJson(v.subject);
          j["seq"] = v.seq;
          j["x"] = quantizePosition(v.x);
          j["y"] = quantizePosition(v.y);
          j["z"] = quantizePosition(v.z);
          j["yaw"] = quantizeAngle16(v.yaw);
        } else if constexpr (std::is_same_v<T, Joints> || std::is_same_v<T, HandJoints>) {
          j["subject"] = subjectJson(v.subject);
          j["seq"] = v.seq;
          j["angles"] = anglesJson(v.angles);
        } else if constexpr (std::is_same_v<T, FaceExpression>) {
          j["subject"] = subjectJson(v.subject);
          j["seq"] = v.seq;
          j["expression"] = v.expression;
          json w = json::array();
          for (const float x : v.weights) w.push_back(static_cast<int>(x * 255.0f + 0.5f));
          j["weights"] = w;
        } else if constexpr (std::is_same_v<T, Guide> || std::is_same_v<T, Release>) {
          j["token"] = std::to_string(v.token);
          j["groupId"] = v.groupId;
        } else if constexpr (std::is_same_v<T, GuideResult>) {
          j["groupId"] = v.groupId;
          j["ok"] = v.ok;
          j["guiding"] = v.guiding;
          j["reason"] = static_cast<int>(v.reason);
        } else if constexpr (std::is_same_v<T, Ack>) {
          j["token"] = std::to_string(v.token);
          j["frameNumber"] = v.frameNumber;
        } else if constexpr (std::is_same_v<T, CrowdFrame>) {
          j["header"] = headerJson(v.header);
        } else if constexpr (std::is_same_v<T, Presence>) {
          j["participantId"] = v.participantId;
          j["present"] = v.present;
          j["name"] = v.name;
          if (v.avatar) j["avatar"] = *v.avatar;
        } else if constexpr (std::is_same_v<T, ReplayControl>) {
          j["token"] = std::to_string(v.token);
          j["command"] = static_cast<int>(v.command);
          j["value"] = v.value;
        } else if constexpr (std::is_same_v<T, ReplayStatus>) {
          j["time"] = v.time;
          j["duration"] = v.duration;
          j["playing"] = v.playing;
          j["speed"] = v.speed;
        } else if constexpr (std::is_same_v<T, InsertCrowd>) {
          j["token"] = std::to_string(v.token);
          j["requestId"] = v.requestId;
          j["crowdJson"] = v.crowdJson;
        } else if constexpr (std::is_same_v<T, RemoveCrowd>) {
          j["token"] = std::to_string(v.token);
          j["requestId"] = v.requestId;
          j["crowdId"] = v.crowdId;
        } else if constexpr (std::is_same_v<T, CrowdResult>) {
          j["requestId"] = v.requestId;
          j["ok"] = v.ok;
          j["crowdIndex"] = v.crowdIndex;
          j["crowdId"] = v.crowdId;
          j["text"] = v.text;
        } else if constexpr (std::is_same_v<T, Fragment>) {
          j["messageId"] = std::to_string(v.messageId);
          j["index"] = v.index;
          j["count"] = v.count;
          json bytes = json::array();
          for (const std::uint8_t b : v.payload) bytes.push_back(b);
          j["payload"] = bytes;
        } else if constexpr (std::is_same_v<T, Cookie>) {
          j["cookie"] = hex(v.cookie);
        } else if constexpr (std::is_same_v<T, UdpHello>) {
          j["cookie"] = hex(v.cookie);
          j["hello"] = {{"protocolVersion", v.hello.protocolVersion},
                        {"clientKind", static_cast<int>(v.hello.clientKind)},
                        {"clientName", v.hello.clientName}};
        }
      },
      m);
  return j;
}

/// The crowd views of the golden crowd frames: 2 near (sharing one pose), 2 middle, 2 far; then
/// one near agent walks and turns, a middle one leaves, a new one arrives, a far one comes middle.
inline CrowdView goldenCrowd(int step) {
  CrowdView v;
  v.simTick = 1000 + step;
  v.jointCount = 2;
  v.animationInterval = 1;
  const std::vector<float> pose = {0.1f, -0.2f, 0.3f, 1.0f, -1.5f, 3.0f};
  v.agents = {
      {3, Tier::Near, 1.25f, -2.5f, 0.0f, 0.5f, 1, 0.25f, pose},
      {5, Tier::Near, 2.0f, -2.0f, 0.0f, 1.0f, 1, 0.25f, pose},
      {8, Tier::Middle, 10.0f, 4.0f, 0.0f, -1.0f, 0, 0.5f, {}},
      {9, Tier::Middle, 11.0f, 4.5f, 0.0f, 3.0f, 2, 0.75f, {}},
      {20, Tier::Far, 40.0f, 30.0f, 1.5f, 0.0f, 0, 0.0f, {}},
      {300, Tier::Far, -50.0f, 60.0f, 0.0f, 0.0f, 0, 0.0f, {}},
  };
  if (step == 1) {
    v.agents[0].x += 0.07f;
    v.agents[0].yaw += 0.1f;
    v.agents[0].phase = 0.3f;
    v.agents[0].joints = {0.12f, -0.2f, 0.3f, 1.1f, -1.5f, 3.0f};
    v.agents.erase(v.agents.begin() + 2);  // agent 8 leaves
    v.agents.push_back({12, Tier::Middle, 9.0f, 9.0f, 0.0f, 0.25f, 3, 0.1f, {}});
    v.agents[3].tier = Tier::Middle;  // agent 20 comes closer
    v.agents[3].yaw = 2.0f;
    v.agents[3].clip = 1;
  }
  return v;
}

/// Encodes the golden crowd key frame and the delta frame after it; raw or compressed payloads.
inline std::pair<std::vector<std::uint8_t>, std::vector<std::uint8_t>> goldenCrowdFrames(bool compressed) {
  CrowdEncoderOptions o;
  o.farInterval = 2;
  o.jointShift = 4;
  o.compressMinBytes = 1u << 30;
  CrowdEncoder enc(o);
  auto key = enc.encode(goldenCrowd(0), 0).value().bytes;
  auto delta = enc.encode(goldenCrowd(1), 1).value().bytes;
  if (compressed) {  // too small for the encoder to gain: force zstd to have a compressed sample
    for (auto* bytes : {&key, &delta}) {
      CrowdFrame f = std::get<CrowdFrame>(decodeAny(*bytes).value());
      f.header.compressed = true;
      *bytes = encode(f);
    }
  }
  return {key, delta};
}

/// Every golden message but the crowd frames, by file name.
inline std::vector<std::pair<std::string, Message>> goldenMessages() {
  std::vector<std::pair<std::string, Message>> m;
  m.emplace_back("hello", Hello{kProtocolVersion, ClientKind::Browser, "viewer-firefox"});
  m.emplace_back("refuse", Refuse{kProtocolVersion, ReasonCode::VersionMismatch, "protocol 3 requested; this server speaks 2"});
  m.emplace_back("welcome", makeWelcome("throng-museum", 20.0f, R"({"name":"museum","clips":[{"name":"walk","duration":1.05}]})"));
  Welcome raw;
  raw.serverName = "raw";
  raw.tickRateHz = 10.0f;
  raw.worldEncoding = WorldEncoding::Json;
  const std::string world = R"({"points":[]})";
  raw.worldSize = static_cast<std::uint32_t>(world.size());
  raw.world.assign(world.begin(), world.end());
  m.emplace_back("welcome_raw", raw);
  m.emplace_back("join", Join{"Ada", 2});
  m.emplace_back("joined", Joined{7, 0x0123456789abcdefULL});
  m.emplace_back("leave", Leave{0x0123456789abcdefULL});
  m.emplace_back("heartbeat", Heartbeat{0x0123456789abcdefULL, 1700000000123456ULL, 1700000000000001ULL});
  m.emplace_back("bye", Bye{ReasonCode::ShuttingDown, "server shutting down"});
  m.emplace_back("move", Move{{Subject::Kind::Token, 0xfedcba9876543210ULL}, 42, 12.34f, -5.67f, 0.5f, 1.5f});
  Joints joints;
  joints.subject = {Subject::Kind::Participant, 7};
  joints.seq = 300;
  joints.angles = {0.0f, 0.5f, -0.5f, 3.0f, -3.0f, 1.0f};
  m.emplace_back("joints", joints);
  HandJoints hand;
  hand.subject = {Subject::Kind::Token, 99};
  hand.seq = 1;
  hand.angles = {0.25f, 0.0f, -0.25f};
  m.emplace_back("hand_joints", hand);
  m.emplace_back("face_expression", FaceExpression{{Subject::Kind::Participant, 7}, 5, 3, {0.0f, 0.5f, 1.0f}});
  m.emplace_back("guide", Guide{0x0123456789abcdefULL, 4});
  m.emplace_back("release", Release{0x0123456789abcdefULL, 4});
  m.emplace_back("guide_result", GuideResult{4, true, false, ReasonCode::GroupTaken});
  m.emplace_back("ack", Ack{0x0123456789abcdefULL, 129});
  m.emplace_back("presence", Presence{300, true, "Ada", std::nullopt});  // version 1: no avatar (what version-1 clients get)
  m.emplace_back("presence_look", Presence{301, true, "Bo", 3});
  m.emplace_back("replay_control", ReplayControl{0x0123456789abcdefULL, ReplayCommand::Seek, 12.5});
  m.emplace_back("replay_status", ReplayStatus{12.5, 120.25, true, 2.0f});
  m.emplace_back("insert_crowd",
                 InsertCrowd{0x0123456789abcdefULL, 300,
                             R"({"format":"throng-crowd/1","id":"tour","populations":[{"id":"p","count":3}]})"});
  m.emplace_back("remove_crowd", RemoveCrowd{0x0123456789abcdefULL, 301, "tour"});
  m.emplace_back("crowd_result", CrowdResult{300, true, 2, "tour", "crowd 'tour' inserted as 2: 3 agents at most"});
  m.emplace_back("crowd_result_refused",
                 CrowdResult{7, false, 0, "",
                             "participant 1 request 7:1:12: /populations/0/count: -3; expected an integer >= 1\n"
                             "(and 2 more)"});
  // The middle piece of message 300 (a 2-byte varint id): 3 fragments in all.
  m.emplace_back("fragment", Fragment{300, 1, 3, {0x12, 0x2c, 0x01, 0x03, 0x41, 0x64, 0x61, 0xff}});
  // The UDP handshake: a first UdpHello without a cookie, the server's Cookie, the UdpHello again.
  const CookieBytes cookie{0x3c, 0x91, 0x0e, 0x5a, 0xd2, 0x47, 0x18, 0xb6, 0x7f, 0x01, 0xe3, 0x88, 0x2d, 0x64, 0xa9, 0xc5};
  m.emplace_back("udp_hello_first", UdpHello{CookieBytes{}, Hello{kProtocolVersion, ClientKind::Native, "Ada"}});
  m.emplace_back("cookie", Cookie{cookie});
  m.emplace_back("udp_hello", UdpHello{cookie, Hello{kProtocolVersion, ClientKind::Loadgen, "loadgen-0"}});
  return m;
}

}  // namespace throng::protocol::test
