// Tests for libs/io/src/scenario_model_parser.cpp (a population's "model") and the steering keys of
// the preferred velocity, and for the JSON Schema's agreement with the core's model catalogue.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "scenario_test_util.hpp"
#include "throng/sim/models.hpp"

using namespace throng;
using namespace throng::io::test;

namespace {

std::string withModel(const std::string& model) {
  return edit(kBottleneck, "\"radius\": 0.2}", "\"radius\": 0.2, \"model\": " + model + "}");
}

}  // namespace

TEST(ScenarioModel, NoModelMeansTheCalibratedModelWithItsDefaults) {
  auto r = load(kBottleneck);
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  const sim::ModelDesc& m = r->desc.populations[0].model;
  EXPECT_EQ(m.kind, sim::ModelKind::AnticipationVelocity);
  EXPECT_FLOAT_EQ(m.value("timeGap"), 0.9f);
  EXPECT_FLOAT_EQ(m.value("passageRatio"), 0.65f);
}

TEST(ScenarioModel, ANameOrAnObjectWithParameters) {
  auto r = load(withModel("\"cfsm\""));
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  EXPECT_EQ(r->desc.populations[0].model.kind, sim::ModelKind::CollisionFreeSpeed);
  EXPECT_FLOAT_EQ(r->desc.populations[0].model.value("timeGap"), 1.0f);

  r = load(withModel(R"({"name": "cfsm", "timeGap": 0.8, "neighbourRange": 0.15})"));
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  const sim::ModelDesc& m = r->desc.populations[0].model;
  EXPECT_EQ(m.kind, sim::ModelKind::CollisionFreeSpeed);
  EXPECT_FLOAT_EQ(m.value("timeGap"), 0.8f);
  EXPECT_FLOAT_EQ(m.value("neighbourRange"), 0.15f);
  EXPECT_FLOAT_EQ(m.value("neighbourStrength"), 8.0f) << "parameters not given keep their defaults";

  r = load(withModel(R"({"name": "orca", "yieldResponsibility": 0.5, "lodNeighbours": 6})"));
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  EXPECT_FLOAT_EQ(r->desc.populations[0].model.value("yieldResponsibility"), 0.5f);
  EXPECT_FLOAT_EQ(r->desc.populations[0].model.value("lodNeighbours"), 6.0f);
}

TEST(ScenarioModel, UnknownModelGetsDidYouMean) {
  const std::string text = withModel("\"ocra\"");
  const auto ds = errorsOf(text);
  const core::Diagnostic d = at(ds, "/populations/0/model");
  expectAt(d, text, "\"ocra\"");
  EXPECT_EQ(d.what, "unknown model \"ocra\"");
  EXPECT_TRUE(contains(d.expected, "\"orca\", \"cfsm\" or \"avm\"")) << d.format();
  EXPECT_EQ(d.hint, "did you mean \"orca\"?");
}

TEST(ScenarioModel, AParameterOfAnotherModelIsNamedAsSuch) {
  const std::string text = withModel(R"({"name": "orca", "timeGap": 1.2})");
  const auto ds = errorsOf(text);
  const core::Diagnostic d = at(ds, "/populations/0/model/timeGap");
  expectAt(d, text, "\"timeGap\"");
  EXPECT_EQ(d.what, "parameter \"timeGap\" belongs to model \"cfsm\", not \"orca\"");
  EXPECT_EQ(d.expected, "one of: yieldResponsibility, lodNeighbours, wallMargin (the parameters of \"orca\")");
  EXPECT_EQ(d.hint, "set \"name\": \"cfsm\" to use it");
}

TEST(ScenarioModel, ParametersOutOfRangeOrMisspeltOrMissingName) {
  auto ds = errorsOf(withModel(R"({"name": "cfsm", "timeGap": 0})"));
  core::Diagnostic d = at(ds, "/populations/0/model/timeGap");
  EXPECT_EQ(d.what, "value 0 s is out of range");
  EXPECT_EQ(d.expected, "a number > 0 and <= 10 s");

  ds = errorsOf(withModel(R"({"name": "orca", "lodNeighbours": 2.5})"));
  d = at(ds, "/populations/0/model/lodNeighbours");
  EXPECT_TRUE(contains(d.what, "not a whole number")) << d.format();

  ds = errorsOf(withModel(R"({"name": "cfsm", "timegap": 1})"));
  d = at(ds, "/populations/0/model/timegap");
  EXPECT_EQ(d.what, "unknown parameter \"timegap\" of model \"cfsm\"");
  EXPECT_EQ(d.hint, "did you mean \"timeGap\"?");

  ds = errorsOf(withModel(R"({"timeGap": 1})"));
  d = at(ds, "/populations/0/model");
  EXPECT_EQ(d.what, "missing required key \"name\"");

  ds = errorsOf(withModel("3"));
  d = at(ds, "/populations/0/model");
  EXPECT_EQ(d.what, "wrong type: an integer");
}

