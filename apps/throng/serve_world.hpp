// `throng serve`'s world served: Served (a live scenario or a recording played back, its World, its
// description and, for a glTF world file, the file and its external resources: WorldModel) and what
// the server's parts are configured with from it: openServed, webRoot (where the viewer's files
// are), hubOptionsFor and transportOptionsFor.
#pragma once
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "live_world.hpp"
#include "throng/hub/hub.hpp"
#include "throng/hub/replay.hpp"
#include "throng/transport/transport.hpp"

namespace throng::cli::serve {

/// The glTF world file the world was read from, for the viewer to draw its materials
/// (GET /api/world/model, serve_api.hpp); empty for a JSON scenario, or a recording whose glTF file
/// is not found again (replayWorldModelOf).
struct WorldModel {
  std::filesystem::path file;           ///< the .gltf or .glb file; empty: none
  std::vector<std::string> resources;   ///< the external buffers and images it names that may be served
  std::string missing;                  ///< with no file: why a recording's world file is not served
  /// The name it is served under: "world.gltf" or "world.glb".
  [[nodiscard]] std::string servedName() const;
};

/// The model of the world file at `path` (.gltf or .glb, any case), else an empty one. Of a
/// .gltf's buffers[].uri and images[].uri only relative paths inside its directory made of
/// letters, digits, '.', '_', '-' and '/' are listed (no data: URIs, no "..", nothing to decode).
[[nodiscard]] WorldModel worldModelOf(const std::string& path);

/// The model of a recording's world: the glTF / GLB file it names (metadata `throng_world_file`, a
/// plain file name), looked for where the stored scenario is (beside the recording, then the bundled
/// scenarios/) and taken only when it describes exactly the world recorded (its scenario text is the
/// stored one); its resources as worldModelOf's. Else an empty model saying why (`missing`).
[[nodiscard]] WorldModel replayWorldModelOf(const hub::Replay& replay, const std::string& recording);

/// The scenario served: simulated live, or a recording (`throng run`'s SQLite file) played back.
struct Served {
  LiveWorld live;
  std::optional<hub::Replay> replay;
  double tickRate = 0.0;  ///< ticks per second in real time
  std::string worldJson;  ///< the world description (Welcome, /api/world)
  WorldModel model;       ///< the glTF world file served, if it is one (a recording's: replayWorldModelOf)
};

/// Opens the scenario or the recording at `path` and builds the World; diagnostics printed, nullopt
/// on failure.
[[nodiscard]] std::optional<Served> openServed(const ServeOptions& options, const std::string& path);

/// The viewer's files: --web, else an installed tree's <prefix>/share/throng/web, else web/dist of
/// the source tree this binary was built from (data_dirs.hpp).
[[nodiscard]] std::filesystem::path webRoot(const std::string& flag);

/// The hub's options for `served` (its name: the scenario's, else the file's stem).
[[nodiscard]] hub::HubOptions hubOptionsFor(const ServeOptions& options, const Served& served, const std::string& path);

/// The transport's options, without the HTTP hook; `web` is the viewer's directory when it is built.
[[nodiscard]] transport::TransportOptions transportOptionsFor(const ServeOptions& options,
                                                              const std::filesystem::path& web);

}  // namespace throng::cli::serve
