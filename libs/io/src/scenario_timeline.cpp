// throng::io scenario timeline — the scenario's "timeline": crowds inserted and removed at given
// times ([{"time": 60, "insert": "crowds/tour.json"}, {"time": 120, "remove": "tour-group"}]).
// readTimeline checks the entries' structure; loadScenarioTimeline reads each crowd file (relative
// to the scenario's directory) with parseCrowd against the scenario, so its diagnostics point into
// the crowd file, and checks that removals name a crowd inserted before. Reads the crowd files;
// writes sim::ScenarioDesc::timeline and diagnostics.
#include "scenario_timeline.hpp"

#include <filesystem>
#include <map>

#include "confined_path.hpp"
#include "scenario_reader.hpp"
#include "throng/io/crowd_loader.hpp"

namespace throng::io {

namespace detail {

void ScenarioReader::readTimeline(const Json& v, const std::string& ptr, std::vector<sim::TimelineEntry>& out) {
  const std::string entryExpected = "{\"time\": seconds, and \"insert\": \"crowd file\", \"remove\": \"crowd id\", \"close\": \"exit id\" or \"open\": \"exit id\"}";
  if (!v.is_array()) {
    error(ptr, "wrong type: " + describeType(v), "an array of timeline entries, times ascending");
    return;
  }
  float previous = 0.0f;
  bool previousOk = false;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::string eptr = ptr + "/" + std::to_string(i);
    const Json& e = v[i];
    if (!isObject(e, eptr, entryExpected)) continue;
    checkKeys(e, eptr, {"time", "insert", "remove", "close", "open"}, "a timeline entry");
    sim::TimelineEntry entry;
    bool ok = true;
    if (auto* t = require(e, eptr, "time", "a time in seconds >= 0")) {
      ok = readFloat(*t, eptr + "/time", {0, 1e6, false, "s"}, entry.time);
      if (ok && previousOk && entry.time < previous) {
        error(eptr + "/time", "time " + num(entry.time) + " s is before the previous entry's " + num(previous) + " s",
              "times ascending along the timeline");
        ok = false;
      }
      previousOk = ok;
      if (ok) previous = entry.time;
    } else {
      ok = false;
    }
    const Json* insert = optional(e, "insert");
    const Json* remove = optional(e, "remove");
    const Json* close = optional(e, "close");
    const Json* open = optional(e, "open");
    std::vector<std::string> given;
    for (const auto& [key, value] : {std::pair{"insert", insert}, {"remove", remove}, {"close", close}, {"open", open}}) {
      if (value != nullptr) given.push_back(quote(key));
    }
    if (given.size() != 1) {
      std::string what = "entry has no action";
      if (given.size() == 2) what = "entry has both " + given[0] + " and " + given[1];
      if (given.size() > 2) what = "entry has " + std::to_string(given.size()) + " actions";
      error(eptr, what, entryExpected);
      ok = false;
    } else if (insert != nullptr) {
      entry.action = sim::TimelineAction::Insert;
      readRelativePath(*insert, eptr + "/insert", "a crowd file path relative to the scenario (\"crowds/tour.json\")", entry.path);
      ok = !entry.path.empty() && ok;
    } else if (remove != nullptr) {
      entry.action = sim::TimelineAction::Remove;
      const std::string expected = "the id of a crowd inserted earlier in the timeline";
      if (readString(*remove, eptr + "/remove", expected, entry.crowdId) && entry.crowdId.empty()) {
        error(eptr + "/remove", "empty crowd id", expected);
      }
      ok = !entry.crowdId.empty() && ok;
    } else {
      entry.action = close != nullptr ? sim::TimelineAction::CloseExit : sim::TimelineAction::OpenExit;
      const std::string key = close != nullptr ? "close" : "open";
      const std::string kptr = eptr + "/" + key;
      if (!resolvePoint(close != nullptr ? *close : *open, kptr, entry.point)) {
        ok = false;
      } else if (entry.point < pointIsExit_.size() && pointIsExit_[entry.point] == 0) {
        error(kptr, "point " + quote(pointIds_[entry.point]) + " is not an exit", "the id of a point of kind \"exit\"");
        ok = false;
      }
    }
    // Entries keep their JSON index (pointers name desc.timeline[i]); bad ones are never loaded.
    if (!ok) entry.path.clear(), entry.crowdId.clear();
    out.push_back(std::move(entry));
  }
}

}  // namespace detail

