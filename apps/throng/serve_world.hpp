// `throng serve`'s world served: Served (a live scenario or a recording played back, its World and
// its description) and what the server's parts are configured with from it: openServed, webRoot
// (where the viewer's files are), hubOptionsFor and transportOptionsFor.
#pragma once
#include <filesystem>
#include <optional>
#include <string>

#include "commands.hpp"
#include "live_world.hpp"
#include "throng/hub/hub.hpp"
#include "throng/hub/replay.hpp"
#include "throng/transport/transport.hpp"

namespace throng::cli::serve {

/// The scenario served: simulated live, or a recording (`throng run`'s SQLite file) played back.
struct Served {
  LiveWorld live;
  std::optional<hub::Replay> replay;
  double tickRate = 0.0;  ///< ticks per second in real time
  std::string worldJson;  ///< the world description (Welcome, /api/world)
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
