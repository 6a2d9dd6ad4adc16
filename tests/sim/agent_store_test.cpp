// The agents' published columns (libs/sim/src/agent_store.hpp, World::agentColumns in world.cpp):
// read in place they equal the frame's copy, and with keepRetired a column that grows keeps its old
// buffer alive (the Python module's zero-copy views rely on it) without changing any value.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "agent_store.hpp"
#include "throng/sim/world.hpp"

namespace throng::sim {
namespace {

template <class T>
std::vector<T> copyOf(std::span<const T> s) {
  return {s.begin(), s.end()};
}

ScenarioDesc room(std::uint32_t groups) {
  ScenarioDesc d;
  d.seed = 5;
  d.duration = 60.0f;
  d.walkable = {{{0, 0}, {20, 0}, {20, 8}, {0, 8}}};
  PointDesc exit;
  exit.id = "exit";
  exit.kind = PointKind::Exit;
  exit.polygon = {{19, 0}, {20, 0}, {20, 8}, {19, 8}};
  exit.position = {19.5f, 4};
  d.points = {exit};
  PopulationDesc p;
  p.id = "walkers";
  p.groups = groups;
  p.sizeMin = 1;
  p.sizeMax = 3;
  p.spawn.kind = SpawnKind::Polygon;
  p.spawn.polygon = {{1, 1}, {6, 1}, {6, 7}, {1, 7}};
  p.goals = {0};
  p.radius = 0.2f;
  d.populations = {p};
  return d;
}

/// A crowd of `groups` lone walkers appearing near the start and walking to the world's exit.
CrowdDesc lateCrowd(const ScenarioDesc& world, std::uint32_t groups) {
  CrowdDesc c;
  c.id = "late";
  c.basePoints = static_cast<std::uint32_t>(world.points.size());
  c.basePopulations = static_cast<std::uint32_t>(world.populations.size());
  PopulationDesc p = world.populations[0];
  p.id = "late-walkers";
  p.groups = groups;
  p.sizeMin = p.sizeMax = 1;
  c.populations = {p};
  return c;
}

void expectColumnsEqualFrame(const AgentColumns& c, const Frame& f) {
  ASSERT_EQ(c.size(), f.size());
  EXPECT_EQ(copyOf(c.id), f.ids);
  EXPECT_EQ(copyOf(c.posX), f.posX);
  EXPECT_EQ(copyOf(c.posY), f.posY);
  EXPECT_EQ(copyOf(c.velX), f.velX);
  EXPECT_EQ(copyOf(c.velY), f.velY);
  EXPECT_EQ(copyOf(c.oriX), f.oriX);
  EXPECT_EQ(copyOf(c.oriY), f.oriY);
  EXPECT_EQ(copyOf(c.mode), f.mode);
  EXPECT_EQ(copyOf(c.clip), f.clip);
  EXPECT_EQ(copyOf(c.phase), f.phase);
  EXPECT_TRUE(c.posZ.empty());  // a flat world
  EXPECT_EQ(c.group.size(), c.size());
}

TEST(AgentColumns, EqualTheFrameAtEveryTickWithoutDrainingIt) {
  auto w = std::move(World::create(room(12))).value();
  core::TaskSystem tasks(2);
  for (int t = 0; t < 400; ++t) {
    const AgentColumns c = w->agentColumns();
    const FramePtr f = w->takeFrame();
    expectColumnsEqualFrame(c, *f);
    for (std::size_t i = 0; i < c.size(); ++i) {
      EXPECT_EQ(c.group[i], w->agentInfo(c.id[i])->group);
    }
    w->step(tasks);
  }
  EXPECT_GT(w->stats().exited, 0u) << "agents left and rows were compacted meanwhile";
}

TEST(AgentColumns, ReadingThemDrainsNoEvents) {
  auto w = std::move(World::create(room(12))).value();
  EXPECT_GE(w->agentColumns().size(), 12u);
  const FramePtr f = w->takeFrame();
  EXPECT_EQ(f->events.size(), f->size()) << "every spawn event is still there for the frame";
}

TEST(AgentColumns, GrowingKeepsTheOldBuffersWhenAskedAndChangesNoValue) {
  const ScenarioDesc d = room(4);
  std::uint64_t hashes[2] = {};
  for (const bool keep : {false, true}) {
    auto w = std::move(World::create(d)).value();
    w->keepRetiredColumns(keep);
    core::TaskSystem tasks(1);
    for (int t = 0; t < 10; ++t) w->step(tasks);
    const AgentColumns before = w->agentColumns();
    const std::vector<std::uint32_t> ids = copyOf(before.id);
    const std::vector<float> xs = copyOf(before.posX);
    ASSERT_TRUE(w->insertCrowd(lateCrowd(d, 200)).ok());  // far beyond the capacity reserved at creation
    w->step(tasks);
    const AgentColumns after = w->agentColumns();
    ASSERT_GT(after.size(), ids.size() + 100);
    EXPECT_NE(after.id.data(), before.id.data()) << "the columns grew into new buffers";
    std::vector<std::shared_ptr<const void>> retired = w->takeRetiredColumns();
    if (keep) {
      EXPECT_GE(retired.size(), 11u) << "every published column's old buffer";
      // The old memory is still owned (by the handles) and still holds the tick it was read at.
      EXPECT_EQ(std::vector<std::uint32_t>(before.id.begin(), before.id.end()), ids);
      EXPECT_EQ(std::vector<float>(before.posX.begin(), before.posX.end()), xs);
      EXPECT_TRUE(w->takeRetiredColumns().empty()) << "handed out once";
    } else {
      EXPECT_TRUE(retired.empty());
    }
    for (int t = 0; t < 100; ++t) w->step(tasks);
    expectColumnsEqualFrame(w->agentColumns(), *w->takeFrame());
    hashes[keep ? 1 : 0] = w->stateHash();
  }
  EXPECT_EQ(hashes[0], hashes[1]) << "keeping old buffers changes no trajectory";
}

TEST(AgentStore, RetiringMovesEveryPublishedColumnTogether) {
  AgentStore a;
  a.keepRetired = true;
  for (int i = 0; i < 3; ++i) {
    const std::size_t row = a.addRow();
    a.id[row] = static_cast<std::uint32_t>(i);
    a.posX[row] = static_cast<float>(i) * 0.5f;
  }
  a.retired.clear();
  // Fill to capacity, then one more row: the published columns move, the old buffers are retired.
  while (a.size() < a.minPublishedCapacity()) a.addRow();
  const std::uint32_t* oldIds = a.id.data();
  const float* oldX = a.posX.data();
  const std::size_t n = a.size();
  a.addRow();
  EXPECT_NE(a.id.data(), oldIds);
  EXPECT_EQ(a.retired.size(), 11u);  // id, group, pos, vel, ori, mode, clip, phase (no levels)
  EXPECT_EQ(oldIds[1], 1u);           // still allocated, still the old values
  EXPECT_EQ(oldX[2], 1.0f);
  EXPECT_EQ(a.size(), n + 1);
  EXPECT_EQ(a.id[2], 2u);
  EXPECT_GE(a.minPublishedCapacity(), 2 * n);
  EXPECT_EQ(a.radius.size(), a.size()) << "the other columns grow as usual";
}

TEST(AgentStore, PermuteMovesEveryByteOfEveryColumnToItsNewRow) {
  AgentStore a;
  a.commonGround = true;  // 8-byte interests and the visited lists (moved in place) too
  constexpr std::uint32_t kRows = 7;
  for (std::uint32_t i = 0; i < kRows; ++i) {
    const std::size_t row = a.addRow();
    a.id[row] = 100 + i;                                                  // 4 bytes
    a.groupSize[row] = static_cast<std::uint16_t>(0x1100 + i);           // 2 bytes
    a.lookTurn[row] = static_cast<std::int8_t>(-static_cast<int>(i));    // 1 byte
    a.posX[row] = 0.25f * static_cast<float>(i);
    a.ticket[row] = (std::uint64_t{0xabc0 + i} << 32) | (7 * i);           // 8 bytes: both halves differ
    a.interests[row] = ~std::uint64_t{0} << i;
    a.visited[row] = std::vector<std::uint32_t>(i, i);                   // not trivially copyable
  }
  const std::vector<std::uint32_t> from = {3, 0, 6, 1, 5, 2, 4};  // new row r is old row from[r]
  std::vector<std::uint64_t> keys;
  for (std::uint32_t r = 0; r < kRows; ++r) keys.push_back(std::uint64_t{r} << 32 | from[r]);  // key's low half: the row
  std::vector<std::byte> scratch(4 * kRows);
  a.permute(keys, scratch);
  for (std::uint32_t r = 0; r < kRows; ++r) {
    const std::uint32_t i = from[r];
    EXPECT_EQ(a.id[r], 100 + i);
    EXPECT_EQ(a.groupSize[r], 0x1100 + i);
    EXPECT_EQ(a.lookTurn[r], -static_cast<int>(i));
    EXPECT_EQ(a.posX[r], 0.25f * static_cast<float>(i));
    EXPECT_EQ(a.ticket[r], (std::uint64_t{0xabc0 + i} << 32) | (7 * i)) << "row " << r;
    EXPECT_EQ(a.interests[r], ~std::uint64_t{0} << i);
    EXPECT_EQ(a.visited[r], std::vector<std::uint32_t>(i, i));
  }
}

}  // namespace
}  // namespace throng::sim
