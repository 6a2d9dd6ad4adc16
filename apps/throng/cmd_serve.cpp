// `throng serve SCENARIO.json` — runs the simulation in real time and serves it into a shared
// world (docs/server.md): HTTP (the browser viewer's files, the motion clips, /api/status) and
// WebSocket (/ws) on one port, the same protocol over UDP on another. The hub (libs/hub) does the
// sessions and crowd messages; the transport (libs/transport) the sockets; this file wires them to
// the World and keeps the tick on time. Reads the scenario and its clips; writes sockets, a status
// line on stderr (terminal only) and a summary on stdout. Ctrl-C tells every client why, then stops.
//
// The parts: Bridge (transport callbacks → hub, hub sends → transport), Served (the scenario or
// recording and its World), WorldQueries (HTTP questions answered between ticks), HttpApi (the
// dynamic HTTP paths), Publisher (crowd frames encoded on their own thread), TickLoop (the real-time
// loop), Session (all of these for one world), Router (HTTP to the session in use and to the
// recordings directory, recording_routes.hpp), switchRecording (a viewer opened another recording:
// a new Session, the clients told and closed) and printSummary.
#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <future>
#include <condition_variable>
#include <map>
#include <mutex>
#include <shared_mutex>
#include <unistd.h>
#include <thread>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "bench_files.hpp"
#include "commands.hpp"
#include "data_dirs.hpp"
#include "edit_jobs.hpp"
#include "edit_routes.hpp"
#include "live_world.hpp"
#include "output.hpp"
#include "recording_routes.hpp"
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

/// Connects the transport's callbacks to the hub, and the hub's sends to the transport. The hub
/// changes when a viewer opens another recording (setHub, simulation thread): without one, a new
/// connection is closed at once (its viewer reconnects to the next hub) and messages are dropped.
class Bridge final : public transport::TransportHandler, public hub::Outbox {
 public:
  explicit Bridge(Clock::time_point start) : start_(start) {}
  void attach(transport::Transport* t) { transport_ = t; }
  void setHub(hub::Hub* h) {
    std::unique_lock lock(hubMutex_);
    hub_ = h;
  }
  [[nodiscard]] double now() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

  // TransportHandler (transport thread).
  void onOpen(transport::PeerId peer, transport::PeerKind kind, std::string remote) override {
    std::shared_lock lock(hubMutex_);
    if (hub_) {
      hub_->onOpen(peer.value, std::move(remote), now());
    } else if (transport_) {
      transport_->close(peer, "switching recordings");
    }
  }
  void onMessage(transport::PeerId peer, std::span<const std::uint8_t> message) override {
    std::shared_lock lock(hubMutex_);
    if (hub_) hub_->onMessage(peer.value, message, now());
  }
  void onClose(transport::PeerId peer, std::string_view reason) override {
    std::shared_lock lock(hubMutex_);
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
  std::shared_mutex hubMutex_;
  hub::Hub* hub_ = nullptr;
  transport::Transport* transport_ = nullptr;
};

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t k = std::min(v.size() - 1, static_cast<std::size_t>(p * static_cast<double>(v.size())));
  return v[k];
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

/// A SQLite file (a recording) rather than a scenario: by its first bytes.
bool isRecording(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) return false;
  char head[16] = {};
  const std::size_t n = std::fread(head, 1, sizeof head, f);
  std::fclose(f);
  return n == sizeof head && std::memcmp(head, "SQLite format 3", 16) == 0;
}

