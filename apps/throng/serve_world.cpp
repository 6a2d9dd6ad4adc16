// `throng serve`'s world served (serve_world.hpp): opening a scenario or a recording (isRecording,
// parseStoredScenario: the scenario a recording stores, found beside it or in the bundled
// scenarios/), a glTF world file's model (worldModelOf: which of its resources may be served; a
// recording's: replayWorldModelOf, the glTF file it names found again beside it or in scenarios/),
// where the viewer's files are, and the hub's and the transport's options.
#include "serve_world.hpp"

#include <algorithm>
#include <cstdio>
#include <cctype>
#include <cstring>
#include <fstream>

#include <nlohmann/json.hpp>

#include "bench_files.hpp"
#include "data_dirs.hpp"
#include "output.hpp"
#include "throng/hub/text.hpp"
#include "throng/hub/world_description.hpp"
#include "throng/io/scenario_loader.hpp"

namespace throng::cli::serve {
namespace {

namespace fs = std::filesystem;

/// A SQLite file (a recording) rather than a scenario: by its first bytes.
bool isRecording(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) return false;
  char head[16] = {};
  const std::size_t n = std::fread(head, 1, sizeof head, f);
  std::fclose(f);
  return n == sizeof head && std::memcmp(head, "SQLite format 3", 16) == 0;
}

/// Where a recording's stored scenario and world file are looked for: beside the recording, then the
/// bundled scenarios/ (installed, else the source tree's).
std::vector<fs::path> storedScenarioDirs(const std::string& recording) {
  std::vector<fs::path> dirs{fs::path(recording).parent_path()};
  if (const auto installed = installedDataDir(currentExecutable()); !installed.empty()) {
    dirs.push_back(installed / "scenarios");
  }
#ifdef THRONG_SCENARIOS_DIR
  dirs.emplace_back(THRONG_SCENARIOS_DIR);
#endif
  return dirs;
}

/// The scenario stored in a recording, parsed as if it lay beside the recording, else in the bundled
/// scenarios/ (installed, else the source tree's: where the bundled scenarios, their motion clips and databases are): its clip
/// and database paths are relative to the scenario's directory, which the recording does not keep.
/// `dir` receives the directory that worked.
core::Result<io::LoadedScenario> parseStoredScenario(const hub::Replay& replay, const std::string& recording,
                                                     fs::path& dir) {
  const std::vector<fs::path> dirs = storedScenarioDirs(recording);
  const std::string name = fs::path(recording).stem().string() + ".stored-scenario.json";
  // The first directory where it parses and its motion clips are; else the first where it parses
  // (bodies then get the viewer's built-in skeleton and procedural clips).
  std::optional<core::Result<io::LoadedScenario>> first, firstParsed;
  fs::path firstParsedDir;
  for (const fs::path& candidate : dirs) {
    auto parsed = io::parseScenario(replay.scenarioText(), (candidate / name).string());
    if (parsed) {
      std::error_code ec;
      if (fs::is_directory(candidate / parsed.value().desc.social.motions, ec)) {
        dir = candidate;
        return parsed;
      }
      if (!firstParsed) {
        firstParsedDir = candidate;
        firstParsed.emplace(std::move(parsed));
      }
      continue;
    }
    if (!first) first.emplace(std::move(parsed));
  }
  if (firstParsed) {
    dir = firstParsedDir;
    return std::move(*firstParsed);
  }
  return std::move(*first);
}

/// `path`'s extension in lower case (".gltf").
std::string lowerExtension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

/// A resource URI the viewer may fetch beside the world file: relative, inside its directory,
/// nothing to percent-decode.
bool servableUri(const std::string& uri) {
  if (uri.empty() || uri.front() == '/' || uri == "world.gltf" || uri == "world.glb") return false;
  const bool plain = std::all_of(uri.begin(), uri.end(), [](unsigned char c) {
    return std::isalnum(c) != 0 || c == '.' || c == '_' || c == '-' || c == '/';
  });
  if (!plain) return false;
  const fs::path p(uri);
  return std::none_of(p.begin(), p.end(), [](const fs::path& part) { return part == ".." || part == "."; });
}

/// The servable external resources (buffers, images) a .gltf names; none for a .glb.
std::vector<std::string> modelResources(const fs::path& file) {
  if (lowerExtension(file) != ".gltf") return {};
  std::ifstream in(file, std::ios::binary);
  const nlohmann::json gltf = nlohmann::json::parse(in, nullptr, false);
  if (gltf.is_discarded() || !gltf.is_object()) return {};
  std::vector<std::string> out;
  for (const char* key : {"buffers", "images"}) {
    const auto list = gltf.find(key);
    if (list == gltf.end() || !list->is_array()) continue;
    for (const nlohmann::json& entry : *list) {
      if (!entry.is_object()) continue;
      const auto uri = entry.find("uri");
      if (uri != entry.end() && uri->is_string() && servableUri(uri->get<std::string>())) out.push_back(uri->get<std::string>());
    }
  }
  return out;
}

}  // namespace

std::string WorldModel::servedName() const { return lowerExtension(file) == ".glb" ? "world.glb" : "world.gltf"; }

