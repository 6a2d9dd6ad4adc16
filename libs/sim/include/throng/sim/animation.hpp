// throng::sim animation state — which motion clip each agent plays and where in it, so a viewer
// (or the server's crowd messages) can animate bodies without receiving joint data: the receiver
// samples the clip itself (Musse et al. §4.3: animation is described, not streamed joint by joint).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "throng/sim/scenario.hpp"

namespace throng::sim {

struct ClipInfo {
  std::string name;       ///< "idle", "walk", or an action point's `action`
  std::string file;       ///< BVH file of the clip, relative to the scenario ("" = built in)
  float duration = 1.0f;  ///< [s]: one cycle (idle, walk at 1.34 m/s) or the whole action
  bool loops = true;      ///< idle and walk loop; actions play once
};

inline constexpr std::uint16_t kClipIdle = 0;
inline constexpr std::uint16_t kClipWalk = 1;
/// Distance covered by one walk cycle (two steps) [m]; the walk phase advances with distance.
inline constexpr float kWalkCycleLength = 1.4f;
/// Length of the idle cycle [s].
inline constexpr float kIdleCycle = 2.0f;

/// The clips of a scenario: idle, walk, then one per distinct action name of its action points,
/// in the order the points first use them.
[[nodiscard]] std::vector<ClipInfo> animationClips(const ScenarioDesc& desc);

/// For every point of the scenario, the index of its action clip in animationClips (kClipIdle for
/// points without an action).
[[nodiscard]] std::vector<std::uint16_t> pointClips(const ScenarioDesc& desc);

}  // namespace throng::sim
