// Tests for libs/sim/src/partition.cpp: the steer phase split between copies of one world
// (partition.hpp) gives the same trajectories as one world alone, bit for bit. Every build checks
// it, MPI or not: the "ranks" here are threads in one process, each stepping its own World, joined
// by an in-memory StepExchange (a barrier and shared buffers) that behaves like MPI_Allgatherv.
#include "throng/sim/partition.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <barrier>
#include <filesystem>
#include <memory>
#include <thread>

#include "throng/io/scenario_loader.hpp"
#include "throng/sim/world.hpp"

namespace fs = std::filesystem;
using namespace throng;

namespace {

/// The shared side of the in-process exchange: one block per rank, two barriers per gather.
class LocalGroup {
 public:
  explicit LocalGroup(std::uint32_t ranks) : blocks_(ranks), barrier_(static_cast<std::ptrdiff_t>(ranks)) {}
  [[nodiscard]] std::uint32_t ranks() const { return static_cast<std::uint32_t>(blocks_.size()); }
  void gather(std::uint32_t rank, std::span<const std::byte> mine, std::span<const std::size_t> sizes,
              std::vector<std::byte>& all) {
    blocks_[rank].assign(mine.begin(), mine.end());
    barrier_.arrive_and_wait();  // every block written
    all.clear();
    for (std::size_t r = 0; r < blocks_.size(); ++r) {
      EXPECT_EQ(blocks_[r].size(), sizes[r]) << "rank " << rank << " expected another size from rank " << r;
      all.insert(all.end(), blocks_[r].begin(), blocks_[r].end());
    }
    barrier_.arrive_and_wait();  // every block read before anyone writes the next
  }

 private:
  std::vector<std::vector<std::byte>> blocks_;
  std::barrier<> barrier_;
};

class LocalExchange final : public sim::StepExchange {
 public:
  LocalExchange(LocalGroup& group, std::uint32_t rank) : group_(group), rank_(rank) {}
  [[nodiscard]] std::uint32_t ranks() const override { return group_.ranks(); }
  [[nodiscard]] std::uint32_t rank() const override { return rank_; }
  void allGather(std::span<const std::byte> mine, std::span<const std::size_t> sizes, std::vector<std::byte>& all) override {
    group_.gather(rank_, mine, sizes, all);
  }

