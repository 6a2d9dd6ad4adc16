// The world description sent to joining participants (see world_description.hpp).
#include "throng/hub/world_description.hpp"

#include <nlohmann/json.hpp>

#include "throng/hub/text.hpp"

namespace throng::hub {

std::string describeWorld(const io::LoadedScenario& scenario, const MotionLibrary& motions,
                          const sim::World& world, double tickRate) {
  using nlohmann::json;
  json out;
  out["description"] = kWorldDescriptionVersion;
  out["name"] = scenario.desc.name;
  out["dt"] = scenario.desc.dt;
  out["tickRate"] = tickRate;
  // The scenario as written: a viewer draws floors, walls and points from the same format the
  // engine reads. The loader validated it, so it parses.
  // A text that is not UTF-8 does not parse as JSON: its bad bytes become U+FFFD first.
  json written = json::parse(scenario.text, nullptr, false);
  if (written.is_discarded()) written = json::parse(validUtf8(scenario.text), nullptr, false);
  out["scenario"] = written.is_discarded() ? json(nullptr) : std::move(written);
  json joints = json::array();
  const Skeleton& sk = motions.skeleton();
  for (std::size_t j = 0; j < sk.names.size(); ++j) {
    joints.push_back({{"name", sk.names[j]}, {"parent", sk.parents[j]},
                      {"offset", {sk.offsets[j][0], sk.offsets[j][1], sk.offsets[j][2]}}});
  }
  out["skeleton"] = {{"joints", std::move(joints)}};
  json clips = json::array();
  for (std::size_t c = 0; c < motions.clips().size(); ++c) {
    const sim::ClipInfo& info = motions.clips()[c];
    json clip = {{"id", c}, {"name", info.name}, {"duration", info.duration}, {"loops", info.loops}};
    clip["url"] = motions.clipFile(c).empty() ? json(nullptr) : json("/motions/" + std::to_string(c) + ".bvh");
    clips.push_back(std::move(clip));
  }
  out["clips"] = std::move(clips);
  json groups = json::array();
  for (std::size_t g = 0; g < world.groupCount(); ++g) {
    const auto info = world.groupInfo(world.groupById(static_cast<std::uint32_t>(g)));
    if (!info) continue;
    const std::string population = info->population < scenario.desc.populations.size()
                                       ? scenario.desc.populations[info->population].id
                                       : std::string();
    groups.push_back({{"id", info->id}, {"population", population}, {"members", info->members}});
  }
  out["groups"] = std::move(groups);
  // Names come from the scenario: never let one that is not UTF-8 make the description throw.
  return out.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace throng::hub
