// throng::protocol crowd frame — the aggregated per-client-per-tick crowd message: what the server
// sends (CrowdView: every agent in the client's area of interest with its detail tier), the
// quantization applied on the wire, and the message itself (CrowdFrame: header + payload) as
// decodeAny returns it. The payload is delta-coded against an acknowledged frame: CrowdEncoder
// (server side, one per client) writes it, CrowdDecoder (client side) applies it.
#pragma once
#include <cstdint>
#include <vector>

#include "throng/protocol/protocol.hpp"

namespace throng::protocol {

/// One agent as the client should show it. Input of the encoder (server, from the simulation)
/// and output of the decoder (the same values, quantized).
struct AgentState {
  std::uint32_t id = 0;       ///< stable spawn-order id of the agent
  Tier tier = Tier::Middle;
  float x = 0, y = 0, z = 0;  ///< position relative to the world origin [m]; 1 cm steps, |v| < 2^31 cm
  float yaw = 0;              ///< heading [rad]; 1/65536 turn (near), 1/256 turn (middle), 0 (far)
  std::uint16_t clip = 0;     ///< motion clip index (world description); 0 for far
  float phase = 0;            ///< position in the clip [0, 1); 1/256 steps; 0 for far
  std::vector<float> joints;  ///< near only: 3 × jointCount angles [rad]; empty for middle and far
  bool operator==(const AgentState&) const = default;
};

/// The crowd one client sees at one tick.
struct CrowdView {
  std::uint64_t simTick = 0;
  std::uint8_t animationInterval = 1;  ///< X ≥ 1: clip, phase and joints are refreshed every X frames
  std::uint8_t jointCount = 0;         ///< joints per near pose, ≤ kMaxJoints
  std::vector<AgentState> agents;      ///< any order in; ascending id out; ≤ kMaxAgents
  bool operator==(const CrowdView&) const = default;
};

/// Wire header of a crowd frame (uncompressed, readable without the base frame).
struct CrowdFrameHeader {
  bool compressed = false;            ///< payload is one zstd frame
  bool farIncluded = true;            ///< far agents were updated in this frame (informative)
  std::uint32_t frameNumber = 0;      ///< ≥ 1, grows by one per frame sent to this client
  std::uint32_t baseFrame = 0;        ///< 0: key frame; otherwise the acked frame this is delta-coded against
  std::uint64_t simTick = 0;
  std::uint8_t animationInterval = 1; ///< X in effect (≥ 1)
  std::uint8_t jointCount = 0;        ///< joints per near pose (≤ kMaxJoints)
  std::uint8_t jointShift = 0;        ///< joint angles travel as int16 >> jointShift (≤ 8)
  std::uint32_t nearCount = 0;        ///< agents per tier in the reconstructed view (checked)
  std::uint32_t middleCount = 0;
  std::uint32_t farCount = 0;
  std::uint32_t payloadSize = 0;      ///< uncompressed payload size [bytes] ≤ kMaxCrowdPayload
  bool operator==(const CrowdFrameHeader&) const = default;
};

/// A crowd frame message: decodeAny returns it with `payload` decompressed; encode(CrowdFrame)
/// compresses it when header.compressed. Only CrowdDecoder gives it meaning.
struct CrowdFrame {
  CrowdFrameHeader header;
  std::vector<std::uint8_t> payload;  ///< uncompressed payload (docs/protocol.md "Crowd payload")
};

// Quantization (exact inverses on quantized values: dequantize(quantize(q)) == q).
[[nodiscard]] std::int32_t quantizePosition(float meters);  ///< 1 cm, saturating to int32
[[nodiscard]] float dequantizePosition(std::int32_t centimeters);
[[nodiscard]] std::uint16_t quantizeAngle16(float radians);  ///< 1/65536 turn, wraps
[[nodiscard]] float dequantizeAngle16(std::uint16_t turns);  ///< [-π, π)
[[nodiscard]] std::uint8_t quantizePhase(float phase);      ///< 1/256, wraps into [0, 1)
[[nodiscard]] float dequantizePhase(std::uint8_t phase);

/// The agent as a client decodes it from a frame with all fields fresh: tier rules applied
/// (middle: yaw to 1/256 turn, no joints; far: position only), every value quantized.
/// `jointCount` pads or cuts near joints to 3 × jointCount; `jointShift` as in the header.
[[nodiscard]] AgentState quantized(const AgentState& agent, std::uint8_t jointCount, std::uint8_t jointShift);

/// The same for a whole view (agents sorted by id).
[[nodiscard]] CrowdView quantized(const CrowdView& view, std::uint8_t jointShift);

}  // namespace throng::protocol
