// One seed, the same trajectories, whatever the thread count — with the work really split.
//
// The default chunk is 256 agents (1,024 from 4,096 on), so a world of a few dozen agents runs as
// one chunk on one thread however many threads it is given. These tests cap the chunk size
// (TaskSystem::setGrainLimit) so that every parallel phase — sense, decide, group shapes, steer,
// integrate, the neighbour grid — cuts the crowd into at least as many chunks as there are
// threads, then compare 1, 2 and 8 threads tick by tick: the state hash after every tick, every
// event, and (Common Ground) every action-script line. Together they cover flocking groups,
// following and guided groups, action points, Common Ground coordinations, and crowds inserted and
// removed at run time (a scenario timeline and World::insertCrowd/removeCrowd between ticks).
#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "throng/core/simd.hpp"
#include "throng/io/scenario_loader.hpp"
#include "throng/sim/world.hpp"

namespace throng::sim {
namespace {

struct Trace {
  std::vector<std::uint64_t> hashes;  ///< stateHash() after every tick
  std::vector<Event> events;          ///< every event, in order
  std::vector<std::uint64_t> script;  ///< Common Ground action-script entries (agent, seq, start, clip) folded
  std::size_t mostAgents = 0;         ///< the largest crowd seen
  std::size_t splitTicks = 0;         ///< ticks whose crowd was cut into at least 8 chunks
};

using Hook = std::function<void(World&, int tick)>;

Trace run(const io::LoadedScenario& s, int threads, std::size_t grainLimit, int ticks, const Hook& hook = {},
          RowOrder order = RowOrder::Auto) {
  Trace t;
  ScenarioDesc desc = s.desc;
  desc.rowOrder = order;
  auto created = World::create(desc, s.navmesh);
  EXPECT_TRUE(created.ok());
  if (!created.ok()) return t;
  World& w = *created.value();
  core::TaskSystem tasks(threads);
  tasks.setGrainLimit(grainLimit);
  for (int i = 0; i < ticks && !w.finished(); ++i) {
    if (hook) hook(w, i);
    w.step(tasks);
    t.hashes.push_back(w.stateHash());
    const auto f = w.takeFrame();
    t.events.insert(t.events.end(), f->events.begin(), f->events.end());
    for (const ScriptRecord& r : f->script) {
      std::uint64_t bits = 0;
      static_assert(sizeof bits == sizeof r.start);
      std::memcpy(&bits, &r.start, sizeof bits);
      t.script.push_back((std::uint64_t{r.agent} << 32 | r.seq) ^ bits ^ std::hash<std::string>{}(r.motion));
    }
    const std::size_t n = f->ids.size();
    t.mostAgents = std::max(t.mostAgents, n);
    if (core::TaskSystem::chunkCount(n, tasks.grain(256)) >= 8) ++t.splitTicks;
  }
  return t;
}

io::LoadedScenario load(const std::string& name) {
  auto loaded = io::loadScenarioFile(std::string(THRONG_SOURCE_DIR) + "/scenarios/" + name + ".json");
  EXPECT_TRUE(loaded.ok()) << (loaded.ok() ? "" : core::formatAll(loaded.errors()));
  return std::move(loaded).value();
}

/// Runs at 1, 2 and 8 threads with chunks of at most `grainLimit` agents; all three must agree on
/// every tick. `one` receives the single-thread trace for the caller's own checks.
void expectSameAcrossThreads(Trace& one, const io::LoadedScenario& s, std::size_t grainLimit, int ticks,
                             const Hook& hook = {}, RowOrder order = RowOrder::Auto) {
  one = run(s, 1, grainLimit, ticks, hook, order);
  for (int threads : {2, 8}) {
    const Trace many = run(s, threads, grainLimit, ticks, hook, order);
    ASSERT_EQ(one.hashes.size(), many.hashes.size()) << threads << " threads";
    for (std::size_t i = 0; i < one.hashes.size(); ++i) {
      ASSERT_EQ(one.hashes[i], many.hashes[i]) << "trajectories differ at tick " << i + 1 << " between 1 and "
                                               << threads << " threads";
    }
    ASSERT_EQ(one.events.size(), many.events.size()) << threads << " threads";
    for (std::size_t i = 0; i < one.events.size(); ++i) {
      EXPECT_EQ(one.events[i].tick, many.events[i].tick) << "event " << i;
      EXPECT_EQ(one.events[i].agent, many.events[i].agent) << "event " << i;
      EXPECT_EQ(one.events[i].kind, many.events[i].kind) << "event " << i;
      EXPECT_EQ(one.events[i].a, many.events[i].a) << "event " << i;
      EXPECT_EQ(one.events[i].b, many.events[i].b) << "event " << i;
    }
    EXPECT_EQ(one.script, many.script) << threads << " threads";
  }
  // The premise: most ticks cut the crowd into at least 8 chunks, so 8 threads all had work.
  EXPECT_GE(one.splitTicks * 10, one.hashes.size() * 9)
      << "only " << one.splitTicks << " of " << one.hashes.size() << " ticks were split into 8 chunks or more ("
      << one.mostAgents << " agents at most)";
}

std::size_t count(const Trace& t, EventKind kind) {
  std::size_t n = 0;
  for (const Event& e : t.events) n += e.kind == kind ? 1 : 0;
  return n;
}

TEST(Determinism, GroupsFollowingAndActionPointsAcrossThreads) {
  // The museum: a school class, a family, couples, friends, wanderers, a guided tour, solo visitors
  // (flocking groups, a followed guide, interest and action points) — about 50 agents in chunks of 1.
  const io::LoadedScenario s = load("museum");
  Trace t;
  ASSERT_NO_FATAL_FAILURE(expectSameAcrossThreads(t, s, 1, 1200));
  EXPECT_GE(t.mostAgents, 20u);
  EXPECT_GT(count(t, EventKind::ActionStart), 0u) << "action points were used within 60 s";
}

/// museum_tour's timeline inserts a guided tour at 20 s and removes it at 60 s; on top, the hook
/// inserts the same crowd again through World::insertCrowd at tick 500 (under another id) and
/// removes it at tick 1100, between ticks, as a server or a link host would.
Hook tourAgain(const io::LoadedScenario& s) {
  CrowdDesc again = s.desc.timeline.front().crowd;
  again.id = "tour-again";
  for (auto& p : again.points) p.id += "-again";
  for (auto& p : again.populations) p.id += "-again";
  return [again](World& w, int tick) {
    if (tick == 500) ASSERT_TRUE(w.insertCrowd(again).ok());
    if (tick == 1100) ASSERT_TRUE(w.removeCrowd("tour-again"));
  };
}

TEST(Determinism, CrowdsInsertedAndRemovedAtRunTimeAcrossThreads) {
  const io::LoadedScenario s = load("museum_tour");
  ASSERT_FALSE(s.desc.timeline.empty());
  ASSERT_EQ(s.desc.timeline.front().action, TimelineAction::Insert);
  Trace t;
  ASSERT_NO_FATAL_FAILURE(expectSameAcrossThreads(t, s, 1, 1400, tourAgain(s)));
  EXPECT_GE(t.mostAgents, 16u) << "the inserted crowds were there";
}

TEST(Determinism, RowsSortedSpatiallyAcrossThreads) {
  // The same, rows sorted along the Hilbert curve every 2 s (ScenarioDesc::rowOrder): rows move
  // while crowds come and go, and 1, 2 and 8 threads still agree tick by tick.
  const io::LoadedScenario s = load("museum_tour");
  Trace t;
  ASSERT_NO_FATAL_FAILURE(expectSameAcrossThreads(t, s, 1, 1400, tourAgain(s), RowOrder::Spatial));
  EXPECT_GE(t.mostAgents, 16u);
}

TEST(Determinism, CommonGroundAcrossThreads) {
  // The mall (Park et al., Common Ground on) for its first 40 s (about 300 of its 1000 characters
  // have arrived) in chunks of 2: coordinations start, scripts are written, agents leave for shops
  // and restrooms.
  const io::LoadedScenario s = load("mall");
  ASSERT_TRUE(s.desc.social.commonGround);
  Trace t;
  ASSERT_NO_FATAL_FAILURE(expectSameAcrossThreads(t, s, 2, 800));
  EXPECT_GE(t.mostAgents, 250u);
  EXPECT_GE(count(t, EventKind::CoordinationStart), 1u) << "Common Ground was at work";
  EXPECT_FALSE(t.script.empty());
}

/// The first tick at which two traces differ (their length when they agree).
std::size_t firstDifference(const Trace& a, const Trace& b) {
  std::size_t i = 0;
  while (i < a.hashes.size() && i < b.hashes.size() && a.hashes[i] == b.hashes[i]) ++i;
  return i;
}

TEST(Determinism, RowsSortedSpatiallyGiveTheSameTrajectoriesAsRowsInIdOrder) {
  // What depends on the order of agents is done in id order (path requests under the budget, the
  // targets drawn from a region's free spots) or summed exactly (avm's crowd grid), so sorting the
  // rows changes no trajectory: flocking groups and action points (museum), Common Ground (mall),
  // avm at a door (bottleneck), exits (evacuation), crossing flows (plaza), crowds inserted and
  // removed at run time (museum_tour), 60 s each (stateHash hashes by ascending id).
  for (const char* name : {"museum", "mall", "bottleneck", "evacuation", "plaza", "museum_tour"}) {
    const io::LoadedScenario s = load(name);
    const Hook hook = std::string(name) == "museum_tour" ? tourAgain(s) : Hook{};
    const Trace byId = run(s, 1, 256, 1200, hook, RowOrder::Id);
    const Trace spatial = run(s, 1, 256, 1200, hook, RowOrder::Spatial);
    EXPECT_EQ(firstDifference(byId, spatial), byId.hashes.size()) << name;
    EXPECT_EQ(byId.events.size(), spatial.events.size()) << name;
  }
}

TEST(Determinism, EverySimdPathGivesTheSameTrajectories) {
  // The neighbour search, ORCA's half-planes and the avm's velocities have an AVX2 path beside the
  // portable one (core::simdPath()); both give the same bits, so the same trajectories: ORCA and the avm at a
  // door (bottleneck, both models), crossing flows (crossing, ORCA), 30 s each on 2 threads.
  std::vector<core::SimdPath> paths{core::SimdPath::Portable};
  if (core::simdSupported(core::SimdPath::Avx2)) paths.push_back(core::SimdPath::Avx2);
  const core::SimdPath before = core::simdPath();
  for (const char* name : {"bottleneck", "crossing"}) {
    for (ModelKind model : {ModelKind::Orca, ModelKind::AnticipationVelocity}) {
      io::LoadedScenario s = load(name);
      for (PopulationDesc& pop : s.desc.populations) pop.model = ModelDesc(model);
      std::vector<Trace> traces;
      for (core::SimdPath path : paths) {
        ASSERT_TRUE(core::setSimdPath(path));
        traces.push_back(run(s, 2, 64, 600));
      }
      core::setSimdPath(before);
      ASSERT_GT(traces[0].mostAgents, 50u) << name;
      for (std::size_t p = 1; p < traces.size(); ++p) {
        EXPECT_EQ(firstDifference(traces[0], traces[p]), traces[0].hashes.size())
            << name << " (" << static_cast<int>(model) << "): " << core::simdPathName(paths[p]) << " differs from portable";
      }
    }
  }
}

}  // namespace
}  // namespace throng::sim
