// throng CLI live worlds — what `throng serve` and `throng link` both need before they run in real
// time: the loaded scenario, its World (seed overridden on request) and the motion library of its
// clips. Prints the diagnostics and warnings itself (one line each, on stderr).
#pragma once
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "throng/core/result.hpp"
#include "throng/hub/motion_library.hpp"
#include "throng/io/scenario_loader.hpp"
#include "throng/sim/world.hpp"

namespace throng::cli {

struct LiveWorld {
  io::LoadedScenario scenario;
  std::unique_ptr<sim::World> world;
  hub::MotionLibrary motions;
};

/// The World of `loaded` (its diagnostics printed when it failed to load or build) with `seed`
/// overriding the scenario's, and the clips found relative to `clipDir`. Warnings about missing
/// clips are printed as "throng <command>: warning: …" unless `quiet`. Nothing on failure.
[[nodiscard]] std::optional<LiveWorld> makeLiveWorld(core::Result<io::LoadedScenario> loaded,
                                                     std::optional<std::uint64_t> seed,
                                                     const std::filesystem::path& clipDir, const std::string& command,
                                                     bool quiet);

}  // namespace throng::cli
