// The scenario editor's HTTP routes (docs/editor.md), shared by `throng edit` (at /, on its file)
// and `throng serve` (at /editor/, on the world it serves, never saving): GET <prefix>/api/scenario,
// POST <prefix>/api/check, /api/preview, /api/save and /api/import, each POST on a Jobs worker
// thread (edit_jobs.hpp) with the work of edit_api.hpp.
#pragma once
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "edit_api.hpp"
#include "edit_jobs.hpp"
#include "throng/transport/transport.hpp"

namespace throng::cli::edit {

/// The largest request body the editor's routes take (TransportOptions::maxPostBytes) [bytes].
inline constexpr std::size_t kMaxBodyBytes = std::size_t(8) << 20;

class EditApi {
 public:
  /// `file`: what save writes (empty: save refused with 409). `prefix`: where the routes start ("" or
  /// "/editor"). `served`: the scenario text GET /api/scenario gives instead of reading `file`
  /// (throng serve's world; then canSave is false), from the file `servedName` (its path: clip paths
  /// are resolved against its directory; GET gives its file name).
  EditApi(std::filesystem::path file, Jobs& jobs, std::string prefix = {}, std::optional<std::string> served = {},
          std::string servedName = {});

  /// GET <prefix>/api/scenario: {"file", "exists", "canSave", "text"}; nullopt for any other path.
  [[nodiscard]] std::optional<transport::HttpResponse> get(std::string_view target) const;
  /// POST <prefix>/api/check, /api/preview, /api/save, /api/import; false for any other path (404).
  bool post(transport::HttpRequest request, const transport::HttpResponder& responder);

 private:
  /// The path after `prefix_` (query dropped), empty when the target is not under it.
  [[nodiscard]] std::string route(std::string_view target) const;
  bool preview(ScenarioRequest parsed, const transport::HttpResponder& responder);
  static void busy(const transport::HttpResponder& responder);
  /// What diagnostics name and clip paths are resolved against.
  [[nodiscard]] std::string source() const;

  std::filesystem::path file_;
  Jobs& jobs_;
  std::string prefix_;
  std::optional<std::string> served_;
  std::string servedName_;
};

}  // namespace throng::cli::edit
