// `throng serve SCENARIO.json` — runs the simulation in real time and serves it into a shared
// world (docs/server.md): HTTP (the browser viewer's files, the motion clips, /api/status) and
// WebSocket (/ws) on one port, the same protocol over UDP on another. The hub (libs/hub) does the
// sessions and crowd messages; the transport (libs/transport) the sockets. Reads the scenario and
// its clips; writes sockets, a status line on stderr (terminal only) and a summary on stdout.
// Ctrl-C tells every client why, then stops.
//
// This file holds the command line (addServeCommand, its --help footer) and runServe, which wires
// the parts together: serve_bridge.hpp (transport ↔ hub), serve_world (the scenario or recording
// served), serve_api (the dynamic HTTP answers), serve_loop (publisher and tick loop) and
// serve_session (a Session per world, the Router, switching recordings); then the banner and the
// summary (printBanner, printSummary).
#include <algorithm>
#include <filesystem>
#include <memory>
#include <optional>
#include <system_error>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "edit_routes.hpp"
#include "output.hpp"
#include "recording_routes.hpp"
#include "serve_bridge.hpp"
#include "serve_loop.hpp"
#include "serve_session.hpp"
#include "serve_world.hpp"
#include "signal.hpp"
#include "validators.hpp"
#include "throng/transport/transport.hpp"

