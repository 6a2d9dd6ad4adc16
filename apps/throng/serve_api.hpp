// `throng serve`'s dynamic HTTP answers: TickWindow (tick and publish times for /api/status),
// WorldQueries (questions about the World, and exits to open or close, that the simulation thread
// answers between ticks) and HttpApi (/api/groups, /api/crowds, /api/agent/<id>, /api/status,
// /api/world, /api/world/model (a glTF world file and its resources), /motions/<n>.bvh, and
// POST /api/exits/<id>).
#pragma once
#include <cstdint>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "serve_bridge.hpp"
#include "serve_world.hpp"
#include "throng/hub/hub.hpp"
#include "throng/hub/tick_watch.hpp"
#include "throng/sim/world.hpp"
#include "throng/transport/transport.hpp"

namespace throng::cli::serve {

/// Tick and publish times of the last 10 s, for /api/status: written by the simulation thread once
/// a second, read on the transport thread.
struct TickWindow {
  std::mutex mutex;
  double tickMedianMs = 0.0, tickP99Ms = 0.0, publishMedianMs = 0.0, publishP99Ms = 0.0;
};

/// Questions about the World asked by HTTP handlers (GET /api/agent/<id>, /api/groups,
/// /api/crowds) and exits to open or close (POST /api/exits/<id>), answered by the simulation
/// thread between ticks, the only thread that may read or change the World.
class WorldQueries {
 public:
  std::future<std::optional<sim::AgentInfo>> askAgent(std::uint32_t id);
  std::future<std::string> askGroups() { return ask(groups_); }
  std::future<std::string> askCrowds() { return ask(crowds_); }
  /// World::setExitOpen(id, open) between two ticks: true when `id` names an exit.
  std::future<bool> askSetExitOpen(std::string id, bool open);

  /// Answers every waiting question; `world` null (a replay): no agent, no groups, no crowds, no exit.
  void answer(sim::World* world, const hub::Hub& hub);

 private:
  struct AgentQuery {
    std::uint32_t id = 0;
    std::promise<std::optional<sim::AgentInfo>> answer;
  };
  struct ExitCommand {
    std::string id;
    bool open = true;
    std::promise<bool> found;
  };
  using TextQueries = std::vector<std::shared_ptr<std::promise<std::string>>>;
  std::future<std::string> ask(TextQueries& queries);

  std::mutex mutex_;
  std::vector<std::shared_ptr<AgentQuery>> agents_;
  TextQueries groups_;  ///< GET /api/groups
  TextQueries crowds_;  ///< GET /api/crowds
  std::vector<std::shared_ptr<ExitCommand>> exits_;  ///< POST /api/exits/<id>
};

/// `body` as application/json with `status`.
[[nodiscard]] transport::HttpResponse jsonResponse(unsigned status, std::string body);

/// The server's dynamic HTTP paths (TransportOptions::httpHandler, on the transport thread):
/// /api/groups, /api/crowds, /api/agent/<id>, /api/status, /api/world, /api/world/model[/<file>]
/// and /motions/<n>.bvh; POST /api/exits/<id> (post).
class HttpApi {
 public:
  HttpApi(const Served& served, hub::Hub& hub, const Bridge& bridge, WorldQueries& queries, TickWindow& window,
          const hub::TickWatch& tickWatch);

  /// The answer for `target`'s path; nullopt when it is none of the paths above.
  std::optional<transport::HttpResponse> operator()(std::string_view target) const;
  /// POST /api/exits/<id> (id percent-encoded) with {"open": true|false}: the exit opens or closes
  /// from the next tick. 400 for a bad body, 404 for an id that is no exit, 409 in a replay;
  /// nullopt for any other path.
  std::optional<transport::HttpResponse> post(const transport::HttpRequest& request) const;

 private:
  static transport::HttpResponse waitForText(std::future<std::string> future);
  transport::HttpResponse agent(std::string_view digits) const;
  transport::HttpResponse status() const;
  transport::HttpResponse motion(std::string_view id) const;
  transport::HttpResponse model(std::string_view rest) const;
  transport::HttpResponse setExitOpen(std::string_view encodedId, const std::string& body) const;

  const Served& served_;
  hub::Hub& hub_;
  const Bridge& bridge_;
  WorldQueries& queries_;
  TickWindow& window_;
  const hub::TickWatch& tickWatch_;
  const std::vector<sim::ClipInfo> clipTable_;
};

}  // namespace throng::cli::serve
