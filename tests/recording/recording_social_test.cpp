// Tests for the Common Ground part of recordings: the recorder's throng_coordinations /
// throng_script tables, point categories and metadata (libs/recording/src/recorder.cpp), the
// readers and metrics of throng/recording/recording_social.hpp (recording_social.cpp,
// metrics_queries.cpp, metrics_analysis.cpp) on the hand-built fixture of
// social_recording_fixture.hpp, and their diagnostics on old or bad files.
#include <gtest/gtest.h>
#include <sqlite3.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "temp_dir.hpp"
#include "social_recording_fixture.hpp"
#include "throng/recording/recording_social.hpp"

namespace throng::recording {
namespace {

namespace fs = std::filesystem;

using throng::test::TempDir;

/// Runs SQL on a file (read-write) and returns the first column of every row as text.
std::vector<std::string> sql(const std::string& path, const std::string& query) {
  sqlite3* db = nullptr;
  std::vector<std::string> out;
  EXPECT_EQ(sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READWRITE, nullptr), SQLITE_OK);
  sqlite3_stmt* s = nullptr;
  if (sqlite3_prepare_v2(db, query.c_str(), -1, &s, nullptr) != SQLITE_OK) {
    ADD_FAILURE() << query << ": " << sqlite3_errmsg(db);
  } else {
    int rc = 0;
    while ((rc = sqlite3_step(s)) == SQLITE_ROW) {
      const auto* t = sqlite3_column_text(s, 0);
      out.emplace_back(t ? reinterpret_cast<const char*>(t) : "NULL");
    }
    EXPECT_EQ(rc, SQLITE_DONE) << query << ": " << sqlite3_errmsg(db);
  }
  sqlite3_finalize(s);
  sqlite3_close(db);
  return out;
}

class SocialRecording : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = dir_.file("cg.sqlite");
    ASSERT_EQ(testing::writeSocialRecording(path_), "");
  }
  TempDir dir_;
  std::string path_;
};

TEST_F(SocialRecording, RecorderWritesCoordinationsScriptCategoriesAndMetadata) {
  EXPECT_EQ(sql(path_, "SELECT id || '|' || group_id || '|' || initiator || '|' || respondents || '|' || goal_point || '|' || "
                       "goal_kind || '|' || trigger || '|' || coalesce(relation, 'NULL') || '|' || plan || '|' || outcome || "
                       "'|' || retries || '|' || start || '|' || execute || '|' || end_time FROM throng_coordinations ORDER BY id"),
            (std::vector<std::string>{"1|7|0|1|0|personal|need|A3|divide_and_wait|grounded|1|0.0|2.5|10.0",
                                      "2|8|2||1|personal|attraction|NULL|divide_and_proceed|alone|0|3.0|3.0|5.0",
                                      "3|7|1|0|1|shared|attraction|A6|resume|failed|3|1.0|4.0|4.5"}));
  EXPECT_EQ(sql(path_, "SELECT role || ' ' || step || ' ' || part || ' ' || plan || ' ' || motion || ' ' || behaviour || ' ' || "
                       "target_type || ' ' || coalesce(target_agent, '-') || ' ' || coalesce(target_x, '-') FROM throng_script "
                       "WHERE coordination = 1 AND agent = 0 ORDER BY seq LIMIT 2"),
            (std::vector<std::string>{"initiator 1 0 divide_and_wait walk move_into_view point - 4.0",
                                      "initiator 2 0 divide_and_wait wave wave agent 1 5.0"}));
  EXPECT_EQ(sql(path_, "SELECT count(*) FROM throng_script"), std::vector<std::string>{"10"});
  EXPECT_EQ(sql(path_, "SELECT count(*) FROM sqlite_master WHERE name = 'throng_script_agent_idx'"),
            std::vector<std::string>{"1"});
  EXPECT_EQ(sql(path_, "SELECT coalesce(category, 'NULL') FROM throng_points ORDER BY idx"),
            (std::vector<std::string>{"restroom", "shoes", "NULL"}));
  EXPECT_EQ(sql(path_, "SELECT value FROM metadata WHERE key = 'throng_common_ground'"), std::vector<std::string>{"on"});
  EXPECT_EQ(sql(path_, "SELECT kind FROM throng_events WHERE kind NOT IN ('spawn', 'exit') ORDER BY rowid"),
            (std::vector<std::string>{"goal_generated", "goal_generated", "visit_start", "visit_start", "reunited"}));
  // Old readers still work.
  const auto summary = readRecordingSummary(path_);
  ASSERT_TRUE(summary.ok()) << core::formatAll(summary.errors());
  EXPECT_EQ(summary->frames, 5u);
}

