// `throng serve`'s sessions: Session (one world served and everything serving it: hub, HTTP
// answers, editor, publisher, tick loop), Router (the transport's HTTP hooks, to the recordings
// directory and the session in use), openRecordings (--recordings DIR) and runSessions (the tick
// loop of the session in use, a new Session each time a viewer opens another recording).
#pragma once
#include <memory>
#include <optional>
#include <shared_mutex>
#include <string>
#include <string_view>

#include "commands.hpp"
#include "edit_routes.hpp"
#include "edit_jobs.hpp"
#include "recording_routes.hpp"
#include "serve_api.hpp"
#include "serve_bridge.hpp"
#include "serve_loop.hpp"
#include "serve_world.hpp"
#include "throng/hub/hub.hpp"
#include "throng/hub/tick_watch.hpp"
#include "throng/transport/transport.hpp"

namespace throng::cli::serve {

/// One world served and everything that serves it: the hub, its HTTP answers, the editor on its
/// scenario, the publisher and the tick loop. Rebuilt when a viewer opens another recording; the
/// transport and the recordings directory outlive it. Not movable (its parts refer to each other).
struct Session {
  Session(const ServeOptions& options, Served world, std::string path, Bridge& bridge, const RecordingRoutes* recordings);
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  /// Stops publishing, tells every client `reason` and closes it, ends the editor's jobs.
  void close(const std::string& reason);

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

  /// GET `target`: the recordings routes, else the editor's, else HttpApi's; 503 while sessions change.
  std::optional<transport::HttpResponse> get(std::string_view target);

  /// POST: the recordings routes (an upload, an open), else HttpApi's (an exit opened or closed), else the
  /// editor's; true when answered.
  bool post(transport::HttpRequest request, const transport::HttpResponder& responder);

 private:
  RecordingRoutes* recordings_;
  std::shared_mutex mutex_;
  Session* session_ = nullptr;
};

/// The recordings directory of --recordings, or nullptr without it; false when it cannot be used.
bool openRecordings(const ServeOptions& options, std::unique_ptr<RecordingRoutes>& out);

/// Runs the tick loop of the session in use, switching recordings on request, until Ctrl-C or
/// --duration; why it ended.
std::string runSessions(const ServeOptions& options, std::unique_ptr<Session>& session, Bridge& bridge, Router& router,
                        RecordingRoutes* recordings);

}  // namespace throng::cli::serve