WorldModel worldModelOf(const std::string& path) {
  const fs::path file(path);
  const std::string ext = lowerExtension(file);
  if (ext != ".gltf" && ext != ".glb") return {};
  return WorldModel{file, modelResources(file), {}};
}

WorldModel replayWorldModelOf(const hub::Replay& replay, const std::string& recording) {
  const std::string& name = replay.worldFile();
  WorldModel none;
  if (name.empty()) {
    none.missing = "the recording names no glTF world file (recorded from a scenario JSON, or before recordings kept it)";
    return none;
  }
  const std::string ext = lowerExtension(name);
  const bool plainName = servableUri(name) && name.find('/') == std::string::npos;
  if (!plainName || (ext != ".gltf" && ext != ".glb")) {
    none.missing = "the recording's world file name is not a plain .gltf / .glb file name";
    return none;
  }
  for (const fs::path& dir : storedScenarioDirs(recording)) {
    const fs::path file = dir / name;
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) continue;
    auto loaded = io::loadScenarioFile(file.string());
    if (loaded && loaded.value().text == replay.scenarioText()) return worldModelOf(file.string());
  }
  none.missing = "no " + name + " describing the recorded world beside the recording or in the bundled scenarios";
  return none;
}

/// The viewer's files: --web, else an installed tree's <prefix>/share/throng/web, else web/dist of
/// the source tree this binary was built from (data_dirs.hpp).
fs::path webRoot(const std::string& flag) {
  if (!flag.empty()) return flag;
#ifdef THRONG_WEB_DIST
  return bundledDataDir(currentExecutable(), "web", THRONG_WEB_DIST);
#else
  return bundledDataDir(currentExecutable(), "web", {});
#endif
}

/// Opens the scenario or the recording at `path` and builds the World; diagnostics printed, nullopt
/// on failure.
std::optional<Served> openServed(const ServeOptions& options, const std::string& path) {
  if (auto missing = checkInputFile(path, "scenario"); !missing.empty()) {
    printDiagnostics(missing);
    return std::nullopt;
  }
  std::optional<hub::Replay> replay;
  if (isRecording(path)) {
    auto opened = hub::Replay::open(path);
    if (!opened) {
      printDiagnostics(opened.errors());
      return std::nullopt;
    }
    replay.emplace(std::move(opened).value());
  }
  fs::path storedScenarioDir;
  auto loaded = replay ? parseStoredScenario(*replay, path, storedScenarioDir) : io::loadScenarioFile(path);
  const fs::path scenarioDir = replay ? storedScenarioDir : fs::path(path).parent_path();
  auto live = makeLiveWorld(std::move(loaded), options.seed, scenarioDir, "serve", options.quiet);
  if (!live) return std::nullopt;
  const double dt = live->scenario.desc.dt;
  const double tickRate = options.tick ? *options.tick : replay ? std::max(1.0, replay->fps()) : 1.0 / dt;
  std::string worldJson = hub::describeWorld(live->scenario, live->motions, *live->world, tickRate);
  if (replay) {
    nlohmann::json described = nlohmann::json::parse(worldJson);
    described["replay"] = {{"duration", replay->duration()}, {"fps", replay->fps()}, {"frames", replay->frameCount()}};
    worldJson = dumpJson(described);
  }
  WorldModel model = replay ? replayWorldModelOf(*replay, path) : worldModelOf(path);
  return Served{std::move(*live), std::move(replay), tickRate, std::move(worldJson), std::move(model)};
}

hub::HubOptions hubOptionsFor(const ServeOptions& options, const Served& served, const std::string& path) {
  hub::HubOptions hubOptions;
  const std::string& name = served.live.scenario.desc.name;
  // Sent in Welcome and printed: valid UTF-8, control characters escaped, at most 64 bytes.
  hubOptions.serverName =
      hub::printable(name.empty() ? fs::path(path).stem().string() : name, protocol::kMaxNameLength);
  hubOptions.maxClients = static_cast<std::size_t>(options.maxClients);
  hubOptions.granularity.budgetKbitPerSecond = options.budgetKbit;
  hubOptions.replay = served.replay.has_value();
  return hubOptions;
}

/// The transport's options, without the HTTP hook; `web` is the viewer's directory when it is built.
transport::TransportOptions transportOptionsFor(const ServeOptions& options, const fs::path& web) {
  transport::TransportOptions t;
  t.bindAddress = options.bind;
  t.httpPort = static_cast<std::uint16_t>(options.port);
  t.udpPort = static_cast<std::uint16_t>(options.udpPort);
  t.maxPeers = static_cast<std::size_t>(options.maxClients) + 16;  // room to refuse politely
  t.maxUdpPeers = t.maxPeers;  // a separate budget: UDP peers never take a /ws slot
  t.maxDatagramBytes = 65507;  // the largest datagram accepted from a UDP client
  t.udpFragmentBytes = static_cast<std::size_t>(options.udpFragment);  // larger messages go as Fragments
  if (!web.empty()) t.staticRoot = web;
  return t;
}

}  // namespace throng::cli::serve
