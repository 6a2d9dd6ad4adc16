// Spatial row order (ScenarioDesc::rowOrder, libs/sim/src/row_order.cpp): the World sorts its rows
// along a Hilbert curve every kRowSortPeriod, and nobody outside can tell but by speed — frames
// still list agents by ascending id, agentInfo and removeAgents find them by id, and (in the
// determinism tests) the trajectories are those of rows kept in id order.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "throng/io/scenario_loader.hpp"
#include "throng/sim/world.hpp"

namespace throng::sim {
namespace {

io::LoadedScenario square() {
  // 1000 strollers in flocking groups of four on a 40 m square, wandering.
  auto loaded = io::loadScenarioFile(std::string(THRONG_SOURCE_DIR) + "/scenarios/square.json");
  EXPECT_TRUE(loaded.ok());
  return std::move(loaded).value();
}

std::unique_ptr<World> create(const io::LoadedScenario& s, RowOrder order) {
  ScenarioDesc d = s.desc;
  d.rowOrder = order;
  auto created = World::create(d, s.navmesh);
  EXPECT_TRUE(created.ok());
  return std::move(created).value();
}

/// Mean distance between the agents of consecutive rows [m].
double meanStepBetweenRows(const AgentColumns& c) {
  double sum = 0.0;
  for (std::size_t i = 1; i < c.size(); ++i) sum += std::hypot(c.posX[i] - c.posX[i - 1], c.posY[i] - c.posY[i - 1]);
  return sum / static_cast<double>(c.size() - 1);
}

TEST(RowOrder, SortedRowsLieNearEachOtherAndFramesStillListAgentsById) {
  const io::LoadedScenario s = square();
  auto byId = create(s, RowOrder::Id);
  auto spatial = create(s, RowOrder::Spatial);
  core::TaskSystem tasks(2);
  const auto ticks = static_cast<int>(std::lround(3.0f * kRowSortPeriod / s.desc.dt)) + 1;  // three sorts
  for (int t = 0; t < ticks; ++t) {
    byId->step(tasks);
    spatial->step(tasks);
  }
  const AgentColumns rows = spatial->agentColumns(), idRows = byId->agentColumns();
  ASSERT_GE(rows.size(), 900u);
  EXPECT_FALSE(std::is_sorted(rows.id.begin(), rows.id.end())) << "the rows were sorted spatially";
  EXPECT_TRUE(std::is_sorted(idRows.id.begin(), idRows.id.end()));
  // Consecutive rows: a few body widths apart, where rows in id order jump across the square.
  const double near = meanStepBetweenRows(rows), far = meanStepBetweenRows(idRows);
  EXPECT_LT(near, 1.5) << "sorted";
  EXPECT_LT(near * 4.0, far) << "id order";

  // Frames: ascending ids, every agent with its own row's values.
  const FramePtr f = spatial->takeFrame();
  ASSERT_EQ(f->size(), rows.size());
  EXPECT_TRUE(std::is_sorted(f->ids.begin(), f->ids.end()));
  std::size_t checked = 0;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const auto i = static_cast<std::size_t>(std::lower_bound(f->ids.begin(), f->ids.end(), rows.id[r]) - f->ids.begin());
    ASSERT_LT(i, f->size());
    ASSERT_EQ(f->ids[i], rows.id[r]);
    EXPECT_EQ(f->posX[i], rows.posX[r]);
    EXPECT_EQ(f->posY[i], rows.posY[r]);
    EXPECT_EQ(f->velX[i], rows.velX[r]);
    EXPECT_EQ(f->oriY[i], rows.oriY[r]);
    EXPECT_EQ(f->mode[i], rows.mode[r]);
    const auto info = spatial->agentInfo(rows.id[r]);
    ASSERT_TRUE(info.has_value());
    EXPECT_EQ(info->position.x, rows.posX[r]);
    EXPECT_EQ(info->group, rows.group[r]);
    ++checked;
  }
  EXPECT_EQ(checked, rows.size());
  // And they are the frames of the world that kept its rows by id.
  const FramePtr g = byId->takeFrame();
  EXPECT_EQ(f->ids, g->ids);
  EXPECT_EQ(f->posX, g->posX);
  EXPECT_EQ(f->velY, g->velY);
  EXPECT_EQ(spatial->stateHash(), byId->stateHash());
}

TEST(RowOrder, AgentsRemovedByIdFromSortedRowsAreTheOnesNamed) {
  const io::LoadedScenario s = square();
  auto w = create(s, RowOrder::Spatial);
  core::TaskSystem tasks(2);
  const auto ticks = static_cast<int>(std::lround(kRowSortPeriod / s.desc.dt)) + 1;
  for (int t = 0; t < ticks; ++t) w->step(tasks);
  const AgentColumns rows = w->agentColumns();
  ASSERT_FALSE(std::is_sorted(rows.id.begin(), rows.id.end()));
  // The agents of the first ten rows: ids scattered, not the ten lowest.
  std::vector<std::uint32_t> gone(rows.id.begin(), rows.id.begin() + 10);
  const std::size_t before = rows.size();
  ASSERT_TRUE(w->removeAgents(gone).ok());
  w->step(tasks);
  const FramePtr f = w->takeFrame();
  EXPECT_EQ(f->size(), before - gone.size());
  for (const std::uint32_t id : gone) {
    EXPECT_FALSE(std::binary_search(f->ids.begin(), f->ids.end(), id)) << id;
    EXPECT_FALSE(w->agentInfo(id).has_value()) << id;
  }
  EXPECT_FALSE(w->removeAgents(std::vector<std::uint32_t>{gone.front()}).ok()) << "gone already";
  std::size_t exits = 0;
  for (const Event& e : f->events) exits += e.kind == EventKind::Exit && std::find(gone.begin(), gone.end(), e.agent) != gone.end();
  EXPECT_EQ(exits, gone.size());
}

TEST(RowOrder, AutoSortsFromFiveThousandAgents) {
  // A plain crowd a little over the threshold, and the same crowd a little under it.
  for (const std::uint32_t people : {static_cast<std::uint32_t>(kSpatialRowsMinAgents + 500),
                                     static_cast<std::uint32_t>(kSpatialRowsMinAgents - 500)}) {
    ScenarioDesc d;
    d.seed = 3;
    d.duration = 60.0f;
    d.dt = 0.1f;
    const float side = std::sqrt(static_cast<float>(people)) * 1.2f;
    d.walkable = {{{0, 0}, {side, 0}, {side, side}, {0, side}}};
    PopulationDesc p;
    p.id = "crowd";
    p.groups = people;
    p.sizeMin = p.sizeMax = 1;
    p.spawn.kind = SpawnKind::Polygon;
    p.spawn.polygon = {{0.5f, 0.5f}, {side - 0.5f, 0.5f}, {side - 0.5f, side - 0.5f}, {0.5f, side - 0.5f}};
    p.wander = true;
    d.populations = {p};
    auto created = World::create(d);
    ASSERT_TRUE(created.ok()) << core::formatAll(created.errors());
    World& w = *created.value();
    core::TaskSystem tasks(2);
    for (int t = 0; t < static_cast<int>(std::lround(kRowSortPeriod / d.dt)) + 1; ++t) w.step(tasks);
    const AgentColumns rows = w.agentColumns();
    ASSERT_EQ(rows.size(), people);
    EXPECT_EQ(std::is_sorted(rows.id.begin(), rows.id.end()), people < kSpatialRowsMinAgents) << people << " agents";
  }
}

}  // namespace
}  // namespace throng::sim
