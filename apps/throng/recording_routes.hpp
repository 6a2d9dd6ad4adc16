// `throng serve --recordings DIR`'s HTTP routes (docs/server.md, docs/viewer.md): GET
// /api/recordings lists DIR, POST /api/recordings?name=FILE stores an upload (checked on a worker
// thread, edit::Jobs), POST /api/recordings/open {"name": …} asks to play one, POST
// /api/recordings/live asks to go back to the live scenario the server was started with (from its
// start). Opening is the simulation thread's to do (it owns the served world): the request waits
// here, with its responder, until the tick loop takes it (takeOpen) and answers once the switch is
// done or failed.
#pragma once
#include <atomic>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>

#include "edit_jobs.hpp"
#include "recordings_dir.hpp"
#include "throng/transport/transport.hpp"

namespace throng::cli {

/// A viewer's request to play the recording `name` (at `path`, resolved in DIR), or, `live`, the
/// live scenario the server was started with (`name` its file name, `path` empty).
struct OpenRequest {
  std::string name;
  std::filesystem::path path;
  transport::HttpResponder responder;
  bool live = false;
};

class RecordingRoutes {
 public:
  RecordingRoutes(RecordingsDir dir, std::size_t maxUploadBytes) : dir_(std::move(dir)), maxUpload_(maxUploadBytes) {}
  ~RecordingRoutes() { stop(); }
  RecordingRoutes(const RecordingRoutes&) = delete;
  RecordingRoutes& operator=(const RecordingRoutes&) = delete;

  /// GET /api/recordings: {"dir", "playing", "live", "maxUploadBytes", "recordings": [{name, size,
  /// duration, agents, scenario[, error]}]} ("live": the live scenario's file name, null when the
  /// server was started with a recording); nullopt for any other path. (A server without --recordings answers
  /// "dir": null and no recordings: serve_session.hpp's Router.)
  [[nodiscard]] std::optional<transport::HttpResponse> get(std::string_view target) const;
  /// POST /api/recordings?name=FILE (the body: the file), /api/recordings/open and
  /// /api/recordings/live; false otherwise.
  bool post(transport::HttpRequest& request, const transport::HttpResponder& responder);

  /// The latest open request not yet taken (simulation thread); pending() is its cheap check.
  [[nodiscard]] std::optional<OpenRequest> takeOpen();
  [[nodiscard]] bool pending() const { return pending_.load(std::memory_order_acquire); }
  /// The name now played ("" when the positional scenario or recording is), for the listing.
  void setPlaying(std::string name);
  /// The live scenario's file name (the positional argument when it is no recording): what
  /// /api/recordings/live goes back to; "" (the default) when there is none.
  void setLive(std::string name);
  /// Ends the upload jobs and answers a waiting open request (before the transport goes).
  void stop();

 private:
  void upload(transport::HttpRequest& request, const transport::HttpResponder& responder);
  void open(const transport::HttpRequest& request, const transport::HttpResponder& responder);
  void live(const transport::HttpResponder& responder);
  /// Queues `request` for the tick loop; a request still waiting is answered 409.
  void queue(OpenRequest request);

  RecordingsDir dir_;
  std::size_t maxUpload_;
  edit::Jobs jobs_;
  mutable std::mutex mutex_;
  std::optional<OpenRequest> open_;
  std::atomic<bool> pending_{false};
  std::string playing_;
  std::string live_;
};

/// `{"error": text}` with `status`.
[[nodiscard]] transport::HttpResponse jsonError(unsigned status, const std::string& text);

}  // namespace throng::cli
