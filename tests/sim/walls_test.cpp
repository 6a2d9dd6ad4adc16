// Walls (libs/sim/src/walls.cpp): the disc and ray queries over the navmesh boundary's grid.
#include "walls.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "goal_world.hpp"

namespace throng::sim {
namespace {

using test::rect;

/// Whether the ray from p along the unit vector dir crosses segment s within len.
bool crosses(const core::Segment& s, core::Vec2 p, core::Vec2 dir, float len) {
  const core::Vec2 e = s.b - s.a;
  const float den = core::cross(dir, e);
  if (std::abs(den) < 1e-9f) return false;
  const core::Vec2 q = s.a - p;
  const float t = core::cross(q, e) / den, u = core::cross(q, dir) / den;
  return t >= 0.0f && t <= len && u >= 0.0f && u <= 1.0f;
}

TEST(Walls, RayQueryHoldsEveryWallTheRayCrossesAndFewerThanTheDisc) {
  // A 40 × 30 m room with three pillars (walls inside as well as round it), 2 m cells.
  auto mesh = nav::NavMesh::build(std::vector<core::Polygon>{rect(0, 0, 40, 30)},
                                  std::vector<core::Polygon>{rect(8, 8, 10, 10), rect(20, 5, 21, 25), rect(30, 14, 33, 16)},
                                  nav::NavMeshConfig{});
  ASSERT_TRUE(mesh.ok());
  Walls walls;
  walls.build(*mesh.value(), 2.0f);
  ASSERT_GT(walls.segments().size(), 12u);
  std::uint32_t state = 12345u;  // a fixed LCG: the same rays on every platform
  const auto uniform = [&](float lo, float hi) {
    state = state * 1664525u + 1013904223u;
    return lo + (hi - lo) * static_cast<float>(state >> 8) / 16777216.0f;
  };
  std::size_t rayTotal = 0, discTotal = 0, crossed = 0;
  for (int i = 0; i < 2000; ++i) {
    const core::Vec2 p{uniform(-2.0f, 42.0f), uniform(-2.0f, 32.0f)};
    const float angle = uniform(0.0f, 6.2831853f), len = i % 10 == 0 ? 0.0f : uniform(0.0f, 25.0f);
    const core::Vec2 dir{std::cos(angle), std::sin(angle)};
    std::vector<std::uint32_t> ray{7u}, disc;  // what was there before is kept
    walls.queryRay(p, dir, len, ray);
    walls.query(p.x, p.y, len, disc);
    ASSERT_EQ(ray.front(), 7u);
    ray.erase(ray.begin());
    EXPECT_TRUE(std::is_sorted(ray.begin(), ray.end()));
    EXPECT_EQ(std::adjacent_find(ray.begin(), ray.end()), ray.end());
    EXPECT_TRUE(std::includes(disc.begin(), disc.end(), ray.begin(), ray.end()));
    for (std::uint32_t s = 0; s < walls.segments().size(); ++s) {
      if (!crosses(walls.segments()[s], p, dir, len)) continue;
      ++crossed;
      EXPECT_TRUE(std::binary_search(ray.begin(), ray.end(), s)) << "ray " << i << " misses segment " << s;
    }
    rayTotal += ray.size();
    discTotal += disc.size();
  }
  EXPECT_GT(crossed, 500u);               // the rays do cross walls
  EXPECT_LT(rayTotal * 2, discTotal);     // and read far fewer than the discs round them
}

}  // namespace
}  // namespace throng::sim
