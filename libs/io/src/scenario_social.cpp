// Loads a scenario's Common Ground databases and clip lengths (see scenario_social.hpp).
#include "scenario_social.hpp"

#include <filesystem>
#include <optional>
#include <set>

#include "confined_path.hpp"
#include "scenario_reader.hpp"
#include "social_defaults.hpp"
#include "throng/motion/bvh.hpp"
#include "throng/io/social_db.hpp"
#include "throng/common_ground/behaviour_db.hpp"

namespace throng::io {
namespace {

namespace fs = std::filesystem;

using detail::quote;  // control characters shown as '?', long text cut

/// One scenario's social section being loaded: each step reads one file (or set of files) named
/// relative to the scenario, only from its directory and below, and reports what went wrong.
class SocialLoader {
 public:
  SocialLoader(const JsonDocument& doc, ParsedScenario& parsed, core::Diagnostics& diagnostics)
      : doc_(doc),
        parsed_(parsed),
        social_(parsed.desc.social),
        diagnostics_(diagnostics),
        dir_(fs::path(doc.source()).parent_path()),
        namer_(fs::path(doc.source()).filename().string()) {}

  /// The clip directory is checked even before the databases: the server reads it too.
  bool checkMotionDirectory() {
    return confined("/social/motions", social_.motions.empty() ? "." : social_.motions, "a directory of BVH clips")
        .has_value();
  }

  /// The micro-behaviour database: the scenario's file, else the built-in one.
  bool loadMicroBehaviourDb() {
    core::Result<common_ground::MicroBehaviourDb> micro = core::Diagnostic{};
    if (social_.microPath.empty()) {
      micro = parseMicroBehaviours(builtinMicroBehaviours(), "data/social/micro_behaviours.json (built in)");
    } else if (const auto path = confined("/social/microBehaviours", social_.microPath, "a micro-behaviour database (JSON)"); !path) {
      return false;
    } else if (!exists(*path)) {
      fail("/social/microBehaviours", "cannot read " + quote(social_.microPath) + ": no such file",
           "a micro-behaviour database (JSON) relative to the scenario");
      return false;
    } else {
      micro = loadMicroBehaviours(path->string());
    }
    if (!micro.ok()) {
      diagnostics_.insert(diagnostics_.end(), micro.errors().begin(), micro.errors().end());
      return false;
    }
    social_.micro = std::move(micro).value();
    return true;
  }

  /// The macro-plan database (checked against the micro-behaviours): the scenario's, else built in.
  bool loadMacroPlanDb() {
    core::Result<common_ground::MacroPlanDb> macro = core::Diagnostic{};
    if (social_.macroPath.empty()) {
      macro = parseMacroPlans(builtinMacroPlans(), "data/social/macro_plans.json (built in)", social_.micro);
    } else if (const auto path = confined("/social/macroPlans", social_.macroPath, "a macro-plan database (JSON)"); !path) {
      return false;
    } else if (!exists(*path)) {
      fail("/social/macroPlans", "cannot read " + quote(social_.macroPath) + ": no such file",
           "a macro-plan database (JSON) relative to the scenario");
      return false;
    } else {
      macro = loadMacroPlans(path->string(), social_.micro);
    }
    if (!macro.ok()) {
      diagnostics_.insert(diagnostics_.end(), macro.errors().begin(), macro.errors().end());
      return false;
    }
    social_.macro = std::move(macro).value();
    return true;
  }

  /// Populations' preferences name micro-behaviours of the database.
  void checkPreferences() {
    std::vector<std::string> names;
    for (const auto& b : social_.micro.behaviours) names.push_back(b.name);
    for (std::size_t p = 0; p < parsed_.desc.populations.size(); ++p) {
      for (const auto& [name, weight] : parsed_.desc.populations[p].preferences) {
        if (social_.micro.find(name)) continue;
        const std::string match = core::closestMatch(name, names);
        fail("/populations/" + std::to_string(p) + "/preferences/" + escapePointerToken(name),
             "no micro-behaviour " + quote(name) + " in the database", "a behaviour name of the micro-behaviour database",
             match.empty() ? "" : "did you mean " + quote(match) + "?");
      }
    }
  }