TEST_F(SocialRecording, CoordinationsAndScriptsReadBack) {
  const auto coordinations = readCoordinations(path_);
  ASSERT_TRUE(coordinations.ok()) << core::formatAll(coordinations.errors());
  ASSERT_EQ(coordinations->size(), 3u);
  const CoordinationInfo& c = coordinations.value()[0];
  EXPECT_EQ(c.id, 1u);
  EXPECT_EQ(c.respondents, std::vector<std::uint32_t>{1});
  EXPECT_EQ(c.goalPointId, "wc");
  EXPECT_EQ(c.goalCategory, "restroom");
  EXPECT_EQ(c.relation, "A3");
  EXPECT_EQ(c.plan, "divide_and_wait");
  EXPECT_EQ(c.outcome, "grounded");
  EXPECT_DOUBLE_EQ(c.execute, 2.5);
  EXPECT_EQ(coordinations.value()[1].relation, "");
  EXPECT_TRUE(coordinations.value()[1].respondents.empty());

  const auto mine = readScript(path_, 1);
  ASSERT_TRUE(mine.ok()) << core::formatAll(mine.errors());
  ASSERT_EQ(mine->size(), 4u);
  for (std::size_t i = 0; i < mine->size(); ++i) EXPECT_EQ(mine.value()[i].seq, i);
  EXPECT_EQ(mine.value()[0].behaviour, "turn_toward");
  EXPECT_EQ(mine.value()[0].targetAgent, std::optional<std::uint32_t>(0));
  EXPECT_TRUE(std::isnan(mine.value()[1].targetX));  // no target
  EXPECT_DOUBLE_EQ(mine.value()[0].start, 1.6);

  const auto all = readCoordinationScript(path_, 1);
  ASSERT_TRUE(all.ok()) << core::formatAll(all.errors());
  ASSERT_EQ(all->size(), 10u);
  std::vector<std::string> steps;
  for (const auto& e : all.value()) steps.push_back(scriptStepLabel(e.step, e.part, e.attempt));
  EXPECT_EQ(steps, (std::vector<std::string>{"1", "2", "3", "4a", "5a", "4b", "5b", "6", "7", "7"}));
  EXPECT_EQ(scriptStepLabel(2, 0, 1), "2/retry 1");
}

TEST_F(SocialRecording, AgentTrackHasTimesAndCentralDifferenceVelocity) {
  const auto track = readAgentTrack(path_, 1);
  ASSERT_TRUE(track.ok()) << core::formatAll(track.errors());
  EXPECT_TRUE(track->known);
  EXPECT_EQ(track->group, std::optional<std::uint32_t>(7));
  ASSERT_EQ(track->samples.size(), 4u);
  EXPECT_NEAR(track->samples[3].time, 0.3, 1e-12);
  EXPECT_NEAR(track->samples[1].vy, 0.0, 1e-9);
  EXPECT_NEAR(track->samples[2].vy, 35.0, 1e-6);  // (13 - 6) / 0.2 s
  EXPECT_NEAR(track->samples[3].vy, 70.0, 1e-6);  // one-sided at the end
  EXPECT_DOUBLE_EQ(track->samples[0].oriY, 1.0);
  const auto nobody = readAgentTrack(path_, 99);
  ASSERT_TRUE(nobody.ok());
  EXPECT_FALSE(nobody->known);
}

