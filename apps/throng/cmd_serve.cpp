// `throng serve SCENARIO.json` — runs the simulation in real time and serves it into a shared
// world (docs/server.md): HTTP (the browser viewer's files, the motion clips, /api/status) and
// WebSocket (/ws) on one port, the same protocol over UDP on another. The hub (libs/hub) does the
// sessions and crowd messages; the transport (libs/transport) the sockets; this file wires them to
// the World and keeps the tick on time. Reads the scenario and its clips; writes sockets, a status
// line on stderr (terminal only) and a summary on stdout. Ctrl-C tells every client why, then stops.
#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <future>
#include <condition_variable>
#include <map>
#include <mutex>
#include <unistd.h>
#include <thread>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "live_world.hpp"
#include "output.hpp"
#include "signal.hpp"
#include "validators.hpp"
#include "throng/core/parallel.hpp"
#include "throng/hub/hub.hpp"
#include "throng/hub/replay.hpp"
#include "throng/hub/text.hpp"
#include "throng/hub/tick_watch.hpp"
#include "throng/hub/world_description.hpp"
#include "throng/io/scenario_loader.hpp"
#include "throng/transport/transport.hpp"
#include "throng/sim/animation.hpp"
#include "throng/sim/world.hpp"

namespace throng::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/// Connects the transport's callbacks to the hub, and the hub's sends to the transport.
class Bridge final : public transport::TransportHandler, public hub::Outbox {
 public:
  explicit Bridge(Clock::time_point start) : start_(start) {}
  void attach(hub::Hub* h, transport::Transport* t) {
    hub_ = h;
    transport_ = t;
  }
  [[nodiscard]] double now() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

  // TransportHandler (transport thread).
  void onOpen(transport::PeerId peer, transport::PeerKind kind, std::string remote) override {
    if (hub_) hub_->onOpen(peer.value, std::move(remote), now());
  }
  void onMessage(transport::PeerId peer, std::span<const std::uint8_t> message) override {
    if (hub_) hub_->onMessage(peer.value, message, now());
  }
  void onClose(transport::PeerId peer, std::string_view reason) override {
    if (hub_) hub_->onClose(peer.value, reason);
  }

  // Outbox (either thread, hub mutex held; the transport only posts).
  void send(hub::PeerKey peer, std::vector<std::uint8_t> message, bool latest, std::uint32_t slot) override {
    if (transport_) {
      transport_->send(transport::PeerId{peer}, std::move(message),
                       latest ? transport::SendClass::Latest : transport::SendClass::Reliable, slot);
    }
  }
  void close(hub::PeerKey peer, std::string reason) override {
    if (transport_) transport_->close(transport::PeerId{peer}, std::move(reason));
  }
  [[nodiscard]] std::optional<hub::LinkCounters> link(hub::PeerKey peer) const override {
    if (!transport_) return std::nullopt;
    auto s = transport_->stats(transport::PeerId{peer});
    if (!s) return std::nullopt;
    return hub::LinkCounters{s->bytesSent, s->droppedLatest, s->queueBytes};
  }

 private:
  Clock::time_point start_;
  hub::Hub* hub_ = nullptr;
  transport::Transport* transport_ = nullptr;
};

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t k = std::min(v.size() - 1, static_cast<std::size_t>(p * static_cast<double>(v.size())));
  return v[k];
}

/// The viewer's files: --web, else web/dist of the source tree this binary was built from.
fs::path webRoot(const std::string& flag) {
  if (!flag.empty()) return flag;
#ifdef THRONG_WEB_DIST
  return THRONG_WEB_DIST;
#else
  return {};
#endif
}

/// A SQLite file (a recording) rather than a scenario: by its first bytes.
bool isRecording(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) return false;
  char head[16] = {};
  const std::size_t n = std::fread(head, 1, sizeof head, f);
  std::fclose(f);
  return n == sizeof head && std::memcmp(head, "SQLite format 3", 16) == 0;
}

