// Common Ground inside the World (libs/sim/src/social.cpp): the goal generator, coordinations
// planned and played as action scripts, lone visits when Common Ground is off, reunions after a
// divide, determinism across thread counts, and a property test over random layouts: every
// coordination ends, nobody stays in a script forever, groups that divide and wait reunite.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <string>

#include "throng/core/rng.hpp"
#include "throng/io/scenario_loader.hpp"
#include "throng/sim/world.hpp"

namespace throng::sim {
namespace {

/// A scenario text: a corridor with a shop room and a restroom room off it, an exit at the end.
std::string scenarioText(std::uint64_t seed, int groups, int sizeMin, int sizeMax, double restroomRate,
                         double attraction, bool commonGround, double duration = 400.0, double shopX = 24.0,
                         double restroomX = 43.0) {
  const auto n = [](double v) { return std::to_string(v); };
  return R"({"format": "throng/1", "name": "social-test", "seed": )" + std::to_string(seed) +
         R"(, "duration": )" + n(duration) + R"(,
  "walkable": [[[0,0],[60,0],[60,10],[0,10]],
               [[)" + n(shopX - 4) + R"(,10],[)" + n(shopX + 4) + R"(,10],[)" + n(shopX + 4) + R"(,20],[)" + n(shopX - 4) + R"(,20]],
               [[)" + n(restroomX - 3) + R"(,10],[)" + n(restroomX + 3) + R"(,10],[)" + n(restroomX + 3) + R"(,16],[)" + n(restroomX - 3) + R"(,16]]],
  "points": [
    {"id": "shop", "kind": "interest", "position": [)" + n(shopX) + R"(, 13], "radius": 2, "category": "shoes"},
    {"id": "wc", "kind": "interest", "position": [)" + n(restroomX) + R"(, 13], "radius": 1.5, "category": "restroom"},
    {"id": "out", "kind": "exit", "polygon": [[58,0],[60,0],[60,10],[58,10]]}],
  "populations": [
    {"id": "families", "groups": )" + std::to_string(groups) + R"(, "size": [)" + std::to_string(sizeMin) + "," +
         std::to_string(sizeMax) + R"(], "spawn": {"polygon": [[1,1],[10,1],[10,9],[1,9]]},
     "goals": ["out"], "speed": {"mean": 1.2, "sd": 0.1}, "interests": ["shoes"], "interestsPerAgent": 1}],
  "social": {"commonGround": )" + (commonGround ? std::string("true") : std::string("false")) + R"(,
             "needs": [{"category": "restroom", "rate": )" + n(restroomRate) + R"(, "expectedVisit": 60}],
             "attraction": {"probability": )" + n(attraction) + R"(, "expectedVisit": 60},
             "cooldown": 1000}})";
}

std::unique_ptr<World> makeWorld(const std::string& text) {
  // The source names a file in scenarios/ so that "motions" resolves to scenarios/motions.
  auto loaded = io::parseScenario(text, std::string(THRONG_SOURCE_DIR) + "/scenarios/social-test.json");
  if (!loaded.ok()) {
    ADD_FAILURE() << loaded.errors().front().format();
    return nullptr;
  }
  auto world = World::create(loaded.value().desc, loaded.value().navmesh);
  EXPECT_TRUE(world.ok());
  return world.ok() ? std::move(world).value() : nullptr;
}

struct Outcome {
  std::vector<Event> events;
  std::vector<ScriptRecord> script;
  std::vector<CoordinationRecord> coordinations;
  std::uint64_t hash = 0;
  bool finished = false;
};

Outcome run(World& w, double seconds, int threads = 1) {
  core::TaskSystem tasks(threads);
  Outcome out;
  while (w.stats().time < seconds && !w.finished()) {
    w.step(tasks);
    const auto f = w.takeFrame();
    out.events.insert(out.events.end(), f->events.begin(), f->events.end());
    out.script.insert(out.script.end(), f->script.begin(), f->script.end());
    out.coordinations.insert(out.coordinations.end(), f->coordinations.begin(), f->coordinations.end());
  }
  out.hash = w.stateHash();
  out.finished = w.finished();
  return out;
}