TEST_F(SocialRecording, MetricsHaveTheKnownAnswers) {
  MetricsOptions o;
  o.radius = 2.0;
  o.bin = 0.25;
  std::vector<double> progress;
  o.progress = [&](double f) { progress.push_back(f); };
  const auto m = computeMetrics(path_, o);
  ASSERT_TRUE(m.ok()) << core::formatAll(m.errors());
  EXPECT_EQ(m->commonGround, "on");
  EXPECT_EQ(m->frames, 5u);
  EXPECT_NEAR(m->duration, 0.4, 1e-12);
  ASSERT_FALSE(progress.empty());
  EXPECT_DOUBLE_EQ(progress.back(), 1.0);

  // (a) arrivals: wc at t = 0 (bin 0), shoes at t = 0.3 and the exit at t = 0.4 (bin 1).
  EXPECT_EQ(m->categories, (std::vector<std::string>{"restroom", "shoes"}));
  ASSERT_EQ(m->arrivals.size(), 2u);
  EXPECT_EQ(m->arrivals[0].visits, 1u);
  EXPECT_EQ(m->arrivals[0].byCategory.at("restroom"), 1u);
  EXPECT_EQ(m->arrivals[1].byCategory.at("shoes"), 1u);
  EXPECT_EQ(m->arrivals[1].exits, 1u);
  EXPECT_EQ(m->visits, 2u);
  EXPECT_NEAR(m->visitsPerMinute, 2.0 / (0.4 / 60.0), 1e-9);

  // (b) congestion: wc has 2, 2, 2, 1, 0 agents within 2 m; shoes 1, 1, 1, 1, 0.
  const double area = std::numbers::pi * 4.0;
  ASSERT_EQ(m->congestion.size(), 2u);
  EXPECT_EQ(m->congestion[0].category, "restroom");
  EXPECT_EQ(m->congestion[0].samples, 5u);
  EXPECT_NEAR(m->congestion[0].mean, 1.4 / area, 1e-12);
  EXPECT_NEAR(m->congestion[0].p95, 2.0 / area, 1e-12);
  EXPECT_NEAR(m->congestion[0].max, 2.0 / area, 1e-12);
  EXPECT_NEAR(m->congestion[1].mean, 0.8 / area, 1e-12);
  EXPECT_NEAR(m->congestion[1].max, 1.0 / area, 1e-12);
  ASSERT_EQ(m->worstPoints.size(), 2u);
  EXPECT_EQ(m->worstPoints[0].point, "wc");

  // (c) cohesion: group 7 is 0.5 m from its centroid in 3 frames, 4 m in one.
  EXPECT_EQ(m->cohesion.groupFrames, 4u);
  EXPECT_EQ(m->cohesion.groups, 1u);
  EXPECT_NEAR(m->cohesion.meanDistance, (3 * 0.5 + 4.0) / 4.0, 1e-6);
  EXPECT_NEAR(m->cohesion.shareTogether, 0.75, 1e-12);

  // (d) coordinations.
  const CoordinationStats& c = m->coordinations;
  EXPECT_EQ(c.total, 3u);
  EXPECT_EQ(c.byOutcome, (std::map<std::string, std::uint64_t>{{"alone", 1}, {"failed", 1}, {"grounded", 1}}));
  EXPECT_EQ(c.byRelation, (std::map<std::string, std::uint64_t>{{"A3", 1}, {"A6", 1}, {"none", 1}}));
  EXPECT_EQ(c.byTrigger, (std::map<std::string, std::uint64_t>{{"attraction", 2}, {"need", 1}}));
  EXPECT_EQ(c.byPlan.at("divide_and_wait"), 1u);
  EXPECT_EQ(c.microBehaviours.at("nod"), 2u);
  EXPECT_EQ(c.microBehaviours.at("wave"), 1u);
  EXPECT_EQ(c.microBehaviours.count("walk_to_goal"), 0u);
  EXPECT_EQ(c.groundingSamples, 2u);
  EXPECT_DOUBLE_EQ(c.meanGrounding, 2.75);
  EXPECT_DOUBLE_EQ(c.maxGrounding, 3.0);
  EXPECT_EQ(c.divideSamples, 1u);
  EXPECT_DOUBLE_EQ(c.meanDivide, 7.5);
  EXPECT_EQ(c.reunited, 1u);
  EXPECT_EQ(c.goalsGenerated, 2u);
}

TEST_F(SocialRecording, OldFileWithoutTheTablesSaysSo) {
  sql(path_, "DROP TABLE throng_script");
  sql(path_, "DROP TABLE throng_coordinations");
  const auto has = hasCommonGroundData(path_);
  ASSERT_TRUE(has.ok());
  EXPECT_FALSE(has.value());
  for (const core::Diagnostics& errors :
       {readCoordinations(path_).errors(), readScript(path_, 0).errors(), computeMetrics(path_).errors()}) {
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_NE(errors[0].format().find("no Common Ground data in " + path_), std::string::npos) << errors[0].format();
  }
  EXPECT_TRUE(readRecordingSummary(path_).ok());
}

TEST_F(SocialRecording, BadRowsAreNamed) {
  sql(path_, "UPDATE throng_coordinations SET outcome = 'bogus' WHERE id = 3");
  sql(path_, "UPDATE throng_script SET role = 'villain' WHERE agent = 1 AND seq = 2");
  const auto c = readCoordinations(path_);
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.errors()[0].format(),
            path_ + ": throng_coordinations id 3: outcome 'bogus'; expected grounded, failed or alone");
  const auto s = readScript(path_, 1);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.errors()[0].what.find("throng_script row"), std::string::npos);
  EXPECT_NE(s.errors()[0].what.find("role 'villain'"), std::string::npos);
  EXPECT_FALSE(computeMetrics(path_).ok());
}

TEST(SocialReaders, ForeignFilesAndBadOptions) {
  TempDir dir;
  const std::string junk = dir.file("junk.sqlite");
  { std::FILE* f = std::fopen(junk.c_str(), "wb"); std::fputs("not a database at all, just text\n", f); std::fclose(f); }
  const auto r = readCoordinations(junk);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.errors()[0].source, junk);
  EXPECT_FALSE(readCoordinations(dir.file("missing.sqlite")).ok());
  MetricsOptions o;
  o.radius = -1.0;
  o.bin = 0.0;
  const auto m = computeMetrics(junk, o);
  ASSERT_FALSE(m.ok());
  EXPECT_EQ(m.errors().size(), 2u);
}

}  // namespace
}  // namespace throng::recording
