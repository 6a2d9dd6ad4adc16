// Animation clip table of a scenario (see animation.hpp).
#include "throng/sim/animation.hpp"

#include <algorithm>

namespace throng::sim {

std::vector<ClipInfo> animationClips(const ScenarioDesc& desc) {
  std::vector<ClipInfo> clips{{"idle", "", kIdleCycle, true}, {"walk", "", kWalkCycleLength / 1.34f, true}};
  for (const PointDesc& p : desc.points) {
    if (p.kind != PointKind::Action || !p.stop) continue;
    const std::string name = p.action.empty() ? "stand" : p.action;
    if (std::none_of(clips.begin(), clips.end(), [&](const ClipInfo& c) { return c.name == name; })) {
      clips.push_back({name, p.clip, p.actionDuration, false});
    }
  }
  // Clips of the Common Ground micro-behaviours (wave, nod, ...), played from action scripts.
  for (const auto& entry : desc.social.clipLengths) {
    const std::string& name = entry.first;
    if (std::none_of(clips.begin(), clips.end(), [&](const ClipInfo& c) { return c.name == name; })) {
      clips.push_back({name, desc.social.motions + "/" + name + ".bvh", static_cast<float>(entry.second), false});
    }
  }
  return clips;
}

std::vector<std::uint16_t> pointClips(const ScenarioDesc& desc) {
  const std::vector<ClipInfo> clips = animationClips(desc);
  std::vector<std::uint16_t> out;
  for (const PointDesc& p : desc.points) {
    std::uint16_t index = kClipIdle;
    if (p.kind == PointKind::Action && p.stop) {
      const std::string name = p.action.empty() ? "stand" : p.action;
      for (std::size_t c = 0; c < clips.size(); ++c) {
        if (clips[c].name == name) index = static_cast<std::uint16_t>(c);
      }
    }
    out.push_back(index);
  }
  return out;
}

}  // namespace throng::sim