/// The scenario stored in a recording, parsed as if it lay beside the recording, else in the bundled
/// scenarios/ (installed, else the source tree's: where the bundled scenarios, their motion clips and databases are): its clip
/// and database paths are relative to the scenario's directory, which the recording does not keep.
/// `dir` receives the directory that worked.
core::Result<io::LoadedScenario> parseStoredScenario(const hub::Replay& replay, const std::string& recording,
                                                     fs::path& dir) {
  std::vector<fs::path> dirs{fs::path(recording).parent_path()};
  if (const auto installed = installedDataDir(currentExecutable()); !installed.empty()) {
    dirs.push_back(installed / "scenarios");
  }
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


/// The scenario served: simulated live, or a recording (`throng run`'s SQLite file) played back.
struct Served {
  LiveWorld live;
  std::optional<hub::Replay> replay;
  double tickRate = 0.0;  ///< ticks per second in real time
  std::string worldJson;  ///< the world description (Welcome, /api/world)
};

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
  return Served{std::move(*live), std::move(replay), tickRate, std::move(worldJson)};
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

/// Tick and publish times of the last 10 s, for /api/status: written by the simulation thread once
/// a second, read on the transport thread.
struct TickWindow {
  std::mutex mutex;
  double tickMedianMs = 0.0, tickP99Ms = 0.0, publishMedianMs = 0.0, publishP99Ms = 0.0;
};

/// The groups as they are now (most spawn after the start, so the world description lacks them).
nlohmann::json groupsJson(const sim::World& world) {
  nlohmann::json groups = nlohmann::json::array();
  // world.desc(): crowds inserted at run time appended their populations (and groups).
  const sim::ScenarioDesc& desc = world.desc();
  for (std::size_t g = 0; g < world.groupCount(); ++g) {
    const auto info = world.groupInfo(world.groupById(static_cast<std::uint32_t>(g)));
    if (!info) continue;
    groups.push_back({{"id", info->id},
                      {"population", info->population < desc.populations.size() ? desc.populations[info->population].id
                                                                                 : std::string()},
                      {"members", info->members}, {"leader", info->leader}, {"guided", info->guided},
                      {"waiting", info->waiting}});
  }
  return groups;
}

/// Crowds inserted at run time (InsertCrowd, timeline), in insertion order, with their owners.
nlohmann::json crowdsJson(const sim::World& world, const std::map<std::string, std::uint32_t>& owners) {
  nlohmann::json crowds = nlohmann::json::array();
  const sim::ScenarioDesc& desc = world.desc();
  for (const sim::CrowdInfo& c : world.crowds()) {
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
  return crowds;
}

/// Questions about the World asked by HTTP handlers (GET /api/agent/<id>, /api/groups,
/// /api/crowds) and answered by the simulation thread between ticks, the only thread that may read
/// the World.
class WorldQueries {
 public:
  std::future<std::optional<sim::AgentInfo>> askAgent(std::uint32_t id) {
    auto query = std::make_shared<AgentQuery>();
    query->id = id;
    auto future = query->answer.get_future();
    std::lock_guard lock(mutex_);
    agents_.push_back(std::move(query));
    return future;
  }
  std::future<std::string> askGroups() { return ask(groups_); }
  std::future<std::string> askCrowds() { return ask(crowds_); }

  /// Answers every waiting question; `world` null (a replay): no agent, no groups, no crowds.
  void answer(const sim::World* world, const hub::Hub& hub) {
    std::lock_guard lock(mutex_);
    for (const auto& q : agents_) q->answer.set_value(world ? world->agentInfo(q->id) : std::nullopt);
    agents_.clear();
    if (!groups_.empty()) {
      const std::string text = dumpJson(world ? groupsJson(*world) : nlohmann::json::array());
      for (const auto& q : groups_) q->set_value(text);
      groups_.clear();
    }
    if (!crowds_.empty()) {
      const std::string text = dumpJson(world ? crowdsJson(*world, hub.crowdOwners()) : nlohmann::json::array());
      for (const auto& q : crowds_) q->set_value(text);
      crowds_.clear();
    }
  }

 private:
  struct AgentQuery {
    std::uint32_t id = 0;
    std::promise<std::optional<sim::AgentInfo>> answer;
  };
  using TextQueries = std::vector<std::shared_ptr<std::promise<std::string>>>;
  std::future<std::string> ask(TextQueries& queries) {
    auto query = std::make_shared<std::promise<std::string>>();
    auto future = query->get_future();
    std::lock_guard lock(mutex_);
    queries.push_back(std::move(query));
    return future;
  }

  std::mutex mutex_;
  std::vector<std::shared_ptr<AgentQuery>> agents_;
  TextQueries groups_;  ///< GET /api/groups
  TextQueries crowds_;  ///< GET /api/crowds
};

transport::HttpResponse jsonResponse(unsigned status, std::string body) {
  return transport::HttpResponse{status, "application/json", std::move(body), {}};
}

/// What the simulation thread did not answer within a second.
transport::HttpResponse simulationTimeout() {
  return jsonResponse(503, R"({"error":"the simulation did not answer in time"})");
}

/// One agent's state, goal, coordination and Common Ground script, for GET /api/agent/<id>.
nlohmann::json agentJson(const sim::AgentInfo& info, const sim::ScenarioDesc& d, const std::vector<sim::ClipInfo>& clips,
                         const std::vector<sim::ScriptRecord>& records) {
  nlohmann::json j = {{"id", info.id}, {"group", info.group},
                      {"population", info.population < d.populations.size() ? d.populations[info.population].id : ""},
                      {"state", info.state}, {"position", {info.position.x, info.position.y}},
                      {"target", {info.target.x, info.target.y}}, {"speed", info.speed},
                      {"guided", info.guided},
                      {"behaviour", info.clip < clips.size() ? clips[info.clip].name : "?"}};
  if (info.goalPoint < d.points.size()) {
    const sim::PointDesc& p = d.points[info.goalPoint];
    j["goal"] = {{"point", p.id}, {"category", p.category}, {"action", p.action}};
  } else {
    j["goal"] = nullptr;
  }
  j["coordination"] = info.coordination == 0xffffffffu ? nlohmann::json(nullptr) : nlohmann::json(info.coordination);
  j["following"] = info.followedAgent == 0xffffffffu ? nlohmann::json(nullptr) : nlohmann::json(info.followedAgent);
  nlohmann::json script = nlohmann::json::array();
  for (const sim::ScriptRecord& r : records) {
    script.push_back({{"coordination", r.coordination}, {"seq", r.seq}, {"role", r.role}, {"step", r.step},
                      {"behaviour", r.behaviour}, {"motion", r.motion}, {"start", r.start}, {"duration", r.duration},
                      {"plannedStart", r.plannedStart}, {"plannedDuration", r.plannedDuration},
                      {"targetAgent", r.targetType == 2 ? nlohmann::json(r.targetAgent) : nlohmann::json(nullptr)}});
  }
  j["script"] = std::move(script);
  return j;
}

/// The server's dynamic HTTP paths (TransportOptions::httpHandler, on the transport thread):
/// /api/groups, /api/crowds, /api/agent/<id>, /api/status, /api/world and /motions/<n>.bvh.
class HttpApi {
 public:
  HttpApi(const Served& served, hub::Hub& hub, const Bridge& bridge, WorldQueries& queries, TickWindow& window,
          const hub::TickWatch& tickWatch)
      : served_(served),
        hub_(hub),
        bridge_(bridge),
        queries_(queries),
        window_(window),
        tickWatch_(tickWatch),
        clipTable_(sim::animationClips(served.live.scenario.desc)) {}

  std::optional<transport::HttpResponse> operator()(std::string_view target) const {
    const std::string_view path = target.substr(0, target.find('?'));
    if (path == "/api/groups" || path == "/api/crowds") {
      return waitForText(path == "/api/groups" ? queries_.askGroups() : queries_.askCrowds());
    }
    constexpr std::string_view kAgent = "/api/agent/";
    if (path.starts_with(kAgent)) return agent(path.substr(kAgent.size()));
    if (path == "/api/status") return status();
    if (path == "/api/world") return jsonResponse(200, served_.worldJson);
    constexpr std::string_view kMotions = "/motions/";
    if (path.starts_with(kMotions) && path.ends_with(".bvh")) {
      return motion(path.substr(kMotions.size(), path.size() - kMotions.size() - 4));
    }
    return std::nullopt;
  }

 private:
  static transport::HttpResponse waitForText(std::future<std::string> future) {
    if (future.wait_for(std::chrono::milliseconds(1000)) != std::future_status::ready) return simulationTimeout();
    return jsonResponse(200, future.get());
  }

  transport::HttpResponse agent(std::string_view digits) const {
    const bool numeric = !digits.empty() && digits.size() <= 9 &&
                         std::all_of(digits.begin(), digits.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
    if (!numeric) return jsonResponse(400, R"({"error":"expected /api/agent/<id>, id a number"})");
    std::uint64_t id = 0;
    for (char ch : digits) id = id * 10 + static_cast<std::uint64_t>(ch - '0');
    auto future = queries_.askAgent(static_cast<std::uint32_t>(id));
    if (future.wait_for(std::chrono::milliseconds(1000)) != std::future_status::ready) return simulationTimeout();
    const std::optional<sim::AgentInfo> info = future.get();
    if (!info) return jsonResponse(404, R"j({"error":"no such agent (not spawned yet, or left)"})j");
    return jsonResponse(200, dumpJson(agentJson(*info, served_.live.scenario.desc, clipTable_, hub_.agentScript(info->id))));
  }

  transport::HttpResponse status() const {
    const hub::HubStatus s = hub_.status();
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
      const hub::TickReport r = tickWatch_.report(bridge_.now());
      std::lock_guard lock(window_.mutex);
      j["tick"] = {{"median_ms", window_.tickMedianMs}, {"p99_ms", window_.tickP99Ms}, {"late", r.late}, {"stalls", r.stalls},
                   {"longest_ms", r.longestMs}, {"running_ms", r.runningMs}, {"rate", served_.tickRate},
                   {"publish_median_ms", window_.publishMedianMs}, {"publish_p99_ms", window_.publishP99Ms}};
    }
    return jsonResponse(200, dumpJson(j));
  }

  transport::HttpResponse motion(std::string_view id) const {
    const hub::MotionLibrary& motions = served_.live.motions;
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

  const Served& served_;
  hub::Hub& hub_;
  const Bridge& bridge_;
  WorldQueries& queries_;
  TickWindow& window_;
  const hub::TickWatch& tickWatch_;
  const std::vector<sim::ClipInfo> clipTable_;
};

/// Encodes and sends each client's crowd frame on its own thread, so the tick stays on time
/// whatever the clients cost; when it falls behind it skips to the newest frame.
class Publisher {
 public:
  Publisher(hub::Hub& hub, const Bridge& bridge, int threads)
      : hub_(hub), bridge_(bridge), tasks_(threads), thread_([this] { loop(); }) {}
  ~Publisher() { stop(); }
  Publisher(const Publisher&) = delete;
  Publisher& operator=(const Publisher&) = delete;

  /// The newest frame; one not yet taken is replaced (and counted as skipped).
  void offer(sim::FramePtr frame) {
    {
      std::lock_guard lock(mutex_);
      if (pending_) ++skipped_;
      pending_ = std::move(frame);
    }
    ready_.notify_one();
  }
  /// The last `n` publish times [ms].
  std::vector<double> recentMs(std::size_t n) {
    std::lock_guard lock(mutex_);
    n = std::min(ms_.size(), n);
    return {ms_.end() - static_cast<std::ptrdiff_t>(n), ms_.end()};
  }
  /// Ends the thread (a frame waiting is dropped). Idempotent.
  void stop() {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
    }
    ready_.notify_one();
    if (thread_.joinable()) thread_.join();
  }
  // After stop():
  [[nodiscard]] const std::vector<double>& ms() const { return ms_; }
  [[nodiscard]] std::uint64_t skipped() const { return skipped_; }

 private:
  void loop() {
    while (true) {
      sim::FramePtr frame;
      {
        std::unique_lock lock(mutex_);
        ready_.wait(lock, [&] { return pending_ != nullptr || stop_; });
        if (stop_) return;
        frame = std::move(pending_);
        pending_.reset();
      }
      const auto p0 = Clock::now();
      hub_.publish(*frame, bridge_.now(), &tasks_);
      const double ms = std::chrono::duration<double, std::milli>(Clock::now() - p0).count();
      std::lock_guard lock(mutex_);
      ms_.push_back(ms);
    }
  }

  hub::Hub& hub_;
  const Bridge& bridge_;
  core::TaskSystem tasks_;
  std::mutex mutex_;
  std::condition_variable ready_;
  sim::FramePtr pending_;
  bool stop_ = false;
  std::vector<double> ms_;
  std::uint64_t skipped_ = 0;
  std::thread thread_;  // last: starts once everything above exists
};

/// What TickLoop::run returns when a viewer asked to open a recording.
constexpr const char* kOpenRecording = "open a recording";

/// The real-time loop on the simulation thread: one frame per period (stepped, or the recording's
/// at the replay clock), questions answered, the frame handed to the publisher, the status window
/// and line refreshed once a second. Runs until Ctrl-C or --duration.
class TickLoop {
 public:
  TickLoop(const ServeOptions& options, Served& served, hub::Hub& hub, const Bridge& bridge, WorldQueries& queries,
           TickWindow& window, hub::TickWatch& tickWatch, Publisher& publisher, const RecordingRoutes* recordings)
      : options_(options),
        served_(served),
        hub_(hub),
        bridge_(bridge),
        queries_(queries),
        window_(window),
        tickWatch_(tickWatch),
        publisher_(publisher),
        recordings_(recordings),
        clock_(served.replay ? served.replay->duration() : 0.0, true),
        tasks_(options.threads),
        terminal_(isatty(fileno(stderr)) != 0) {}

  /// Why it ended: "interrupted (Ctrl-C)", "duration reached" or kOpenRecording (a viewer asked
  /// for another recording: see RecordingRoutes::takeOpen). May be called again after kOpenRecording.
  std::string run() {
    const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / served_.tickRate));
    auto next = Clock::now();
    while (true) {
      if (InterruptGuard::requested()) return "interrupted (Ctrl-C)";
      if (options_.duration && bridge_.now() >= *options_.duration) return "duration reached";
      if (recordings_ && recordings_->pending()) return kOpenRecording;
      const auto t0 = Clock::now();
      tickWatch_.started(bridge_.now());
      const sim::FramePtr frame = nextFrame();
      hub_.observe(*frame);
      queries_.answer(served_.replay ? nullptr : served_.live.world.get(), hub_);
      const auto t1 = Clock::now();
      publisher_.offer(frame);
      tickMs_.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
      next += period;
      tickWatch_.finished(bridge_.now(), t1 > next);
      if (t1 > next) {
        next = t1;  // late: start the next tick now, never try to catch up in a burst
      } else {
        std::this_thread::sleep_until(next);
      }
      const double now = bridge_.now();
      if (now - lastWindow_ >= 1.0) refreshWindow(now);
      if (!options_.quiet && terminal_ && now - lastStatus_ >= 1.0) printStatus(*frame, now);
    }
  }
  [[nodiscard]] const std::vector<double>& tickMs() const { return tickMs_; }
  [[nodiscard]] bool terminal() const { return terminal_; }

 private:
  sim::FramePtr nextFrame() {
    if (!served_.replay) {
      hub_.applyToWorld(*served_.live.world);
      served_.live.world->step(tasks_);
      return served_.live.world->takeFrame();
    }
    // Playback: the clients' controls move the clock; the frame is the recorded one at its time.
    bool changed = false;
    for (const protocol::ReplayControl& c : hub_.takeReplayControls()) changed = clock_.apply(c) || changed;
    const double wall = bridge_.now();
    changed = clock_.advance(wall - lastReplayWall_) || changed;
    lastReplayWall_ = wall;
    if (changed || wall - lastReplayStatus_ >= 1.0) {
      lastReplayStatus_ = wall;
      hub_.broadcast(protocol::encode(clock_.status()));
    }
    return served_.replay->frameAt(clock_.time());
  }

  /// Tick and publish percentiles over the last 10 s, for /api/status.
  void refreshWindow(double now) {
    lastWindow_ = now;
    const std::size_t recent = std::min<std::size_t>(tickMs_.size(), static_cast<std::size_t>(served_.tickRate * 10));
    std::vector<double> window(tickMs_.end() - static_cast<std::ptrdiff_t>(recent), tickMs_.end());
    std::vector<double> publishWindow = publisher_.recentMs(recent);
    std::lock_guard lock(window_.mutex);
    window_.tickMedianMs = percentile(window, 0.5);
    window_.tickP99Ms = percentile(window, 0.99);
    window_.publishMedianMs = percentile(publishWindow, 0.5);
    window_.publishP99Ms = percentile(publishWindow, 0.99);
  }

  /// The status line on a terminal's stderr.
  void printStatus(const sim::Frame& frame, double now) {
    const hub::HubStatus s = hub_.status();
    const double kbit = static_cast<double>(s.crowdBytes - lastBytes_) * 8.0 / 1000.0 / (now - lastStatus_);
    lastBytes_ = s.crowdBytes;
    lastStatus_ = now;
    double p99 = 0.0;
    {
      std::lock_guard lock(window_.mutex);
      p99 = window_.tickP99Ms;
    }
    std::fprintf(stderr, "\r  t %s  agents %zu  clients %zu (%zu participants)  tick p99 %.1f ms  out %.0f kbit/s   ",
                 formatSeconds(frame.time).c_str(), frame.size(), s.clients, s.participants, p99, kbit);
    std::fflush(stderr);
  }

  const ServeOptions& options_;
  Served& served_;
  hub::Hub& hub_;
  const Bridge& bridge_;
  WorldQueries& queries_;
  TickWindow& window_;
  hub::TickWatch& tickWatch_;
  Publisher& publisher_;
  const RecordingRoutes* recordings_;
  hub::ReplayClock clock_;
  core::TaskSystem tasks_;
  const bool terminal_;
  std::vector<double> tickMs_;
  double lastStatus_ = 0.0, lastWindow_ = 0.0, lastReplayWall_ = 0.0, lastReplayStatus_ = -1.0;
  std::uint64_t lastBytes_ = 0;
};

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

