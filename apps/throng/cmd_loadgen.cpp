// `throng loadgen URL --clients N --duration S [--udp]` — simulated participants for a running
// `throng serve`: each joins, walks its avatar along a loop, a share of them guide a group, and
// every one decodes and acknowledges its crowd frames. Reports per client kbit/s, messages/s,
// frame delay percentiles, lost frames, its animation granularity and the agents it saw per detail
// tier (near, middle, far), and the server's tick time (from GET /api/status). Reads and writes
// sockets; writes the report on stdout.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numeric>
#include <thread>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "output.hpp"
#include "signal.hpp"
#include "validators.hpp"
#include "throng/client/session.hpp"
#include "throng/core/rng.hpp"
#include "throng/client/http_client.hpp"

namespace throng::cli {
namespace {

using Clock = std::chrono::steady_clock;

struct Url {
  std::string host;
  std::uint16_t port = 0;
  std::string path;
};

std::optional<Url> parseUrl(const std::string& url) {
  const std::string scheme = "ws://";
  if (url.rfind(scheme, 0) != 0) return std::nullopt;
  const std::string rest = url.substr(scheme.size());
  const std::size_t slash = rest.find('/');
  const std::string authority = rest.substr(0, slash);
  const std::size_t colon = authority.rfind(':');
  if (colon == std::string::npos || colon == 0) return std::nullopt;
  Url u;
  u.host = authority.substr(0, colon);
  try {
    const int port = std::stoi(authority.substr(colon + 1));
    if (port <= 0 || port > 65535) return std::nullopt;
    u.port = static_cast<std::uint16_t>(port);
  } catch (...) {
    return std::nullopt;
  }
  u.path = slash == std::string::npos ? "/ws" : rest.substr(slash);
  return u;
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(p * static_cast<double>(v.size())))];
}

/// The walkable bounds of the served world (from its description's scenario).
struct Bounds {
  float minX = 0, minY = 0, maxX = 10, maxY = 10;
};

Bounds worldBounds(const nlohmann::json& world) {
  Bounds b{1e30f, 1e30f, -1e30f, -1e30f};
  const auto& walkable = world["scenario"]["walkable"];
  for (const auto& polygon : walkable) {
    const auto& ring = polygon.is_object() && polygon.contains("outline") ? polygon["outline"] : polygon;
    for (const auto& p : ring) {
      if (!p.is_array() || p.size() < 2 || !p[0].is_number() || !p[1].is_number()) continue;
      b.minX = std::min(b.minX, p[0].get<float>());
      b.maxX = std::max(b.maxX, p[0].get<float>());
      b.minY = std::min(b.minY, p[1].get<float>());
      b.maxY = std::max(b.maxY, p[1].get<float>());
    }
  }
  if (b.minX > b.maxX) return Bounds{};
  return b;
}

struct Participant {
  std::unique_ptr<client::Session> session;
  float cx = 0, cy = 0, radius = 3;  ///< the loop the avatar walks
  float angle = 0;
  std::optional<std::uint32_t> guiding;
  double nextMove = 0;
  std::string closed;
};


/// What the served world offers the participants: where they may walk, how many groups to guide.
struct ServedWorld {
  Bounds bounds;
  std::size_t groups = 0;
};

/// Places a participant's loop: a random centre in the world and radius 2 to 5 m, unless --at and
/// --loop-radius say otherwise (the draws happen either way, so the others' loops stay put).
void placeLoop(Participant& p, const Bounds& bounds, const LoadgenOptions& options, core::Rng& rng) {
  p.cx = bounds.minX + static_cast<float>(rng.uniform()) * (bounds.maxX - bounds.minX);
  p.cy = bounds.minY + static_cast<float>(rng.uniform()) * (bounds.maxY - bounds.minY);
  p.radius = 2.0f + 3.0f * static_cast<float>(rng.uniform());
  if (options.at.size() == 2) {
    p.cx = static_cast<float>(options.at[0]);
    p.cy = static_cast<float>(options.at[1]);
  }
  if (options.loopRadius > 0.0) p.radius = static_cast<float>(options.loopRadius);
  p.angle = 6.2831853f * static_cast<float>(rng.uniform());
}

