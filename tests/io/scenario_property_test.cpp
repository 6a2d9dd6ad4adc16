// Property tests for libs/io scenario loading (RapidCheck): a scenario with random polygons
// (random vertices, often self-intersecting or degenerate) either loads or is rejected with
// located diagnostics, and never crashes or throws.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cstdio>

#include "scenario_test_util.hpp"

using namespace throng;

namespace {

std::string polygonJson(const std::vector<std::pair<int, int>>& pts) {
  std::string s = "[";
  for (std::size_t i = 0; i < pts.size(); ++i) {
    char buf[64];
    // Coordinates in decimetres keep many collinear and coincident cases.
    std::snprintf(buf, sizeof buf, "%s[%g,%g]", i ? "," : "", pts[i].first / 10.0, pts[i].second / 10.0);
    s += buf;
  }
  return s + "]";
}

rc::Gen<std::vector<std::pair<int, int>>> genPolygon() {
  return rc::gen::container<std::vector<std::pair<int, int>>>(
      rc::gen::pair(rc::gen::inRange(-20, 220), rc::gen::inRange(-20, 220)));
}

}  // namespace

RC_GTEST_PROP(ScenarioProperty, RandomPolygonsLoadOrDiagnose, ()) {
  const auto walk = *genPolygon();
  const auto obstacle = *genPolygon();
  const auto spawn = *genPolygon();
  const bool reachability = *rc::gen::inRange(0, 4) == 0;
  const std::string text = std::string(R"({"format": "throng/1", "walkable": [)") + polygonJson(walk) +
                           R"(], "obstacles": [)" + polygonJson(obstacle) + R"(],
    "points": [{"id": "g", "kind": "exit", "polygon": )" + polygonJson(walk) + R"(}],
    "populations": [{"groups": 3, "spawn": {"polygon": )" + polygonJson(spawn) + R"(}, "goals": ["g"]}]})";
  auto r = io::parseScenario(text, "p.json", io::LoadOptions{reachability});
  if (r.ok()) {
    RC_ASSERT(r->desc.walkable.size() == 1u);
    RC_ASSERT(r->desc.walkable[0].size() >= 3u);
    RC_ASSERT(!core::findSelfIntersection(r->desc.walkable[0]).has_value());
    RC_ASSERT(r->desc.populations[0].goals.size() == 1u);
  } else {
    RC_ASSERT(!r.errors().empty());
    for (const auto& d : r.errors()) {
      RC_ASSERT(d.source == "p.json");
      RC_ASSERT(d.line >= 1);
      RC_ASSERT(d.column >= 1);
      RC_ASSERT(!d.what.empty());
    }
  }
}

RC_GTEST_PROP(ScenarioProperty, ArbitraryTextNeverThrows, (const std::string& junk)) {
  const std::string texts[] = {junk, std::string(io::test::kBottleneck).substr(0, junk.size() % 700) + junk};
  for (const auto& text : texts) {
    auto r = io::parseScenario(text, "j.json", io::LoadOptions{false});
    if (!r.ok()) RC_ASSERT(!r.errors().empty());
  }
}
