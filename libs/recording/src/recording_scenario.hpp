// throng::recording recording scenario tables — the scenario's points and populations as rows of
// `throng_points` and `throng_populations`, and each population's avoidance model as JSON text for
// the metadata, written once when a recording is created.
#pragma once
#include <sqlite3.h>

#include <string>

#include "throng/sim/scenario.hpp"

namespace throng::recording {

/// Inserts one row per point and per population (inside the caller's transaction). Returns
/// SQLite's message on failure, an empty string on success.
[[nodiscard]] std::string writeScenarioTables(sqlite3* db, const sim::ScenarioDesc& scenario);

/// The metadata value throng_models: {"<population id>": {"name": "<model>", "<parameter>": value, …}, …}.
[[nodiscard]] std::string modelsJson(const sim::ScenarioDesc& scenario);

}  // namespace throng::recording
