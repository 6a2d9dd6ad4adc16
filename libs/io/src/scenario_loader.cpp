// throng::io scenario loading — the public entry points: text (or a file) → JsonDocument →
// ParsedScenario (+ motion clips, scenario_clips; timeline crowd files, scenario_timeline) →
// validated LoadedScenario. Reads the file and
// the BVH clips it names; writes nothing. No exception escapes: even an internal failure becomes a
// diagnostic.
#include "throng/io/scenario_loader.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "json_document.hpp"
#include "scenario_clips.hpp"
#include "scenario_parser.hpp"
#include "scenario_social.hpp"
#include "scenario_timeline.hpp"
#include "scenario_validator.hpp"
#include "throng/io/world_file.hpp"

namespace throng::io {

namespace {

bool cancelled(const LoadOptions& options) {
  return options.cancel != nullptr && options.cancel->load(std::memory_order_relaxed) != 0;
}

core::Diagnostic interrupted(const std::string& source) {
  return core::Diagnostic{source, 0, 0, "", "interrupted: checking stopped by a signal before it was complete", "", ""};
}

}  // namespace

core::Result<LoadedScenario> parseScenario(std::string_view text, const std::string& source,
                                           const LoadOptions& options) {
  try {
    auto doc = JsonDocument::parse(text, source);
    if (!doc.ok()) return std::move(doc).takeErrors();
    if (cancelled(options)) return interrupted(source);
    core::Diagnostics diagnostics;
    ParsedScenario parsed = parseScenarioJson(doc.value(), diagnostics);
    if (cancelled(options)) return interrupted(source);
    MotionClips clips = loadScenarioClips(doc.value(), parsed, diagnostics);
    loadScenarioSocial(doc.value(), parsed, diagnostics);
    std::shared_ptr<const nav::NavMesh> navmesh;
    if (cancelled(options)) return interrupted(source);
    if (doc.value().root().is_object()) validateScenario(doc.value(), parsed, options, diagnostics, navmesh);
    if (cancelled(options)) return interrupted(source);
    // Timeline crowds join the scenario as validated (its navmesh when reachability was checked).
    if (diagnostics.empty()) loadScenarioTimeline(doc.value(), parsed.desc, navmesh, diagnostics);
    if (cancelled(options)) return interrupted(source);
    if (!diagnostics.empty()) {
      // Report in file order: that is how people fix them. The scenario's own come first, then
      // those of its motion clips, file by file.
      std::stable_sort(diagnostics.begin(), diagnostics.end(),
                       [&source](const core::Diagnostic& a, const core::Diagnostic& b) {
                         const bool aOwn = a.source == source, bOwn = b.source == source;
                         if (aOwn != bOwn) return aOwn;
                         if (a.source != b.source) return a.source < b.source;
                         return a.line != b.line ? a.line < b.line : a.column < b.column;
                       });
      return diagnostics;
    }
    return LoadedScenario{std::move(parsed.desc), std::move(navmesh), std::string(text), std::move(clips)};
  } catch (const std::exception& e) {
    return core::Diagnostic{source, 0, 0, "", std::string("internal error while loading the scenario: ") + e.what(), "", ""};
  }
}

core::Result<LoadedScenario> loadScenarioFile(const std::string& path, const LoadOptions& options) {
  // glTF worlds (.gltf, .glb) load through the world-file naming rules (world_file.hpp).
  if (isWorldFile(path)) return loadWorldFile(path, options);
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    return core::Diagnostic{path, 0, 0, "", std::string("cannot open file: ") + std::strerror(errno),
                            "a readable scenario file", ""};
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) {
    return core::Diagnostic{path, 0, 0, "", "cannot read file", "a readable scenario file", ""};
  }
  return parseScenario(text.str(), path, options);
}

}  // namespace throng::io
