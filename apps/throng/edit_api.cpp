// `throng edit`'s API work (edit_api.hpp): check, preview and save a scenario text (formatted and
// written by io's scenario writer), and import a floor plan (io::importPlan).
#include "edit_api.hpp"

#include <fmt/format.h>

#include <cmath>

#include "output.hpp"
#include "throng/core/parallel.hpp"
#include "throng/core/text.hpp"
#include "throng/io/plan_import.hpp"
#include "throng/io/scenario_loader.hpp"
#include "throng/io/scenario_writer.hpp"
#include "throng/sim/world.hpp"

namespace throng::cli::edit {
namespace {
namespace fs = std::filesystem;
using ordered_json = nlohmann::ordered_json;

std::string jsonText(const nlohmann::json& value) { return dumpJson(value); }

/// The one-line message of a diagnostic, without its source and position.
std::string messageOf(const core::Diagnostic& d) {
  std::string text = d.what;
  if (!d.expected.empty()) text += "; expected " + d.expected;
  if (!d.hint.empty()) text += " (" + d.hint + ")";
  return text;
}

/// Diagnostics of a load, the interruption replaced by what stopped it.
core::Diagnostics loadProblems(core::Diagnostics diagnostics, const std::atomic<int>& cancel,
                               const std::atomic<bool>& timedOut, double limitSeconds) {
  if (cancel.load() == 0) return diagnostics;
  core::Diagnostic d;
  d.what = timedOut.load() ? fmt::format("stopped after the time limit of {:g} s", limitSeconds)
                           : std::string("stopped: the request was cancelled");
  d.expected = "a scenario that can be checked within the limit";
  return {d};
}

struct AgentRange {
  std::uint64_t min = 0;
  std::uint64_t max = 0;
};

nlohmann::json summaryOf(const io::LoadedScenario& loaded) {
  AgentRange agents;
  for (const auto& p : loaded.desc.populations) {
    agents.min += static_cast<std::uint64_t>(p.groups) * p.sizeMin;
    agents.max += static_cast<std::uint64_t>(p.groups) * p.sizeMax;
  }
  return {{"populations", loaded.desc.populations.size()},
          {"agents_min", agents.min},
          {"agents_max", agents.max},
          {"points", loaded.desc.points.size()},
          {"navmesh_polygons", loaded.navmesh ? loaded.navmesh->polygonCount() : 0}};
}

ApiAnswer invalid(const core::Diagnostics& diagnostics) {
  return {422, jsonText({{"ok", false}, {"diagnostics", diagnosticsJson(diagnostics)}})};
}

// --- preview ------------------------------------------------------------------------------------

/// Appends one frame: {"t":time,"ids":[...],"xy":[x0,y0,...]} with positions to the centimetre.
void appendFrame(std::string& out, const sim::Frame& frame) {
  out += fmt::format("{{\"t\":{:.3f},\"ids\":[", frame.time);
  for (std::size_t i = 0; i < frame.size(); ++i) out += (i ? "," : "") + std::to_string(frame.ids[i]);
  out += "],\"xy\":[";
  for (std::size_t i = 0; i < frame.size(); ++i) {
    out += fmt::format("{}{:.2f},{:.2f}", i ? "," : "", frame.posX[i], frame.posY[i]);
  }
  out += "]}";
}

struct PreviewRun {
  std::string frames;  ///< the frames, comma-separated
  std::string end = "duration";
  double time = 0.0;
  std::uint32_t exited = 0;
};

PreviewRun simulatePreview(sim::World& world, double seconds, std::uint64_t stride, const std::atomic<int>& cancel,
                           const std::atomic<bool>& timedOut) {
  const core::TaskSystem tasks(2);
  const auto totalTicks = static_cast<std::uint64_t>(std::llround(seconds / world.desc().dt));
  PreviewRun run;
  appendFrame(run.frames, *world.takeFrame());
  std::uint64_t agentTicks = 0;
  for (std::uint64_t tick = 0; tick < totalTicks; ++tick) {
    if (cancel.load() != 0) {
      run.end = timedOut.load() ? "time limit" : "cancelled";
      break;
    }
    if (world.finished()) {
      run.end = "finished";
      break;
    }
    agentTicks += world.stats().active;
    if (agentTicks > kMaxPreviewAgentTicks) {
      run.end = "agent limit";
      break;
    }
    world.step(tasks);
    if ((tick + 1) % stride == 0) {
      run.frames += ',';
      appendFrame(run.frames, *world.takeFrame());
    }
  }
  run.time = world.stats().time;
  run.exited = world.stats().exited;
  return run;
}

}  // namespace

std::string emptyScenario(const std::string& name) {
  const ordered_json scenario = {{"format", "throng/1"}, {"name", name},          {"duration", 60},
                                 {"walkable", ordered_json::array()}, {"points", ordered_json::array()},
                                 {"populations", ordered_json::array()}};
  return io::formatJsonForDiffs(scenario);
}

nlohmann::json diagnosticsJson(const core::Diagnostics& diagnostics) {
  auto list = nlohmann::json::array();
  for (const core::Diagnostic& d : diagnostics) {
    list.push_back({{"pointer", core::printable(d.pointer)},
                    {"line", d.line},
                    {"column", d.column},
                    {"message", core::printable(messageOf(d), 2000)},
                    {"severity", "error"},
                    {"what", core::printable(d.what, 2000)},
                    {"expected", core::printable(d.expected, 2000)},
                    {"hint", core::printable(d.hint, 2000)}});
  }
  return list;
}

ScenarioRequest readScenarioRequest(std::string_view body, bool bodyIsScenario) {
  ScenarioRequest request;
  try {
    request.body = ordered_json::parse(body);
  } catch (const ordered_json::parse_error& e) {
    request.error = fmt::format("the request body is not JSON: {}", e.what());
    return request;
  }
  if (bodyIsScenario) {
    request.text = std::string(body);
    return request;
  }
  if (!request.body.is_object() || !request.body.contains("scenario")) {
    request.error = "expected a JSON object with \"scenario\"";
    return request;
  }
  const ordered_json& scenario = request.body["scenario"];
  request.text = scenario.is_string() ? scenario.get<std::string>() : scenario.dump();
  return request;
}

ApiAnswer checkScenario(const std::string& text, const std::string& source, const std::atomic<int>& cancel,
                        const std::atomic<bool>& timedOut) {
  io::LoadOptions options;
  options.cancel = &cancel;
  auto loaded = io::parseScenario(text, source, options);
  if (!loaded) {
    const core::Diagnostics problems = loadProblems(loaded.errors(), cancel, timedOut, kCheckSeconds);
    return {200, jsonText({{"ok", false}, {"diagnostics", diagnosticsJson(problems)}})};
  }
  return {200, jsonText({{"ok", true}, {"diagnostics", nlohmann::json::array()}, {"summary", summaryOf(*loaded)}})};
}

ApiAnswer previewScenario(const std::string& text, const std::string& source, double seconds, double fps,
                          const std::atomic<int>& cancel, const std::atomic<bool>& timedOut) {
  io::LoadOptions options;
  options.cancel = &cancel;
  auto loaded = io::parseScenario(text, source, options);
  if (!loaded) return invalid(loadProblems(loaded.errors(), cancel, timedOut, kPreviewSeconds));
  auto world = sim::World::create(loaded->desc, loaded->navmesh);
  if (!world) return invalid(world.errors());
  const double dt = loaded->desc.dt;
  const auto stride = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::llround(1.0 / (fps * dt))));
  const PreviewRun run = simulatePreview(**world, seconds, stride, cancel, timedOut);
  std::string body = fmt::format(R"({{"ok":true,"dt":{},"fps":{},"end":"{}","time":{:.3f},"exited":{},"frames":[)",
                                 fmt::format("{:.6g}", dt), fmt::format("{:.6g}", 1.0 / (static_cast<double>(stride) * dt)), run.end, run.time,
                                 run.exited);
  body += run.frames;
  body += "]}";
  return {200, std::move(body)};
}

