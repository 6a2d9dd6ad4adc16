// throng::io world files — a glTF 2.0 world (.gltf JSON or .glb binary) → the same validated
// LoadedScenario a scenario file gives, the way the paper's system loads DIVE world files: node
// names and node extras ("extras": {"throng": {...}}) mark walkable floors, obstacles, interest,
// action and exit points and crowds (docs/world-files.md). The world becomes a scenario JSON
// document (LoadedScenario::text, so recordings replay it like any scenario) that goes through the
// scenario parser and validator; their diagnostics are given back naming the glTF node and the
// extras key ("world.gltf node 7 \"crowd:visitors\" /extras/throng/groups: ..."). Reads the file
// and the buffers it names; writes nothing.
#pragma once
#include <string>
#include <string_view>

#include "throng/core/result.hpp"
#include "throng/io/scenario_loader.hpp"

namespace throng::io {

/// True for paths ending in ".gltf" or ".glb" (any case): io::loadScenarioFile hands them here.
[[nodiscard]] bool isWorldFile(std::string_view path);

/// Parses glTF bytes (binary when they start with the "glTF" magic, JSON otherwise). `source`
/// names the file in diagnostics; external buffers, motion clips and crowd files resolve against
/// its directory.
core::Result<LoadedScenario> parseWorld(std::string_view bytes, const std::string& source, const LoadOptions& options = {});

/// Reads the file and calls parseWorld; an unreadable file is one diagnostic naming it.
core::Result<LoadedScenario> loadWorldFile(const std::string& path, const LoadOptions& options = {});

}  // namespace throng::io
