// Building multi-level test worlds (nav::TerrainMesh, ScenarioDesc::terrain) from quads. Shared by
// the sim tests of floors, stairs, spawning on levels and transports.
#pragma once
#include <array>
#include <cstdint>
#include <initializer_list>

#include "throng/nav/navmesh.hpp"

namespace throng::test {

/// Adds the quad a, b, c, d (x, y, z each) to the terrain as two walkable triangles.
inline void quad(nav::TerrainMesh& t, std::initializer_list<std::array<float, 3>> corners) {
  const auto base = static_cast<std::uint32_t>(t.vertices.size() / 3);
  for (const auto& c : corners) t.vertices.insert(t.vertices.end(), c.begin(), c.end());
  for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) t.walkable.push_back(base + i);
}

}  // namespace throng::test