ApiAnswer saveScenario(const ScenarioRequest& request, const fs::path& file, const std::atomic<int>& cancel,
                       const std::atomic<bool>& timedOut) {
  if (file.empty()) {
    return {409, jsonText({{"ok", false}, {"saved", false},
                           {"error", "no file to save to: start the editor with `throng edit FILE.json` (or download)"}})};
  }
  const bool force = request.body.is_object() && request.body.value("force", false);
  io::LoadOptions options;
  options.cancel = &cancel;
  auto loaded = io::parseScenario(request.text, file.string(), options);
  const core::Diagnostics problems = loaded ? core::Diagnostics{} : loadProblems(loaded.errors(), cancel, timedOut, kCheckSeconds);
  const nlohmann::json diagnostics = diagnosticsJson(problems);
  if (!problems.empty() && !force) {
    return {422, jsonText({{"ok", false}, {"saved", false}, {"path", file.string()}, {"diagnostics", diagnostics}})};
  }
  ordered_json scenario;
  try {
    scenario = ordered_json::parse(request.text);
  } catch (const ordered_json::parse_error& e) {
    return {400, jsonText({{"ok", false}, {"saved", false}, {"error", std::string("the scenario is not JSON: ") + e.what()}})};
  }
  if (auto written = io::writeFileAtomically(file.string(), io::formatJsonForDiffs(scenario), true); !written) {
    return {500, jsonText({{"ok", false}, {"saved", false}, {"path", file.string()},
                           {"error", core::formatAll(written.errors())}})};
  }
  return {200, jsonText({{"ok", problems.empty()}, {"saved", true}, {"path", file.string()}, {"diagnostics", diagnostics}})};
}

}  // namespace throng::cli::edit

namespace throng::cli::edit {

ApiAnswer importPlanText(std::string_view body) {
  ordered_json request;
  try {
    request = ordered_json::parse(body);
  } catch (const ordered_json::parse_error& e) {
    return {400, jsonText({{"ok", false}, {"error", fmt::format("the request body is not JSON: {}", e.what())}})};
  }
  const bool wellFormed = request.is_object() && request.contains("text") && request["text"].is_string() &&
                          request.contains("name") && request["name"].is_string();
  if (!wellFormed) return {400, jsonText({{"ok", false}, {"error", "expected {\"name\": \"plan.dxf\", \"text\": \"...\"}"}})};
  const std::string name = request["name"].get<std::string>();
  const auto format = io::planFormatOf(name);
  if (!format) return {400, jsonText({{"ok", false}, {"error", fmt::format("{}: expected a .dxf, .wkt or .gltf file", name)}})};
  io::PlanImportOptions options;
  const double scale = request.value("scale", 1.0);
  if (!(scale > 0)) return {400, jsonText({{"ok", false}, {"error", "expected \"scale\" > 0"}})};
  options.scale = scale;
  auto fragment = io::importPlan(request["text"].get<std::string>(), *format, name, options);
  if (!fragment) return invalid(fragment.errors());
  return {200, jsonText({{"ok", true}, {"fragment", *fragment}})};
}

}  // namespace throng::cli::edit
