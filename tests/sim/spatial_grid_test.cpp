// Tests for libs/sim/src/spatial_grid.cpp.
#include "spatial_grid.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "throng/core/rng.hpp"

using namespace throng;

TEST(SpatialGrid, FindsEveryAgentWithinRangeAndClampsOutsiders) {
  sim::SpatialGrid grid;
  grid.configure(core::Aabb{{0, 0}, {20, 20}}, 2.0f);
  std::vector<float> xs, ys;
  core::Rng rng(1, 0, core::RngPurpose::Bench);
  for (int i = 0; i < 500; ++i) {
    xs.push_back(static_cast<float>(rng.uniform(-2, 22)));  // some outside the bounds
    ys.push_back(static_cast<float>(rng.uniform(-2, 22)));
  }
  core::TaskSystem tasks(2);
  grid.rebuild(xs, ys, tasks);
  for (int q = 0; q < 50; ++q) {
    const float x = static_cast<float>(rng.uniform(0, 20)), y = static_cast<float>(rng.uniform(0, 20)), r = 2.5f;
    std::set<std::uint32_t> found;
    std::vector<std::uint32_t> order;
    grid.forEachNear(x, y, r, [&](std::uint32_t row) { found.insert(row); order.push_back(row); });
    for (std::uint32_t i = 0; i < xs.size(); ++i) {
      const float dx = xs[i] - x, dy = ys[i] - y;
      if (dx * dx + dy * dy <= r * r) EXPECT_TRUE(found.count(i)) << "row " << i << " missed";
    }
    EXPECT_EQ(found.size(), order.size()) << "a row was visited twice";
  }
  EXPECT_EQ(grid.rowsInCellOrder().size(), xs.size());
}

TEST(SpatialGrid, NearestMatchesBruteForce) {
  sim::SpatialGrid grid;
  grid.configure(core::Aabb{{0, 0}, {30, 30}}, 1.0f);
  std::vector<float> xs, ys;
  core::Rng rng(2, 0, core::RngPurpose::Bench);
  for (int i = 0; i < 900; ++i) {
    xs.push_back(static_cast<float>(rng.uniform(0, 30)));
    ys.push_back(static_cast<float>(rng.uniform(0, 30)));
  }
  core::TaskSystem tasks(1);
  grid.rebuild(xs, ys, tasks);
  std::vector<std::pair<float, std::uint32_t>> scratch;
  for (std::uint32_t self = 0; self < xs.size(); self += 7) {
    for (std::size_t k : {1u, 5u, 10u}) {
      for (float range : {0.5f, 2.0f, 3.0f}) {
        std::vector<std::uint32_t> out(k);
        const std::size_t n = grid.nearest(xs[self], ys[self], range, k, self, xs.data(), ys.data(), scratch, out.data());
        std::vector<std::pair<float, std::uint32_t>> all;
        for (std::uint32_t i = 0; i < xs.size(); ++i) {
          if (i == self) continue;
          const float dx = xs[i] - xs[self], dy = ys[i] - ys[self];
          if (dx * dx + dy * dy < range * range) all.push_back({dx * dx + dy * dy, i});
        }
        std::sort(all.begin(), all.end());
        ASSERT_EQ(n, std::min(k, all.size()));
        for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(out[i], all[i].second) << "self " << self << " k " << k;
      }
    }
  }
}

TEST(SpatialGrid, DensityCountsAgentsPerSquareMetreAround) {
  // Musse et al. §3.2.4's density: agents in the 3 × 3 cells around a point over their area.
  sim::SpatialGrid grid;
  grid.configure(core::Aabb{{0, 0}, {10, 10}}, 1.0f);
  std::vector<float> xs, ys;
  for (int i = 0; i < 18; ++i) {  // 18 agents in the 3 m × 3 m block [4, 7)²: 2 per m²
    xs.push_back(4.1f + 0.35f * static_cast<float>(i % 9) / 1.0f * 0.95f);
    ys.push_back(4.1f + 1.4f * static_cast<float>(i / 9) + 0.2f);
  }
  xs.push_back(0.5f);  // one far away
  ys.push_back(9.5f);
  core::TaskSystem tasks(1);
  grid.rebuild(xs, ys, tasks);
  EXPECT_NEAR(grid.density(5.5f, 5.5f), 18.0f / 9.0f, 1e-5f);
  EXPECT_NEAR(grid.density(0.5f, 9.5f), 1.0f / 4.0f, 1e-5f) << "a corner cell has 2 × 2 cells around it";
}