std::size_t count(const Outcome& r, EventKind kind) {
  return static_cast<std::size_t>(std::count_if(r.events.begin(), r.events.end(), [&](const Event& e) { return e.kind == kind; }));
}

TEST(SocialWorld, RestroomNeedIsGroundedAndPlayedAsScripts) {
  auto w = makeWorld(scenarioText(3, 2, 3, 3, 0.05, 0.0, true));
  ASSERT_TRUE(w);
  const Outcome r = run(*w, 400.0);
  EXPECT_TRUE(r.finished) << "everybody exits in the end";
  ASSERT_GE(r.coordinations.size(), 1u);
  EXPECT_EQ(count(r, EventKind::CoordinationStart), count(r, EventKind::CoordinationEnd));
  EXPECT_EQ(count(r, EventKind::CoordinationStart), r.coordinations.size());
  for (const CoordinationRecord& c : r.coordinations) {
    EXPECT_EQ(c.trigger, GoalTrigger::Need);
    EXPECT_EQ(c.respondents.size(), 2u) << "B and one companion in a group of three";
    EXPECT_NE(c.outcome, CoordinationOutcome::Alone);
    EXPECT_GE(c.relation, 1);
    EXPECT_LE(c.relation, 6);
    EXPECT_LE(c.start, c.executeTime);
    EXPECT_LE(c.executeTime, c.end);
    // Every actor's entries: in sequence, never overlapping, never before the plan said.
    std::map<std::uint32_t, std::vector<const ScriptRecord*>> byAgent;
    for (const ScriptRecord& s : r.script) {
      if (s.coordination == c.id) byAgent[s.agent].push_back(&s);
    }
    EXPECT_EQ(byAgent.size(), 3u);
    bool grounding = false;
    for (const auto& [agent, entries] : byAgent) {
      for (std::size_t i = 0; i < entries.size(); ++i) {
        EXPECT_EQ(entries[i]->seq, i);
        EXPECT_GE(entries[i]->start + 1e-6, entries[i]->plannedStart) << entries[i]->behaviour;
        EXPECT_GE(entries[i]->duration, 0.0);
        if (i > 0) EXPECT_GE(entries[i]->start + 1e-6, entries[i - 1]->start + entries[i - 1]->duration);
        grounding = grounding || entries[i]->step < 7;
      }
    }
    EXPECT_TRUE(grounding) << "steps 1-6 were played before the plan";
  }
  // The initiator really went there: a visit started and ended at the restroom.
  EXPECT_GE(count(r, EventKind::VisitStart), 1u);
  EXPECT_EQ(count(r, EventKind::VisitStart), count(r, EventKind::VisitEnd));
}

TEST(SocialWorld, CommonGroundOffGivesLoneVisitsWithoutGrounding) {
  auto w = makeWorld(scenarioText(3, 2, 3, 3, 0.05, 0.0, false));
  ASSERT_TRUE(w);
  const Outcome r = run(*w, 400.0);
  ASSERT_GE(r.coordinations.size(), 1u);
  for (const CoordinationRecord& c : r.coordinations) {
    EXPECT_EQ(c.outcome, CoordinationOutcome::Alone);
    EXPECT_TRUE(c.respondents.empty());
  }
  for (const ScriptRecord& s : r.script) EXPECT_EQ(s.step, 7) << s.behaviour;
}

