// throng::hub motion library — the skeleton and the motion clips (BVH) a served world animates its
// crowd with. The simulation only says which clip each agent plays and where in it (sim::Frame's
// clip and phase); receivers sample the clips themselves, except for the few agents nearest to a
// client, whose full joint poses the server samples here (Musse et al. §4.3: joint-based messages
// for close bodies, described animation for the rest).
// Reads the BVH files of a scenario (action points' clips, the micro-behaviours' clips in
// <social.motions>/, idle and walk in the same directory); writes nothing.
#pragma once
#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "throng/motion/bvh.hpp"
#include "throng/io/scenario_loader.hpp"
#include "throng/sim/animation.hpp"

namespace throng::hub {

/// The joint hierarchy shared by every clip (H-Anim names in the bundled library).
struct Skeleton {
  std::vector<std::string> names;                ///< depth-first: a parent before its children
  std::vector<int> parents;                      ///< index into names, -1 for the root
  std::vector<std::array<float, 3>> offsets;     ///< from the parent joint [m]
};

class MotionLibrary {
 public:
  /// Clips of `scenario` (sim::animationClips order), resolved against `scenarioDir`. A clip whose
  /// file is missing or malformed stays in the table with its length but no samples (its bodies
  /// stand in the rest pose); each such clip adds a line to `warnings`.
  static MotionLibrary load(const io::LoadedScenario& scenario, const std::filesystem::path& scenarioDir,
                            std::vector<std::string>& warnings);

  [[nodiscard]] const Skeleton& skeleton() const { return skeleton_; }
  [[nodiscard]] std::size_t jointCount() const { return skeleton_.names.size(); }
  [[nodiscard]] const std::vector<sim::ClipInfo>& clips() const { return clips_; }
  /// The BVH file behind clip `index` (empty when it has none), for serving it to viewers.
  [[nodiscard]] const std::filesystem::path& clipFile(std::size_t index) const { return files_[index]; }

  /// Joint rotations of clip `clip` at `phase` in [0, 1): three angles per skeleton joint, X, Y and
  /// Z rotation in degrees, in skeleton order (joints the clip lacks: 0). `out` holds 3 × jointCount.
  void sample(std::uint16_t clip, float phase, std::span<float> out) const;

 private:
  Skeleton skeleton_;
  std::vector<sim::ClipInfo> clips_;
  std::vector<std::filesystem::path> files_;
  std::vector<std::shared_ptr<const motion::MotionClip>> motions_;  ///< null: no samples
  /// Per clip, per skeleton joint, the columns of its X, Y and Z rotation channels (-1: none).
  std::vector<std::vector<std::array<int, 3>>> columns_;
};

}  // namespace throng::hub
