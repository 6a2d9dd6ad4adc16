// Tests for libs/sim/src/spatial_grid.cpp.
#include "throng/sim/spatial_grid.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "throng/core/rng.hpp"
#include "throng/core/simd.hpp"

using namespace throng;

namespace {

/// The (at most k) rows within `range` of row `self`, nearest first, ties by row: what
/// SpatialGrid::nearest must give.
std::vector<std::uint32_t> bruteForceNearest(const std::vector<float>& xs, const std::vector<float>& ys, std::uint32_t self,
                                             std::size_t k, float range) {
  std::vector<std::pair<float, std::uint32_t>> all;
  for (std::uint32_t i = 0; i < xs.size(); ++i) {
    if (i == self) continue;
    const float dx = xs[i] - xs[self], dy = ys[i] - ys[self];
    if (dx * dx + dy * dy < range * range) all.push_back({dx * dx + dy * dy, i});
  }
  std::sort(all.begin(), all.end());
  std::vector<std::uint32_t> rows;
  for (std::size_t i = 0; i < std::min(k, all.size()); ++i) rows.push_back(all[i].second);
  return rows;
}

}  // namespace

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
  for (std::uint32_t self = 0; self < xs.size(); self += 7) {
    for (std::size_t k : {1u, 5u, 10u}) {
      for (float range : {0.5f, 2.0f, 3.0f}) {
        std::vector<std::uint32_t> out(k);
        const std::size_t n = grid.nearest(xs[self], ys[self], range, k, self, out.data());
        const std::vector<std::uint32_t> expected = bruteForceNearest(xs, ys, self, k, range);
        ASSERT_EQ(n, expected.size());
        for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(out[i], expected[i]) << "self " << self << " k " << k;
      }
    }
  }
}

