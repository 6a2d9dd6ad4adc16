// Shared by the C API tests: a corridor scenario as JSON text (the Python tests' corridor), owning
// wrappers for the C handles, and every agent column read through the count/capacity protocol.
#pragma once
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "throng/throng.h"

namespace throng::capi_test {

/// A 20 m corridor `width` m wide; n agents walk from its left end to the exit at its right end.
inline std::string corridor(int n = 20, double duration = 30.0, int seed = 3, double width = 4.0) {
  const std::string w = std::to_string(width);
  const std::string inner = std::to_string(width - 0.5);
  return R"({"format": "throng/1", "name": "capi-corridor", "seed": )" + std::to_string(seed) +
         R"(, "duration": )" + std::to_string(duration) + R"(,
    "walkable": [[[0, 0], [20, 0], [20, )" + w + "], [0, " + w + R"(]]],
    "points": [{"id": "exit", "kind": "exit", "polygon": [[19, 0], [20, 0], [20, )" + w + "], [19, " + w + R"(]]}],
    "populations": [{"id": "walkers", "groups": )" + std::to_string(n) + R"(, "size": 1,
      "spawn": {"polygon": [[0.5, 0.5], [6, 0.5], [6, )" + inner + "], [0.5, " + inner + R"(]]},
      "goals": ["exit"], "speed": {"mean": 1.3, "sd": 0.2}, "radius": 0.2}]})";
}

struct ScenarioFree {
  void operator()(throng_scenario* s) const { EXPECT_EQ(throng_scenario_free(s), THRONG_OK); }
};
struct WorldFree {
  void operator()(throng_world* w) const { EXPECT_EQ(throng_world_free(w), THRONG_OK) << throng_last_error(); }
};
using ScenarioPtr = std::unique_ptr<throng_scenario, ScenarioFree>;
using WorldPtr = std::unique_ptr<throng_world, WorldFree>;

inline ScenarioPtr loadJson(const std::string& json) {
  throng_scenario* s = nullptr;
  EXPECT_EQ(throng_scenario_load_json(json.c_str(), "capi-test.json", &s, nullptr), THRONG_OK) << throng_last_error();
  return ScenarioPtr(s);
}

inline WorldPtr makeWorld(const throng_scenario* s, int threads = 1, const uint64_t* seed = nullptr) {
  throng_world_options o = throng_world_options_default();
  o.threads = threads;
  if (seed != nullptr) o.seed = *seed, o.use_seed = 1;
  throng_world* w = nullptr;
  EXPECT_EQ(throng_world_create(s, &o, &w), THRONG_OK) << throng_last_error();
  return WorldPtr(w);
}

/// Every column of the agents present, read with the count/capacity protocol.
struct Agents {
  std::vector<uint32_t> ids, groups;
  std::vector<float> positions, heights, velocities, headings, phases;
  std::vector<uint8_t> modes;
  std::vector<uint16_t> clips;
  [[nodiscard]] std::size_t size() const { return ids.size(); }
  [[nodiscard]] float x(std::size_t i) const { return positions[2 * i]; }
  [[nodiscard]] float y(std::size_t i) const { return positions[2 * i + 1]; }
};

inline Agents readAgents(throng_world* w) {
  Agents a;
  throng_agent_arrays arrays{};
  std::size_t count = 0;
  const throng_status first = throng_world_agents(w, &arrays, &count);
  EXPECT_TRUE(first == THRONG_OK || first == THRONG_ERROR_BUFFER_TOO_SMALL) << throng_status_name(first);
  a.ids.resize(count), a.groups.resize(count), a.positions.resize(2 * count), a.heights.resize(count);
  a.velocities.resize(2 * count), a.headings.resize(2 * count), a.phases.resize(count), a.modes.resize(count);
  a.clips.resize(count);
  arrays = throng_agent_arrays{count,          a.ids.data(),        a.positions.data(), a.heights.data(),
                               a.velocities.data(), a.headings.data(), a.groups.data(),    a.modes.data(),
                               a.clips.data(),  a.phases.data()};
  std::size_t again = 0;
  EXPECT_EQ(throng_world_agents(w, &arrays, &again), THRONG_OK) << throng_last_error();
  EXPECT_EQ(again, count);
  return a;
}

inline throng_world_stats stats(throng_world* w) {
  throng_world_stats s{};
  EXPECT_EQ(throng_world_stats_get(w, &s), THRONG_OK) << throng_last_error();
  return s;
}

/// Every pending event, drained in batches of `batch`.
inline std::vector<throng_event> drainEvents(throng_world* w, std::size_t batch = 7) {
  std::vector<throng_event> all;
  std::vector<throng_event> buffer(batch);
  std::size_t n = 0;
  do {
    EXPECT_EQ(throng_world_events(w, buffer.data(), buffer.size(), &n), THRONG_OK) << throng_last_error();
    all.insert(all.end(), buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(n));
  } while (n > 0);
  return all;
}

}  // namespace throng::capi_test
