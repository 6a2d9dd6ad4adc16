// The motion library of a served world (see motion_library.hpp).
#include "throng/hub/motion_library.hpp"

#include <algorithm>
#include <cmath>

namespace throng::hub {
namespace fs = std::filesystem;

namespace {

std::shared_ptr<const motion::MotionClip> loadClip(const fs::path& path, std::vector<std::string>& warnings) {
  auto clip = motion::loadBvhFile(path.string());
  if (!clip.ok()) {
    warnings.push_back(clip.errors().front().format());
    return nullptr;
  }
  return std::make_shared<const motion::MotionClip>(std::move(clip).value());
}

}  // namespace

MotionLibrary MotionLibrary::load(const io::LoadedScenario& scenario, const fs::path& scenarioDir,
                                  std::vector<std::string>& warnings) {
  MotionLibrary lib;
  lib.clips_ = sim::animationClips(scenario.desc);
  const std::string motionsDir = scenario.desc.social.motions.empty() ? std::string("motions") : scenario.desc.social.motions;
  for (const sim::ClipInfo& info : lib.clips_) {
    fs::path file;
    std::shared_ptr<const motion::MotionClip> motion;
    if (auto it = scenario.clips.find(info.file); !info.file.empty() && it != scenario.clips.end()) {
      file = scenarioDir / info.file;
      motion = it->second;
    } else {
      // Built-in clips (idle, walk) and micro-behaviours live in the motion directory by name.
      file = info.file.empty() ? scenarioDir / motionsDir / (info.name + ".bvh") : scenarioDir / info.file;
      std::error_code ec;
      if (fs::is_regular_file(file, ec)) {
        motion = loadClip(file, warnings);
      } else {
        warnings.push_back("motion clip '" + info.name + "': no file " + file.string() + "; its bodies stand still");
        file.clear();
      }
      if (!motion) file.clear();
    }
    lib.files_.push_back(file);
    lib.motions_.push_back(std::move(motion));
  }
  // The skeleton: that of the walk clip, else of the first clip that loaded.
  const motion::MotionClip* reference = nullptr;
  if (lib.motions_.size() > sim::kClipWalk && lib.motions_[sim::kClipWalk]) reference = lib.motions_[sim::kClipWalk].get();
  for (std::size_t i = 0; reference == nullptr && i < lib.motions_.size(); ++i) reference = lib.motions_[i].get();
  if (reference != nullptr) {
    for (const motion::MotionClip::Joint& j : reference->joints) {
      lib.skeleton_.names.push_back(j.name);
      lib.skeleton_.parents.push_back(j.parent);
      lib.skeleton_.offsets.push_back(j.offset);
    }
  }
  // Map every clip's rotation channels onto the skeleton's joints by name.
  for (const auto& motion : lib.motions_) {
    std::vector<std::array<int, 3>> cols(lib.skeleton_.names.size(), {-1, -1, -1});
    if (motion) {
      for (std::size_t j = 0; j < cols.size(); ++j) {
        const int index = motion->findJoint(lib.skeleton_.names[j]);
        if (index < 0) continue;
        const motion::MotionClip::Joint& joint = motion->joints[static_cast<std::size_t>(index)];
        for (std::size_t c = 0; c < joint.channels.size(); ++c) {
          const int column = static_cast<int>(joint.firstChannel + c);
          switch (joint.channels[c]) {
            case motion::MotionChannel::Xrotation: cols[j][0] = column; break;
            case motion::MotionChannel::Yrotation: cols[j][1] = column; break;
            case motion::MotionChannel::Zrotation: cols[j][2] = column; break;
            default: break;
          }
        }
      }
    }
    lib.columns_.push_back(std::move(cols));
  }
  return lib;
}

void MotionLibrary::sample(std::uint16_t clip, float phase, std::span<float> out) const {
  std::fill(out.begin(), out.end(), 0.0f);
  if (clip >= motions_.size() || !motions_[clip]) return;
  const motion::MotionClip& motion = *motions_[clip];
  const float p = std::isfinite(phase) ? std::clamp(phase, 0.0f, 1.0f) : 0.0f;
  const std::size_t frame = std::min(motion.frameCount - 1, static_cast<std::size_t>(p * static_cast<float>(motion.frameCount)));
  const auto& cols = columns_[clip];
  const std::size_t joints = std::min(cols.size(), out.size() / 3);
  for (std::size_t j = 0; j < joints; ++j) {
    for (int axis = 0; axis < 3; ++axis) {
      const int column = cols[j][static_cast<std::size_t>(axis)];
      if (column >= 0) out[3 * j + static_cast<std::size_t>(axis)] = motion.value(frame, static_cast<std::size_t>(column));
    }
  }
}

}  // namespace throng::hub