/// The editor's routes for the world served: its scenario text (a JSON scenario, or the one a
/// recording stores; none for a glTF world, whose editor page starts empty), never saved.
edit::EditApi editorFor(const std::string& path, const Served& served, edit::Jobs& jobs) {
  const std::string& text = served.live.scenario.text;
  const auto first = text.find_first_not_of(" \t\r\n");
  std::optional<std::string> scenario;
  if (first != std::string::npos && text[first] == '{') scenario = text;
  return edit::EditApi({}, jobs, "/editor", std::move(scenario), path);
}

/// One world served and everything that serves it: the hub, its HTTP answers, the editor on its
/// scenario, the publisher and the tick loop. Rebuilt when a viewer opens another recording; the
/// transport and the recordings directory outlive it. Not movable (its parts refer to each other).
struct Session {
  Session(const ServeOptions& options, Served world, std::string path, Bridge& bridge, const RecordingRoutes* recordings)
      : source(std::move(path)),
        served(std::move(world)),
        hubOptions(hubOptionsFor(options, served, source)),
        hub(hubOptions, served.worldJson, static_cast<float>(served.tickRate), served.live.motions, bridge),
        tickWatch(1.0 / served.tickRate),  // late and stalled ticks, the one running now included
        api(served, hub, bridge, queries, tickWindow, tickWatch),
        editor(editorFor(source, served, editJobs)),
        publisher(hub, bridge, options.threads),
        loop(options, served, hub, bridge, queries, tickWindow, tickWatch, publisher, recordings) {}
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  /// Stops publishing, tells every client `reason` and closes it, ends the editor's jobs.
  void close(const std::string& reason) {
    publisher.stop();
    hub.shutdown(reason);
    editJobs.stop();  // each job holds an HttpResponder: done before the transport goes
  }

