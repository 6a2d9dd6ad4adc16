// `throng run` on a scenario with a timeline (scenarios/museum_tour.json): the tour group of
// scenarios/crowds/tour.json arrives at 20 s and leaves at 60 s; the recording shows it; the run
// is the same for 1 and 2 threads; a bad crowd file stops the run with its own file:line:column.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "sqlite_query.hpp"

namespace throng::e2e {
namespace {

const std::filesystem::path kScenario = std::filesystem::path(THRONG_SOURCE_DIR) / "scenarios" / "museum_tour.json";

TEST(Timeline, TourGroupArrivesAndLeaves) {
  ScratchDir dir("timeline");
  std::string hashes[2];
  for (int t = 1; t <= 2; ++t) {
    const std::string out = "tour" + std::to_string(t) + ".sqlite";
    const CliResult r = runThrong({"run", kScenario.string(), "--out", out, "--threads", std::to_string(t), "--json", "-q"}, dir.path());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto summary = nlohmann::json::parse(r.out);
    EXPECT_EQ(summary["agents_spawned"].get<int>(), summary["agents_active"].get<int>() + 8);
    hashes[t - 1] = summary["state_hash"].get<std::string>();
    // The 8 tourists: spawned at 20 s (tick 400), left at 60 s (tick 1200), population 1.
    const auto rows = queryText(dir / out, "SELECT count(*), min(population), max(population) FROM throng_agents WHERE population = 1");
    ASSERT_EQ(rows.size(), 1u);
    EXPECT_EQ(rows[0][0], "8");
    const auto events = queryText(dir / out, "SELECT kind, count(*), min(tick), max(tick) FROM throng_events WHERE agent >= "
                                          "(SELECT min(id) FROM throng_agents WHERE population = 1) AND kind IN ('spawn', 'exit') "
                                          "GROUP BY kind ORDER BY kind");
    ASSERT_EQ(events.size(), 2u);
    EXPECT_EQ(events[0], (std::vector<std::string>{"exit", "8", "1200", "1200"}));
    EXPECT_EQ(events[1], (std::vector<std::string>{"spawn", "8", "400", "400"}));
  }
  EXPECT_EQ(hashes[0], hashes[1]);
}

TEST(Timeline, ABadCrowdFileIsReportedInItsOwnFile) {
  ScratchDir dir("timeline-bad");
  std::string scenario = readFile(kScenario);
  const std::string clip = "\"clip\": \"motions/look.bvh\", ";
  ASSERT_NE(scenario.find(clip), std::string::npos);
  scenario.erase(scenario.find(clip), clip.size());
  dir.write("s.json", scenario);
  std::filesystem::create_directories(dir / "crowds");
  dir.write("crowds/tour.json", "{\n  \"format\": \"throng-crowd/1\",\n  \"id\": \"tour-group\",\n  \"populations\": [{\"id\": \"tour\", \"spawn\": {\"point\": \"entrace\"}}]\n}\n");
  const CliResult r = runThrong({"run", "s.json", "--out", "x.sqlite"}, dir.path());
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("crowds/tour.json:4:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("unknown point \"entrace\""), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("did you mean \"entrance\"?"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "x.sqlite"));
}

}  // namespace
}  // namespace throng::e2e
