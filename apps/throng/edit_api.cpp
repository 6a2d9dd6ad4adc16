// `throng edit`'s API work (edit_api.hpp): check, preview, format and save a scenario text.
#include "edit_api.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <system_error>
#include <unistd.h>

#include "output.hpp"
#include "throng/core/parallel.hpp"
#include "throng/core/text.hpp"
#include "throng/io/scenario_loader.hpp"
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

// --- formatting ---------------------------------------------------------------------------------

/// True when `value` holds no object at any depth (points, polygons, lists of ids).
bool flat(const ordered_json& value) {
  if (value.is_object()) return false;
  if (!value.is_array()) return true;
  for (const auto& item : value) {
    if (!flat(item)) return false;
  }
  return true;
}

/// An object without objects inside ({"mean": 1.34, "sd": 0.26}, {"polygon": [[0,0],[1,0],[1,1]]}).
bool flatObject(const ordered_json& value) {
  if (!value.is_object()) return false;
  for (const auto& item : value) {
    if (!flat(item)) return false;
  }
  return true;
}

std::string inlineText(const ordered_json& value) {
  if (value.is_object()) {
    std::string out = "{";
    bool first = true;
    for (const auto& [key, item] : value.items()) {
      out += (first ? "" : ", ") + ordered_json(key).dump() + ": " + inlineText(item);
      first = false;
    }
    return out + "}";
  }
  return value.dump(-1, ' ', false, ordered_json::error_handler_t::replace);
}

void writeValue(std::string& out, const ordered_json& value, std::size_t indent) {
  constexpr std::size_t kLine = 100;
  const std::string inner(indent + 2, ' ');
  const bool inlinable = indent > 0 && ((value.is_array() && flat(value)) || flatObject(value));
  if (inlinable || !value.is_structured() || value.empty()) {
    const std::string text = inlineText(value);
    if (!value.is_structured() || value.empty() || indent + text.size() <= kLine) {
      out += text;
      return;
    }
  }
  if (value.is_object()) {
    out += "{\n";
    std::size_t i = 0;
    for (const auto& [key, item] : value.items()) {
      out += inner + ordered_json(key).dump() + ": ";
      writeValue(out, item, indent + 2);
      out += ++i < value.size() ? ",\n" : "\n";
    }
    out += std::string(indent, ' ') + "}";
    return;
  }
  out += "[\n";
  for (std::size_t i = 0; i < value.size(); ++i) {
    out += inner;
    writeValue(out, value[i], indent + 2);
    out += i + 1 < value.size() ? ",\n" : "\n";
  }
  out += std::string(indent, ' ') + "]";
}

/// Writes `text` next to `file` and renames it over `file`; an error message, or empty.
std::string writeAtomically(const fs::path& file, const std::string& text) {
  const fs::path temp = file.parent_path() / (".#" + file.filename().string() + "." + std::to_string(::getpid()));
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    out << text;
    out.flush();
    if (!out) {
      std::error_code ignored;
      fs::remove(temp, ignored);
      return fmt::format("cannot write {}: {}", temp.string(), std::strerror(errno));
    }
  }
  std::error_code ec;
  fs::rename(temp, file, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    return fmt::format("cannot replace {}: {}", file.string(), ec.message());
  }
  return {};
}

}  // namespace

std::string emptyScenario(const std::string& name) {
  const ordered_json scenario = {{"format", "throng/1"}, {"name", name},          {"duration", 60},
                                 {"walkable", ordered_json::array()}, {"points", ordered_json::array()},
                                 {"populations", ordered_json::array()}};
  return formatScenario(scenario);
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

std::string formatScenario(const ordered_json& scenario) {
  std::string out;
  writeValue(out, scenario, 0);
  out += '\n';
  return out;
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
  if (const std::string error = writeAtomically(file, formatScenario(scenario)); !error.empty()) {
    return {500, jsonText({{"ok", false}, {"saved", false}, {"path", file.string()}, {"error", error}})};
  }
  return {200, jsonText({{"ok", problems.empty()}, {"saved", true}, {"path", file.string()}, {"diagnostics", diagnostics}})};
}

}  // namespace throng::cli::edit