TEST(SpatialGrid, NearestIsTheSameOnEverySimdPathAndMatchesBruteForce) {
  // Dense clusters (up to ~20 candidates a cell, so the narrowing and the ranking run on long
  // lists), exact duplicates (ties settled by row), k up to 70 (past the stack buffer), on every
  // SIMD path this CPU runs.
  std::vector<float> xs, ys;
  core::Rng rng(3, 0, core::RngPurpose::Bench);
  for (int i = 0; i < 1500; ++i) {
    const bool dense = i % 3 != 0;
    xs.push_back(static_cast<float>(rng.uniform(dense ? 10 : 0, dense ? 16 : 30)));
    ys.push_back(static_cast<float>(rng.uniform(dense ? 10 : 0, dense ? 16 : 30)));
  }
  for (int i = 0; i < 100; ++i) {  // duplicates of earlier agents
    xs.push_back(xs[static_cast<std::size_t>(i * 7)]);
    ys.push_back(ys[static_cast<std::size_t>(i * 7)]);
  }
  std::vector<core::SimdPath> paths{core::SimdPath::Portable};
  if (core::simdSupported(core::SimdPath::Avx2)) paths.push_back(core::SimdPath::Avx2);
  const core::SimdPath before = core::simdPath();
  core::TaskSystem tasks(1);
  std::size_t compared = 0;
  for (core::SimdPath path : paths) {
    ASSERT_TRUE(core::setSimdPath(path));
    sim::SpatialGrid grid;
    grid.configure(core::Aabb{{0, 0}, {30, 30}}, 1.0f);
    grid.rebuild(xs, ys, tasks);
    for (std::uint32_t self = 0; self < xs.size(); self += 5) {
      for (std::size_t k : {1u, 4u, 10u, 17u, 70u}) {
        for (float range : {0.5f, 2.0f, 3.0f, 7.0f}) {
          std::vector<std::uint32_t> out(k);
          const std::size_t n = grid.nearest(xs[self], ys[self], range, k, self, out.data());
          const std::vector<std::uint32_t> expected = bruteForceNearest(xs, ys, self, k, range);
          ASSERT_EQ(n, expected.size()) << core::simdPathName(path) << " self " << self << " k " << k;
          for (std::size_t i = 0; i < n; ++i) {
            ASSERT_EQ(out[i], expected[i]) << core::simdPathName(path) << " self " << self << " k " << k << " range " << range;
          }
          compared += n;
        }
      }
    }
  }
  core::setSimdPath(before);
  EXPECT_GT(compared, 100000u);
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

namespace {

/// Brute-force reference: rows within range (excluding self) by (distance², row), first k.
std::vector<std::uint32_t> bruteNearest(const std::vector<float>& xs, const std::vector<float>& ys, std::uint32_t self,
                                        float range, std::size_t k) {
  std::vector<std::pair<float, std::uint32_t>> all;
  for (std::uint32_t i = 0; i < xs.size(); ++i) {
    if (i == self) continue;
    const float dx = xs[i] - xs[self], dy = ys[i] - ys[self];
    const float d2 = dx * dx + dy * dy;
    if (d2 < range * range) all.push_back({d2, i});
  }
  std::sort(all.begin(), all.end());
  std::vector<std::uint32_t> rows;
  for (std::size_t i = 0; i < std::min(k, all.size()); ++i) rows.push_back(all[i].second);
  return rows;
}

void expectNearestMatchesBruteForce(const std::vector<float>& xs, const std::vector<float>& ys, const core::Aabb& bounds,
                                    float cell, std::initializer_list<std::size_t> ks, std::initializer_list<float> ranges,
                                    std::uint32_t stride) {
  sim::SpatialGrid grid;
  grid.configure(bounds, cell);
  core::TaskSystem tasks(1);
  grid.rebuild(xs, ys, tasks);
  for (std::uint32_t self = 0; self < xs.size(); self += stride) {
    for (std::size_t k : ks) {
      for (float range : ranges) {
        std::vector<std::uint32_t> out(k);
        const std::size_t n = grid.nearest(xs[self], ys[self], range, k, self, out.data());
        out.resize(n);
        ASSERT_EQ(out, bruteNearest(xs, ys, self, range, k)) << "self " << self << " k " << k << " range " << range;
      }
    }
  }
}

}  // namespace

TEST(SpatialGrid, NearestBreaksExactDistanceTiesByRow) {
  // A lattice: every agent has four neighbours at exactly the same distance, and eight more in
  // tied rings; rows are shuffled against the lattice so that cell order is not row order.
  std::vector<float> xs, ys;
  std::vector<std::uint32_t> slot(400);
  for (std::uint32_t i = 0; i < slot.size(); ++i) slot[i] = i;
  core::Rng rng(3, 0, core::RngPurpose::Bench);
  for (std::size_t i = slot.size(); i > 1; --i) std::swap(slot[i - 1], slot[rng.uniformInt(0, static_cast<std::uint32_t>(i - 1))]);
  for (std::uint32_t s : slot) {
    xs.push_back(0.5f + 0.75f * static_cast<float>(s % 20));
    ys.push_back(0.5f + 0.75f * static_cast<float>(s / 20));
  }
  expectNearestMatchesBruteForce(xs, ys, core::Aabb{{0, 0}, {16, 16}}, 1.0f, {1, 4, 10, 13}, {0.75f, 1.5f, 3.0f}, 3);
}

TEST(SpatialGrid, NearestInDenseCrowdsAndWithLargeK) {
  // 600 agents in a 2 m × 2 m square (150 per m²): hundreds of candidates per search, more than
  // the search buffers at once; k = 100 takes the large-k path.
  std::vector<float> xs, ys;
  core::Rng rng(4, 0, core::RngPurpose::Bench);
  for (int i = 0; i < 600; ++i) {
    xs.push_back(static_cast<float>(rng.uniform(4, 6)));
    ys.push_back(static_cast<float>(rng.uniform(4, 6)));
  }
  expectNearestMatchesBruteForce(xs, ys, core::Aabb{{0, 0}, {10, 10}}, 1.0f, {1, 10, 100}, {0.3f, 3.0f}, 37);
}

TEST(SpatialGrid, NearestAtGridBordersAndOutsideIt) {
  // Sparse agents, some outside the bounds (clamped into border cells), searched with ranges
  // reaching past the grid and several rings out.
  std::vector<float> xs, ys;
  core::Rng rng(5, 0, core::RngPurpose::Bench);
  for (int i = 0; i < 150; ++i) {
    xs.push_back(static_cast<float>(rng.uniform(-3, 23)));
    ys.push_back(static_cast<float>(rng.uniform(-3, 13)));
  }
  expectNearestMatchesBruteForce(xs, ys, core::Aabb{{0, 0}, {20, 10}}, 0.5f, {1, 10}, {0.5f, 1.5f, 6.0f}, 1);
}
