// Tests for libs/sim/src/phases.hpp: each phase called on its own through its context, on
// hand-built columns (no World), as a reader of the phase's signature would expect it to behave.
#include "phases.hpp"

#include <gtest/gtest.h>

#include <vector>

using namespace throng;
using namespace throng::sim;

namespace {

/// The rows a phase wrote for `row` in a flat neighbour buffer.
std::vector<std::uint32_t> neighboursOf(const std::vector<std::uint32_t>& all, const std::vector<std::uint16_t>& count,
                                        std::size_t row, std::size_t k) {
  return {all.begin() + static_cast<std::ptrdiff_t>(row * k),
          all.begin() + static_cast<std::ptrdiff_t>(row * k + count[row])};
}

}  // namespace

TEST(Phases, SenseFillsNeighboursNearestFirstWithTiesByRow) {
  // Six agents on a line (x = 0, 1, 2, 3, 4 and a loner at 10); chunks of one row on two threads.
  const std::vector<float> xs{0, 1, 2, 3, 4, 10}, ys(6, 5.0f);
  SteeringDesc steering;
  steering.maxNeighbours = 3;
  steering.neighbourDistance = 3.5f;
  steering.denseNeighbourDistance = 0.0f;  // one range everywhere
  SpatialGrid grid;
  grid.configure(core::Aabb{{-1, 0}, {12, 10}}, 1.0f);
  std::vector<std::uint32_t> neighbours;
  std::vector<std::uint16_t> count;
  core::TaskSystem tasks(2);
  tasks.setGrainLimit(1);
  sense(SenseInput{xs, ys, {}, steering}, SenseOutput{grid, neighbours, count}, tasks);
  ASSERT_EQ(neighbours.size(), 6u * 3u);
  ASSERT_EQ(count.size(), 6u);
  EXPECT_EQ(neighboursOf(neighbours, count, 0, 3), (std::vector<std::uint32_t>{1, 2, 3}));
  // Rows 1 and 3 are both 1 m from row 2, rows 0 and 4 both 2 m: ties go to the lower row.
  EXPECT_EQ(neighboursOf(neighbours, count, 2, 3), (std::vector<std::uint32_t>{1, 3, 0}));
  EXPECT_EQ(neighboursOf(neighbours, count, 4, 3), (std::vector<std::uint32_t>{3, 2, 1}));
  EXPECT_EQ(count[5], 0u) << "the loner at x = 10 is beyond neighbourDistance of everyone";
}

TEST(Phases, SenseKeepsOnlyNeighboursOnTheSameFloor) {
  // Three agents above each other's footprint: rows 0 and 2 on the ground floor, row 1 on the
  // floor above (3 m up); with floor heights given, row 1 is nobody's neighbour.
  const std::vector<float> xs{0, 0.5f, 1}, ys{0, 0, 0}, zs{0, 3, 0.2f};
  SteeringDesc steering;
  steering.denseNeighbourDistance = 0.0f;
  SpatialGrid grid;
  grid.configure(core::Aabb{{-2, -2}, {3, 2}}, 1.0f);
  std::vector<std::uint32_t> neighbours;
  std::vector<std::uint16_t> count;
  core::TaskSystem tasks(1);
  const std::size_t k = steering.maxNeighbours;
  sense(SenseInput{xs, ys, zs, steering}, SenseOutput{grid, neighbours, count}, tasks);
  EXPECT_EQ(neighboursOf(neighbours, count, 0, k), (std::vector<std::uint32_t>{2}));
  EXPECT_EQ(count[1], 0u);
  EXPECT_EQ(neighboursOf(neighbours, count, 2, k), (std::vector<std::uint32_t>{0}));
  // Without floor heights (a flat world) all three see each other.
  sense(SenseInput{xs, ys, {}, steering}, SenseOutput{grid, neighbours, count}, tasks);
  EXPECT_EQ(neighboursOf(neighbours, count, 0, k), (std::vector<std::uint32_t>{1, 2}));
  EXPECT_EQ(neighboursOf(neighbours, count, 1, k), (std::vector<std::uint32_t>{0, 2}));
}