/// Opens and joins --clients sessions (the first one's world description gives `world`);
/// nullopt when one fails (printed).
std::optional<std::vector<Participant>> openParticipants(const LoadgenOptions& options, const Url& url, ServedWorld& world) {
  std::vector<Participant> people;
  core::Rng rng(1, 0, core::RngPurpose::Spawn);
  for (int i = 0; i < options.clients; ++i) {
    client::SessionOptions so;
    so.host = url.host;
    so.port = url.port;
    so.path = url.path;
    so.udp = options.udp;
    so.udpPort = static_cast<std::uint16_t>(options.udpPort);
    so.kind = protocol::ClientKind::Loadgen;
    so.name = fmt::format("loadgen-{}", i);
    auto opened = client::Session::open(so);
    if (!opened) {
      printDiagnostics(opened.errors());
      return std::nullopt;
    }
    Participant p;
    p.session = std::move(opened).value();
    if (i == 0) {
      const auto described = nlohmann::json::parse(p.session->worldJson(), nullptr, false);
      if (!described.is_discarded()) {
        world.bounds = worldBounds(described);
        world.groups = described.contains("groups") ? described["groups"].size() : 0;
      }
    }
    auto joined = p.session->join(so.name);
    if (!joined) {
      printDiagnostics(joined.errors());
      return std::nullopt;
    }
    placeLoop(p, world.bounds, options, rng);
    people.push_back(std::move(p));
  }
  return people;
}

/// Every 0.1 s a participant steps along its loop at 1.3 m/s; guide `i` (i < guides) takes group
/// i mod groups after 0.5 s. Then its session reads what arrived.
void stepParticipant(Participant& p, std::size_t i, double now, std::size_t guides, std::size_t groups) {
  if (!p.session->open()) return;
  if (now >= p.nextMove) {
    p.nextMove = now + 0.1;
    p.angle += 1.3f * 0.1f / p.radius;
    const float x = p.cx + p.radius * std::cos(p.angle), y = p.cy + p.radius * std::sin(p.angle);
    (void)p.session->move(x, y, p.angle + 1.5707963f);
    if (i < guides && !p.guiding && now > 0.5) {
      p.guiding = static_cast<std::uint32_t>(i % groups);
      (void)p.session->guide(*p.guiding);
    }
  }
  if (!p.session->pump()) p.closed = p.session->closeReason();
}

