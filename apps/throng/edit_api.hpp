// `throng edit`'s work behind its JSON API (cmd_edit.cpp routes the requests here): checking a
// scenario text with the validator of `throng check`, previewing it (a short simulation whose
// positions come back per frame), saving it atomically, formatted for diffs, and importing a floor
// plan (DXF, WKT). Pure of HTTP: each takes text (and a cancel flag) and returns the response body;
// the callers run them on worker threads. Reads and writes only the one scenario file it is given.
#pragma once
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "throng/core/diagnostic.hpp"

namespace throng::cli::edit {

/// An HTTP status and a JSON body.
struct ApiAnswer {
  unsigned status = 200;
  std::string body;
};

/// Limits of the API [documented in docs/editor.md].
inline constexpr double kMaxPreviewSeconds = 120.0;       ///< simulated time of one preview [s]
inline constexpr double kMaxPreviewFps = 10.0;            ///< frames sent per simulated second [Hz]
inline constexpr std::uint64_t kMaxPreviewAgentTicks = 20'000'000;  ///< agents × ticks of one preview
inline constexpr double kCheckSeconds = 20.0;             ///< wall-clock limit of a check or a save's check [s]
inline constexpr double kPreviewSeconds = 60.0;           ///< wall-clock limit of a preview [s]

/// What the editor starts from when FILE does not exist yet: a valid-looking empty scenario
/// (the checker then says what is missing).
[[nodiscard]] std::string emptyScenario(const std::string& name);

/// The diagnostics as the API sends them: [{pointer, line, column, message, severity, what,
/// expected, hint}], `message` the one-line text without the source.
[[nodiscard]] nlohmann::json diagnosticsJson(const core::Diagnostics& diagnostics);

/// The scenario in a request body: {"scenario": object} (or a JSON string holding the text).
/// Empty with `error` set when the body is not JSON or has no scenario.
struct ScenarioRequest {
  nlohmann::ordered_json body;  ///< the whole request
  std::string text;             ///< the scenario's JSON text
  std::string error;            ///< why the request is bad (400)
};
[[nodiscard]] ScenarioRequest readScenarioRequest(std::string_view body, bool bodyIsScenario);

/// POST /api/check: {"ok", "diagnostics", "summary"?}. `source` names the file (clip paths are
/// resolved against its directory); `cancel` (client gone or time up) stops the validation.
[[nodiscard]] ApiAnswer checkScenario(const std::string& text, const std::string& source, const std::atomic<int>& cancel,
                                      const std::atomic<bool>& timedOut);

/// POST /api/preview: {"ok", "dt", "fps", "end", "frames": [{"t", "ids", "xy"}]} or the
/// diagnostics when the scenario is invalid (422). Stops at `seconds`, when every agent has left,
/// at kMaxPreviewAgentTicks, or when `cancel` turns non-zero.
[[nodiscard]] ApiAnswer previewScenario(const std::string& text, const std::string& source, double seconds, double fps,
                                        const std::atomic<int>& cancel, const std::atomic<bool>& timedOut);

/// POST /api/save to `file`: checks first; writes (temp file + rename, formatted for diffs:
/// io::formatJsonForDiffs, as `throng import` writes) when valid or `force`.
/// {"ok", "saved", "path", "diagnostics"}; 422 when invalid and not forced, 409 without a file.
[[nodiscard]] ApiAnswer saveScenario(const ScenarioRequest& request, const std::filesystem::path& file,
                                     const std::atomic<int>& cancel, const std::atomic<bool>& timedOut);

/// POST /api/import, body {"name": "plan.dxf" or ".wkt", "text", "scale"?}: {"ok", "fragment":
/// {"walkable", "obstacles", "walls"}} (io::importPlan), or the located diagnostics (422).
[[nodiscard]] ApiAnswer importPlanText(std::string_view body);

}  // namespace throng::cli::edit
