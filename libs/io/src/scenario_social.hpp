// throng::io scenario social loading — for a scenario with a "social" section: the micro-behaviour
// and macro-plan databases (the files it names, relative to the scenario, or the built-in ones)
// and the length of every clip the micro-behaviours play (<motions>/<clip>.bvh). Reads those
// files; writes ScenarioDesc::social and diagnostics (the databases' own file:line:column, or the
// scenario's /social pointer for a missing file). Private to throng_io.
#pragma once
#include "json_document.hpp"
#include "scenario_parser.hpp"

namespace throng::io {

void loadScenarioSocial(const JsonDocument& doc, ParsedScenario& parsed, core::Diagnostics& diagnostics);

}  // namespace throng::io