/// Runs the participants until --duration or Ctrl-C, with a progress line on a terminal; returns
/// the seconds they ran.
double runParticipants(std::vector<Participant>& people, const LoadgenOptions& options, std::size_t guides,
                       std::size_t groups) {
  const Clock::time_point start = Clock::now();
  auto seconds = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  const bool terminal = !options.quiet && isatty(fileno(stderr)) != 0;
  double lastStatus = 0;
  while (seconds() < options.duration && !InterruptGuard::requested()) {
    const double now = seconds();
    for (std::size_t i = 0; i < people.size(); ++i) stepParticipant(people[i], i, now, guides, groups);
    if (terminal && now - lastStatus >= 1.0) {
      lastStatus = now;
      std::uint64_t frames = 0;
      for (const Participant& p : people) frames += p.session->stats().crowdFrames;
      std::fprintf(stderr, "\r  %.0f/%.0f s  %zu clients  %llu crowd frames received   ", now, options.duration,
                   people.size(), static_cast<unsigned long long>(frames));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  if (terminal) std::fputs("\n", stderr);
  return seconds();
}

nlohmann::json tierJson(double near, double middle, double far) {
  return nlohmann::json{{"near", near}, {"middle", middle}, {"far", far}};
}

/// One client's figures, for --json.
nlohmann::json clientJson(std::size_t i, const client::SessionStats& s, double kbit, double elapsed, const std::string& closed) {
  const double perFrame = 1.0 / static_cast<double>(std::max<std::uint64_t>(1, s.crowdFrames));
  return nlohmann::json{{"client", i}, {"kbit_per_s", kbit},
                        {"messages_per_s", static_cast<double>(s.messagesReceived) / elapsed},
                        {"crowd_frames", s.crowdFrames}, {"key_frames", s.keyFrames},
                        {"lost_frames", s.lostFrames}, {"undecodable", s.undecodable},
                        {"frame_delay_ms_p50", percentile(s.frameDelayMs, 0.5)},
                        {"frame_delay_ms_p99", percentile(s.frameDelayMs, 0.99)},
                        {"round_trip_ms", s.roundTripMs}, {"agents_in_view", s.agentsInView},
                        {"tiers", nlohmann::json{{"near", s.tiersInView[0]}, {"middle", s.tiersInView[1]},
                                                 {"far", s.tiersInView[2]}}},
                        {"tiers_mean", tierJson(static_cast<double>(s.tierSums[0]) * perFrame,
                                                static_cast<double>(s.tierSums[1]) * perFrame,
                                                static_cast<double>(s.tierSums[2]) * perFrame)},
                        {"far_max", s.farMax},
                        {"granularity", s.animationInterval}, {"closed", closed}};
}

/// Every client's figures together.
struct LoadTotals {
  std::vector<double> kbits, delays;
  std::uint64_t lost = 0, frames = 0, closed = 0;
  std::array<std::uint64_t, 3> tierSums{};  ///< over every client's frames
  std::uint32_t farMax = 0;
  double tierMean[3] = {};                  ///< agents per frame in each tier

  [[nodiscard]] double kbitMean() const {
    return kbits.empty() ? 0.0 : std::accumulate(kbits.begin(), kbits.end(), 0.0) / static_cast<double>(kbits.size());
  }
  [[nodiscard]] double kbitMax() const { return kbits.empty() ? 0.0 : *std::max_element(kbits.begin(), kbits.end()); }
};

/// Adds up the clients' figures; with --json prints each client's line on the way.
LoadTotals addUp(const std::vector<Participant>& people, double elapsed, bool json) {
  LoadTotals t;
  for (std::size_t i = 0; i < people.size(); ++i) {
    const client::SessionStats& s = people[i].session->stats();
    const double kbit = static_cast<double>(s.bytesReceived) * 8.0 / 1000.0 / elapsed;
    t.kbits.push_back(kbit);
    t.delays.insert(t.delays.end(), s.frameDelayMs.begin(), s.frameDelayMs.end());
    t.lost += s.lostFrames;
    t.frames += s.crowdFrames;
    for (std::size_t k = 0; k < 3; ++k) t.tierSums[k] += s.tierSums[k];
    t.farMax = std::max(t.farMax, s.farMax);
    if (!people[i].closed.empty()) ++t.closed;
    if (json) printLine(stdout, clientJson(i, s, kbit, elapsed, people[i].closed).dump());
  }
  const double allFrames = static_cast<double>(std::max<std::uint64_t>(1, t.frames));
  for (std::size_t k = 0; k < 3; ++k) t.tierMean[k] = static_cast<double>(t.tierSums[k]) / allFrames;
  return t;
}

/// The summary: one JSON object (--json) or five lines. `server` is GET /api/status's answer.
void printLoadSummary(const LoadgenOptions& options, const LoadTotals& t, const nlohmann::json& server,
                      std::size_t clients, std::size_t guides, double elapsed) {
  const double tickP99 = server.is_object() && server.contains("tick") ? server["tick"].value("p99_ms", 0.0) : 0.0;
  const double tickMedian = server.is_object() && server.contains("tick") ? server["tick"].value("median_ms", 0.0) : 0.0;
  if (options.json) {
    printLine(stdout, nlohmann::json{{"summary", true}, {"clients", clients}, {"udp", options.udp},
                                     {"seconds", elapsed}, {"kbit_per_s_mean", t.kbitMean()},
                                     {"kbit_per_s_max", t.kbitMax()},
                                     {"crowd_frames", t.frames}, {"lost_frames", t.lost},
                                     {"frame_delay_ms_p50", percentile(t.delays, 0.5)},
                                     {"frame_delay_ms_p95", percentile(t.delays, 0.95)},
                                     {"frame_delay_ms_p99", percentile(t.delays, 0.99)}, {"closed_by_server", t.closed},
                                     {"tiers_mean", tierJson(t.tierMean[0], t.tierMean[1], t.tierMean[2])}, {"far_max", t.farMax},
                                     {"server_tick_ms_median", tickMedian}, {"server_tick_ms_p99", tickP99}}
                          .dump());
    return;
  }
  printLine(stdout, fmt::format("throng loadgen: {} {} clients for {:.1f} s ({} guiding)", clients,
                                options.udp ? "UDP" : "WebSocket", elapsed, guides));
  printLine(stdout, fmt::format("  per client   {:.1f} kbit/s mean, {:.1f} max; {:.1f} crowd frames/s", t.kbitMean(),
                                t.kbitMax(),
                                static_cast<double>(t.frames) / elapsed / static_cast<double>(std::max<std::size_t>(1, clients))));
  printLine(stdout, fmt::format("  frame delay  p50 {:.1f} ms, p95 {:.1f} ms, p99 {:.1f} ms; {} frames lost of {}",
                                percentile(t.delays, 0.5), percentile(t.delays, 0.95), percentile(t.delays, 0.99), t.lost,
                                t.frames + t.lost));
  printLine(stdout, fmt::format("  in view      near {:.1f}, middle {:.1f}, far {:.1f} agents (mean per frame); at most {} far",
                                t.tierMean[0], t.tierMean[1], t.tierMean[2], t.farMax));
  printLine(stdout, fmt::format("  server tick  median {:.2f} ms, p99 {:.2f} ms; {} clients closed by the server",
                                tickMedian, tickP99, t.closed));
}

}  // namespace

CLI::App* addLoadgenCommand(CLI::App& app, LoadgenOptions& options) {
  CLI::App* cmd = app.add_subcommand("loadgen", "Simulated participants for a running throng serve");
  cmd->footer(
      "Opens --clients sessions to a throng server; each joins as a participant, walks its avatar\n"
      "along a loop at 1.3 m/s (10 Move messages per second), a share of them guide a group, and\n"
      "all decode and acknowledge their crowd frames. At the end: per-client kbit/s, messages/s,\n"
      "frame delay percentiles (arrival against the tick schedule), lost frames, animation\n"
      "granularity X, agents in view per detail tier (near: joint poses, middle: clip and phase,\n"
      "far: position only; mean per frame, and the most far agents in any frame), and the server's\n"
      "tick time from GET /api/status. --at and --loop-radius place the avatars' loops, e.g. at the\n"
      "centre of a world to keep every agent within the animated tiers.");
  cmd->add_option("url", options.url, "The server's WebSocket URL")->type_name("ws://HOST:PORT/ws")->capture_default_str();
  cmd->add_option("--clients", options.clients, "Simulated participants")->check(integerRange(1, 10000))->capture_default_str();
  cmd->add_option("--duration", options.duration, "How long they stay [s]")->check(positiveNumber("s"))->capture_default_str();
  cmd->add_flag("--udp", options.udp, "Speak UDP to --udp-port (native clients) instead of WebSocket");
  cmd->add_option("--udp-port", options.udpPort, "The server's UDP port")->check(integerRange(1, 65535))->capture_default_str();
  cmd->add_option("--guide-share", options.guideShare, "Share of the clients that guide a group [0, 1]")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--at", options.at, "Centre of every avatar's loop (default: a random point of the world each)")
      ->type_name("X,Y")
      ->expected(2)
      ->delimiter(',')
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            double v = 0;
            if (!CLI::detail::lexical_cast(text, v) || !std::isfinite(v) || std::abs(v) > 1e6) {
              return "value " + text + " is not a coordinate in metres (a finite number within ±1e6 m)";
            }
            return {};
          },
          "m", "COORDINATE"));
  cmd->add_option("--loop-radius", options.loopRadius, "Radius of the avatars' loops [m] (default: random, 2 to 5 m)")
      ->check(positiveNumber("m"));
  cmd->add_flag("--json", options.json, "One JSON object per client and a summary object, one per line");
  cmd->add_flag("--quiet", options.quiet, "No progress line");
  return cmd;
}

