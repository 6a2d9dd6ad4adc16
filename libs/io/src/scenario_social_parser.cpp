// Scenario parser, Common Ground part (Park, Peng, Quek, Cao; docs/social-model.md): a point's
// "category", a population's "interests" and "interestsPerAgent", and the top-level "social"
// section (senses, needs, attraction, coordination, databases, motions). Reads the JSON document;
// writes PointDesc::category, PopulationDesc interests and ScenarioDesc::social, and diagnostics.
// The databases and clip lengths themselves are loaded by scenario_social.cpp.
#include <set>

#include "scenario_reader.hpp"

namespace throng::io::detail {
namespace {

constexpr double kPi = 3.14159265358979323846;
const char* const kCategoryExpected = "a category name of letters, digits, '_' or '-' (\"restroom\", \"shoes\")";

bool validCategory(const std::string& s) {
  if (s.empty() || s.size() > 64) return false;
  for (const char c : s) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
    if (!ok) return false;
  }
  return true;
}

}  // namespace

bool ScenarioReader::readCategory(const Json& v, const std::string& ptr, std::string& out) {
  std::string s;
  if (!readString(v, ptr, kCategoryExpected, s)) return false;
  if (!validCategory(s)) {
    error(ptr, "bad category " + quote(s), kCategoryExpected);
    return false;
  }
  out = s;
  return true;
}

bool ScenarioReader::readInterests(const Json& v, const std::string& ptr, sim::PopulationDesc& p) {
  bool ok = true;
  if (auto* x = optional(v, "interests")) {
    const std::string iptr = ptr + "/interests";
    if (!x->is_array()) {
      error(iptr, "wrong type: " + describeType(*x), "an array of category names");
      ok = false;
    } else {
      std::set<std::string> seen;
      for (std::size_t i = 0; i < x->size(); ++i) {
        std::string c;
        if (!readCategory((*x)[i], iptr + "/" + std::to_string(i), c)) {
          ok = false;
        } else if (!seen.insert(c).second) {
          error(iptr + "/" + std::to_string(i), "duplicate interest " + quote(c), "each category once");
          ok = false;
        } else {
          p.interests.push_back(c);
        }
      }
    }
  }
  if (auto* x = optional(v, "preferences")) {
    const std::string pp = ptr + "/preferences";
    if (!x->is_object()) {
      error(pp, "wrong type: " + describeType(*x), "an object of micro-behaviour name → weight multiplier (>= 0)");
      ok = false;
    } else {
      for (const auto& [name, value] : x->items()) {
        double w = 1.0;
        if (readNumber(value, pp + "/" + escapePointerToken(name), {0, 1000, false, ""}, w)) p.preferences[name] = w;
        else ok = false;
      }
    }
  }
  if (auto* x = optional(v, "interestsPerAgent")) {
    double d;
    if (readInteger(*x, ptr + "/interestsPerAgent", 0, 64, "categories", d)) p.interestsPerAgent = static_cast<std::uint32_t>(d);
    else ok = false;
  }
  return ok;
}

