// throng::io scenario clips — resolves each action point's "clip" against the scenario's
// directory, loads it with motion::loadBvhFile and fills the point's defaults from it (see
// scenario_clips.hpp). Reads clip files and one directory tree (bounded); writes the parsed
// scenario's points, the clip map and diagnostics.
#include "scenario_clips.hpp"

#include "confined_path.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <optional>

namespace throng::io {

namespace {

namespace fs = std::filesystem;

/// The longest stop an action may last [s]; matches the range of a point's "duration".
constexpr double kMaxActionDuration = 86400.0;

std::string quote(const std::string& s) {
  std::string q = "\"";
  for (const char c : s.substr(0, 120)) q += (static_cast<unsigned char>(c) < 0x20) ? '?' : c;
  if (s.size() > 120) q += "...";
  return q + "\"";
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

bool isBvh(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".bvh";
}

/// BVH files under `dir` (depth <= 3, at most kMaxClipSuggestionEntries entries looked at), as
/// paths relative to `dir` with '/' separators, sorted.
std::vector<std::string> clipCandidates(const fs::path& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  const fs::path base = dir.empty() ? fs::path(".") : dir;
  fs::recursive_directory_iterator it(base, fs::directory_options::skip_permission_denied, ec);
  std::size_t seen = 0;
  for (; !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (++seen > kMaxClipSuggestionEntries) break;
    if (it.depth() >= 2) it.disable_recursion_pending();
    std::error_code fileEc;
    if (it->is_regular_file(fileEc) && isBvh(it->path())) {
      out.push_back(it->path().lexically_relative(base).generic_string());
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

/// What happened to one clip path (loaded once, however many points use it).
struct ClipLoad {
  std::shared_ptr<const motion::MotionClip> clip;  ///< null when it failed
  std::string what;                        ///< the failure, said at each point using it
  std::string expected;
  std::string hint;
};

class ClipLoader {
 public:
  ClipLoader(const JsonDocument& doc, core::Diagnostics& diags)
      : doc_(doc), diags_(diags), dir_(fs::path(doc.source()).parent_path()),
        namer_(fs::path(doc.source()).filename().string()) {}

  void run(ParsedScenario& parsed, MotionClips& clips) {
    const Json& root = doc_.root();
    if (!root.is_object()) return;
    const auto points = root.find("points");
    if (points == root.end() || !points->is_array()) return;
    const std::size_t n = std::min(points->size(), parsed.desc.points.size());
    for (std::size_t i = 0; i < n; ++i) {
      sim::PointDesc& p = parsed.desc.points[i];
      if (p.kind != sim::PointKind::Action || p.clip.empty()) continue;
      const std::string ptr = "/points/" + std::to_string(i) + "/clip";
      const ClipLoad& load = loadOnce(p.clip);
      if (!load.clip) {
        diags_.push_back(doc_.diagnostic(ptr, load.what, load.expected, load.hint));
        continue;
      }
      clips.emplace(p.clip, load.clip);
      const Json& json = (*points)[i];
      if (!json.contains("duration")) {
        const double d = load.clip->duration();
        if (d > kMaxActionDuration) {
          diags_.push_back(doc_.diagnostic(ptr, "clip " + quote(p.clip) + " lasts " + num(d) + " s",
                                           "a clip of at most " + num(kMaxActionDuration) + " s",
                                           "or give the point a \"duration\""));
        } else {
          p.actionDuration = static_cast<float>(d);
        }
      }
      if (!json.contains("action")) p.action = load.clip->name;
    }
  }

 private:
  const ClipLoad& loadOnce(const std::string& clip) {
    if (auto it = loads_.find(clip); it != loads_.end()) return it->second;
    ClipLoad& load = loads_[clip];
    const std::string expected = "a BVH file path relative to the scenario";
    // Only files in the scenario's directory and below (never read, so never quoted, otherwise).
    const detail::ConfinedPath confined = detail::confinePath(dir_, clip, namer_);
    if (!confined.ok()) {
      load.what = "clip " + confined.problem;
      load.expected = detail::confinedExpectation("a BVH file", namer_);
      return load;
    }
    const fs::path& path = confined.path;
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (ec || !fs::is_regular_file(status)) {
      load.what = "cannot read " + quote(clip) + (fs::exists(status) ? ": not a regular file" : ": no such file");
      load.expected = expected;
      if (!candidates_) candidates_ = clipCandidates(dir_);
      const std::string match = core::closestMatch(clip, *candidates_);
      if (!match.empty() && match != clip) load.hint = "did you mean " + quote(match) + "?";
      return load;
    }
    auto result = motion::loadBvhFile(path.string());
    if (result.ok()) {
      load.clip = std::make_shared<const motion::MotionClip>(std::move(result).value());
      return load;
    }
    const core::Diagnostics& errors = result.errors();
    const bool located = std::any_of(errors.begin(), errors.end(), [](const core::Diagnostic& d) { return d.line > 0; });
    if (!located) {  // the file itself could not be read: say so at the scenario's pointer
      load.what = "cannot read " + quote(clip) + ": " + errors.front().what;
      load.expected = expected;
      return load;
    }
    diags_.insert(diags_.end(), errors.begin(), errors.end());
    load.what = "motion clip " + quote(clip) + " is not valid BVH (" + std::to_string(errors.size()) + " problem" +
                (errors.size() == 1 ? "" : "s") + " reported in " + path.string() + ")";
    load.expected = "a valid BVH file";
    return load;
  }

  const JsonDocument& doc_;
  core::Diagnostics& diags_;
  fs::path dir_;
  std::string namer_;  ///< the scenario's file name, for messages
  std::map<std::string, ClipLoad> loads_;
  std::optional<std::vector<std::string>> candidates_;
};

}  // namespace

MotionClips loadScenarioClips(const JsonDocument& doc, ParsedScenario& parsed, core::Diagnostics& diagnostics) {
  MotionClips clips;
  ClipLoader(doc, diagnostics).run(parsed, clips);
  return clips;
}

}  // namespace throng::io
