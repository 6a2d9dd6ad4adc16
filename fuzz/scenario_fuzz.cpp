// libFuzzer target for scenario loading (libs/io scenario_loader): arbitrary bytes →
// parseScenario. Reads the input only. Checks that nothing crashes, throws or hangs, and that
// results are coherent: a loaded scenario has simple walkable polygons and resolved goals; a
// rejected one has located diagnostics. Small worlds also run the navmesh reachability check.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "throng/io/scenario_loader.hpp"

namespace {

void check(bool condition) {
  if (!condition) std::abort();
}

void checkResult(const throng::core::Result<throng::io::LoadedScenario>& r) {
  if (!r.ok()) {
    check(!r.errors().empty());
    for (const auto& d : r.errors()) {
      // The scenario's own problems name it; a database or clip file it names reports its own path.
      check(!d.source.empty());
      check(!d.what.empty());
      check(d.line >= 0 && d.column >= 0);
    }
    return;
  }
  const auto& desc = r->desc;
  check(!desc.walkable.empty() || !desc.terrain.empty());  // a flat world, or a multi-level one
  for (const auto& t : desc.transports) {
    check(t.stops[0] < desc.points.size() && t.stops[1] < desc.points.size() && t.stops[0] != t.stops[1]);
  }
  for (const auto& poly : desc.walkable) check(poly.size() >= 3 && !throng::core::findSelfIntersection(poly));
  for (const auto& pop : desc.populations) {
    for (const auto goal : pop.goals) check(goal < desc.points.size());
    check(pop.sizeMin >= 1 && pop.sizeMin <= pop.sizeMax);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto structural = throng::io::parseScenario(text, "fuzz.json", throng::io::LoadOptions{false});
  checkResult(structural);
  if (!structural.ok()) return 0;
  // Navmesh building costs grow with the world's area: only small worlds get the full check.
  throng::core::Aabb box;
  for (const auto& poly : structural->desc.walkable) {
    for (const auto p : poly) box.extend(p);
  }
  // A multi-level world's area is that of its terrain's vertices (walkable or obstacle).
  const auto& vertices = structural->desc.terrain.vertices;
  for (std::size_t v = 0; v + 2 < vertices.size(); v += 3) box.extend({vertices[v], vertices[v + 1]});
  const float extent = std::max(box.max.x - box.min.x, box.max.y - box.min.y);
  if (size <= 4096 && extent <= 60.0f) {
    auto full = throng::io::parseScenario(text, "fuzz.json", throng::io::LoadOptions{true});
    checkResult(full);
    if (full.ok()) check(full->navmesh != nullptr);
  }
  return 0;
}