  /// Clip lengths: every clip a micro-behaviour plays, from <motions>/<clip>.bvh.
  void loadClipLengths() {
    std::set<std::string> clips;
    for (const auto& b : social_.micro.behaviours) {
      if (b.clip != common_ground::kWalkMotion && b.clip != common_ground::kTurnMotion && b.clip != common_ground::kIdleMotion) clips.insert(b.clip);
    }
    const std::string ptr =
        doc_.root().contains("social") && doc_.root()["social"].contains("motions") ? "/social/motions" : "/social";
    for (const std::string& clip : clips) {
      if (const auto length = clipLength(ptr, clip)) social_.clipLengths[clip] = *length;
    }
  }

 private:
  void fail(const std::string& ptr, std::string what, std::string expected, std::string hint = {}) {
    diagnostics_.push_back(doc_.diagnostic(ptr, std::move(what), std::move(expected), std::move(hint)));
  }

  /// `rel` under the scenario's directory; nullopt (and a diagnostic) when it leaves it. A refused
  /// file is never opened, so its content never reaches a message.
  std::optional<fs::path> confined(const std::string& ptr, const std::string& rel, const std::string& what) {
    const detail::ConfinedPath c = detail::confinePath(dir_, rel, namer_);
    if (!c.ok()) {
      fail(ptr, c.problem, detail::confinedExpectation(what, namer_));
      return std::nullopt;
    }
    return c.path;
  }

  static bool exists(const fs::path& path) {
    std::error_code ec;
    return fs::is_regular_file(path, ec);
  }

  /// The length of <motions>/<clip>.bvh [s]; nullopt (and a diagnostic at `ptr`) when it cannot be had.
  std::optional<double> clipLength(const std::string& ptr, const std::string& clip) {
    const fs::path rel = fs::path(social_.motions) / (clip + ".bvh");
    const detail::ConfinedPath c = detail::confinePath(dir_, rel.generic_string(), namer_);
    if (!c.ok()) {  // a clip name of the database such as "../../secret"
      fail(ptr, "micro-behaviour clip " + quote(clip) + ": " + c.problem,
           detail::confinedExpectation("<motions>/<clip>.bvh", namer_));
      return std::nullopt;
    }
    if (!exists(c.path)) {
      fail(ptr, "micro-behaviour clip " + quote(clip) + ": cannot read " + quote(rel.generic_string()) + ": no such file",
           "a BVH file <motions>/<clip>.bvh for every clip the micro-behaviour database plays",
           "\"motions\" is the clip directory relative to the scenario (now " + quote(social_.motions) + ")");
      return std::nullopt;
    }
    auto loaded = motion::loadBvhFile(c.path.string());
    if (!loaded.ok()) {
      diagnostics_.insert(diagnostics_.end(), loaded.errors().begin(), loaded.errors().end());
      fail(ptr, "micro-behaviour clip " + quote(rel.generic_string()) + " is not valid BVH", "a valid BVH file");
      return std::nullopt;
    }
    const double length = loaded.value().duration();
    if (!(length > 0.0 && length <= 3600.0)) {
      fail(ptr, "micro-behaviour clip " + quote(rel.generic_string()) + " lasts " + std::to_string(length) + " s",
           "a clip longer than 0 s and at most 3600 s");
      return std::nullopt;
    }
    return length;
  }

  const JsonDocument& doc_;
  ParsedScenario& parsed_;
  sim::CommonGroundDesc& social_;
  core::Diagnostics& diagnostics_;
  const fs::path dir_;
  const std::string namer_;
};

}  // namespace

void loadScenarioSocial(const JsonDocument& doc, ParsedScenario& parsed, core::Diagnostics& diagnostics) {
  if (!parsed.desc.social.enabled) return;
  SocialLoader loader(doc, parsed, diagnostics);
  if (!loader.checkMotionDirectory() || !loader.loadMicroBehaviourDb() || !loader.loadMacroPlanDb()) return;
  loader.checkPreferences();
  loader.loadClipLengths();
}

}  // namespace throng::io