int runLoadgen(const LoadgenOptions& options) {
  InterruptGuard interrupts;
  const auto url = parseUrl(options.url);
  if (!url) {
    std::fprintf(stderr, "throng loadgen: bad URL '%s'; expected ws://HOST:PORT/PATH (e.g. ws://127.0.0.1:8080/ws)\n",
                 options.url.c_str());
    return kExitUsage;
  }
  ServedWorld world;
  auto opened = openParticipants(options, *url, world);
  if (!opened) return kExitFailure;
  std::vector<Participant>& people = *opened;
  const std::size_t guides =
      world.groups == 0 ? 0
                        : std::min<std::size_t>(world.groups, static_cast<std::size_t>(std::round(
                                                                  options.guideShare * static_cast<double>(people.size()))));
  const double elapsed = runParticipants(people, options, guides, world.groups);
  // The server's view (tick time under this load) before the clients leave.
  nlohmann::json server;
  if (auto reply = client::httpRequest(url->host, url->port, "GET", "/api/status"); reply && reply->status == 200) {
    server = nlohmann::json::parse(reply->body, nullptr, false);
  }
  for (Participant& p : people) {
    if (p.guiding) (void)p.session->release(*p.guiding);
    p.session->close("loadgen done");
  }
  const LoadTotals totals = addUp(people, elapsed, options.json);
  printLoadSummary(options, totals, server, people.size(), guides, elapsed);
  return totals.closed == 0 ? kExitOk : kExitFailure;
}

}  // namespace throng::cli
