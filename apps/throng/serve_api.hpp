// `throng serve`'s dynamic HTTP answers: TickWindow (tick and publish times for /api/status),
// WorldQueries (questions about the World that the simulation thread answers between ticks) and
// HttpApi (/api/groups, /api/crowds, /api/agent/<id>, /api/status, /api/world, /api/world/model
// (a glTF world file and its resources), /motions/<n>.bvh).
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
/// /api/crowds) and answered by the simulation thread between ticks, the only thread that may read
/// the World.
class WorldQueries {
 public:
  std::future<std::optional<sim::AgentInfo>> askAgent(std::uint32_t id);
  std::future<std::string> askGroups() { return ask(groups_); }
  std::future<std::string> askCrowds() { return ask(crowds_); }

  /// Answers every waiting question; `world` null (a replay): no agent, no groups, no crowds.
  void answer(const sim::World* world, const hub::Hub& hub);

 private:
  struct AgentQuery {
    std::uint32_t id = 0;
    std::promise<std::optional<sim::AgentInfo>> answer;
  };
  using TextQueries = std::vector<std::shared_ptr<std::promise<std::string>>>;
  std::future<std::string> ask(TextQueries& queries);

  std::mutex mutex_;
  std::vector<std::shared_ptr<AgentQuery>> agents_;
  TextQueries groups_;  ///< GET /api/groups
  TextQueries crowds_;  ///< GET /api/crowds
};

/// `body` as application/json with `status`.
[[nodiscard]] transport::HttpResponse jsonResponse(unsigned status, std::string body);

/// The server's dynamic HTTP paths (TransportOptions::httpHandler, on the transport thread):
/// /api/groups, /api/crowds, /api/agent/<id>, /api/status, /api/world, /api/world/model[/<file>]
/// and /motions/<n>.bvh.
class HttpApi {
 public:
  HttpApi(const Served& served, hub::Hub& hub, const Bridge& bridge, WorldQueries& queries, TickWindow& window,
          const hub::TickWatch& tickWatch);

  /// The answer for `target`'s path; nullopt when it is none of the paths above.
  std::optional<transport::HttpResponse> operator()(std::string_view target) const;

 private:
  static transport::HttpResponse waitForText(std::future<std::string> future);
  transport::HttpResponse agent(std::string_view digits) const;
  transport::HttpResponse status() const;
  transport::HttpResponse motion(std::string_view id) const;
  transport::HttpResponse model(std::string_view rest) const;

  const Served& served_;
  hub::Hub& hub_;
  const Bridge& bridge_;
  WorldQueries& queries_;
  TickWindow& window_;
  const hub::TickWatch& tickWatch_;
  const std::vector<sim::ClipInfo> clipTable_;
};

}  // namespace throng::cli::serve
