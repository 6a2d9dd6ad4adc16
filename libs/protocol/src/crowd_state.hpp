// throng::protocol crowd state (private) — an agent as it travels (QAgent: integers in wire
// units), the tier rules both ends apply before a record's deltas, and the change-mask bits.
// CrowdEncoder and CrowdDecoder share these so their reconstructions cannot drift apart.
#pragma once
#include <cstdint>
#include <vector>

#include "throng/protocol/crowd_frame.hpp"

namespace throng::protocol::detail {

// Per-record change mask (one byte per record, payload "masks" column).
inline constexpr std::uint8_t kMaskX = 1;
inline constexpr std::uint8_t kMaskY = 2;
inline constexpr std::uint8_t kMaskZ = 4;
inline constexpr std::uint8_t kMaskYaw = 8;
inline constexpr std::uint8_t kMaskClip = 16;
inline constexpr std::uint8_t kMaskPhase = 32;
inline constexpr std::uint8_t kMaskPose = 64;
inline constexpr std::uint8_t kMaskTier = 128;

struct QAgent {
  std::uint32_t id = 0;
  Tier tier = Tier::Near;  ///< the zero state (base of a new agent) is Near with every field 0
  std::int32_t x = 0, y = 0, z = 0;  ///< [cm]
  std::uint16_t yaw = 0;             ///< [1/65536 turn]; a multiple of 256 for middle, 0 for far
  std::uint16_t clip = 0;
  std::uint8_t phase = 0;            ///< [1/256]
  std::vector<std::uint16_t> joints; ///< near: 3 × jointCount, multiples of 2^jointShift
  bool operator==(const QAgent&) const = default;
};

using QView = std::vector<QAgent>;  ///< ascending id

[[nodiscard]] QAgent quantizeAgent(const AgentState& a, std::uint8_t jointCount, std::uint8_t jointShift);
[[nodiscard]] AgentState dequantizeAgent(const QAgent& q);

/// What a record's base becomes when the agent is (now) in `tier`, before its deltas: far drops
/// yaw, clip, phase and joints; middle drops joints and yaw's low byte; near gets 3 × jointCount
/// joints (zeros when the base had another count).
void applyTierRules(QAgent& a, Tier tier, std::uint8_t jointCount);

/// Joint angle component in shifted units: (q >> shift), and back.
[[nodiscard]] inline std::uint32_t jointUnits(std::uint16_t q, std::uint8_t shift) { return q >> shift; }

}  // namespace throng::protocol::detail