  std::string source;  ///< the scenario or recording served
  Served served;
  hub::HubOptions hubOptions;
  hub::Hub hub;
  TickWindow tickWindow;
  hub::TickWatch tickWatch;
  WorldQueries queries;
  HttpApi api;
  edit::Jobs editJobs;
  edit::EditApi editor;  // the scenario editor at /editor/: check, preview, import, download; never saves
  Publisher publisher;
  TickLoop loop;
};

/// The transport's HTTP hooks (transport thread), for the transport's whole life: the recordings
/// directory's routes, then the current session's (editor first), none while sessions change.
class Router {
 public:
  explicit Router(RecordingRoutes* recordings) : recordings_(recordings) {}

  void set(Session* session) {
    std::unique_lock lock(mutex_);
    session_ = session;
  }

  std::optional<transport::HttpResponse> get(std::string_view target) {
    if (recordings_) {
      if (auto answer = recordings_->get(target)) return answer;
    } else if (target.substr(0, target.find('?')) == "/api/recordings") {
      // Answered, not 404: the viewer asks every server, and a browser logs each failed fetch.
      return transport::HttpResponse{200, "application/json",
                                     R"({"dir":null,"playing":null,"maxUploadBytes":0,"recordings":[]})", {}};
    }
    std::shared_lock lock(mutex_);
    if (session_ == nullptr) return jsonError(503, "switching recordings; try again");
    if (auto answer = session_->editor.get(target)) return answer;
    return session_->api(target);
  }