/// The scenario stored in a recording, parsed as if it lay beside the recording, else in the source
/// tree's scenarios/ (where the bundled scenarios, their motion clips and databases are): its clip
/// and database paths are relative to the scenario's directory, which the recording does not keep.
/// `dir` receives the directory that worked.
core::Result<io::LoadedScenario> parseStoredScenario(const hub::Replay& replay, const std::string& recording,
                                                     fs::path& dir) {
  std::vector<fs::path> dirs{fs::path(recording).parent_path()};
#ifdef THRONG_SCENARIOS_DIR
  dirs.emplace_back(THRONG_SCENARIOS_DIR);
#endif
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

}  // namespace

CLI::App* addServeCommand(CLI::App& app, ServeOptions& options) {
  CLI::App* cmd = app.add_subcommand("serve", "Serve a live crowd into a shared world (HTTP, WebSocket, UDP)");
  cmd->footer(
      "Runs the scenario in real time and serves it: the browser viewer and the motion clips over HTTP,\n"
      "the shared-world protocol (docs/protocol.md) over WebSocket at /ws on the same port and over UDP\n"
      "on --udp-port. Participants join with a name, move their avatars and guide groups. Each client\n"
      "gets one compressed, delta-coded crowd message per tick with the agents in its area of interest,\n"
      "at a level of detail by distance, and its animation every X frames, X regulated from its link.\n"
      "Ctrl-C tells every client why and stops. GET /api/status gives the server's state as JSON.\n"
      "Participants may insert crowds (InsertCrowd: a crowd file's JSON) and remove them; GET /api/crowds lists them.\n"
      "Given a recording (FILE.sqlite) instead, it plays it back as the same crowd messages: viewers\n"
      "play, pause, seek and change speed with ReplayControl messages (the viewer's timeline).");
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
  cmd->add_option("--web", options.web, "Directory of the browser viewer's built files (default: web/dist of the "
                                        "source tree)")
      ->type_name("DIR");
  cmd->add_option("--budget", options.budgetKbit, "Bandwidth target per client [kbit/s]: above it a client's "
                                                  "animation granularity X grows")
      ->check(positiveNumber("kbit/s"))
      ->capture_default_str();
  cmd->add_flag("--quiet", options.quiet, "No status line and no summary, only errors");
  cmd->add_flag("--json", options.json, "Summary as one JSON object on stdout");
  return cmd;
}