void loadScenarioTimeline(const JsonDocument& doc, sim::ScenarioDesc& desc, std::shared_ptr<const nav::NavMesh> navmesh,
                          core::Diagnostics& diagnostics) {
  if (desc.timeline.empty()) return;
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(doc.source()).parent_path();
  CrowdOptions options;
  options.navmesh = std::move(navmesh);
  std::map<std::string, bool> inserted;  // crowd id → removed already
  for (std::size_t i = 0; i < desc.timeline.size(); ++i) {
    sim::TimelineEntry& e = desc.timeline[i];
    const std::string ptr = "/timeline/" + std::to_string(i);
    if (e.action == sim::TimelineAction::Insert) {
      if (e.path.empty()) continue;  // reported by the parser
      // Crowd files only from the scenario's directory and below (a refused one is never opened).
      const detail::ConfinedPath confined = detail::confinePath(dir, e.path, fs::path(doc.source()).filename().string());
      if (!confined.ok()) {
        diagnostics.push_back(doc.diagnostic(ptr + "/insert", "crowd file " + confined.problem,
                                             detail::confinedExpectation("a crowd file", fs::path(doc.source()).filename().string())));
        continue;
      }
      const std::string path = confined.path.string();
      // Each timeline crowd joins the scenario as written (never another timeline crowd's points):
      // its indices stay right whatever else is inserted in between.
      auto crowd = loadCrowdFile(path, desc, options);
      if (!crowd.ok()) {
        const core::Diagnostics& errors = crowd.errors();
        if (errors.size() == 1 && errors.front().line == 0 && errors.front().source == path) {
          diagnostics.push_back(doc.diagnostic(ptr + "/insert", "cannot load crowd file " + detail::quote(e.path) + ": " + errors.front().what,
                                               "a readable crowd file relative to the scenario's directory"));
        } else {
          diagnostics.insert(diagnostics.end(), errors.begin(), errors.end());
        }
        continue;
      }
      e.crowd = std::move(crowd).value();
      if (inserted.count(e.crowd.id) != 0) {
        diagnostics.push_back(doc.diagnostic(ptr + "/insert", "crowd id " + detail::quote(e.crowd.id) + " (from " + detail::quote(e.path) +
                                                                  ") is inserted twice",
                                             "each crowd once in a timeline (give a copy another id)"));
        continue;
      }
      inserted[e.crowd.id] = false;
      options.takenCrowdIds.push_back(e.crowd.id);
      for (const auto& p : e.crowd.points) options.takenPointIds.push_back(p.id);
      for (const auto& p : e.crowd.populations) options.takenPopulationIds.push_back(p.id);
    } else if (!e.crowdId.empty()) {
      const auto it = inserted.find(e.crowdId);
      if (it == inserted.end() || it->second) {
        std::vector<std::string> ids;
        for (const auto& [id, removed] : inserted) if (!removed) ids.push_back(id);
        const std::string match = core::closestMatch(e.crowdId, ids);
        diagnostics.push_back(doc.diagnostic(ptr + "/remove",
                                             it == inserted.end() ? "no crowd " + detail::quote(e.crowdId) + " is inserted before"
                                                                  : "crowd " + detail::quote(e.crowdId) + " is removed twice",
                                             "the id of a crowd inserted earlier in the timeline",
                                             match.empty() ? "" : "did you mean " + detail::quote(match) + "?"));
      } else {
        it->second = true;
      }
    }
  }
}

}  // namespace throng::io