  bool post(transport::HttpRequest request, const transport::HttpResponder& responder) {
    if (recordings_ && recordings_->post(request, responder)) return true;
    if (!recordings_ && request.target.starts_with("/api/recordings")) {
      responder.respond(noRecordings());
      return true;
    }
    // The transport's limit is the upload's; the editor keeps its own.
    if (request.body.size() > edit::kMaxBodyBytes) {
      responder.respond(jsonError(413, fmt::format("request body too large; the limit is {} bytes", edit::kMaxBodyBytes)));
      return true;
    }
    std::shared_lock lock(mutex_);
    if (session_ == nullptr) {
      responder.respond(jsonError(503, "switching recordings; try again"));
      return true;
    }
    return session_->editor.post(std::move(request), responder);
  }

 private:
  static transport::HttpResponse noRecordings() {
    return jsonError(404, "this server has no recordings directory (throng serve --recordings DIR)");
  }
  RecordingRoutes* recordings_;
  std::shared_mutex mutex_;
  Session* session_ = nullptr;
};

/// The recordings directory of --recordings, or nullptr without it; false when it cannot be used.
bool openRecordings(const ServeOptions& options, std::unique_ptr<RecordingRoutes>& out) {
  if (options.recordings.empty()) return true;
  auto dir = RecordingsDir::open(options.recordings);
  if (!dir) {
    printDiagnostics(dir.errors());
    return false;
  }
  const std::size_t maxUpload = static_cast<std::size_t>(options.maxUploadMiB) << 20;
  // The positional recording, when it is one of DIR's, is listed as playing.
  std::error_code ec;
  const fs::path given = fs::weakly_canonical(options.scenario, ec);
  const std::string name = fs::path(options.scenario).filename().string();
  auto inDir = dir.value().resolve(name);
  const bool playing = !ec && inDir && inDir.value() == given;
  out = std::make_unique<RecordingRoutes>(std::move(dir).value(), maxUpload);
  if (playing) out->setPlaying(name);
  return true;
}

