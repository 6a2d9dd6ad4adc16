// The scenario editor's HTTP routes (edit_routes.hpp): GET and POST under a prefix, POST work on
// Jobs' threads, answered with edit_api.hpp's functions.
#include "edit_routes.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <fstream>
#include <sstream>

#include "output.hpp"

namespace throng::cli::edit {
namespace {
namespace fs = std::filesystem;
using transport::HttpRequest;
using transport::HttpResponder;
using transport::HttpResponse;

HttpResponse jsonResponse(unsigned status, const nlohmann::json& body) {
  return HttpResponse{status, "application/json", dumpJson(body), {}};
}

HttpResponse fromAnswer(ApiAnswer answer) {
  return HttpResponse{answer.status, "application/json", std::move(answer.body), {}};
}

}  // namespace

EditApi::EditApi(std::filesystem::path file, Jobs& jobs, std::string prefix, std::optional<std::string> served, std::string servedName)
    : file_(std::move(file)), jobs_(jobs), prefix_(std::move(prefix)), served_(std::move(served)),
      servedName_(std::move(servedName)) {}

std::string EditApi::route(std::string_view target) const {
  const std::string_view path = target.substr(0, target.find('?'));
  if (path.substr(0, prefix_.size()) != prefix_) return {};
  return std::string(path.substr(prefix_.size()));
}

std::optional<HttpResponse> EditApi::get(std::string_view target) const {
    if (route(target) != "/api/scenario") return std::nullopt;
    if (served_) {  // throng serve: the world it serves, never written
      return jsonResponse(200, {{"file", fs::path(servedName_).filename().string()}, {"exists", true}, {"canSave", false},
                              {"text", *served_}});
    }
    std::error_code ec;
    const bool exists = !file_.empty() && fs::is_regular_file(file_, ec);
    std::string text;
    if (exists) {
      std::ifstream in(file_, std::ios::binary);
      std::ostringstream buffer;
      buffer << in.rdbuf();
      text = buffer.str();
    } else {
      text = emptyScenario(file_.empty() ? "scenario" : file_.stem().string());
    }
    return jsonResponse(200, {{"file", file_.empty() ? nlohmann::json() : nlohmann::json(file_.filename().string())},
                              {"exists", exists},
                              {"canSave", !file_.empty()},
                              {"text", text}});
  }

bool EditApi::post(HttpRequest request, const HttpResponder& responder) {
    const std::string path = route(request.target);
    if (path == "/api/import") {
      const bool started = jobs_.launch(responder, std::chrono::milliseconds(static_cast<long>(kCheckSeconds * 1000)),
                                        [body = std::move(request.body), responder](const JobFlags&) {
                                          responder.respond(fromAnswer(importPlanText(body)));
                                        });
      if (!started) busy(responder);
      return true;
    }
    if (path != "/api/check" && path != "/api/preview" && path != "/api/save") return false;
    const bool isCheck = path == "/api/check";
    ScenarioRequest parsed = readScenarioRequest(request.body, isCheck);
    if (!parsed.error.empty()) {
      responder.respond(jsonResponse(400, {{"ok", false}, {"error", parsed.error}}));
      return true;
    }
    if (path == "/api/preview") return preview(std::move(parsed), responder);
    const auto limit = std::chrono::milliseconds(static_cast<long>(kCheckSeconds * 1000));
    const bool started = jobs_.launch(responder, limit, [this, isCheck, parsed = std::move(parsed), responder](const JobFlags& f) {
      responder.respond(fromAnswer(isCheck ? checkScenario(parsed.text, source(), f.cancel, f.timedOut)
                                           : saveScenario(parsed, file_, f.cancel, f.timedOut)));
    });
    if (!started) busy(responder);
    return true;
}

bool EditApi::preview(ScenarioRequest parsed, const HttpResponder& responder) {
    const double seconds = parsed.body.value("seconds", 20.0);
    const double fps = parsed.body.value("fps", 5.0);
    if (!(seconds > 0 && seconds <= kMaxPreviewSeconds) || !(fps > 0 && fps <= kMaxPreviewFps)) {
      responder.respond(jsonResponse(
          400, {{"ok", false},
                {"error", fmt::format("expected \"seconds\" in (0, {:g}] and \"fps\" in (0, {:g}]", kMaxPreviewSeconds,
                                      kMaxPreviewFps)}}));
      return true;
    }
    const auto limit = std::chrono::milliseconds(static_cast<long>(kPreviewSeconds * 1000));
    const bool started = jobs_.launch(responder, limit, [this, text = std::move(parsed.text), seconds, fps, responder](const JobFlags& f) {
      responder.respond(fromAnswer(previewScenario(text, source(), seconds, fps, f.cancel, f.timedOut)));
    });
    if (!started) busy(responder);
    return true;
}

void EditApi::busy(const HttpResponder& responder) {
  responder.respond(jsonResponse(503, {{"ok", false}, {"error", "the server is busy with other requests; try again"}}));
}

std::string EditApi::source() const {
  if (!file_.empty()) return file_.string();
  return servedName_.empty() ? std::string("scenario.json") : servedName_;
}


}  // namespace throng::cli::edit
