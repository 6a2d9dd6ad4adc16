// throng::hub interest management — which agents of a frame one client needs, and at which level
// of detail (Musse et al. §4: levels of detail and the area of interest of each participant).
// Reads a sim::Frame and the client's viewpoint; writes a list of (row, tier). No I/O.
//
// Tiers, by distance from the client's viewpoint:
//   near   (≤ nearRadius, at most nearMax agents, the closest first): position, yaw, clip, phase and
//          the full joint pose;
//   middle (≤ middleRadius): position, yaw, clip and phase — the receiver samples the clip itself;
//   far    (≤ areaOfInterest): position only (the crowd encoder refreshes them at a lower rate).
// Agents beyond the area of interest are not sent at all.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "throng/core/vec2.hpp"
#include "throng/protocol/protocol.hpp"
#include "throng/sim/frame.hpp"

namespace throng::hub {

using Tier = protocol::Tier;

struct InterestOptions {
  float areaOfInterest = 80.0f;  ///< radius beyond which agents are not sent [m]
  float middleRadius = 30.0f;    ///< agents closer than this get animation (clip and phase) [m]
  float nearRadius = 6.0f;       ///< agents closer than this get full joint poses [m]
  std::size_t nearMax = 16;      ///< at most this many near agents (the closest)
  /// A client without a viewpoint (no avatar yet, an overview camera) sees everything: the whole
  /// crowd at middle detail.
  bool overviewWhenNoViewpoint = true;
};

struct Interested {
  std::uint32_t row = 0;  ///< index into the frame's arrays
  Tier tier = Tier::Middle;
};

/// Agents of `frame` that a client at `viewpoint` needs, ascending by row (so by stable id). `viewpoint` null:
/// every agent at middle detail (or none when !overviewWhenNoViewpoint). `scratch` avoids
/// allocation across calls.
void selectInterest(const sim::Frame& frame, const core::Vec2* viewpoint,
                    const InterestOptions& options, std::vector<Interested>& out,
                    std::vector<std::pair<float, std::uint32_t>>& scratch);

}  // namespace throng::hub
