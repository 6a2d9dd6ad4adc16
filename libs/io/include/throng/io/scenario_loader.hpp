// throng::io scenario loading — JSON text → validated sim::ScenarioDesc (parse → validate → build).
// Every problem is reported as a Diagnostic with file:line:column, JSON pointer, what is wrong and
// what was expected; nothing stops at the first error.
#pragma once
#include <atomic>
#include <map>
#include <memory>
#include <string>
#include <string_view>

#include "throng/core/result.hpp"
#include "throng/motion/bvh.hpp"
#include "throng/nav/navmesh.hpp"
#include "throng/sim/scenario.hpp"

namespace throng::io {

/// Motion clips of a scenario's action points, keyed by sim::PointDesc::clip (the path as written
/// in the scenario); each file is loaded once however many points use it.
using MotionClips = std::map<std::string, std::shared_ptr<const motion::MotionClip>>;

struct LoadedScenario {
  sim::ScenarioDesc desc;
  /// The navmesh built during validation (reachability checks); hand it to World::create.
  std::shared_ptr<const nav::NavMesh> navmesh;
  std::string text;  ///< the scenario's JSON text as read (stored in recordings)
  MotionClips clips;  ///< loaded from the points' "clip" paths, relative to the scenario's directory
};

struct LoadOptions {
  /// Build the navmesh and check that spawns and goals are connected. Off only for fuzzing the
  /// parser and for structural checks where speed matters.
  bool checkReachability = true;
  /// When set, loading stops soon after `*cancel` becomes non-zero (a signal handler sets it:
  /// Ctrl-C during `throng check`) and returns one diagnostic saying it was interrupted.
  const std::atomic<int>* cancel = nullptr;
};

/// Parses and validates scenario JSON. `source` names the text in diagnostics (usually the path);
/// clip paths are resolved against its directory (the working directory when it has none).
core::Result<LoadedScenario> parseScenario(std::string_view text, const std::string& source,
                                           const LoadOptions& options = {});

/// Reads the file and calls parseScenario; an unreadable file is one diagnostic naming it.
core::Result<LoadedScenario> loadScenarioFile(const std::string& path, const LoadOptions& options = {});

}  // namespace throng::io
