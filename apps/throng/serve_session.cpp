// `throng serve`'s sessions (serve_session.hpp): a Session's parts built and closed, the Router's
// GET and POST, the recordings directory opened, and switchRecording (a viewer opened another
// recording: a new Session, the old one's clients told and closed) run by runSessions.
#include "serve_session.hpp"

#include <chrono>
#include <filesystem>
#include <future>
#include <system_error>

#include <fmt/format.h>

#include "output.hpp"

namespace throng::cli::serve {
namespace {

namespace fs = std::filesystem;

/// The editor's routes for the world served: its scenario text (a JSON scenario, or the one a
/// recording stores; none for a glTF world, whose editor page starts empty), never saved.
edit::EditApi editorFor(const std::string& path, const Served& served, edit::Jobs& jobs) {
  const std::string& text = served.live.scenario.text;
  const auto first = text.find_first_not_of(" \t\r\n");
  std::optional<std::string> scenario;
  if (first != std::string::npos && text[first] == '{') scenario = text;
  return edit::EditApi({}, jobs, "/editor", std::move(scenario), path);
}

/// A recordings route asked of a server without --recordings.
transport::HttpResponse noRecordings() {
  return jsonError(404, "this server has no recordings directory (throng serve --recordings DIR)");
}

/// How often the old session's questions are answered while the next world loads.
constexpr auto kAnswerWhileLoading = std::chrono::milliseconds(20);

/// Replaces `session` by one playing the recording a viewer asked for, or the live scenario the
/// server was started with (from its start: the live world that was left is not kept); on failure
/// the old one goes on. Answers the request either way. Every client of the old one is told why and
/// closed: its viewer reconnects and, finding another world, reloads itself (docs/viewer.md).
void switchRecording(const ServeOptions& options, OpenRequest request, std::unique_ptr<Session>& session,
                     Bridge& bridge, Router& router, RecordingRoutes& recordings) {
  if (request.live) request.path = options.scenario;
  // Loading may take seconds (a live world's navmesh): meanwhile the old session's questions
  // (/api/groups, which live viewers poll) are answered from its world as it stands, not left to
  // time out with 503 (seen in the viewer's e2e test on the 2-core CI machine).
  auto loading = std::async(std::launch::async, [&options, path = request.path.string()] { return openServed(options, path); });
  sim::World* standing = session->served.replay ? nullptr : session->served.live.world.get();
  while (loading.wait_for(kAnswerWhileLoading) != std::future_status::ready) session->queries.answer(standing, session->hub);
  std::optional<Served> next = loading.get();
  session->queries.answer(standing, session->hub);
  if (!next) {
    request.responder.respond(
        jsonError(422, fmt::format("{}: cannot be played (the server's log says why)", request.name)));
    return;
  }
  bridge.setHub(nullptr);
  router.set(nullptr);
  session->close(request.live ? "switching to the live scenario " + request.name : "switching to recording " + request.name);
  session.reset();
  session = std::make_unique<Session>(options, std::move(*next), request.path.string(), bridge, &recordings);
  // The HTTP routes first: a viewer reloads on the new hub's Welcome and at once asks for the world;
  // the other way round, that request could come before the routes and get 503 (seen in CI).
  router.set(session.get());
  bridge.setHub(&session->hub);
  recordings.setPlaying(request.live ? std::string() : request.name);
  request.responder.respond(transport::HttpResponse{
      200, "application/json",
      dumpJson({{"opened", request.live ? nlohmann::json(nullptr) : nlohmann::json(request.name)},
                {"live", request.live},
                {"server", session->hubOptions.serverName}}),
      {}});
  if (!options.quiet) printLine(stdout, request.live ? "throng serve: live again, " + request.name : "throng serve: now playing " + request.name);
}

}  // namespace

Session::Session(const ServeOptions& options, Served world, std::string path, Bridge& bridge, const RecordingRoutes* recordings)
    : source(std::move(path)),
      served(std::move(world)),
      hubOptions(hubOptionsFor(options, served, source)),
      hub(hubOptions, served.worldJson, static_cast<float>(served.tickRate), served.live.motions, bridge),
      tickWatch(1.0 / served.tickRate),  // late and stalled ticks, the one running now included
      api(served, hub, bridge, queries, tickWindow, tickWatch),
      editor(editorFor(source, served, editJobs)),
      publisher(hub, bridge, options.threads),
      loop(options, served, hub, bridge, queries, tickWindow, tickWatch, publisher, recordings) {}

void Session::close(const std::string& reason) {
  publisher.stop();
  hub.shutdown(reason);
  editJobs.stop();  // each job holds an HttpResponder: done before the transport goes
}

std::optional<transport::HttpResponse> Router::get(std::string_view target) {
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

bool Router::post(transport::HttpRequest request, const transport::HttpResponder& responder) {
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
  if (auto answer = session_->api.post(request)) {
    responder.respond(std::move(*answer));
    return true;
  }
  return session_->editor.post(std::move(request), responder);
}

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

}  // namespace throng::cli::serve