TEST(SocialWorld, SeeingAnInterestingStoreMakesAnAttractionGoal) {
  // No needs; every agent is interested in shoes and always tempted: the shop is seen through its
  // doorway on the way to the exit.
  auto w = makeWorld(scenarioText(5, 1, 2, 2, 0.0, 1.0, true));
  ASSERT_TRUE(w);
  const Outcome r = run(*w, 400.0);
  ASSERT_GE(r.coordinations.size(), 1u);
  const CoordinationRecord& c = r.coordinations.front();
  EXPECT_EQ(c.trigger, GoalTrigger::Attraction);
  EXPECT_EQ(c.goalPoint, 0u) << "the shop";
  EXPECT_EQ(c.goalKind, 1) << "both members like shoes: a shared goal";
  EXPECT_EQ(c.plan, 2) << "a shared goal nearby: detour together";
}

TEST(SocialWorld, DeterministicAcrossThreadCounts) {
  const std::string text = scenarioText(11, 6, 2, 6, 0.02, 0.3, true, 200.0);
  auto w1 = makeWorld(text);
  auto w2 = makeWorld(text);
  ASSERT_TRUE(w1 && w2);
  const Outcome a = run(*w1, 200.0, 1);
  const Outcome b = run(*w2, 200.0, 2);
  EXPECT_EQ(a.hash, b.hash);
  ASSERT_EQ(a.script.size(), b.script.size());
  for (std::size_t i = 0; i < a.script.size(); ++i) {
    EXPECT_EQ(a.script[i].agent, b.script[i].agent);
    EXPECT_EQ(a.script[i].behaviour, b.script[i].behaviour);
    EXPECT_EQ(a.script[i].start, b.script[i].start);
  }
  EXPECT_GE(a.coordinations.size(), 1u);
}

TEST(SocialWorld, PropertyEveryCoordinationEndsAndDividedGroupsReunite) {
  // Random layouts (shop and restroom positions), group sizes, rates and Common Ground on or off.
  std::size_t coordinations = 0, waits = 0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    core::Rng rng(seed, 0, core::RngPurpose::Bench);
    const int sizeMax = static_cast<int>(rng.uniformInt(2, 6));
    const double shopX = rng.uniform(10.0, 30.0), restroomX = rng.uniform(36.0, 50.0);
    const bool cg = seed % 4 != 0;
    auto w = makeWorld(scenarioText(seed, 3, 2, sizeMax, rng.uniform(0.005, 0.05), rng.uniform(0.0, 1.0), cg, 900.0,
                                    shopX, restroomX));
    ASSERT_TRUE(w);
    const Outcome r = run(*w, 900.0);
    EXPECT_TRUE(r.finished) << "seed " << seed << ": everybody left in the end (nobody waits forever)";
    EXPECT_EQ(count(r, EventKind::CoordinationStart), r.coordinations.size()) << "seed " << seed << ": every coordination ended";
    std::set<std::uint32_t> reunited;
    for (const Event& e : r.events) {
      if (e.kind == EventKind::Reunited) reunited.insert(e.b);
    }
    for (const CoordinationRecord& c : r.coordinations) {
      ++coordinations;
      // Bounded: the planned script plus its walks' overruns stay under the safety deadline.
      EXPECT_LT(c.end - c.start, 600.0) << "seed " << seed;
      if (c.plan == 1 && c.outcome == CoordinationOutcome::Grounded) {  // divide and wait
        ++waits;
        EXPECT_TRUE(reunited.count(c.id)) << "seed " << seed << ": group of coordination " << c.id << " reunited";
      }
    }
  }
  EXPECT_GE(coordinations, 8u);
  EXPECT_GE(waits, 1u);
}

}  // namespace
}  // namespace throng::sim

