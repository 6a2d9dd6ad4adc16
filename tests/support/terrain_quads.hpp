// Building multi-level test worlds (nav::TerrainMesh, ScenarioDesc::terrain) from quads, and
// rectangular points on their floors. Shared by the sim tests of floors, stairs, spawning on levels
// and transports.
#pragma once
#include <array>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <utility>

#include "throng/nav/navmesh.hpp"
#include "throng/sim/scenario.hpp"

namespace throng::test {

/// Adds the quad a, b, c, d (x, y, z each) to the terrain as two walkable triangles.
inline void quad(nav::TerrainMesh& t, std::initializer_list<std::array<float, 3>> corners) {
  const auto base = static_cast<std::uint32_t>(t.vertices.size() / 3);
  for (const auto& c : corners) t.vertices.insert(t.vertices.end(), c.begin(), c.end());
  for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) t.walkable.push_back(base + i);
}

/// A point of `kind` over the rectangle x0..x1 × y0..y1 on the floor at `height`.
inline sim::PointDesc region(std::string id, sim::PointKind kind, float x0, float x1, float y0, float y1, float height) {
  sim::PointDesc p;
  p.id = std::move(id);
  p.kind = kind;
  p.polygon = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  p.position = {(x0 + x1) / 2, (y0 + y1) / 2};
  p.height = height;
  return p;
}

}  // namespace throng::test
