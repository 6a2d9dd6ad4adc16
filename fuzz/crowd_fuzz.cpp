// libFuzzer target for crowd files (libs/io crowd_parser): arbitrary bytes → parseCrowd against a
// fixed small world (parsed once, with its navmesh, so reachability runs too). Reads the input
// only. Checks that nothing crashes, throws or hangs, and that results are coherent: an accepted
// crowd's indices are inside the world's and its own points, its agents within the insertion
// limit; a rejected one has located diagnostics.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "throng/io/crowd_loader.hpp"
#include "throng/io/scenario_loader.hpp"

namespace {

void check(bool condition) {
  if (!condition) std::abort();
}

constexpr std::string_view kWorld = R"({
  "format": "throng/1",
  "walkable": [[[0, 0], [30, 0], [30, 10], [0, 10]]],
  "obstacles": [[[14, 0], [16, 0], [16, 4], [14, 4]], [[14, 6], [16, 6], [16, 10], [14, 10]]],
  "points": [
    {"id": "left", "kind": "interest", "position": [3, 5], "radius": 1.5},
    {"id": "look", "kind": "action", "position": [10, 5], "radius": 1, "action": "look", "duration": 3},
    {"id": "exit", "kind": "exit", "position": [29, 5], "radius": 1}
  ],
  "populations": [
    {"id": "walkers", "groups": 2, "size": [1, 3], "spawn": {"polygon": [[1, 1], [8, 1], [8, 9], [1, 9]]},
     "goals": ["left", "exit"], "radius": 0.25}
  ]
})";

const throng::io::LoadedScenario& world() {
  static const throng::io::LoadedScenario w = [] {
    auto r = throng::io::parseScenario(kWorld, "world.json");
    check(r.ok());
    return std::move(r).value();
  }();
  return w;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  throng::io::CrowdOptions options;
  options.navmesh = size < 4096 ? world().navmesh : nullptr;  // reachability for small inputs
  options.takenCrowdIds = {"taken"};
  const auto r = throng::io::parseCrowd(text, "crowd.json", world().desc, options);
  if (!r.ok()) {
    check(!r.errors().empty());
    for (const auto& d : r.errors()) {
      check(d.source == "crowd.json");
      check(!d.what.empty());
      check(d.line >= 0 && d.column >= 0);
    }
    return 0;
  }
  const auto& c = r.value();
  check(!c.id.empty() && c.id != "taken");
  check(c.basePoints == world().desc.points.size());
  check(c.maxAgents() <= throng::sim::kMaxInsertAgents);
  const std::size_t points = c.basePoints + c.points.size();
  for (const auto& pop : c.populations) {
    for (const auto goal : pop.goals) check(goal < points);
    if (pop.spawn.kind == throng::sim::SpawnKind::Point) check(pop.spawn.point < points);
    check(pop.sizeMin >= 1 && pop.sizeMin <= pop.sizeMax);
    check(pop.radius <= world().desc.maxRadius());
  }
  return 0;
}
