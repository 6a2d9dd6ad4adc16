// Tests for a population's "preMovement" key (libs/io/src/scenario_parser.cpp, readPreMovement):
// every distribution loads into sim::PreMovementDesc, an omitted key means no wait, and each class
// of bad value gives one located diagnostic (JSON pointer, what was expected).
#include <gtest/gtest.h>

#include <string>

#include "scenario_test_util.hpp"

using namespace throng;
using namespace throng::io::test;

namespace {

/// kBottleneck whose population has `"preMovement": <json>`.
std::string withPreMovement(const std::string& json) {
  return edit(kBottleneck, "\"radius\": 0.2}", "\"radius\": 0.2, \"preMovement\": " + json + "}");
}

const std::string kPointer = "/populations/0/preMovement";

}  // namespace

TEST(ScenarioPreMovement, EveryDistributionLoads) {
  auto u = load(withPreMovement(R"({"distribution": "uniform", "min": 10, "max": 100})"));
  ASSERT_TRUE(u.ok()) << core::formatAll(u.errors());
  const sim::PreMovementDesc& pu = u.value().desc.populations[0].preMovement;
  EXPECT_EQ(pu.distribution, sim::PreMovementDistribution::Uniform);
  EXPECT_FLOAT_EQ(pu.min, 10.0f);
  EXPECT_FLOAT_EQ(pu.max, 100.0f);

  auto n = load(withPreMovement(R"({"distribution": "normal", "mean": 30, "sd": 8})"));
  ASSERT_TRUE(n.ok()) << core::formatAll(n.errors());
  const sim::PreMovementDesc& pn = n.value().desc.populations[0].preMovement;
  EXPECT_EQ(pn.distribution, sim::PreMovementDistribution::Normal);
  EXPECT_FLOAT_EQ(pn.mean, 30.0f);
  EXPECT_FLOAT_EQ(pn.sd, 8.0f);

  auto l = load(withPreMovement(R"({"distribution": "lognormal", "mu": 3.4, "sigma": 0.5})"));
  ASSERT_TRUE(l.ok()) << core::formatAll(l.errors());
  const sim::PreMovementDesc& pl = l.value().desc.populations[0].preMovement;
  EXPECT_EQ(pl.distribution, sim::PreMovementDistribution::LogNormal);
  EXPECT_FLOAT_EQ(pl.mu, 3.4f);
  EXPECT_FLOAT_EQ(pl.sigma, 0.5f);
}

TEST(ScenarioPreMovement, OmittedMeansAgentsWalkAtOnce) {
  auto r = load(kBottleneck);
  ASSERT_TRUE(r.ok());
  EXPECT_FALSE(r.value().desc.populations[0].preMovement.enabled());
}

TEST(ScenarioPreMovement, NegativeTimeIsOutOfRange) {
  const std::string text = withPreMovement(R"({"distribution": "uniform", "min": -5, "max": 100})");
  const auto d = at(errorsOf(text), kPointer + "/min");
  expectAt(d, text, "-5");
  EXPECT_EQ(d.what, "value -5 s is out of range");
  EXPECT_EQ(d.expected, "a number from 0 to 1e+06 s");
  const auto sd = at(errorsOf(withPreMovement(R"({"distribution": "normal", "mean": 30, "sd": -1})")), kPointer + "/sd");
  EXPECT_EQ(sd.expected, "a number from 0 to 1e+06 s");
}

TEST(ScenarioPreMovement, MinAboveMaxIsAnError) {
  const auto d = at(errorsOf(withPreMovement(R"({"distribution": "uniform", "min": 50, "max": 10})")), kPointer + "/min");
  EXPECT_EQ(d.what, "min pre-movement time 50 s exceeds max 10 s");
  EXPECT_EQ(d.expected, "min <= max");
}

TEST(ScenarioPreMovement, UnknownDistributionWithDidYouMean) {
  const std::string text = withPreMovement(R"({"distribution": "normel", "mean": 30, "sd": 5})");
  const auto d = at(errorsOf(text), kPointer + "/distribution");
  expectAt(d, text, "\"normel\"");
  EXPECT_EQ(d.what, "unknown pre-movement distribution \"normel\"");
  EXPECT_EQ(d.expected, "\"uniform\", \"normal\" or \"lognormal\"");
  EXPECT_EQ(d.hint, "did you mean \"normal\"?");
}

TEST(ScenarioPreMovement, MissingAndForeignKeys) {
  const auto missing = at(errorsOf(withPreMovement(R"({"distribution": "normal", "mean": 30})")), kPointer);
  EXPECT_EQ(missing.what, "missing required key \"sd\"");
  const auto noDistribution = at(errorsOf(withPreMovement(R"({"min": 10, "max": 100})")), kPointer);
  EXPECT_EQ(noDistribution.what, "missing required key \"distribution\"");
  const auto foreign = at(errorsOf(withPreMovement(R"({"distribution": "normal", "mean": 30, "sd": 5, "max": 60})")),
                          kPointer + "/max");
  EXPECT_EQ(foreign.what, "\"max\" does not belong to a normal distribution");
  EXPECT_EQ(foreign.expected, "the keys of a normal distribution: \"mean\", \"sd\"");
  const auto unknown = at(errorsOf(withPreMovement(R"({"distribution": "uniform", "min": 1, "max": 2, "mode": 1})")),
                          kPointer + "/mode");
  EXPECT_TRUE(contains(unknown.what, "unknown key \"mode\"")) << unknown.format();
  const auto type = at(errorsOf(withPreMovement("30")), kPointer);
  EXPECT_TRUE(contains(type.what, "wrong type")) << type.format();
}
