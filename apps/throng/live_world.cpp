// Live worlds for `throng serve` and `throng link` (see live_world.hpp).
#include "live_world.hpp"

#include "output.hpp"

namespace throng::cli {

std::optional<LiveWorld> makeLiveWorld(core::Result<io::LoadedScenario> loaded, std::optional<std::uint64_t> seed,
                                       const std::filesystem::path& clipDir, const std::string& command, bool quiet) {
  if (!loaded) {
    printDiagnostics(loaded.errors());
    return std::nullopt;
  }
  if (seed) loaded->desc.seed = *seed;
  auto created = sim::World::create(loaded->desc, loaded->navmesh);
  if (!created) {
    printDiagnostics(created.errors());
    return std::nullopt;
  }
  std::vector<std::string> warnings;
  hub::MotionLibrary motions = hub::MotionLibrary::load(*loaded, clipDir, warnings);
  if (!quiet) {
    for (const std::string& w : warnings) printLine(stderr, "throng " + command + ": warning: " + w);
  }
  return LiveWorld{std::move(loaded).value(), std::move(created).value(), std::move(motions)};
}

}  // namespace throng::cli