TEST(ScenarioModel, SteeringKeysOfThePreferredVelocity) {
  auto r = load(edit(kBottleneck, "\"duration\": 300,",
                     "\"duration\": 300, \"steering\": {\"cornerReach\": 0.4, \"levelLookAhead\": 5, \"arrivalTime\": 1, "
                     "\"formationSpeedUp\": 1.5, \"stuckPatience\": 2, \"stuckAttempt\": 0.5},"));
  ASSERT_TRUE(r.ok()) << core::formatAll(r.errors());
  const sim::SteeringDesc& s = r->desc.steering;
  EXPECT_FLOAT_EQ(s.cornerReach, 0.4f);
  EXPECT_EQ(s.levelLookAhead, 5u);
  EXPECT_FLOAT_EQ(s.arrivalTime, 1.0f);
  EXPECT_FLOAT_EQ(s.formationSpeedUp, 1.5f);
  EXPECT_FLOAT_EQ(s.stuckPatience, 2.0f);
  EXPECT_FLOAT_EQ(s.stuckAttempt, 0.5f);
  const auto ds = errorsOf(edit(kBottleneck, "\"duration\": 300,", "\"duration\": 300, \"steering\": {\"formationSpeedUp\": 0.5},"));
  EXPECT_EQ(at(ds, "/steering/formationSpeedUp").expected, "a number from 1 to 3");
}

// The schema is written by hand for editors; it must say what the catalogue says.
TEST(ScenarioModel, TheSchemaDescribesEveryModelAsTheCatalogueDoes) {
  std::ifstream in(std::string(THRONG_SOURCE_DIR) + "/scenarios/schema/scenario.schema.json");
  ASSERT_TRUE(in) << "scenarios/schema/scenario.schema.json";
  const nlohmann::json schema = nlohmann::json::parse(in);
  const nlohmann::json& oneOf = schema.at("/$defs/model/oneOf"_json_pointer);
  ASSERT_EQ(oneOf.size(), sim::kModelCount + 1);
  std::vector<std::string> names;
  for (const sim::ModelInfo& m : sim::modelCatalogue()) names.emplace_back(m.name);
  EXPECT_EQ(oneOf[0].at("enum").get<std::vector<std::string>>(), names);
  for (std::size_t k = 0; k < sim::kModelCount; ++k) {
    const sim::ModelInfo& m = sim::modelCatalogue()[k];
    const nlohmann::json& props = oneOf[k + 1].at("properties");
    EXPECT_EQ(props.at("name").at("const"), std::string(m.name));
    EXPECT_EQ(props.size(), m.parameters.size() + 1) << m.name << ": parameters in the schema";
    for (const sim::ModelParameter& p : m.parameters) {
      SCOPED_TRACE(std::string(m.name) + "." + std::string(p.key));
      ASSERT_TRUE(props.contains(std::string(p.key)));
      const nlohmann::json& q = props.at(std::string(p.key));
      EXPECT_EQ(q.at("type"), p.integer ? "integer" : "number");
      EXPECT_DOUBLE_EQ(q.value(p.minExclusive ? "exclusiveMinimum" : "minimum", -1.0), p.min);
      EXPECT_DOUBLE_EQ(q.at("maximum").get<double>(), p.max);
      EXPECT_FLOAT_EQ(q.at("default").get<float>(), p.defaultValue);
    }
  }
  EXPECT_TRUE(schema.at("/$defs/population/properties"_json_pointer).contains("model"));
}

// Issue 17: `throng check` accepts a 0.5 m door for the default body, whose model (avm) lets people
// turn their shoulders (passageRatio), and for ORCA's hard discs it refuses it naming the real
// narrowest opening of the navmesh (0.5 m for r = 0.2 m: the radius rounded up to whole cells plus
// one cell), not 2 × radius.
TEST(ScenarioModel, AHalfMetreDoorIsOpenToTheDefaultBodyWithShouldersTurned) {
  std::string door = edit(kBottleneck, "[[9,0],[10,0],[10,4.5],[9,4.5]], [[9,5.5],[10,5.5],[10,10],[9,10]]",
                                "[[9,0],[10,0],[10,4.75],[9,4.75]], [[9,5.25],[10,5.25],[10,10],[9,10]]");
  door = edit(edit(door, R"({"id": "gap",  "kind": "interest", "position": [9.5, 5], "radius": 0.5},)", ""),
              R"("goals": ["gap", "exit"])", R"("goals": ["exit"])");
  const auto byDefault = load(door, true);
  EXPECT_TRUE(byDefault.ok()) << core::formatAll(byDefault.errors());
  const auto ds = errorsOf(edit(door, "\"radius\": 0.2}", "\"radius\": 0.2, \"model\": \"orca\"}"), true);
  const auto d = at(ds, "/populations/0/goals/0");
  EXPECT_TRUE(contains(d.expected, "at least 0.5 m wide")) << d.format();
}