void ScenarioReader::readSocial(const Json& v, const std::string& ptr, sim::CommonGroundDesc& s) {
  if (!isObject(v, ptr, "a social object {\"needs\", \"attraction\", \"senses\", ...}")) return;
  checkKeys(v, ptr,
            {"commonGround", "senses", "needs", "attraction", "coordination", "cooldown", "microBehaviours", "macroPlans",
             "motions"},
            "the social section");
  s.enabled = true;
  if (auto* x = optional(v, "commonGround")) readBool(*x, ptr + "/commonGround", s.commonGround);
  if (auto* x = optional(v, "cooldown")) readFloat(*x, ptr + "/cooldown", {0, 1e6, false, "s"}, s.cooldown);
  if (auto* x = optional(v, "senses")) {
    const std::string sp = ptr + "/senses";
    if (isObject(*x, sp, "an object {\"touchMargin\", \"hearing\", \"vision\", \"fieldOfView\"}")) {
      checkKeys(*x, sp, {"touchMargin", "hearing", "vision", "fieldOfView"}, "the senses");
      float fovDeg = static_cast<float>(s.senses.fieldOfView * 180.0 / kPi);
      readFloatKeys(*x, sp, {{"touchMargin", {0, 10, false, "m"}, &s.senses.touchMargin},
                             {"hearing", {0, 1000, false, "m"}, &s.senses.hearingRange},
                             {"vision", {0, 10000, false, "m"}, &s.senses.visionRange},
                             {"fieldOfView", {0, 360, true, "degrees"}, &fovDeg}});
      s.senses.fieldOfView = static_cast<float>(fovDeg * kPi / 180.0);
    }
  }
  if (auto* x = optional(v, "needs")) {
    const std::string np = ptr + "/needs";
    if (!x->is_array()) {
      error(np, "wrong type: " + describeType(*x), "an array of needs {\"category\", \"rate\", \"expectedVisit\"}");
    } else {
      for (std::size_t i = 0; i < x->size(); ++i) {
        const std::string ip = np + "/" + std::to_string(i);
        const Json& n = (*x)[i];
        if (!isObject(n, ip, "a need {\"category\", \"rate\", \"expectedVisit\", \"kind\"}")) continue;
        checkKeys(n, ip, {"category", "rate", "expectedVisit", "kind"}, "a need");
        sim::NeedDesc need;
        if (auto* c = require(n, ip, "category", kCategoryExpected)) readCategory(*c, ip + "/category", need.category);
        readFloatKeys(n, ip, {{"rate", {0, 10, false, "1/s"}, &need.rate},
                              {"expectedVisit", {0, 86400, false, "s"}, &need.expectedVisit}});
        if (auto* k = optional(n, "kind")) {
          std::size_t kind = 0;
          if (readChoice(*k, ip + "/kind", {"personal", "shared"}, "goal kind", kind)) {
            need.kind = kind == 0 ? common_ground::GoalKind::Personal : common_ground::GoalKind::Shared;
          }
        }
        s.needs.push_back(std::move(need));
      }
    }
  }
  if (auto* x = optional(v, "attraction")) {
    const std::string ap = ptr + "/attraction";
    if (isObject(*x, ap, "an object {\"probability\", \"expectedVisit\", \"checkPeriod\"}")) {
      checkKeys(*x, ap, {"probability", "expectedVisit", "checkPeriod"}, "the attraction");
      readFloatKeys(*x, ap, {{"probability", {0, 1, false, ""}, &s.attraction.probability},
                             {"expectedVisit", {0, 86400, false, "s"}, &s.attraction.expectedVisit},
                             {"checkPeriod", {0, 3600, true, "s"}, &s.attraction.checkPeriod}});
    }
  }
  if (auto* x = optional(v, "coordination")) {
    const std::string cp = ptr + "/coordination";
    if (isObject(*x, cp, "an object {\"turnRate\", \"responseTimeout\", \"maxAttempts\", \"touchDistance\"}")) {
      checkKeys(*x, cp, {"turnRate", "responseTimeout", "maxAttempts", "touchDistance", "missProbability"}, "the coordination");
      if (auto* y = optional(*x, "missProbability")) readFloat(*y, cp + "/missProbability", {0, 1, false, ""}, s.missProbability);
      auto& c = s.coordination;
      if (auto* y = optional(*x, "turnRate")) readNumber(*y, cp + "/turnRate", {0, 100, true, "rad/s"}, c.turnRate);
      if (auto* y = optional(*x, "responseTimeout")) readNumber(*y, cp + "/responseTimeout", {0, 3600, false, "s"}, c.responseTimeout);
      if (auto* y = optional(*x, "touchDistance")) readNumber(*y, cp + "/touchDistance", {0, 10, true, "m"}, c.touchDistance);
      double d;
      if (auto* y = optional(*x, "maxAttempts"); y && readInteger(*y, cp + "/maxAttempts", 1, 10, "attempts", d)) {
        c.maxAttempts = static_cast<int>(d);
      }
    }
  }
  if (auto* x = optional(v, "microBehaviours")) readRelativePath(*x, ptr + "/microBehaviours", "a JSON file path relative to the scenario", s.microPath);
  if (auto* x = optional(v, "macroPlans")) readRelativePath(*x, ptr + "/macroPlans", "a JSON file path relative to the scenario", s.macroPath);
  if (auto* x = optional(v, "motions")) readRelativePath(*x, ptr + "/motions", "a directory of BVH clips relative to the scenario", s.motions);
}

void ScenarioReader::checkCategories(const ParsedScenario& out) {
  const sim::ScenarioDesc& desc = out.desc;
  std::vector<std::string> categories;
  for (const auto& p : desc.points) {
    if (!p.category.empty() && std::find(categories.begin(), categories.end(), p.category) == categories.end()) {
      categories.push_back(p.category);
    }
  }
  auto check = [&](const std::string& c, const std::string& ptr) {
    if (c.empty() || std::find(categories.begin(), categories.end(), c) != categories.end()) return;
    std::string list;
    for (const auto& k : categories) list += (list.empty() ? "" : ", ") + k;
    const std::string match = core::closestMatch(c, categories);
    error(ptr, "no point has category " + quote(c),
          categories.empty() ? "points with a \"category\"" : "a category of some point: " + list,
          match.empty() ? "" : "did you mean " + quote(match) + "?");
  };
  for (std::size_t i = 0; i < desc.social.needs.size(); ++i) {
    check(desc.social.needs[i].category, "/social/needs/" + std::to_string(i) + "/category");
  }
  for (std::size_t p = 0; p < desc.populations.size(); ++p) {
    for (std::size_t i = 0; i < desc.populations[p].interests.size(); ++i) {
      check(desc.populations[p].interests[i], "/populations/" + std::to_string(p) + "/interests/" + std::to_string(i));
    }
  }
}

}  // namespace throng::io::detail