 private:
  LocalGroup& group_;
  std::uint32_t rank_;
};

/// A bundled scenario; with `model` set, every population walks with that model.
std::unique_ptr<sim::World> load(const std::string& scenario, const std::string& model = "") {
  const std::string path = (fs::path(THRONG_SOURCE_DIR) / "scenarios" / (scenario + ".json")).string();
  auto loaded = io::loadScenarioFile(path);
  if (loaded.ok() && !model.empty()) {
    auto doc = nlohmann::json::parse(loaded->text);
    for (auto& pop : doc["populations"]) pop["model"] = model;
    loaded = io::parseScenario(doc.dump(), path);
  }
  EXPECT_TRUE(loaded.ok()) << (loaded.ok() ? "" : core::formatAll(loaded.errors()));
  if (!loaded.ok()) return nullptr;
  auto created = sim::World::create(loaded->desc, loaded->navmesh);
  EXPECT_TRUE(created.ok());
  return created.ok() ? std::move(created.value()) : nullptr;
}

/// State hash after every tick, plus the events' count (frames carry the events).
struct Trace {
  std::vector<std::uint64_t> hashes;
  std::size_t events = 0;
  sim::PartitionStats partition;
};

Trace runAlone(const std::string& scenario, int ticks, const std::string& model = "") {
  Trace t;
  auto w = load(scenario, model);
  if (!w) return t;
  core::TaskSystem tasks(1);
  for (int i = 0; i < ticks; ++i) {
    w->step(tasks);
    t.hashes.push_back(w->stateHash());
    t.events += w->takeFrame()->events.size();
  }
  return t;
}

std::vector<Trace> runRanks(const std::string& scenario, int ticks, std::uint32_t ranks, int threadsPerRank,
                            std::uint32_t rebalanceTicks, const std::string& model = "") {
  LocalGroup group(ranks);
  std::vector<std::unique_ptr<sim::World>> worlds;
  std::vector<std::unique_ptr<LocalExchange>> exchanges;
  for (std::uint32_t r = 0; r < ranks; ++r) {
    worlds.push_back(load(scenario, model));
    if (!worlds.back()) return {};
    exchanges.push_back(std::make_unique<LocalExchange>(group, r));
    worlds.back()->setPartition(exchanges.back().get(), {rebalanceTicks});
  }
  std::vector<Trace> traces(ranks);
  std::vector<std::thread> threads;
  for (std::uint32_t r = 0; r < ranks; ++r) {
    threads.emplace_back([&, r] {
      core::TaskSystem tasks(threadsPerRank);
      for (int i = 0; i < ticks; ++i) {
        worlds[r]->step(tasks);
        traces[r].hashes.push_back(worlds[r]->stateHash());
        traces[r].events += worlds[r]->takeFrame()->events.size();
      }
      traces[r].partition = worlds[r]->partitionStats();
    });
  }
  for (auto& t : threads) t.join();
  return traces;
}

void expectSame(const std::string& scenario, int ticks, std::uint32_t ranks, int threadsPerRank,
                std::uint32_t rebalanceTicks = 20, const std::string& model = "") {
  const Trace alone = runAlone(scenario, ticks, model);
  const std::vector<Trace> split = runRanks(scenario, ticks, ranks, threadsPerRank, rebalanceTicks, model);
  ASSERT_EQ(split.size(), ranks);
  std::uint64_t owned = 0;
  for (std::uint32_t r = 0; r < ranks; ++r) {
    const Trace& t = split[r];
    ASSERT_EQ(t.hashes.size(), alone.hashes.size());
    for (std::size_t i = 0; i < t.hashes.size(); ++i) {
      ASSERT_EQ(t.hashes[i], alone.hashes[i]) << scenario << ": rank " << r << " of " << ranks << " differs at tick " << i + 1;
    }
    EXPECT_EQ(t.events, alone.events);
    const sim::PartitionStats& p = t.partition;
    EXPECT_EQ(p.ranks, ranks);
    EXPECT_EQ(p.ticks, static_cast<std::uint64_t>(ticks));
    // Every rank received every agent-step's record once (its own included).
    EXPECT_EQ(p.gatheredBytes, p.agentSteps * sim::kSteerRecordBytes);
    EXPECT_EQ(p.sentBytes, p.ownedAgentSteps * sim::kSteerRecordBytes);
    EXPECT_GT(p.ownedAgentSteps, 0u) << "rank " << r << " steered nobody";
    EXPECT_EQ(p.migrations, split[0].partition.migrations);  // every rank counts the same
    owned += p.ownedAgentSteps;
  }
  EXPECT_EQ(owned, split[0].partition.agentSteps);  // each agent-step steered by exactly one rank
}

}  // namespace

TEST(Partition, BottleneckTwoRanksMatchesOneProcess) {
  expectSame("bottleneck", 400, 2, 1);
}

TEST(Partition, BottleneckCountsMigrations) {
  // The crowd walks toward the door along x: agents cross the cut between the two strips.
  const std::vector<Trace> split = runRanks("bottleneck", 300, 2, 1, 1000000);
  ASSERT_EQ(split.size(), 2u);
  EXPECT_GT(split[0].partition.migrations, 0u);
  EXPECT_EQ(split[0].partition.rebalanceMoves, 0u);  // the cuts were chosen once, at the first tick
}

TEST(Partition, MuseumGroupsThreeRanksTwoThreadsMatchesOneProcess) {
  // Groups (flocking, a guided tour, waiting): the serial group pass runs on every rank.
  expectSame("museum", 300, 3, 2, 7);
}

TEST(Partition, CrossingRebalancedEveryTickMatchesOneProcess) {
  expectSame("crossing", 300, 2, 2, 1);
}

TEST(Partition, CrossingWithTheAnticipationModelMatchesOneProcess) {
  // The anticipation model reads what its neighbours wanted a tick ago (ModelInput::priorDesiredX/Y): the same on
  // every rank, whichever rank steers them.
  expectSame("crossing", 300, 3, 2, 1, "avm");
}

TEST(Partition, ExitChoiceThreeRanksTwoThreadsMatchesOneProcess) {
  // Exit choice (exit_choice.cpp) runs on every rank; its queue lookups in parallel within each.
  // 700 ticks: past the east exit's closing at 30 s.
  expectSame("exit_choice", 700, 3, 2, 5);
}

TEST(Partition, AtriumLiftsAndEscalatorsTwoRanksTwoThreadsMatchesOneProcess) {
  // Lifts and escalators (vertical_transport.cpp) run serially on every rank; 316 people, so two threads
  // each get rows. 2400 ticks: through the queues, the lift's trips and most rides.
  expectSame("atrium", 2400, 2, 2, 7);
}

TEST(Partition, MallCommonGroundTwoRanksMatchesOneProcess) {
  // Common Ground coordinations and action scripts (social.cpp) on top of groups.
  expectSame("mall", 120, 2, 1);
}
