// throng::protocol crowd quantization — SI values to wire units and back: positions in cm, angles
// in 1/65536 turn (joints in 2^jointShift of those), phase in 1/256. Decoded values requantize to
// the same integers (exact round trip for |position| ≤ 40 km).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "crowd_state.hpp"

namespace throng::protocol {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

/// round(turns × steps) modulo steps (steps a power of two ≤ 65536); NaN → 0.
std::uint32_t quantizeTurns(float radians, std::uint32_t steps) {
  const double t = static_cast<double>(radians) / kTwoPi * steps;
  if (!std::isfinite(t)) return 0;
  const double r = std::nearbyint(t - std::floor(t / steps) * steps);  // in [0, steps]
  return static_cast<std::uint32_t>(static_cast<std::int64_t>(r)) & (steps - 1);
}

}  // namespace

std::int32_t quantizePosition(float meters) {
  const double cm = std::nearbyint(static_cast<double>(meters) * 100.0);
  if (!(cm == cm)) return 0;
  return static_cast<std::int32_t>(std::clamp(cm, static_cast<double>(std::numeric_limits<std::int32_t>::min()),
                                              static_cast<double>(std::numeric_limits<std::int32_t>::max())));
}

float dequantizePosition(std::int32_t centimeters) { return static_cast<float>(static_cast<double>(centimeters) / 100.0); }

std::uint16_t quantizeAngle16(float radians) { return static_cast<std::uint16_t>(quantizeTurns(radians, 65536)); }

float dequantizeAngle16(std::uint16_t turns) {
  return static_cast<float>(static_cast<double>(static_cast<std::int16_t>(turns)) * kTwoPi / 65536.0);
}

std::uint8_t quantizePhase(float phase) {
  const double t = static_cast<double>(phase) * 256.0;
  if (!std::isfinite(t)) return 0;
  const double r = std::nearbyint(t - std::floor(t / 256.0) * 256.0);
  return static_cast<std::uint8_t>(static_cast<std::int64_t>(r) & 0xff);
}

float dequantizePhase(std::uint8_t phase) { return static_cast<float>(phase) / 256.0f; }

namespace detail {

QAgent quantizeAgent(const AgentState& a, std::uint8_t jointCount, std::uint8_t jointShift) {
  QAgent q;
  q.id = a.id;
  q.tier = a.tier;
  q.x = quantizePosition(a.x);
  q.y = quantizePosition(a.y);
  q.z = quantizePosition(a.z);
  if (a.tier == Tier::Far) return q;
  q.clip = a.clip;
  q.phase = quantizePhase(a.phase);
  if (a.tier == Tier::Middle) {
    q.yaw = static_cast<std::uint16_t>(quantizeTurns(a.yaw, 256) << 8);
    return q;
  }
  q.yaw = quantizeAngle16(a.yaw);
  const std::uint32_t steps = 65536u >> jointShift;
  q.joints.assign(std::size_t{3} * jointCount, 0);
  const std::size_t n = std::min(q.joints.size(), a.joints.size());
  for (std::size_t i = 0; i < n; ++i) {
    q.joints[i] = static_cast<std::uint16_t>(quantizeTurns(a.joints[i], steps) << jointShift);
  }
  return q;
}

AgentState dequantizeAgent(const QAgent& q) {
  AgentState a;
  a.id = q.id;
  a.tier = q.tier;
  a.x = dequantizePosition(q.x);
  a.y = dequantizePosition(q.y);
  a.z = dequantizePosition(q.z);
  a.yaw = dequantizeAngle16(q.yaw);
  a.clip = q.clip;
  a.phase = dequantizePhase(q.phase);
  a.joints.reserve(q.joints.size());
  for (const std::uint16_t j : q.joints) a.joints.push_back(dequantizeAngle16(j));
  return a;
}

void applyTierRules(QAgent& a, Tier tier, std::uint8_t jointCount) {
  a.tier = tier;
  switch (tier) {
    case Tier::Far:
      a.yaw = 0;
      a.clip = 0;
      a.phase = 0;
      a.joints.clear();
      break;
    case Tier::Middle:
      a.yaw &= 0xff00;
      a.joints.clear();
      break;
    case Tier::Near:
      if (a.joints.size() != std::size_t{3} * jointCount) a.joints.assign(std::size_t{3} * jointCount, 0);
      break;
  }
}

}  // namespace detail

AgentState quantized(const AgentState& agent, std::uint8_t jointCount, std::uint8_t jointShift) {
  return detail::dequantizeAgent(detail::quantizeAgent(agent, jointCount, jointShift));
}

CrowdView quantized(const CrowdView& view, std::uint8_t jointShift) {
  CrowdView out;
  out.simTick = view.simTick;
  out.animationInterval = view.animationInterval;
  out.jointCount = view.jointCount;
  out.agents.reserve(view.agents.size());
  for (const AgentState& a : view.agents) out.agents.push_back(quantized(a, view.jointCount, jointShift));
  std::sort(out.agents.begin(), out.agents.end(), [](const AgentState& a, const AgentState& b) { return a.id < b.id; });
  return out;
}

}  // namespace throng::protocol