namespace throng::cli {
namespace {

namespace fs = std::filesystem;
using serve::percentile;

/// The addresses served, on stdout.
void printBanner(const std::string& serverName, double tickRate, const ServeOptions& options,
                 const transport::Transport& transport, bool haveViewer) {
  const std::string host = options.bind == "0.0.0.0" ? "127.0.0.1" : options.bind;
  printLine(stdout, fmt::format("throng serve: {} — {:.4g} ticks/s", serverName, tickRate));
  printLine(stdout, fmt::format("  viewer     http://{}:{}/{}", host, transport.httpPort(),
                                haveViewer ? "" : "  (not built: scripts/demo.sh builds it)"));
  printLine(stdout, fmt::format("  websocket  ws://{}:{}/ws", host, transport.httpPort()));
  printLine(stdout, fmt::format("  udp        {}:{}", host, transport.udpPort()));
  printLine(stdout, "  Ctrl-C to stop");
}

/// What a run of the server did, for the summary.
struct ServeSummary {
  std::string endReason;
  double wall = 0.0;                      ///< [s]
  double tickRate = 0.0;
  const std::vector<double>* tickMs = nullptr;
  const std::vector<double>* publishMs = nullptr;
  std::uint64_t framesSkipped = 0;
  hub::TickReport ticks;
  transport::TransportTotals totals;
  hub::HubStatus hub;
};

/// The summary on stdout: one JSON object (--json) or three lines (unless --quiet).
void printSummary(const ServeOptions& options, const ServeSummary& r) {
  const std::vector<double>& tickMs = *r.tickMs;
  const std::vector<double>& publishMs = *r.publishMs;
  const std::uint64_t overruns = r.ticks.late;
  if (options.json) {
    nlohmann::json j = {{"scenario", options.scenario}, {"end", r.endReason}, {"seconds", r.wall},
                        {"ticks", tickMs.size()}, {"tickRate", r.tickRate},
                        {"ms_per_tick_median", percentile(tickMs, 0.5)}, {"ms_per_tick_p99", percentile(tickMs, 0.99)},
                        {"overruns", overruns}, {"stalls", r.ticks.stalls}, {"longest_tick_ms", r.ticks.longestMs},
                        {"publish_ms_median", percentile(publishMs, 0.5)},
                        {"publish_ms_p99", percentile(publishMs, 0.99)}, {"frames_skipped", r.framesSkipped},
                        {"peers_opened", r.totals.peersOpened},
                        {"crowd_frames", r.hub.crowdFrames}, {"crowd_bytes", r.hub.crowdBytes},
                        {"bytes_sent", r.totals.bytesSent}, {"bytes_received", r.totals.bytesReceived},
                        {"closed_for_errors", r.hub.closedForErrors}, {"http_requests", r.totals.httpRequests}};
    printLine(stdout, dumpJson(j));
  } else if (!options.quiet) {
    printLine(stdout, fmt::format("throng serve: {} after {}: {} ticks, tick median {:.2f} ms, p99 {:.2f} ms, {} late",
                                  r.endReason, formatSeconds(r.wall), tickMs.size(), percentile(tickMs, 0.5),
                                  percentile(tickMs, 0.99), overruns));
    printLine(stdout, fmt::format("  crowd frames: encoding for every client median {:.2f} ms, p99 {:.2f} ms per tick; "
                                  "{} ticks skipped by the publisher",
                                  percentile(publishMs, 0.5), percentile(publishMs, 0.99), r.framesSkipped));
    printLine(stdout, fmt::format("  {} connections, {} crowd frames, {} sent, {} received", r.totals.peersOpened,
                                  r.hub.crowdFrames, formatBytes(static_cast<double>(r.totals.bytesSent)),
                                  formatBytes(static_cast<double>(r.totals.bytesReceived))));
  }
}

}  // namespace


/// `throng serve --help`'s text after the options.
constexpr const char* kServeFooter =
      "Runs the scenario in real time and serves it: the browser viewer and the motion clips over HTTP,\n"
      "the shared-world protocol (docs/protocol.md) over WebSocket at /ws on the same port and over UDP\n"
      "on --udp-port. Participants join with a name, move their avatars and guide groups. Each client\n"
      "gets one compressed, delta-coded crowd message per tick with the agents in its area of interest,\n"
      "at a level of detail by distance, and its animation every X frames, X regulated from its link.\n"
      "Ctrl-C tells every client why and stops. GET /api/status gives the server's state as JSON.\n"
      "Participants may insert crowds (InsertCrowd: a crowd file's JSON) and remove them; GET /api/crowds lists them.\n"
      "Given a recording (FILE.sqlite) instead, it plays it back as the same crowd messages: viewers\n"
      "play, pause, seek and change speed with ReplayControl messages (the viewer's timeline).\n"
      "With --recordings DIR the viewer lists the recordings in DIR (GET /api/recordings), uploads one into\n"
      "it (POST /api/recordings?name=FILE.sqlite: stored under a safe unique name once it checks as a throng\n"
      "recording, at most --max-upload MiB) and opens one (POST /api/recordings/open {\"name\": FILE}). Opening\n"
      "switches what this server plays for every viewer, as the replay timeline is shared: each client is told\n"
      "\"switching to recording FILE\" and closed, and the viewer reconnects and shows the new recording.\n"
      "Only plain .sqlite names directly in DIR are read (no paths, no links out of DIR). When the server was\n"
      "started with a scenario, POST /api/recordings/live (the viewer's Live button) plays it again, from its\n"
      "start, for every viewer.";

CLI::App* addServeCommand(CLI::App& app, ServeOptions& options) {
  CLI::App* cmd = app.add_subcommand("serve", "Serve a live crowd into a shared world (HTTP, WebSocket, UDP)");
  cmd->footer(kServeFooter);
  cmd->add_option("scenario", options.scenario, "Scenario JSON file, or a recording of `throng run` to play back")
      ->required()
      ->type_name("SCENARIO.json|FILE.sqlite");
  cmd->add_option("--port", options.port, "HTTP and WebSocket port (0: any free port, printed)")
      ->check(integerRange(0, 65535))
      ->capture_default_str();
  cmd->add_option("--udp-port", options.udpPort, "UDP port for native clients (0: any free port)")
      ->check(integerRange(0, 65535))
      ->capture_default_str();
  cmd->add_option("--udp-fragment", options.udpFragment,
                  "Largest datagram sent to UDP clients; a larger message (a key frame of a big crowd, the "
                  "world description) goes as several Fragment datagrams of at most this size")
      ->type_name("BYTES")
      ->check(integerRange(200, 65507))
      ->capture_default_str();
  cmd->add_option("--bind", options.bind, "Address to listen on (0.0.0.0: every interface)")->capture_default_str();
  cmd->add_option("--tick", options.tick, "Ticks per second in real time; default 1/dt of the scenario (the crowd "
                                          "then moves at its real speed)")
      ->type_name("HZ")
      ->check(positiveNumber("Hz"));
  cmd->add_option("--max-clients", options.maxClients, "Clients served at once; more are refused")
      ->check(integerRange(1, 100000))
      ->capture_default_str();
  cmd->add_option("--threads", options.threads, "Simulation worker threads; 0 = all hardware threads")
      ->check(integerRange(0, 1024))
      ->capture_default_str();
  cmd->add_option("--seed", options.seed, "Random seed; overrides the scenario's \"seed\"")->type_name("N");
  cmd->add_option("--duration", options.duration, "Stop after this many seconds of wall-clock time (default: until "
                                                  "Ctrl-C)")
      ->type_name("S")
      ->check(positiveNumber("s"));
  cmd->add_option("--web", options.web, "Directory of the browser viewer's built files (default: <prefix>/share/"
                                        "throng/web when installed, else web/dist of the source tree)")
      ->type_name("DIR");
  cmd->add_option("--budget", options.budgetKbit, "Bandwidth target per client [kbit/s]: above it a client's "
                                                  "animation granularity X grows")
      ->check(positiveNumber("kbit/s"))
      ->capture_default_str();
  cmd->add_option("--recordings", options.recordings, "Directory of recordings the viewer may list, open and upload "
                                                      "to (the page's Recordings row); opening one switches every viewer")
      ->type_name("DIR");
  cmd->add_option("--max-upload", options.maxUploadMiB, "Largest recording a viewer may upload into --recordings [MiB]")
      ->check(integerRange(1, 4096))
      ->capture_default_str();
  cmd->add_flag("--quiet", options.quiet, "No status line and no summary, only errors");
  cmd->add_flag("--json", options.json, "Summary as one JSON object on stdout");
  return cmd;
}

int runServe(const ServeOptions& options) {
  using namespace serve;
  InterruptGuard interrupts;
  std::unique_ptr<RecordingRoutes> recordings;
  if (!openRecordings(options, recordings)) return kExitFailure;
  std::optional<Served> served = openServed(options, options.scenario);
  if (!served) return kExitFailure;
  // A scenario (not a recording) served first is the live world a viewer can go back to.
  if (recordings && !served->replay) recordings->setLive(fs::path(options.scenario).filename().string());
  Bridge bridge(Clock::now());
  auto session = std::make_unique<Session>(options, std::move(*served), options.scenario, bridge, recordings.get());
  bridge.setHub(&session->hub);

  const fs::path web = webRoot(options.web);
  std::error_code ec;
  const bool haveViewer = !web.empty() && fs::is_regular_file(web / "index.html", ec);
  transport::TransportOptions t = transportOptionsFor(options, haveViewer ? web : fs::path());
  Router router(recordings.get());
  router.set(session.get());
  t.httpHandler = [&router](std::string_view target) { return router.get(target); };
  t.postHandler = [&router](transport::HttpRequest request, transport::HttpResponder responder) {
    return router.post(std::move(request), responder);
  };
  t.maxPostBytes = std::max(edit::kMaxBodyBytes, recordings ? static_cast<std::size_t>(options.maxUploadMiB) << 20 : 0);
  auto started = transport::Transport::start(t, bridge);
  if (!started) {
    printDiagnostics(started.errors());
    return kExitFailure;
  }
  std::unique_ptr<transport::Transport> transport = std::move(started).value();
  bridge.attach(transport.get());
  if (!options.quiet) printBanner(session->hubOptions.serverName, session->served.tickRate, options, *transport, haveViewer);

  ServeSummary summary;
  summary.endReason = runSessions(options, session, bridge, router, recordings.get());
  session->publisher.stop();
  if (!options.quiet && session->loop.terminal()) std::fputs("\n", stderr);
  const std::string goodbye = InterruptGuard::requested() ? "server shutting down (Ctrl-C)" : "server shutting down";
  session->close(goodbye);
  if (recordings) recordings->stop();  // its jobs and a waiting request hold HttpResponders
  transport->shutdown(goodbye);
  summary.totals = transport->totals();
  summary.hub = session->hub.status();
  summary.wall = bridge.now();
  summary.ticks = session->tickWatch.report(summary.wall);
  summary.tickRate = session->served.tickRate;
  summary.tickMs = &session->loop.tickMs();
  summary.publishMs = &session->publisher.ms();
  summary.framesSkipped = session->publisher.skipped();
  printSummary(options, summary);
  return InterruptGuard::requested() ? kExitInterrupted : kExitOk;
}

}  // namespace throng::cli
