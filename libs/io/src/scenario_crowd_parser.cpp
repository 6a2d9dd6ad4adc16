// throng::io scenario crowd parser — the Musse et al. crowd-model keys of a population: "goals"
// (a list of point ids and waypoint choices {"choose", "split", "shares"}, or "auto": a final
// action point per group, interest points near the way),
// "paths", "autoNearDistance", "flocking", "waitTimeout", "groupSpacing", "follow" (its population
// id resolved once every population is read), "guide" (a timed waypoint script, its release) and
// "sociological"; see docs/scenario-format.md "Crowd model"; and "exits" with "exitChoice" (rule,
// period, hysteresis, shares, familiar exits and familiarity, herding; "Exit choice"). Reads a population's JSON object;
// writes sim::PopulationDesc fields and diagnostics. Private to throng_io.
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "scenario_reader.hpp"

namespace throng::io::detail {

bool ScenarioReader::readGoals(const Json& v, const std::string& ptr, sim::PopulationDesc& p) {
  const std::string expected = "an array of point ids from /points, or \"auto\"";
  if (v.is_string()) {
    // Automatic goals (Musse et al. §3.1.2): a final action point drawn per group, the interest
    // points near a curve to it on the way.
    const std::string s = v.get<std::string>();
    if (s != "auto") {
      std::string hint;
      if (std::find(pointIds_.begin(), pointIds_.end(), s) != pointIds_.end()) hint = "for one goal write [" + quote(s) + "]";
      else if (!core::closestMatch(s, {"auto"}).empty()) hint = "did you mean \"auto\"?";
      error(ptr, "unknown goals mode " + quote(s), expected, hint);
      return false;
    }
    if (multiLevel_) {
      refuseOnLevels(ptr, "\"goals\": \"auto\"", "an array of point ids from /points (the goals listed)");
      return false;
    }
    if (!hasActionPoint_) {
      error(ptr, "\"goals\": \"auto\" needs at least one point of kind \"action\"",
            "an action point in /points (each group's final goal is drawn among them)",
            "add a point with \"kind\": \"action\", or list the goals");
      return false;
    }
    p.autoGoals = true;
    p.goals.clear();
    return true;
  }
  if (!v.is_array()) {
    error(ptr, "wrong type: " + describeType(v), expected);
    return false;
  }
  bool ok = true;
  for (std::size_t g = 0; g < v.size(); ++g) {
    std::uint32_t index = 0;
    if (v[g].is_object()) ok = readGoalChoice(v[g], ptr + "/" + std::to_string(g), p) && ok;
    else if (resolvePoint(v[g], ptr + "/" + std::to_string(g), index)) p.goals.push_back(index);
    else ok = false;
  }
  return ok;
}

/// A waypoint choice in "goals": {"choose": [ids of interest or action points, >= 2, each once],
/// "split": "shares" | "leastTargeted", "shares": [one per option]}. Its slot holds the first
/// option until a group chooses.
bool ScenarioReader::readGoalChoice(const Json& v, const std::string& ptr, sim::PopulationDesc& p) {
  checkKeys(v, ptr, {"choose", "split", "shares"}, "goal choice");
  sim::GoalChoiceDesc c;
  c.slot = static_cast<std::uint32_t>(p.goals.size());
  p.goals.push_back(0);  // a slot even when the choice is wrong, so later slots keep their index
  bool ok = true;
  const Json* options = optional(v, "choose");
  const std::string optr = ptr + "/choose";
  const std::string expected = "an array of at least 2 ids of interest or action points, each once";
  if (options == nullptr) {
    error(ptr, "a goal choice without \"choose\"", expected, "write {\"choose\": [\"a\", \"b\"]}, or a point id for one goal");
    return false;
  }
  if (!options->is_array() || options->size() < 2) {
    error(optr, options->is_array() ? "fewer than 2 options" : "wrong type: " + describeType(*options), expected);
    return false;
  }
  for (std::size_t k = 0; k < options->size(); ++k) {
    const std::string eptr = optr + "/" + std::to_string(k);
    std::uint32_t index = 0;
    if (!resolvePoint((*options)[k], eptr, index)) {
      ok = false;
    } else if (index < pointIsExit_.size() && pointIsExit_[index] != 0) {
      error(eptr, "point " + quote(pointIds_[index]) + " is an exit", expected,
            "to choose among exits, list them in the population's \"exits\" with \"exitChoice\"");
      ok = false;
    } else if (std::find(c.options.begin(), c.options.end(), index) != c.options.end()) {
      error(eptr, "point " + quote(pointIds_[index]) + " listed twice", expected);
      ok = false;
    } else {
      c.options.push_back(index);
    }
  }
  if (auto* x = optional(v, "split")) {
    std::size_t split = 0;
    if (readChoice(*x, ptr + "/split", {"shares", "leastTargeted"}, "split", split)) c.split = static_cast<sim::GoalSplit>(split);
    else ok = false;
  }
  if (auto* x = optional(v, "shares")) ok = ok && readChoiceShares(*x, ptr + "/shares", c);
  if (!ok) return false;
  p.goals.back() = c.options.front();
  p.goalChoices.push_back(std::move(c));
  return true;
}

bool ScenarioReader::readChoiceShares(const Json& v, const std::string& ptr, sim::GoalChoiceDesc& c) {
  const std::string expected = "one share >= 0 per option (" + std::to_string(c.options.size()) + "), not all 0";
  if (c.split != sim::GoalSplit::Shares) {
    error(ptr, "\"shares\" only apply to the shares split", "\"split\": \"shares\" or no \"shares\"", "", true);
    return false;
  }
  if (!v.is_array() || v.size() != c.options.size()) {
    error(ptr, v.is_array() ? std::to_string(v.size()) + " shares" : "wrong type: " + describeType(v), expected);
    return false;
  }
  bool ok = true;
  float total = 0.0f;
  for (std::size_t k = 0; k < v.size(); ++k) {
    float share = 0.0f;
    if (readFloat(v[k], ptr + "/" + std::to_string(k), {0, 1e6, false, ""}, share)) c.shares.push_back(share), total += share;
    else ok = false;
  }
  if (ok && total <= 0.0f) {
    error(ptr, "every share is 0", expected);
    ok = false;
  }
  return ok;
}

bool ScenarioReader::readExits(const Json& v, const std::string& ptr, sim::PopulationDesc& p) {
  const std::string expected = "an array of at least one id of a point of kind \"exit\"";
  if (!v.is_array() || v.empty()) {
    error(ptr, v.is_array() ? "no exits" : "wrong type: " + describeType(v), expected);
    return false;
  }
  bool ok = true;
  for (std::size_t k = 0; k < v.size(); ++k) {
    const std::string eptr = ptr + "/" + std::to_string(k);
    std::uint32_t index = 0;
    if (!resolvePoint(v[k], eptr, index)) {
      ok = false;
    } else if (index < pointIsExit_.size() && pointIsExit_[index] == 0) {
      error(eptr, "point " + quote(pointIds_[index]) + " is not an exit", expected, "give it \"kind\": \"exit\"");
      ok = false;
    } else if (std::find(p.exits.begin(), p.exits.end(), index) != p.exits.end()) {
      error(eptr, "exit " + quote(pointIds_[index]) + " listed twice", "each exit once");
      ok = false;
    } else {
      p.exits.push_back(index);
    }
  }
  if (!ok) p.exits.clear();
  return ok;
}

/// exitChoice.familiar: ids of exits the population lists in "exits", each once.
bool ScenarioReader::readFamiliar(const Json& v, const std::string& ptr, sim::PopulationDesc& p) {
  const std::string expected = "an array of ids of this population's \"exits\", each once";
  if (!v.is_array()) {
    error(ptr, "wrong type: " + describeType(v), expected);
    return false;
  }
  bool ok = true;
  std::vector<std::uint32_t>& known = p.exitChoice.familiar;
  for (std::size_t k = 0; k < v.size(); ++k) {
    const std::string eptr = ptr + "/" + std::to_string(k);
    std::uint32_t index = 0;
    if (!resolvePoint(v[k], eptr, index)) {
      ok = false;
    } else if (p.exits.empty()) {
      ok = false;  // "exits" itself was wrong, and said so
    } else if (std::find(p.exits.begin(), p.exits.end(), index) == p.exits.end()) {
      error(eptr, "point " + quote(pointIds_[index]) + " is not one of the population's exits", expected,
            "add it to \"exits\"");
      ok = false;
    } else if (std::find(known.begin(), known.end(), index) != known.end()) {
      error(eptr, "exit " + quote(pointIds_[index]) + " listed twice", expected);
      ok = false;
    } else {
      known.push_back(index);
    }
  }
  if (!ok) known.clear();
  return ok;
}

bool ScenarioReader::readExitChoice(const Json& v, const std::string& ptr, sim::PopulationDesc& p) {
  if (!isObject(v, ptr, "{\"rule\": \"quickest\" | \"nearest\" | \"allocation\", \"period\", \"hysteresis\", \"shares\", "
                       "\"familiar\", \"familiarity\", \"herding\", \"herdingRadius\"}")) {
    return false;
  }
  checkKeys(v, ptr, {"rule", "period", "hysteresis", "shares", "familiar", "familiarity", "herding", "herdingRadius"},
            "exit choice");
  sim::ExitChoiceDesc& c = p.exitChoice;
  bool ok = true;
  if (auto* x = optional(v, "rule")) {
    std::size_t rule = 0;
    if (readChoice(*x, ptr + "/rule", {"nearest", "quickest", "allocation"}, "exit choice rule", rule)) {
      c.rule = static_cast<sim::ExitRule>(rule);
    } else {
      ok = false;
    }
  }
  ok = readFloatKeys(v, ptr, {{"period", {0, 3600, true, "s"}, &c.period}, {"hysteresis", {0, 1, false, ""}, &c.hysteresis},
                             {"familiarity", {1, 100, false, ""}, &c.familiarity}, {"herding", {0, 1, false, ""}, &c.herding},
                             {"herdingRadius", {0, 50, true, "m"}, &c.herdingRadius}}) && ok;
  if (optional(v, "herding") != nullptr && c.rule == sim::ExitRule::Allocation) {
    error(ptr + "/herding", "\"herding\" only applies to the nearest and quickest rules",
          "\"rule\": \"nearest\" or \"quickest\", or no \"herding\"", "", true);
    ok = false;
  }
  if (auto* x = optional(v, "familiar")) {
    if (c.rule == sim::ExitRule::Allocation) {
      error(ptr + "/familiar", "\"familiar\" only applies to the nearest and quickest rules",
            "\"rule\": \"nearest\" or \"quickest\", or no \"familiar\"", "", true);
      ok = false;
    } else {
      ok = readFamiliar(*x, ptr + "/familiar", p) && ok;
    }
  }
  if (auto* x = optional(v, "shares")) {
    const std::string sptr = ptr + "/shares";
    const std::string expected = "one share >= 0 per exit (" + std::to_string(p.exits.size()) + "), not all 0";
    if (c.rule != sim::ExitRule::Allocation) {
      error(sptr, "\"shares\" only apply to the allocation rule", "\"rule\": \"allocation\" or no \"shares\"", "", true);
      return false;
    }
    if (!x->is_array() || (!p.exits.empty() && x->size() != p.exits.size())) {
      error(sptr, x->is_array() ? std::to_string(x->size()) + " shares" : "wrong type: " + describeType(*x), expected);
      return false;
    }
    float total = 0.0f;
    for (std::size_t k = 0; k < x->size(); ++k) {
      float share = 0.0f;
      if (readFloat((*x)[k], sptr + "/" + std::to_string(k), {0, 1e6, false, ""}, share)) c.shares.push_back(share), total += share;
      else ok = false;
    }
    if (ok && total <= 0.0f) {
      error(sptr, "every share is 0", expected);
      ok = false;
    }
  }
  return ok;
}

/// The Musse et al. crowd-model keys of a population (group behaviour, paths, following,
/// guidance, sociological effects); see docs/scenario-format.md "Crowd model".
bool ScenarioReader::readCrowdKeys(const Json& v, const std::string& ptr, std::size_t index, sim::PopulationDesc& p) {
  bool ok = readFloatKeys(v, ptr, {{"autoNearDistance", {0, 1000, true, "m"}, &p.autoNearDistance},
                                   {"waitTimeout", {0, 1e6, true, "s"}, &p.waitTimeout},
                                   {"groupSpacing", {0.3, 3, false, "m"}, &p.groupSpacing}});
  if (auto* x = optional(v, "paths")) {
    std::size_t kind = 0;
    if (!readChoice(*x, ptr + "/paths", {"navmesh", "bezier"}, "path kind", kind)) {
      ok = false;
    } else if (kind == 1 && multiLevel_) {
      refuseOnLevels(ptr + "/paths", "\"paths\": \"bezier\"", "\"navmesh\" (or no \"paths\")");
      ok = false;
    } else {
      p.bezierPaths = kind == 1;
    }
  }
  if (auto* x = optional(v, "flocking")) ok = readBool(*x, ptr + "/flocking", p.flocking) && ok;
  if (auto* x = optional(v, "follow")) ok = readFollow(*x, ptr + "/follow", index, p.follow) && ok;
  if (auto* x = optional(v, "guide")) ok = readGuide(*x, ptr + "/guide", p.guide) && ok;
  if (auto* x = optional(v, "sociological")) ok = readSociological(*x, ptr + "/sociological", p.sociological) && ok;
  return ok;
}

bool ScenarioReader::readFollow(const Json& v, const std::string& ptr, std::size_t index, sim::FollowDesc& f) {
  if (!isObject(v, ptr, "a follow object {\"population\", \"group\", \"mode\", \"on\", \"off\"}")) return false;
  checkKeys(v, ptr, {"population", "group", "mode", "on", "off"}, "follow");
  bool ok = true;
  const std::string popExpected = "the id of another population in /populations (a string)";
  if (auto* x = require(v, ptr, "population", popExpected)) {
    std::string target;
    if (readString(*x, ptr + "/population", popExpected, target)) follows_.push_back({index, target, ptr});
    else ok = false;
  } else {
    ok = false;
  }
  f.mode = sim::FollowMode::Permanent;
  bool modeOk = true;
  if (auto* x = optional(v, "mode")) {
    std::size_t mode = 0;
    modeOk = readChoice(*x, ptr + "/mode", {"permanent", "temporary"}, "follow mode", mode);
    if (mode == 1) f.mode = sim::FollowMode::Temporary;
    ok = modeOk && ok;
  }
  if (auto* x = optional(v, "group")) {
    double d;
    // Checked against the followed population's "groups" by resolveFollows.
    if (readInteger(*x, ptr + "/group", 0, kMaxAgents, "", d)) f.group = static_cast<std::uint32_t>(d);
    else ok = false;
  }
  const Range period{0, 1e6, true, "s"};
  for (const char* key : {"on", "off"}) {
    const Json* x = optional(v, key);
    if (x == nullptr || !modeOk) continue;
    const std::string kptr = ptr + "/" + key;
    if (f.mode != sim::FollowMode::Temporary) {
      error(kptr, std::string("\"") + key + "\" only applies to temporary following",
            std::string("\"mode\": \"temporary\" or no \"") + key + "\"", "", true);
      ok = false;
    } else if (std::string(key) == "on") {
      ok = readInterval(*x, kptr, period, f.onMin, f.onMax) && ok;
    } else {
      ok = readInterval(*x, kptr, period, f.offMin, f.offMax) && ok;
    }
  }
  return ok;
}

void ScenarioReader::resolveFollows(ParsedScenario& out) {
  std::vector<std::string> ids;
  for (const auto& p : out.desc.populations) ids.push_back(p.id);
  for (const PendingFollow& pf : follows_) {
    sim::PopulationDesc& pop = out.desc.populations[pf.population];
    const std::string pptr = pf.pointer + "/population";
    const auto it = std::find(ids.begin(), ids.end(), pf.target);
    const std::size_t target = static_cast<std::size_t>(it - ids.begin());
    bool ok = true;
    if (it == ids.end()) {
      std::vector<std::string> others = ids;
      others.erase(others.begin() + static_cast<std::ptrdiff_t>(pf.population));
      const std::string match = core::closestMatch(pf.target, others);
      error(pptr, "unknown population " + quote(pf.target), "an id from /populations",
            match.empty() ? "" : "did you mean " + quote(match) + "?");
      ok = false;
    } else if (target == pf.population) {
      error(pptr, "a population cannot follow itself", "the id of another population in /populations");
      ok = false;
    } else if (out.populationsOk[target] && pop.follow.group >= out.desc.populations[target].groups) {
      const std::uint32_t groups = out.desc.populations[target].groups;
      error(pf.pointer + "/group",
            "group " + std::to_string(pop.follow.group) + " is out of range: population " + quote(pf.target) + " has " +
                std::to_string(groups) + (groups == 1 ? " group" : " groups"),
            "a group index from 0 to " + std::to_string(groups - 1) + " (0-based)");
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

bool ScenarioReader::readGuide(const Json& v, const std::string& ptr, sim::GuideDesc& g) {
  if (!isObject(v, ptr, "a guide object {\"script\", \"distance\", \"release\"}")) return false;
  checkKeys(v, ptr, {"script", "distance", "release"}, "a guide");
  bool ok = readFloatKeys(v, ptr, {{"distance", {0, 100, false, "m"}, &g.distance}});
  const Json* script = optional(v, "script");
  bool firstTimeOk = false;  // the release is checked against the first waypoint whenever it parsed
  if (script != nullptr) ok = readGuideScript(*script, ptr + "/script", g.script, firstTimeOk) && ok;
  if (auto* x = optional(v, "release")) {
    const std::string rptr = ptr + "/release";
    float release = 0.0f;
    if (!readFloat(*x, rptr, {0, 1e6, false, "s"}, release)) {
      ok = false;
    } else if (script == nullptr) {
      error(rptr, "\"release\" without a \"script\"", "a \"script\" of timed waypoints, or no \"release\"", "", true);
      ok = false;
    } else if (firstTimeOk && release < g.script.front().time) {
      error(rptr,
            "release at " + num(release) + " s is before the first waypoint at " + num(g.script.front().time) + " s",
            "a time >= " + num(g.script.front().time) + " s (the first waypoint's time)");
      ok = false;
    } else {
      g.release = release;
    }
  }
  if (!ok) g.script.clear();
  return ok;
}

bool ScenarioReader::readGuideScript(const Json& v, const std::string& ptr, std::vector<sim::GuideWaypoint>& out,
                             bool& firstTimeOk) {
  const std::string waypoint = "a waypoint {\"time\": seconds >= 0, \"position\": [x, y] or [x, y, z] in metres}";
  if (!v.is_array()) {
    error(ptr, "wrong type: " + describeType(v), "an array of waypoints, times strictly ascending");
    return false;
  }
  if (v.empty()) {
    error(ptr, "empty guide script", "at least one " + waypoint);
    return false;
  }
  out.assign(v.size(), {});  // indices equal JSON indices: the validator points at /script/k
  bool ok = true, previousOk = false;
  for (std::size_t k = 0; k < v.size(); ++k) {
    const std::string wptr = ptr + "/" + std::to_string(k);
    bool timeOk = false;
    if (isObject(v[k], wptr, waypoint)) {
      checkKeys(v[k], wptr, {"time", "position"}, "a guide waypoint");
      if (auto* t = require(v[k], wptr, "time", "a time in seconds >= 0")) {
        timeOk = readFloat(*t, wptr + "/time", {0, 1e6, false, "s"}, out[k].time);
      }
      if (auto* p = require(v[k], wptr, "position", "a position [x, y] or [x, y, z] in metres")) {
        ok = readPosition(*p, wptr + "/position", out[k].position, out[k].height) && ok;
      } else {
        ok = false;
      }
    }
    if (timeOk && previousOk && out[k].time <= out[k - 1].time) {
      error(wptr + "/time",
            "waypoint time " + num(out[k].time) + " s is not after the previous waypoint's " + num(out[k - 1].time) + " s",
            "times strictly ascending along the script");
      ok = false;
    }
    ok = timeOk && ok;
    previousOk = timeOk;
    if (k == 0) firstTimeOk = timeOk;
  }
  return ok;
}

bool ScenarioReader::readSociological(const Json& v, const std::string& ptr, sim::SociologicalDesc& s) {
  if (!isObject(v, ptr, "an object of sociological-model parameters")) return false;
  checkKeys(v, ptr,
            {"enabled", "meetDistance", "changeGroupRate", "followAgentRate", "followDuration", "leaderChangeRate",
             "sociability", "domination"},
            "sociological");
  s.enabled = true;  // giving the object turns the model on
  bool ok = true;
  if (auto* x = optional(v, "enabled")) ok = readBool(*x, ptr + "/enabled", s.enabled) && ok;
  const Range rate{0, 100, false, "1/s"};
  return readFloatKeys(v, ptr, {{"meetDistance", {0, 100, true, "m"}, &s.meetDistance},
                                {"changeGroupRate", rate, &s.changeGroupRate},
                                {"followAgentRate", rate, &s.followAgentRate},
                                {"followDuration", {0, 1e6, true, "s"}, &s.followDuration},
                                {"leaderChangeRate", rate, &s.leaderChangeRate},
                                {"sociability", {0, 100, false, ""}, &s.sociability},
                                {"domination", {0, 1, false, ""}, &s.domination}}) &&
         ok;
}

}  // namespace throng::io::detail
