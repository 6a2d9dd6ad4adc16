// throng::io crowd parser — a crowd file ("throng-crowd/1": id, points, populations) read by the
// scenario reader's own point and population readers against the world it joins, then checked by
// the scenario validator (spawns, capacity, reachability on the world's navmesh) and turned into
// a sim::CrowdDesc. Reads crowd JSON (or a file) and the world's description; writes the CrowdDesc
// or diagnostics. See docs/scenario-format.md "Crowd files".
#include "throng/io/crowd_loader.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include "json_document.hpp"
#include "scenario_reader.hpp"
#include "scenario_validator.hpp"
#include "throng/sim/animation.hpp"

namespace throng::io {

namespace detail {

ParsedScenario ScenarioReader::runCrowd(const sim::ScenarioDesc& world, const std::vector<std::string>& takenPoints,
                                        const std::vector<std::string>& takenPopulations, std::string& crowdId) {
  ParsedScenario out;
  const std::size_t before = diags_.size();
  const Json& root = doc_.root();
  if (!isObject(root, "", "a crowd object {\"format\": \"throng-crowd/1\", \"id\", \"points\", \"populations\"}")) return out;
  checkKeys(root, "", {"$schema", "format", "id", "points", "populations"}, "the crowd file");
  readCrowdHeader(root, crowdId);
  adoptWorld(world, out);
  readCrowdPointList(root, world, takenPoints, out);
  indexPoints(out.desc);
  readCrowdPopulationList(root, world, takenPopulations, out);
  checkCategories(out);
  out.structureOk = diags_.size() == before;
  return out;
}

void ScenarioReader::readCrowdHeader(const Json& root, std::string& crowdId) {
  std::string format;
  if (auto* x = require(root, "", "format", "\"throng-crowd/1\"")) {
    if (readString(*x, "/format", "\"throng-crowd/1\"", format) && format != "throng-crowd/1") {
      const std::string hint = format == "throng/1" ? "this is a scenario's format; a crowd file says \"throng-crowd/1\"" : "";
      error("/format", "unsupported format " + quote(format), "\"throng-crowd/1\"", hint);
    }
  }
  if (auto* x = optional(root, "$schema")) {
    std::string ignored;
    readString(*x, "/$schema", "a schema URI (a string)", ignored);
  }
  const std::string idExpected = "a non-empty string id (World::removeCrowd and a timeline's \"remove\" name it)";
  if (auto* x = require(root, "", "id", idExpected)) {
    if (readString(*x, "/id", idExpected, crowdId) && crowdId.empty()) error("/id", "empty id", idExpected);
  }
}

void ScenarioReader::adoptWorld(const sim::ScenarioDesc& world, ParsedScenario& out) {
  // The world the crowd joins: its geometry and social section, its points first.
  sim::ScenarioDesc& desc = out.desc;
  desc.walkable = world.walkable;
  desc.obstacles = world.obstacles;
  desc.terrain = world.terrain;
  multiLevel_ = !world.terrain.empty();
  desc.social = world.social;
  desc.navCellSize = world.navCellSize;
  desc.stairSlopeDeg = world.stairSlopeDeg;
  desc.points = world.points;
  out.walkableOk.assign(desc.walkable.size(), true);
  out.obstaclesOk.assign(desc.obstacles.size(), true);
  out.pointsOk.assign(desc.points.size(), true);
}

void ScenarioReader::readCrowdPointList(const Json& root, const sim::ScenarioDesc& world,
                                        const std::vector<std::string>& takenPoints, ParsedScenario& out) {
  sim::ScenarioDesc& desc = out.desc;
  const std::size_t base = world.points.size();
  std::map<std::string, std::string> takenPoint;  // id → who has it
  for (const auto& p : world.points) takenPoint.emplace(p.id, "a point of the world");
  for (const auto& id : takenPoints) takenPoint.emplace(id, "a point of a crowd inserted before");
  const std::vector<sim::ClipInfo> clips = sim::animationClips(world);
  auto* x = optional(root, "points");
  if (x == nullptr) return;
  if (!x->is_array()) {
    error("/points", "wrong type: " + describeType(*x), "an array of point objects");
    return;
  }
  if (x->size() > kMaxPoints) {
    error("/points", std::to_string(x->size()) + " points", "at most " + std::to_string(kMaxPoints) + " points");
    return;
  }
  desc.points.resize(base + x->size());
  out.pointsOk.resize(base + x->size());
  std::map<std::string, std::size_t> seen;
  for (std::size_t i = 0; i < x->size(); ++i) {
    const std::string ptr = "/points/" + std::to_string(i);
    sim::PointDesc& p = desc.points[base + i];
    out.pointsOk[base + i] = readPoint((*x)[i], ptr, p);
    if ((*x)[i].is_object() && (*x)[i].contains("clip")) {
      error(ptr + "/clip", "a crowd file cannot load motion clips into a running world",
            "no \"clip\": an \"action\" the world already plays", "", true);
    }
    checkCrowdAction((*x)[i], ptr, p, clips);
    if (p.id.empty()) continue;
    if (auto it = takenPoint.find(p.id); it != takenPoint.end()) {
      error(ptr + "/id", "point id " + quote(p.id) + " is already " + it->second, "an id no point of the world has",
            "to use the world's point, name it in \"goals\" or \"spawn\" without redefining it");
    } else if (auto [s, fresh] = seen.emplace(p.id, i); !fresh) {
      error(ptr + "/id", "duplicate point id " + quote(p.id), "ids unique within /points",
            "first used at /points/" + std::to_string(s->second));
    }
  }
}

void ScenarioReader::checkCrowdAction(const Json& v, const std::string& ptr, const sim::PointDesc& p,
                                      const std::vector<sim::ClipInfo>& clips) {
  if (p.kind != sim::PointKind::Action || !p.stop) return;
  const std::string name = p.action.empty() ? "stand" : p.action;
  if (std::any_of(clips.begin(), clips.end(), [&](const sim::ClipInfo& c) { return c.name == name; })) return;
  std::vector<std::string> names;
  std::string list;
  for (std::size_t c = 2; c < clips.size(); ++c) {  // 0, 1: idle and walk
    names.push_back(clips[c].name);
    list += (list.empty() ? "" : ", ") + quote(clips[c].name);
  }
  const std::string match = core::closestMatch(name, names);
  error(ptr + (v.is_object() && v.contains("action") ? "/action" : ""), "action " + quote(name) + " has no clip in the world",
        list.empty() ? "no stopping action point (the world plays no actions)"
                     : "an action the world's action points play: " + list,
        match.empty() ? "" : "did you mean " + quote(match) + "?");
}

void ScenarioReader::readCrowdPopulationList(const Json& root, const sim::ScenarioDesc& world,
                                             const std::vector<std::string>& takenPopulations, ParsedScenario& out) {
  sim::ScenarioDesc& desc = out.desc;
  const std::string popExpected = "an array of at least one population object";
  auto* x = require(root, "", "populations", popExpected);
  if (x == nullptr) return;
  if (!x->is_array()) {
    error("/populations", "wrong type: " + describeType(*x), popExpected);
    return;
  }
  if (x->empty()) {
    error("/populations", "no population", popExpected);
    return;
  }
  if (x->size() > kMaxPopulations) {
    error("/populations", std::to_string(x->size()) + " populations",
          "at most " + std::to_string(kMaxPopulations) + " populations (give one population more groups)");
    return;
  }
  desc.populations.resize(x->size());
  out.populationsOk.resize(x->size());
  std::map<std::string, std::string> takenPop;
  for (const auto& p : world.populations) takenPop.emplace(p.id, "a population of the world");
  for (const auto& id : takenPopulations) takenPop.emplace(id, "a population of a crowd inserted before");
  std::map<std::string, std::size_t> seen;
  for (std::size_t i = 0; i < x->size(); ++i) {
    const std::string ptr = "/populations/" + std::to_string(i);
    sim::PopulationDesc& pop = desc.populations[i];
    out.populationsOk[i] = readPopulation((*x)[i], ptr, i, pop);
    const bool hasId = (*x)[i].is_object() && (*x)[i].contains("id");
    if (auto it = takenPop.find(pop.id); it != takenPop.end()) {
      error(hasId ? ptr + "/id" : ptr, "population id " + quote(pop.id) + " is already " + it->second,
            "an id no population of the world has", hasId ? "" : "give the population an \"id\"");
      out.populationsOk[i] = false;
    } else if (auto [s, fresh] = seen.emplace(pop.id, i); !fresh) {
      error(ptr + "/id", "duplicate population id " + quote(pop.id), "ids unique within /populations",
            "first used at /populations/" + std::to_string(s->second));
    }
    if (out.populationsOk[i] && pop.largestRadius() * pop.model.passageRatio() > world.navRadius() + 1e-6f) {
      const bool hasRadius = (*x)[i].is_object() && (*x)[i].contains("radius");
      const float limit = world.navRadius() / pop.model.passageRatio();
      error(hasRadius ? ptr + "/radius" : ptr,
            "body radius " + num(pop.radius) + " m is larger than the world's navmesh allows for this model, " + num(limit) + " m",
            "a radius <= " + num(limit) + " m (the world's navmesh keeps centres " + num(world.navRadius()) +
                " m from walls: its largest body radius × its model's passage ratio)");
      out.populationsOk[i] = false;
    }
  }
  resolveCrowdFollows(world, out);
  double agents = 0;
  for (const auto& p : desc.populations) agents += double(p.groups) * p.sizeMax;
  if (agents > double(sim::kMaxInsertAgents)) {
    error("/populations", "the crowd may spawn " + num(agents) + " agents (groups × largest group size, summed)",
          "at most " + num(double(sim::kMaxInsertAgents)) + " agents per crowd insertion", "split it into several crowds");
  }
}

void ScenarioReader::resolveCrowdFollows(const sim::ScenarioDesc& world, ParsedScenario& out) {
  sim::ScenarioDesc& desc = out.desc;
  std::vector<std::string> ids;
  for (const auto& p : world.populations) ids.push_back(p.id);
  for (const auto& p : desc.populations) ids.push_back(p.id);
  const std::size_t popBase = world.populations.size();
  for (const PendingFollow& pf : follows_) {
    sim::PopulationDesc& pop = desc.populations[pf.population];
    const auto it = std::find(ids.begin(), ids.end(), pf.target);
    const auto target = static_cast<std::size_t>(it - ids.begin());
    const sim::PopulationDesc* followed = it == ids.end() ? nullptr
                                          : target < popBase ? &world.populations[target]
                                                             : &desc.populations[target - popBase];
    bool ok = true;
    if (followed == nullptr) {
      const std::string match = core::closestMatch(pf.target, ids);
      error(pf.pointer + "/population", "unknown population " + quote(pf.target),
            "an id from the world's or this file's populations", match.empty() ? "" : "did you mean " + quote(match) + "?");
      ok = false;
    } else if (target == popBase + pf.population) {
      error(pf.pointer + "/population", "a population cannot follow itself", "the id of another population");
      ok = false;
    } else if (pop.follow.group >= followed->groups) {
      error(pf.pointer + "/group",
            "group " + std::to_string(pop.follow.group) + " is out of range: population " + quote(pf.target) + " has " +
                std::to_string(followed->groups) + (followed->groups == 1 ? " group" : " groups"),
            "a group index from 0 to " + std::to_string(followed->groups - 1) + " (0-based)");
      ok = false;
    }
    if (ok) {
      pop.follow.population = static_cast<std::uint32_t>(target);
    } else {
      pop.follow = {};
      out.populationsOk[pf.population] = false;
    }
  }
}

}  // namespace detail

core::Result<sim::CrowdDesc> parseCrowd(std::string_view text, const std::string& source, const sim::ScenarioDesc& world,
                                        const CrowdOptions& options) {
  try {
    auto doc = JsonDocument::parse(text, source);
    if (!doc.ok()) return std::move(doc).takeErrors();
    core::Diagnostics diagnostics;
    std::string id;
    ParsedScenario parsed = detail::ScenarioReader(doc.value(), diagnostics)
                                .runCrowd(world, options.takenPointIds, options.takenPopulationIds, id);
    if (!id.empty() && std::find(options.takenCrowdIds.begin(), options.takenCrowdIds.end(), id) != options.takenCrowdIds.end()) {
      diagnostics.push_back(doc.value().diagnostic("/id", "crowd id " + detail::quote(id) + " is already taken",
                                                   "an id no crowd of this world has (removed crowds keep theirs)"));
    }
    if (doc.value().root().is_object()) validateCrowd(doc.value(), parsed, world.points.size(), options.navmesh, diagnostics);
    if (!diagnostics.empty()) {
      std::stable_sort(diagnostics.begin(), diagnostics.end(), [](const core::Diagnostic& a, const core::Diagnostic& b) {
        return a.line != b.line ? a.line < b.line : a.column < b.column;
      });
      return diagnostics;
    }
    sim::CrowdDesc crowd;
    crowd.id = std::move(id);
    crowd.points.assign(parsed.desc.points.begin() + static_cast<std::ptrdiff_t>(world.points.size()), parsed.desc.points.end());
    crowd.populations = std::move(parsed.desc.populations);
    crowd.basePoints = static_cast<std::uint32_t>(world.points.size());
    crowd.basePopulations = static_cast<std::uint32_t>(world.populations.size());
    return crowd;
  } catch (const std::exception& e) {
    return core::Diagnostic{source, 0, 0, "", std::string("internal error while loading the crowd: ") + e.what(), "", ""};
  }
}

core::Result<sim::CrowdDesc> loadCrowdFile(const std::string& path, const sim::ScenarioDesc& world, const CrowdOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    return core::Diagnostic{path, 0, 0, "", std::string("cannot open file: ") + std::strerror(errno), "a readable crowd file", ""};
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) return core::Diagnostic{path, 0, 0, "", "cannot read file", "a readable crowd file", ""};
  return parseCrowd(text.str(), path, world, options);
}

}  // namespace throng::io