int runServe(const ServeOptions& options) {
  InterruptGuard interrupts;
  if (auto missing = checkInputFile(options.scenario, "scenario"); !missing.empty()) {
    printDiagnostics(missing);
    return kExitFailure;
  }
  // A recording (`throng run`'s SQLite file) is played back instead of simulated.
  std::optional<hub::Replay> replay;
  if (isRecording(options.scenario)) {
    auto opened = hub::Replay::open(options.scenario);
    if (!opened) {
      printDiagnostics(opened.errors());
      return kExitFailure;
    }
    replay.emplace(std::move(opened).value());
  }
  fs::path storedScenarioDir;
  auto loaded = replay ? parseStoredScenario(*replay, options.scenario, storedScenarioDir)
                       : io::loadScenarioFile(options.scenario);
  const fs::path scenarioDir = replay ? storedScenarioDir : fs::path(options.scenario).parent_path();
  auto live = makeLiveWorld(std::move(loaded), options.seed, scenarioDir, "serve", options.quiet);
  if (!live) return kExitFailure;
  io::LoadedScenario* const scenario = &live->scenario;
  std::unique_ptr<sim::World>& world = live->world;
  const hub::MotionLibrary& motions = live->motions;
  const double dt = scenario->desc.dt;
  const double tickRate = options.tick ? *options.tick : replay ? std::max(1.0, replay->fps()) : 1.0 / dt;
  std::string worldJson = hub::describeWorld(*scenario, motions, *world, tickRate);
  if (replay) {
    nlohmann::json described = nlohmann::json::parse(worldJson);
    described["replay"] = {{"duration", replay->duration()}, {"fps", replay->fps()}, {"frames", replay->frameCount()}};
    worldJson = dumpJson(described);
  }
  hub::ReplayClock clock(replay ? replay->duration() : 0.0, true);

  const Clock::time_point start = Clock::now();
  Bridge bridge(start);
  hub::HubOptions hubOptions;
  // Sent in Welcome and printed: valid UTF-8, control characters escaped, at most 64 bytes.
  hubOptions.serverName = hub::printable(
      scenario->desc.name.empty() ? fs::path(options.scenario).stem().string() : scenario->desc.name, protocol::kMaxNameLength);
  hubOptions.maxClients = static_cast<std::size_t>(options.maxClients);
  hubOptions.granularity.budgetKbitPerSecond = options.budgetKbit;
  hubOptions.replay = replay.has_value();
  hub::Hub hub(hubOptions, worldJson, static_cast<float>(tickRate), motions, bridge);

  transport::TransportOptions t;
  t.bindAddress = options.bind;
  t.httpPort = static_cast<std::uint16_t>(options.port);
  t.udpPort = static_cast<std::uint16_t>(options.udpPort);
  t.maxPeers = static_cast<std::size_t>(options.maxClients) + 16;  // room to refuse politely
  t.maxUdpPeers = t.maxPeers;  // a separate budget: UDP peers never take a /ws slot
  t.maxDatagramBytes = 65507;  // the largest datagram accepted from a UDP client
  t.udpFragmentBytes = static_cast<std::size_t>(options.udpFragment);  // larger messages go as Fragments
  const fs::path web = webRoot(options.web);
  std::error_code ec;
  const bool haveViewer = !web.empty() && fs::is_regular_file(web / "index.html", ec);
  if (haveViewer) t.staticRoot = web;
  // Tick times of the last 10 s, for /api/status (read on the transport thread).
  std::mutex tickMutex;
  double tickMedianMs = 0.0, tickP99Ms = 0.0, publishMedianMs = 0.0, publishP99Ms = 0.0;
  // Late and stalled ticks, the one running now included (a tick stuck for 14 s shows at once).
  hub::TickWatch tickWatch(1.0 / tickRate);
  // Questions about one agent (GET /api/agent/<id>) are answered by the simulation thread between
  // ticks, the only thread that may read the World.
  struct AgentQuery {
    std::uint32_t id = 0;
    std::promise<std::optional<sim::AgentInfo>> answer;
  };
  std::mutex queryMutex;
  std::vector<std::shared_ptr<AgentQuery>> queries;
  std::vector<std::shared_ptr<std::promise<std::string>>> groupQueries;  ///< GET /api/groups
  std::vector<std::shared_ptr<std::promise<std::string>>> crowdQueries;  ///< GET /api/crowds
  const std::vector<sim::ClipInfo> clipTable = sim::animationClips(scenario->desc);
  t.httpHandler = [&](std::string_view target) -> std::optional<transport::HttpResponse> {
    const std::string_view path = target.substr(0, target.find('?'));
    if (path == "/api/groups" || path == "/api/crowds") {
      auto query = std::make_shared<std::promise<std::string>>();
      auto future = query->get_future();
      {
        std::lock_guard lock(queryMutex);
        (path == "/api/groups" ? groupQueries : crowdQueries).push_back(query);
      }
      if (future.wait_for(std::chrono::milliseconds(1000)) != std::future_status::ready) {
        return transport::HttpResponse{503, "application/json", R"({"error":"the simulation did not answer in time"})", {}};
      }
      return transport::HttpResponse{200, "application/json", future.get(), {}};
    }
    constexpr std::string_view kAgent = "/api/agent/";
    if (path.starts_with(kAgent)) {
      const std::string_view digits = path.substr(kAgent.size());
      std::uint64_t id = 0;
      const bool numeric = !digits.empty() && digits.size() <= 9 &&
                           std::all_of(digits.begin(), digits.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
      if (!numeric) return transport::HttpResponse{400, "application/json", R"({"error":"expected /api/agent/<id>, id a number"})", {}};
      for (char ch : digits) id = id * 10 + static_cast<std::uint64_t>(ch - '0');
      auto query = std::make_shared<AgentQuery>();
      query->id = static_cast<std::uint32_t>(id);
      auto future = query->answer.get_future();
      {
        std::lock_guard lock(queryMutex);
        queries.push_back(query);
      }
      if (future.wait_for(std::chrono::milliseconds(1000)) != std::future_status::ready) {
        return transport::HttpResponse{503, "application/json", R"({"error":"the simulation did not answer in time"})", {}};
      }
      const std::optional<sim::AgentInfo> info = future.get();
      if (!info) return transport::HttpResponse{404, "application/json", R"j({"error":"no such agent (not spawned yet, or left)"})j", {}};
      const sim::ScenarioDesc& d = scenario->desc;
      nlohmann::json j = {{"id", info->id}, {"group", info->group},
                          {"population", info->population < d.populations.size() ? d.populations[info->population].id : ""},
                          {"state", info->state}, {"position", {info->position.x, info->position.y}},
                          {"target", {info->target.x, info->target.y}}, {"speed", info->speed},
                          {"guided", info->guided},
                          {"behaviour", info->clip < clipTable.size() ? clipTable[info->clip].name : "?"}};
      if (info->goalPoint < d.points.size()) {
        const sim::PointDesc& p = d.points[info->goalPoint];
        j["goal"] = {{"point", p.id}, {"category", p.category}, {"action", p.action}};
      } else {
        j["goal"] = nullptr;
      }
      j["coordination"] = info->coordination == 0xffffffffu ? nlohmann::json(nullptr) : nlohmann::json(info->coordination);
      j["following"] = info->followedAgent == 0xffffffffu ? nlohmann::json(nullptr) : nlohmann::json(info->followedAgent);
      nlohmann::json script = nlohmann::json::array();
      for (const sim::ScriptRecord& r : hub.agentScript(info->id)) {
        script.push_back({{"coordination", r.coordination}, {"seq", r.seq}, {"role", r.role}, {"step", r.step},
                          {"behaviour", r.behaviour}, {"motion", r.motion}, {"start", r.start}, {"duration", r.duration},
                          {"plannedStart", r.plannedStart}, {"plannedDuration", r.plannedDuration},
                          {"targetAgent", r.targetType == 2 ? nlohmann::json(r.targetAgent) : nlohmann::json(nullptr)}});
      }
      j["script"] = std::move(script);
      return transport::HttpResponse{200, "application/json", dumpJson(j), {}};
    }
    if (path == "/api/status") {
      const hub::HubStatus s = hub.status();
      nlohmann::json clients = nlohmann::json::array();
      for (const hub::ClientStatus& c : s.perClient) {
        clients.push_back({{"name", c.name}, {"participant", c.participant}, {"participantId", c.participantId},
                           {"granularity", c.granularity}, {"granularityReason", c.granularityReason}, {"kbitPerSecond", c.kbitPerSecond},
                           {"roundTripMs", c.roundTripMs}, {"framesSent", c.framesSent},
                           {"agentsInView", c.agentsInView}, {"guiding", c.guiding}});
      }
      nlohmann::json j = {{"clients", s.clients}, {"participants", s.participants}, {"crowdFrames", s.crowdFrames},
                          {"crowdBytes", s.crowdBytes}, {"perClient", std::move(clients)}};
      {
        const hub::TickReport r = tickWatch.report(bridge.now());
        std::lock_guard lock(tickMutex);
        j["tick"] = {{"median_ms", tickMedianMs}, {"p99_ms", tickP99Ms}, {"late", r.late}, {"stalls", r.stalls},
                     {"longest_ms", r.longestMs}, {"running_ms", r.runningMs}, {"rate", tickRate},
                     {"publish_median_ms", publishMedianMs}, {"publish_p99_ms", publishP99Ms}};
      }
      return transport::HttpResponse{200, "application/json", dumpJson(j), {}};
    }
    if (path == "/api/world") return transport::HttpResponse{200, "application/json", worldJson, {}};
    constexpr std::string_view kMotions = "/motions/";
    if (path.starts_with(kMotions) && path.ends_with(".bvh")) {
      const std::string_view id = path.substr(kMotions.size(), path.size() - kMotions.size() - 4);
      std::size_t index = 0;
      for (char ch : id) {
        if (ch < '0' || ch > '9' || index > 100000) return transport::HttpResponse{404, "text/plain", "no such clip\n", {}};
        index = index * 10 + static_cast<std::size_t>(ch - '0');
      }
      if (id.empty() || index >= motions.clips().size() || motions.clipFile(index).empty()) {
        return transport::HttpResponse{404, "text/plain", "no such clip\n", {}};
      }
      return transport::HttpResponse{200, "text/plain; charset=utf-8", {}, motions.clipFile(index)};
    }
    return std::nullopt;
  };
  auto started = transport::Transport::start(t, bridge);
  if (!started) {
    printDiagnostics(started.errors());
    return kExitFailure;
  }
  std::unique_ptr<transport::Transport> transport = std::move(started).value();
  bridge.attach(&hub, transport.get());
  const std::string host = options.bind == "0.0.0.0" ? "127.0.0.1" : options.bind;
  if (!options.quiet) {
    printLine(stdout, fmt::format("throng serve: {} — {:.4g} ticks/s", hubOptions.serverName, tickRate));
    printLine(stdout, fmt::format("  viewer     http://{}:{}/{}", host, transport->httpPort(),
                                  haveViewer ? "" : "  (not built: scripts/demo.sh builds it)"));
    printLine(stdout, fmt::format("  websocket  ws://{}:{}/ws", host, transport->httpPort()));
    printLine(stdout, fmt::format("  udp        {}:{}", host, transport->udpPort()));
    printLine(stdout, "  Ctrl-C to stop");
  }

  core::TaskSystem tasks(options.threads);
  // The publisher: encodes and sends each client's crowd frame on its own thread, so the tick
  // stays on time whatever the clients cost; when it falls behind it skips to the newest frame.
  core::TaskSystem publishTasks(options.threads);
  std::mutex frameMutex;
  std::condition_variable frameReady;
  sim::FramePtr pending;
  bool stopPublisher = false;
  std::vector<double> publishMs;
  std::uint64_t framesSkipped = 0;
  std::thread publisher([&] {
    while (true) {
      sim::FramePtr frame;
      {
        std::unique_lock lock(frameMutex);
        frameReady.wait(lock, [&] { return pending != nullptr || stopPublisher; });
        if (stopPublisher) return;
        frame = std::move(pending);
        pending.reset();
      }
      const auto p0 = Clock::now();
      hub.publish(*frame, bridge.now(), &publishTasks);
      const double ms = std::chrono::duration<double, std::milli>(Clock::now() - p0).count();
      std::lock_guard lock(frameMutex);
      publishMs.push_back(ms);
    }
  });
  const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / tickRate));
  std::vector<double> tickMs;
  auto next = Clock::now();
  double lastStatus = 0.0, lastWindow = 0.0, lastReplayWall = 0.0, lastReplayStatus = -1.0;
  std::uint64_t lastBytes = 0;
  const bool terminal = isatty(fileno(stderr)) != 0;
  std::string endReason = "duration reached";
  while (true) {
    if (InterruptGuard::requested()) {
      endReason = "interrupted (Ctrl-C)";
      break;
    }
    if (options.duration && bridge.now() >= *options.duration) break;
    const auto t0 = Clock::now();
    tickWatch.started(bridge.now());
    sim::FramePtr frame;
    if (replay) {
      // Playback: the clients' controls move the clock; the frame is the recorded one at its time.
      bool changed = false;
      for (const protocol::ReplayControl& c : hub.takeReplayControls()) changed = clock.apply(c) || changed;
      const double wall = bridge.now();
      changed = clock.advance(wall - lastReplayWall) || changed;
      lastReplayWall = wall;
      if (changed || wall - lastReplayStatus >= 1.0) {
        lastReplayStatus = wall;
        hub.broadcast(protocol::encode(clock.status()));
      }
      frame = replay->frameAt(clock.time());
    } else {
      hub.applyToWorld(*world);
      world->step(tasks);
      frame = world->snapshot();
    }
    hub.observe(*frame);
    {
      std::lock_guard lock(queryMutex);
      for (const auto& q : queries) q->answer.set_value(replay ? std::nullopt : world->agentInfo(q->id));
      queries.clear();
      if (!groupQueries.empty()) {
        // The groups as they are now (most spawn after the start, so the world description lacks them).
        nlohmann::json groups = nlohmann::json::array();
        if (!replay) {
          // world->desc(): crowds inserted at run time appended their populations (and groups).
          const sim::ScenarioDesc& desc = world->desc();
          for (std::size_t g = 0; g < world->groupCount(); ++g) {
            const auto info = world->groupInfo(world->groupById(static_cast<std::uint32_t>(g)));
            if (!info) continue;
            groups.push_back({{"id", info->id},
                              {"population", info->population < desc.populations.size()
                                                 ? desc.populations[info->population].id
                                                 : std::string()},
                              {"members", info->members}, {"leader", info->leader}, {"guided", info->guided},
                              {"waiting", info->waiting}});
          }
        }
        const std::string text = dumpJson(groups);
        for (const auto& q : groupQueries) q->set_value(text);
        groupQueries.clear();
      }
      if (!crowdQueries.empty()) {
        // Crowds inserted at run time (InsertCrowd, timeline), in insertion order.
        nlohmann::json crowds = nlohmann::json::array();
        if (!replay) {
          const sim::ScenarioDesc& desc = world->desc();
          const std::map<std::string, std::uint32_t> owners = hub.crowdOwners();
          for (const sim::CrowdInfo& c : world->crowds()) {
            nlohmann::json populations = nlohmann::json::array();
            for (std::uint32_t p = c.firstPopulation; p < c.firstPopulation + c.populations && p < desc.populations.size(); ++p) {
              populations.push_back(desc.populations[p].id);
            }
            // Its owner: the participant that inserted it (only it may remove it); null: the scenario's.
            const auto owner = owners.find(c.id);
            crowds.push_back({{"id", c.id}, {"index", c.index}, {"applied", c.applied}, {"removed", c.removed},
                              {"insertTick", c.insertTick}, {"populations", populations},
                              {"owner", owner == owners.end() ? nlohmann::json(nullptr) : nlohmann::json(owner->second)}});
          }
        }
        const std::string text = dumpJson(crowds);
        for (const auto& q : crowdQueries) q->set_value(text);
        crowdQueries.clear();
      }
    }
    const auto t1 = Clock::now();
    {
      std::lock_guard lock(frameMutex);
      if (pending) ++framesSkipped;
      pending = frame;
    }
    frameReady.notify_one();
    tickMs.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    next += period;
    tickWatch.finished(bridge.now(), t1 > next);
    if (t1 > next) {
      next = t1;  // late: start the next tick now, never try to catch up in a burst
    } else {
      std::this_thread::sleep_until(next);
    }
    const double now = bridge.now();
    if (now - lastWindow >= 1.0) {
      lastWindow = now;
      const std::size_t recent = std::min<std::size_t>(tickMs.size(), static_cast<std::size_t>(tickRate * 10));
      std::vector<double> window(tickMs.end() - static_cast<std::ptrdiff_t>(recent), tickMs.end());
      std::vector<double> publishWindow;
      {
        std::lock_guard lock(frameMutex);
        const std::size_t n = std::min(publishMs.size(), recent);
        publishWindow.assign(publishMs.end() - static_cast<std::ptrdiff_t>(n), publishMs.end());
      }
      std::lock_guard lock(tickMutex);
      tickMedianMs = percentile(window, 0.5);
      tickP99Ms = percentile(window, 0.99);
      publishMedianMs = percentile(publishWindow, 0.5);
      publishP99Ms = percentile(publishWindow, 0.99);
    }
    if (!options.quiet && terminal && now - lastStatus >= 1.0) {
      const hub::HubStatus s = hub.status();
      const double kbit = static_cast<double>(s.crowdBytes - lastBytes) * 8.0 / 1000.0 / (now - lastStatus);
      lastBytes = s.crowdBytes;
      lastStatus = now;
      double p99 = 0.0;
      {
        std::lock_guard lock(tickMutex);
        p99 = tickP99Ms;
      }
      std::fprintf(stderr, "\r  t %s  agents %zu  clients %zu (%zu participants)  tick p99 %.1f ms  out %.0f kbit/s   ",
                   formatSeconds(frame->time).c_str(), frame->size(), s.clients, s.participants, p99, kbit);
      std::fflush(stderr);
    }
  }
  {
    std::lock_guard lock(frameMutex);
    stopPublisher = true;
  }
  frameReady.notify_one();
  publisher.join();
  if (!options.quiet && terminal) std::fputs("\n", stderr);
  const std::string goodbye = InterruptGuard::requested() ? "server shutting down (Ctrl-C)" : "server shutting down";
  hub.shutdown(goodbye);
  transport->shutdown(goodbye);
  const transport::TransportTotals totals = transport->totals();
  const hub::HubStatus s = hub.status();
  const double wall = bridge.now();
  const hub::TickReport ticks = tickWatch.report(wall);
  const std::uint64_t overruns = ticks.late;
  if (options.json) {
    nlohmann::json j = {{"scenario", options.scenario}, {"end", endReason}, {"seconds", wall},
                        {"ticks", tickMs.size()}, {"tickRate", tickRate},
                        {"ms_per_tick_median", percentile(tickMs, 0.5)}, {"ms_per_tick_p99", percentile(tickMs, 0.99)},
                        {"overruns", overruns}, {"stalls", ticks.stalls}, {"longest_tick_ms", ticks.longestMs},
                        {"publish_ms_median", percentile(publishMs, 0.5)},
                        {"publish_ms_p99", percentile(publishMs, 0.99)}, {"frames_skipped", framesSkipped},
                        {"peers_opened", totals.peersOpened},
                        {"crowd_frames", s.crowdFrames}, {"crowd_bytes", s.crowdBytes},
                        {"bytes_sent", totals.bytesSent}, {"bytes_received", totals.bytesReceived},
                        {"closed_for_errors", s.closedForErrors}, {"http_requests", totals.httpRequests}};
    printLine(stdout, dumpJson(j));
  } else if (!options.quiet) {
    printLine(stdout, fmt::format("throng serve: {} after {}: {} ticks, tick median {:.2f} ms, p99 {:.2f} ms, {} late",
                                  endReason, formatSeconds(wall), tickMs.size(), percentile(tickMs, 0.5),
                                  percentile(tickMs, 0.99), overruns));
    printLine(stdout, fmt::format("  crowd frames: encoding for every client median {:.2f} ms, p99 {:.2f} ms per tick; "
                                  "{} ticks skipped by the publisher",
                                  percentile(publishMs, 0.5), percentile(publishMs, 0.99), framesSkipped));
    printLine(stdout, fmt::format("  {} connections, {} crowd frames, {} sent, {} received", totals.peersOpened,
                                  s.crowdFrames, formatBytes(static_cast<double>(totals.bytesSent)),
                                  formatBytes(static_cast<double>(totals.bytesReceived))));
  }
  return InterruptGuard::requested() ? kExitInterrupted : kExitOk;
}

}  // namespace throng::cli
