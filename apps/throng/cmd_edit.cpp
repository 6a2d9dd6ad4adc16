// `throng edit [FILE.json]` — the scenario editor: serves the browser editor (web/dist/editor) and
// its JSON API on one HTTP port until Ctrl-C. GET /api/scenario gives FILE's text (or an empty
// scenario when FILE does not exist yet); POST /api/check, /api/preview and /api/save check,
// simulate and save with the validator of `throng check`, /api/import reads a DXF or WKT floor
// plan (edit_api.hpp), routed by edit_routes.hpp, each on a worker thread
// (edit_jobs.hpp) that stops when the client hangs up or its time is up. Writes only FILE.
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <thread>

#include "bench_files.hpp"
#include "commands.hpp"
#include "data_dirs.hpp"
#include "edit_api.hpp"
#include "edit_jobs.hpp"
#include "edit_routes.hpp"
#include "output.hpp"
#include "signal.hpp"
#include "validators.hpp"
#include "throng/transport/transport.hpp"

namespace throng::cli {
namespace {
namespace fs = std::filesystem;
using namespace std::chrono_literals;
using transport::HttpRequest;
using transport::HttpResponder;

/// The editor's built files: <web>/editor, <web> being --web, an installed tree's
/// <prefix>/share/throng/web, else web/dist of the source tree.
fs::path editorRoot(const std::string& flag) {
  if (!flag.empty()) return fs::path(flag) / "editor";
#ifdef THRONG_WEB_DIST
  const fs::path web = bundledDataDir(currentExecutable(), "web", THRONG_WEB_DIST);
#else
  const fs::path web = bundledDataDir(currentExecutable(), "web", {});
#endif
  return web.empty() ? fs::path() : web / "editor";
}

/// No WebSocket here: any peer that opens is closed at once.
class NoPeers final : public transport::TransportHandler {
 public:
  transport::Transport* transport = nullptr;
  void onOpen(transport::PeerId peer, transport::PeerKind, std::string) override {
    if (transport != nullptr) transport->close(peer, "throng edit has no WebSocket");
  }
  void onMessage(transport::PeerId, std::span<const std::uint8_t>) override {}
  void onClose(transport::PeerId, std::string_view) override {}
};

void openBrowser(const std::string& url) {
  const std::string command = fmt::format("xdg-open '{}' >/dev/null 2>&1 &", url);
  if (std::system(command.c_str()) != 0) printLine(stderr, "throng edit: could not open a browser; open " + url);
}

}  // namespace

CLI::App* addEditCommand(CLI::App& app, EditOptions& options) {
  CLI::App* cmd = app.add_subcommand("edit", "Edit a scenario in the browser: draw, check, preview, save");
  cmd->footer(
      "Serves the scenario editor (docs/editor.md) on http://HOST:PORT/: draw the walkable area, obstacles,\n"
      "walls, points, measurement lines and areas and the crowds on a 2D plan; every edit is checked by\n"
      "the validator of `throng check` and its diagnostics are shown on the plan; preview runs the\n"
      "scenario in the server for a few seconds; save (Ctrl+S) writes FILE, formatted for diffs. FILE\n"
      "need not exist yet. Nothing but FILE is ever written. Ctrl-C stops.");
  cmd->add_option("file", options.file, "Scenario JSON file to edit (created on the first save)")->type_name("FILE.json");
  cmd->add_option("--port", options.port, "HTTP port (0: any free port, printed)")
      ->check(integerRange(0, 65535))
      ->capture_default_str();
  cmd->add_option("--host", options.host, "Address to listen on")->capture_default_str();
  cmd->add_flag("--open", options.open, "Open the editor in the default browser (xdg-open)");
  cmd->add_option("--web", options.web, "Directory of the browser pages' built files, the editor in its editor/ "
                                        "(default: <prefix>/share/throng/web when installed, else web/dist)")
      ->type_name("DIR");
  return cmd;
}

int runEdit(const EditOptions& options) {
  InterruptGuard interrupts;
  const fs::path file = options.file.empty() ? fs::path() : fs::absolute(options.file);
  std::error_code ec;
  if (!file.empty() && (fs::is_directory(file, ec) || !fs::is_directory(file.parent_path(), ec))) {
    printLine(stderr, fmt::format("throng edit: {}: expected a scenario file in an existing directory",
                                  displayText(options.file)));
    return kExitFailure;
  }
  const fs::path root = editorRoot(options.web);
  const bool haveEditor = !root.empty() && fs::is_regular_file(root / "index.html", ec);
  edit::Jobs jobs;
  edit::EditApi api(file, jobs);
  transport::TransportOptions t;
  t.bindAddress = options.host;
  t.httpPort = static_cast<std::uint16_t>(options.port);
  t.enableUdp = false;
  t.maxPeers = 1;
  if (haveEditor) t.staticRoot = root;
  t.maxPostBytes = edit::kMaxBodyBytes;
  t.httpHandler = [&api](std::string_view target) { return api.get(target); };
  t.postHandler = [&api](HttpRequest request, HttpResponder responder) { return api.post(std::move(request), responder); };
  NoPeers peers;
  auto started = transport::Transport::start(t, peers);
  if (!started) {
    printDiagnostics(started.errors());
    return kExitFailure;
  }
  std::unique_ptr<transport::Transport> server = std::move(started).value();
  peers.transport = server.get();
  const std::string url = fmt::format("http://{}:{}/", options.host == "0.0.0.0" ? "127.0.0.1" : options.host,
                                      server->httpPort());
  printLine(stdout, fmt::format("throng edit: {}", file.empty() ? std::string("(no file: download to keep your work)")
                                                                : displayText(file.string())));
  printLine(stdout, fmt::format("  editor  {}{}", url, haveEditor ? "" : "  (not built: cd web && npm ci && npm run build)"));
  printLine(stdout, "  Ctrl-C to stop");
  std::fflush(stdout);
  if (options.open) openBrowser(url);
  while (!InterruptGuard::requested()) std::this_thread::sleep_for(50ms);
  jobs.stop();
  server->shutdown("editor shutting down");
  return kExitInterrupted;
}

}  // namespace throng::cli