/// Replaces `session` by one playing the recording a viewer asked for; on failure the old one goes
/// on. Answers the request either way. Every client of the old one is told why and closed: its
/// viewer reconnects and, finding another world, reloads itself (docs/viewer.md).
void switchRecording(const ServeOptions& options, OpenRequest request, std::unique_ptr<Session>& session,
                     Bridge& bridge, Router& router, RecordingRoutes& recordings) {
  std::optional<Served> next = openServed(options, request.path.string());
  if (!next) {
    request.responder.respond(
        jsonError(422, fmt::format("{}: cannot be played (the server's log says why)", request.name)));
    return;
  }
  bridge.setHub(nullptr);
  router.set(nullptr);
  session->close("switching to recording " + request.name);
  session.reset();
  session = std::make_unique<Session>(options, std::move(*next), request.path.string(), bridge, &recordings);
  bridge.setHub(&session->hub);
  router.set(session.get());
  recordings.setPlaying(request.name);
  request.responder.respond(transport::HttpResponse{
      200, "application/json", dumpJson({{"opened", request.name}, {"server", session->hubOptions.serverName}}), {}});
  if (!options.quiet) printLine(stdout, "throng serve: now playing " + request.name);
}

/// Runs the tick loop of the session in use, switching recordings on request, until Ctrl-C or
/// --duration; why it ended.
std::string runSessions(const ServeOptions& options, std::unique_ptr<Session>& session, Bridge& bridge, Router& router,
                        RecordingRoutes* recordings) {
  while (true) {
    std::string reason = session->loop.run();
    if (reason != kOpenRecording || recordings == nullptr) return reason;
    if (std::optional<OpenRequest> request = recordings->takeOpen()) {
      switchRecording(options, std::move(*request), session, bridge, router, *recordings);
    }
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
      "Only plain .sqlite names directly in DIR are read (no paths, no links out of DIR). Going back to a\n"
      "live scenario takes a restart.";

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
  InterruptGuard interrupts;
  std::unique_ptr<RecordingRoutes> recordings;
  if (!openRecordings(options, recordings)) return kExitFailure;
  std::optional<Served> served = openServed(options, options.scenario);
  if (!served) return kExitFailure;
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
