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
#include "throng/social/behaviour_db.hpp"

namespace throng::io {
namespace {

namespace fs = std::filesystem;

using detail::quote;  // control characters shown as '?', long text cut

}  // namespace

void loadScenarioSocial(const JsonDocument& doc, ParsedScenario& parsed, core::Diagnostics& diagnostics) {
  sim::SocialDesc& social = parsed.desc.social;
  if (!social.enabled) return;
  const fs::path dir = fs::path(doc.source()).parent_path();
  auto fail = [&](const std::string& ptr, std::string what, std::string expected, std::string hint = {}) {
    diagnostics.push_back(doc.diagnostic(ptr, std::move(what), std::move(expected), std::move(hint)));
  };
  const std::string namer = fs::path(doc.source()).filename().string();
  // Every file named here is read only from the scenario's directory and below (a refused one is
  // never opened, so its content never reaches a message).
  auto confined = [&](const std::string& ptr, const std::string& rel, const std::string& what) -> std::optional<fs::path> {
    const detail::ConfinedPath c = detail::confinePath(dir, rel, namer);
    if (!c.ok()) {
      fail(ptr, c.problem, detail::confinedExpectation(what, namer));
      return std::nullopt;
    }
    return c.path;
  };
  auto exists = [&](const fs::path& path) {
    std::error_code ec;
    return fs::is_regular_file(path, ec);
  };
  // The clip directory is checked even before the databases: the server reads it too.
  if (!confined("/social/motions", social.motions.empty() ? "." : social.motions, "a directory of BVH clips")) return;
  // Databases: the scenario's files, else the built-in ones.
  core::Result<social::MicroBehaviourDb> micro = core::Diagnostic{};
  if (social.microPath.empty()) {
    micro = parseMicroBehaviours(builtinMicroBehaviours(), "data/social/micro_behaviours.json (built in)");
  } else if (const auto path = confined("/social/microBehaviours", social.microPath, "a micro-behaviour database (JSON)"); !path) {
    return;
  } else if (!exists(*path)) {
    fail("/social/microBehaviours", "cannot read " + quote(social.microPath) + ": no such file",
         "a micro-behaviour database (JSON) relative to the scenario");
    return;
  } else {
    micro = loadMicroBehaviours(path->string());
  }
  if (!micro.ok()) {
    diagnostics.insert(diagnostics.end(), micro.errors().begin(), micro.errors().end());
    return;
  }
  social.micro = std::move(micro).value();
  core::Result<social::MacroPlanDb> macro = core::Diagnostic{};
  if (social.macroPath.empty()) {
    macro = parseMacroPlans(builtinMacroPlans(), "data/social/macro_plans.json (built in)", social.micro);
  } else if (const auto path = confined("/social/macroPlans", social.macroPath, "a macro-plan database (JSON)"); !path) {
    return;
  } else if (!exists(*path)) {
    fail("/social/macroPlans", "cannot read " + quote(social.macroPath) + ": no such file",
         "a macro-plan database (JSON) relative to the scenario");
    return;
  } else {
    macro = loadMacroPlans(path->string(), social.micro);
  }
  if (!macro.ok()) {
    diagnostics.insert(diagnostics.end(), macro.errors().begin(), macro.errors().end());
    return;
  }
  social.macro = std::move(macro).value();
  // Populations' preferences name micro-behaviours of the database.
  std::vector<std::string> names;
  for (const auto& b : social.micro.behaviours) names.push_back(b.name);
  for (std::size_t p = 0; p < parsed.desc.populations.size(); ++p) {
    for (const auto& [name, weight] : parsed.desc.populations[p].preferences) {
      if (social.micro.find(name)) continue;
      const std::string match = core::closestMatch(name, names);
      fail("/populations/" + std::to_string(p) + "/preferences/" + escapePointerToken(name),
           "no micro-behaviour " + quote(name) + " in the database", "a behaviour name of the micro-behaviour database",
           match.empty() ? "" : "did you mean " + quote(match) + "?");
    }
  }
  // Clip lengths: every clip a micro-behaviour plays, from <motions>/<clip>.bvh.
  std::set<std::string> clips;
  for (const auto& b : social.micro.behaviours) {
    if (b.clip != social::kWalkMotion && b.clip != social::kTurnMotion && b.clip != social::kIdleMotion) clips.insert(b.clip);
  }
  const std::string ptr = doc.root().contains("social") && doc.root()["social"].contains("motions") ? "/social/motions" : "/social";
  for (const std::string& clip : clips) {
    const fs::path rel = fs::path(social.motions) / (clip + ".bvh");
    const detail::ConfinedPath c = detail::confinePath(dir, rel.generic_string(), namer);
    if (!c.ok()) {  // a clip name of the database such as "../../secret"
      fail(ptr, "micro-behaviour clip " + quote(clip) + ": " + c.problem,
           detail::confinedExpectation("<motions>/<clip>.bvh", namer));
      continue;
    }
    const fs::path& path = c.path;
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) {
      fail(ptr, "micro-behaviour clip " + quote(clip) + ": cannot read " + quote(rel.generic_string()) + ": no such file",
           "a BVH file <motions>/<clip>.bvh for every clip the micro-behaviour database plays",
           "\"motions\" is the clip directory relative to the scenario (now " + quote(social.motions) + ")");
      continue;
    }
    auto loaded = motion::loadBvhFile(path.string());
    if (!loaded.ok()) {
      diagnostics.insert(diagnostics.end(), loaded.errors().begin(), loaded.errors().end());
      fail(ptr, "micro-behaviour clip " + quote(rel.generic_string()) + " is not valid BVH", "a valid BVH file");
      continue;
    }
    const double length = loaded.value().duration();
    if (!(length > 0.0 && length <= 3600.0)) {
      fail(ptr, "micro-behaviour clip " + quote(rel.generic_string()) + " lasts " + std::to_string(length) + " s",
           "a clip longer than 0 s and at most 3600 s");
      continue;
    }
    social.clipLengths[clip] = length;
  }
}

}  // namespace throng::io