namespace throng::sim {
namespace {

TEST(SocialWorld, MallIsDeterministicAcrossThreadCounts) {
  // The paper's experiment (scenarios/mall.json, 1000 characters): the first 100 s, 1 vs 2 threads.
  auto loaded = io::loadScenarioFile(std::string(THRONG_SOURCE_DIR) + "/scenarios/mall.json");
  ASSERT_TRUE(loaded.ok()) << loaded.errors().front().format();
  ASSERT_TRUE(loaded.value().desc.social.enabled);
  ASSERT_TRUE(loaded.value().desc.social.commonGround);
  auto w1 = World::create(loaded.value().desc, loaded.value().navmesh);
  auto w2 = World::create(loaded.value().desc, loaded.value().navmesh);
  ASSERT_TRUE(w1.ok() && w2.ok());
  const Outcome a = run(*w1.value(), 100.0, 1);
  const Outcome b = run(*w2.value(), 100.0, 2);
  EXPECT_EQ(a.hash, b.hash);
  EXPECT_EQ(a.events.size(), b.events.size());
  ASSERT_EQ(a.script.size(), b.script.size());
  for (std::size_t i = 0; i < a.script.size(); ++i) {
    EXPECT_EQ(a.script[i].agent, b.script[i].agent);
    EXPECT_EQ(a.script[i].start, b.script[i].start);
  }
  EXPECT_GE(count(a, EventKind::CoordinationStart), 5u) << "Common Ground is at work within 100 s";
}

}  // namespace
}  // namespace throng::sim

#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "throng/sim/animation.hpp"

namespace throng::sim {
namespace {

TEST(SocialWorld, AddingAMicroBehaviourIsEditingData) {
  // A user adds "shout" (a new clip) to a copy of the database, as docs/social-coordination.md says:
  // one JSON entry plus one BVH file; the scenario names its database. No code changes.
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("throng-add-behaviour-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "motions");
  const fs::path source = fs::path(THRONG_SOURCE_DIR);
  for (const auto& entry : fs::directory_iterator(source / "scenarios" / "motions")) {
    fs::copy_file(entry.path(), dir / "motions" / entry.path().filename());
  }
  fs::copy_file(source / "scenarios" / "motions" / "call_out.bvh", dir / "motions" / "shout.bvh");
  std::ifstream in(source / "data" / "social" / "micro_behaviours.json");
  std::stringstream text;
  text << in.rdbuf();
  std::string db = text.str();
  const std::string anchor = "\"behaviours\": [";
  const auto at = db.find(anchor);
  ASSERT_NE(at, std::string::npos);
  db.insert(at + anchor.size(), R"(
    {"name": "shout", "intents": ["request_attention"], "allowedIn": ["A1", "A2", "A4", "A5"], "clip": "shout",
     "target": "partner", "turnFirst": true, "responses": ["turn_toward"], "weight": 1000,
     "description": "a loud call, added by a user"},)");
  std::ofstream(dir / "micro.json") << db;
  std::string scenario = scenarioText(3, 2, 3, 3, 0.05, 0.0, true);
  scenario.replace(scenario.find("\"cooldown\": 1000"), 16, "\"cooldown\": 1000, \"microBehaviours\": \"micro.json\"");
  std::ofstream(dir / "s.json") << scenario;

  auto loaded = io::loadScenarioFile((dir / "s.json").string());
  ASSERT_TRUE(loaded.ok()) << loaded.errors().front().format();
  ASSERT_TRUE(loaded.value().desc.social.clipLengths.count("shout"));
  const double shoutLength = loaded.value().desc.social.clipLengths.at("shout");
  const auto clips = animationClips(loaded.value().desc);
  EXPECT_TRUE(std::any_of(clips.begin(), clips.end(), [](const ClipInfo& c) { return c.name == "shout"; }))
      << "the viewer gets the new clip in the recording's clip table";
  auto world = World::create(loaded.value().desc, loaded.value().navmesh);
  ASSERT_TRUE(world.ok());
  const Outcome r = run(*world.value(), 400.0);
  std::size_t shouts = 0;
  for (const ScriptRecord& s : r.script) {
    if (s.behaviour != "shout" || s.motion != "shout") continue;
    ++shouts;
    EXPECT_NEAR(s.plannedDuration, shoutLength, 1e-9) << "its clip's length times the script";
    EXPECT_EQ(s.step, 2);
  }
  EXPECT_GE(shouts, 1u);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace throng::sim
