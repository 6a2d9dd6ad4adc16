// `throng serve --recordings DIR`'s HTTP routes (recording_routes.hpp): the listing, uploads on a
// worker thread, open requests handed to the simulation thread.
#include "recording_routes.hpp"

#include <chrono>

#include <nlohmann/json.hpp>


namespace throng::cli {
namespace {

constexpr std::string_view kList = "/api/recordings";
constexpr std::string_view kOpen = "/api/recordings/open";
constexpr std::string_view kLive = "/api/recordings/live";
constexpr auto kUploadLimit = std::chrono::seconds(120);  ///< wall-clock limit of one upload's check

transport::HttpResponse json(unsigned status, const nlohmann::json& body) {
  // Replacing invalid UTF-8 (a file name in DIR may have any bytes) rather than throwing.
  return transport::HttpResponse{status, "application/json",
                                 body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace), {}};
}

nlohmann::json entryJson(const RecordingEntry& e) {
  nlohmann::json j = {{"name", e.name}, {"size", e.size}, {"duration", e.duration}, {"agents", e.agents},
                      {"scenario", e.scenario}};
  if (!e.error.empty()) j["error"] = e.error;
  return j;
}

}  // namespace

transport::HttpResponse jsonError(unsigned status, const std::string& text) { return json(status, {{"error", text}}); }

std::optional<transport::HttpResponse> RecordingRoutes::get(std::string_view target) const {
  if (transport::targetPath(target) != kList) return std::nullopt;
  nlohmann::json list = nlohmann::json::array();
  for (const RecordingEntry& e : dir_.list()) list.push_back(entryJson(e));
  std::lock_guard lock(mutex_);
  return json(200, {{"dir", dir_.path().string()},
                    {"playing", playing_.empty() ? nlohmann::json(nullptr) : nlohmann::json(playing_)},
                    {"live", live_.empty() ? nlohmann::json(nullptr) : nlohmann::json(live_)},
                    {"maxUploadBytes", maxUpload_},
                    {"recordings", std::move(list)}});
}

bool RecordingRoutes::post(transport::HttpRequest& request, const transport::HttpResponder& responder) {
  const std::string_view path = transport::targetPath(request.target);
  if (path == kOpen) {
    open(request, responder);
    return true;
  }
  if (path == kLive) {
    live(responder);
    return true;
  }
  if (path == kList) {
    upload(request, responder);
    return true;
  }
  return false;
}

void RecordingRoutes::upload(transport::HttpRequest& request, const transport::HttpResponder& responder) {
  const std::optional<std::string> name = transport::queryValue(request.target, "name");
  if (!name || name->empty()) {
    responder.respond(jsonError(400, "POST /api/recordings?name=FILE.sqlite: the file's name is missing or malformed"));
    return;
  }
  // The check reads the whole recording: off the transport thread.
  auto body = std::make_shared<std::string>(std::move(request.body));
  const bool started = jobs_.launch(responder, kUploadLimit, [this, name = *name, body, responder](const edit::JobFlags&) {
    auto stored = dir_.store(name, *body, maxUpload_);
    if (!stored) {
      const bool tooLarge = body->size() > maxUpload_;
      responder.respond(jsonError(tooLarge ? 413 : 422, stored.errors().front().format()));
      return;
    }
    responder.respond(json(201, entryJson(stored.value())));
  });
  if (!started) responder.respond(jsonError(503, "busy: too many uploads at once; try again"));
}

void RecordingRoutes::open(const transport::HttpRequest& request, const transport::HttpResponder& responder) {
  const nlohmann::json body = nlohmann::json::parse(request.body, nullptr, false);
  if (!body.is_object() || !body.contains("name") || !body["name"].is_string()) {
    responder.respond(jsonError(400, R"(POST /api/recordings/open: expected {"name": "FILE.sqlite"})"));
    return;
  }
  const std::string name = body["name"].get<std::string>();
  auto path = dir_.resolve(name);
  if (!path) {
    responder.respond(jsonError(404, path.errors().front().format()));
    return;
  }
  queue(OpenRequest{name, path.value(), responder});
}

void RecordingRoutes::live(const transport::HttpResponder& responder) {
  std::string name;
  bool playingLive = false;
  {
    std::lock_guard lock(mutex_);
    name = live_;
    playingLive = playing_.empty();
  }
  if (name.empty()) {
    responder.respond(jsonError(409, "this server was started with a recording: there is no live scenario to go back to "
                                     "(throng serve SCENARIO --recordings DIR has one)"));
    return;
  }
  if (playingLive) {
    responder.respond(jsonError(409, "the live scenario " + name + " is already playing"));
    return;
  }
  queue(OpenRequest{name, {}, responder, true});
}

void RecordingRoutes::queue(OpenRequest request) {
  const std::string what = request.live ? "the live scenario" : request.name;
  std::optional<OpenRequest> replaced;
  {
    std::lock_guard lock(mutex_);
    replaced = std::move(open_);
    open_ = std::move(request);
    pending_.store(true, std::memory_order_release);
  }
  if (replaced) replaced->responder.respond(jsonError(409, "superseded: another viewer opened " + what));
}

std::optional<OpenRequest> RecordingRoutes::takeOpen() {
  std::lock_guard lock(mutex_);
  pending_.store(false, std::memory_order_release);
  std::optional<OpenRequest> taken = std::move(open_);
  open_.reset();
  return taken;
}

void RecordingRoutes::setPlaying(std::string name) {
  std::lock_guard lock(mutex_);
  playing_ = std::move(name);
}

void RecordingRoutes::setLive(std::string name) {
  std::lock_guard lock(mutex_);
  live_ = std::move(name);
}

void RecordingRoutes::stop() {
  jobs_.stop();
  if (auto waiting = takeOpen()) waiting->responder.respond(jsonError(503, "server shutting down"));
}

}  // namespace throng::cli
