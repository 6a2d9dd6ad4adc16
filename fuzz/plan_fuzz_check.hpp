// Shared by the floor plan fuzz targets (dxf_fuzz.cpp, wkt_fuzz.cpp): arbitrary bytes → importPlan,
// then the result checked: a refusal has located diagnostics; a fragment has its three arrays and,
// wrapped into a scenario with no populations, loads without a complaint about any polygon or wall
// (the importer checks them as the loader does).
#pragma once
#include <cstdlib>
#include <string>
#include <string_view>

#include "throng/io/plan_import.hpp"
#include "throng/io/scenario_loader.hpp"

namespace throng::fuzz {

inline void check(bool condition) {
  if (!condition) std::abort();
}

inline void checkPlan(std::string_view text, io::PlanFormat format) {
  io::PlanImportOptions options;
  options.arcSegments = 8;  // small shapes: more inputs per second
  const auto r = io::importPlan(text, format, "fuzz.plan", options);
  if (!r.ok()) {
    check(!r.errors().empty());
    for (const auto& d : r.errors()) check(d.source == "fuzz.plan" && !d.what.empty() && !d.expected.empty() && d.line >= 0);
    return;
  }
  const nlohmann::json& f = r.value();
  check(f.size() == 3 && f["walkable"].is_array() && !f["walkable"].empty() && f["obstacles"].is_array() && f["walls"].is_array());
  if (text.size() > 4096) return;  // the loader's polygon union grows with the plan
  nlohmann::json scenario = f;
  scenario["format"] = "throng/1";
  scenario["populations"] = nlohmann::json::array();
  const auto loaded = io::parseScenario(scenario.dump(), "fragment.json", io::LoadOptions{false});
  if (loaded.ok()) return;
  for (const auto& d : loaded.errors()) {
    for (const char* key : {"/walkable/", "/obstacles/", "/walls/"}) check(d.pointer.rfind(key, 0) != 0);
  }
}

}  // namespace throng::fuzz
