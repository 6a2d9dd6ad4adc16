// throng::io social databases loader — JSON (read with JsonDocument, so every diagnostic has
// line:column) into common_ground::MicroBehaviourDb and common_ground::MacroPlanDb. Parse, then validate names
// and cross references; every problem is reported, not the first. Never throws.
#include "throng/io/social_db.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>

#include "json_document.hpp"

namespace throng::io {
namespace {

using common_ground::Relation;

std::string quoteName(std::string_view s) {
  std::string q = "\"";
  for (const char c : s.substr(0, 80)) q += (static_cast<unsigned char>(c) < 0x20) ? '?' : c;
  return q + (s.size() > 80 ? "...\"" : "\"");
}

std::string fmtNum(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

/// Typed readers sharing the document (for positions) and the diagnostics list.
class Reader {
 public:
  Reader(const JsonDocument& doc, core::Diagnostics& diags) : doc_(doc), diags_(diags) {}

  void error(const std::string& ptr, std::string what, std::string expected, std::string hint = {}, bool atKey = false) {
    diags_.push_back(doc_.diagnostic(ptr, std::move(what), std::move(expected), std::move(hint), atKey));
  }

  bool object(const Json& v, const std::string& ptr, const std::string& expected) {
    if (v.is_object()) return true;
    error(ptr, "wrong type: " + describeType(v), expected);
    return false;
  }

  void checkKeys(const Json& obj, const std::string& ptr, const std::vector<std::string>& allowed, const std::string& what) {
    for (const auto& [key, value] : obj.items()) {
      if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
      const std::string match = core::closestMatch(key, allowed);
      error(ptr + "/" + escapePointerToken(key), "unknown key " + quoteName(key) + " in " + what,
            "one of: " + joinNames(allowed), match.empty() ? "" : "did you mean " + quoteName(match) + "?", true);
    }
  }

  const Json* require(const Json& obj, const std::string& ptr, const std::string& key, const std::string& expected) {
    if (auto it = obj.find(key); it != obj.end()) return &*it;
    error(ptr, "missing required key " + quoteName(key), expected);
    return nullptr;
  }

  static const Json* optional(const Json& obj, const std::string& key) {
    auto it = obj.find(key);
    return it == obj.end() ? nullptr : &*it;
  }

  bool string(const Json& v, const std::string& ptr, const std::string& expected, std::string& out, bool nonEmpty = true) {
    if (!v.is_string() || (nonEmpty && v.get_ref<const std::string&>().empty())) {
      error(ptr, v.is_string() ? "empty string" : "wrong type: " + describeType(v), expected);
      return false;
    }
    out = v.get<std::string>();
    return true;
  }

  /// A number in [lo, hi] (lo exclusive when loOpen).
  bool number(const Json& v, const std::string& ptr, double lo, double hi, bool loOpen, const std::string& unit, double& out) {
    const std::string expected = std::string("a number ") + (loOpen ? "> " : ">= ") + fmtNum(lo) + " and <= " +
                                 fmtNum(hi) + (unit.empty() ? "" : " " + unit);
    if (!v.is_number()) {
      error(ptr, "wrong type: " + describeType(v), expected);
      return false;
    }
    const double d = v.get<double>();
    if (!std::isfinite(d) || (loOpen ? d <= lo : d < lo) || d > hi) {
      error(ptr, "value " + fmtNum(d) + (unit.empty() ? "" : " " + unit) + " is out of range", expected);
      return false;
    }
    out = d;
    return true;
  }

  /// A string naming one of `names`; `parse` maps it to the enum.
  template <class E>
  bool choice(const Json& v, const std::string& ptr, const std::vector<std::string>& names,
              const std::function<std::optional<E>(std::string_view)>& parse, const std::string& noun, E& out) {
    const std::string expected = noun + ", one of: " + joinNames(names);
    if (!v.is_string()) {
      error(ptr, "wrong type: " + describeType(v), expected);
      return false;
    }
    const auto& s = v.get_ref<const std::string&>();
    if (auto e = parse(s)) {
      out = *e;
      return true;
    }
    const std::string match = core::closestMatch(s, names);
    error(ptr, "unknown " + noun + " " + quoteName(s), expected, match.empty() ? "" : "did you mean " + quoteName(match) + "?");
    return false;
  }

  /// A non-empty array of choices, without duplicates.
  template <class E>
  bool choices(const Json& v, const std::string& ptr, const std::vector<std::string>& names,
               const std::function<std::optional<E>(std::string_view)>& parse, const std::string& noun,
               std::vector<E>& out) {
    if (!v.is_array() || v.empty()) {
      error(ptr, v.is_array() ? "empty array" : "wrong type: " + describeType(v), "a non-empty array of " + noun + "s");
      return false;
    }
    bool ok = true;
    for (std::size_t i = 0; i < v.size(); ++i) {
      const std::string p = ptr + "/" + std::to_string(i);
      E e{};
      if (!choice<E>(v[i], p, names, parse, noun, e)) {
        ok = false;
      } else if (std::find(out.begin(), out.end(), e) != out.end()) {
        error(p, "duplicate " + noun + " " + quoteName(v[i].get<std::string>()), "each " + noun + " once");
        ok = false;
      } else {
        out.push_back(e);
      }
    }
    return ok;
  }

  /// A non-empty array of non-empty strings.
  bool names(const Json& v, const std::string& ptr, const std::string& expected, std::vector<std::string>& out,
             bool allowEmpty) {
    if (!v.is_array() || (!allowEmpty && v.empty())) {
      error(ptr, v.is_array() ? "empty array" : "wrong type: " + describeType(v), expected);
      return false;
    }
    bool ok = true;
    for (std::size_t i = 0; i < v.size(); ++i) {
      std::string s;
      if (string(v[i], ptr + "/" + std::to_string(i), "a behaviour name", s)) out.push_back(std::move(s));
      else ok = false;
    }
    return ok;
  }

  /// The top-level object: {"version": 1, <listKey>: [...]}; returns the list or null.
  const Json* top(const std::vector<std::string>& keys, const std::string& listKey, const std::string& what) {
    const Json& root = doc_.root();
    if (!object(root, "", "a JSON object (" + what + ")")) return nullptr;
    checkKeys(root, "", keys, what);
    if (const Json* v = require(root, "", "version", "\"version\": 1")) {
      if (!v->is_number_integer() || v->get<long long>() != 1) error("/version", "unsupported version", "1");
    }
    const Json* list = require(root, "", listKey, "an array of " + listKey);
    if (!list) return nullptr;
    if (!list->is_array()) {
      error("/" + listKey, "wrong type: " + describeType(*list), "an array of " + listKey);
      return nullptr;
    }
    if (list->size() > kMaxSocialDbEntries) {
      error("/" + listKey, "too many entries (" + std::to_string(list->size()) + ")",
            "at most " + std::to_string(kMaxSocialDbEntries));
      return nullptr;
    }
    return list;
  }

  const JsonDocument& doc() const { return doc_; }

 private:
  const JsonDocument& doc_;
  core::Diagnostics& diags_;
};

std::vector<std::string> tableNames(auto const& table) {
  std::vector<std::string> out;
  for (const auto n : table.names) out.emplace_back(n);
  return out;
}

const std::function<std::optional<common_ground::Intent>(std::string_view)> kParseIntent = common_ground::intentFromName;
const std::function<std::optional<Relation>(std::string_view)> kParseRelation = common_ground::relationFromName;
const std::function<std::optional<common_ground::TargetKind>(std::string_view)> kParseTarget = common_ground::targetKindFromName;
const std::function<std::optional<common_ground::PlanKind>(std::string_view)> kParsePlan = common_ground::planKindFromName;
const std::function<std::optional<common_ground::GoalKind>(std::string_view)> kParseGoal = common_ground::goalKindFromName;

common_ground::MicroBehaviour readBehaviour(Reader& r, const Json& v, const std::string& ptr) {
  common_ground::MicroBehaviour b;
  if (!r.object(v, ptr, "a micro-behaviour object")) return b;
  r.checkKeys(v, ptr, {"name", "intents", "allowedIn", "clip", "target", "turnFirst", "resultRelation", "responses",
                       "weight", "description"},
              "a micro-behaviour");
  if (const Json* x = r.require(v, ptr, "name", "a behaviour name (a non-empty string)")) {
    (void)r.string(*x, ptr + "/name", "a behaviour name (a non-empty string)", b.name);
  }
  if (const Json* x = r.require(v, ptr, "intents", "a non-empty array of intents")) {
    (void)r.choices<common_ground::Intent>(*x, ptr + "/intents", tableNames(common_ground::detail::kIntentNames), kParseIntent,
                                    "intent", b.intents);
  }
  if (const Json* x = r.require(v, ptr, "allowedIn", "a non-empty array of relations A1..A6")) {
    (void)r.choices<Relation>(*x, ptr + "/allowedIn", tableNames(common_ground::detail::kRelationNames), kParseRelation,
                              "relation", b.allowedIn);
  }
  if (const Json* x = r.require(v, ptr, "clip", "a clip name, or \"walk\" / \"turn\"")) {
    (void)r.string(*x, ptr + "/clip", "a clip name, or \"walk\" / \"turn\"", b.clip);
  }
  if (const Json* x = Reader::optional(v, "target")) {
    (void)r.choice<common_ground::TargetKind>(*x, ptr + "/target", tableNames(common_ground::detail::kTargetNames), kParseTarget,
                                       "target", b.target);
  }
  if (const Json* x = Reader::optional(v, "turnFirst")) {
    if (x->is_boolean()) b.turnFirst = x->get<bool>();
    else r.error(ptr + "/turnFirst", "wrong type: " + describeType(*x), "true or false");
  }
  if (const Json* x = Reader::optional(v, "resultRelation")) {
    Relation rel{};
    if (r.choice<Relation>(*x, ptr + "/resultRelation", tableNames(common_ground::detail::kRelationNames), kParseRelation,
                           "relation", rel)) {
      b.resultRelation = rel;
    }
  }
  if (const Json* x = Reader::optional(v, "responses")) {
    (void)r.names(*x, ptr + "/responses", "an array of behaviour names", b.responses, true);
  }
  if (const Json* x = Reader::optional(v, "weight")) {
    (void)r.number(*x, ptr + "/weight", 0.0, kMaxBehaviourWeight, true, "", b.weight);
  }
  if (const Json* x = Reader::optional(v, "description")) {
    (void)r.string(*x, ptr + "/description", "a string", b.description, false);
  }
  if ((b.clip == common_ground::kWalkMotion || b.clip == common_ground::kTurnMotion) && b.target == common_ground::TargetKind::None) {
    r.error(ptr + "/clip", "procedural motion " + quoteName(b.clip) + " needs a target", "a \"target\" other than \"none\"");
  }
  return b;
}

common_ground::MacroPlan readPlan(Reader& r, const Json& v, const std::string& ptr, const common_ground::MicroBehaviourDb& micro) {
  common_ground::MacroPlan p;
  if (!r.object(v, ptr, "a macro-plan object")) return p;
  r.checkKeys(v, ptr, {"name", "kind", "paperId", "proposal", "visitDuration", "when", "description"}, "a macro-plan");
  if (const Json* x = r.require(v, ptr, "name", "a plan name (a non-empty string)")) {
    (void)r.string(*x, ptr + "/name", "a plan name (a non-empty string)", p.name);
  }
  if (const Json* x = r.require(v, ptr, "kind", "a plan kind")) {
    (void)r.choice<common_ground::PlanKind>(*x, ptr + "/kind", tableNames(common_ground::detail::kPlanNames), kParsePlan,
                                     "plan kind", p.kind);
  }
  if (const Json* x = Reader::optional(v, "paperId")) {
    (void)r.string(*x, ptr + "/paperId", "a string (\"M1\")", p.paperId, false);
  }
  if (const Json* x = r.require(v, ptr, "proposal", "a non-empty array of micro-behaviour names")) {
    if (r.names(*x, ptr + "/proposal", "a non-empty array of micro-behaviour names", p.proposal, false)) {
      for (std::size_t i = 0; i < p.proposal.size(); ++i) {
        const auto idx = micro.find(p.proposal[i]);
        const std::string pp = ptr + "/proposal/" + std::to_string(i);
        if (!idx) {
          std::vector<std::string> all;
          for (const auto& b : micro.behaviours) all.push_back(b.name);
          const std::string match = core::closestMatch(p.proposal[i], all);
          r.error(pp, "unknown micro-behaviour " + quoteName(p.proposal[i]), "a behaviour name from the micro-behaviour database",
                  match.empty() ? "" : "did you mean " + quoteName(match) + "?");
        } else {
          const auto& in = micro.behaviours[*idx].intents;
          if (std::find(in.begin(), in.end(), common_ground::Intent::Propose) == in.end()) {
            r.error(pp, "micro-behaviour " + quoteName(p.proposal[i]) + " cannot propose", "a behaviour with the \"propose\" intent");
          }
        }
      }
    }
  }
  if (const Json* x = r.require(v, ptr, "visitDuration", "the stay at the goal [s]")) {
    (void)r.number(*x, ptr + "/visitDuration", 0.0, kMaxVisitDuration, false, "s", p.visitDuration);
  }
  if (const Json* w = r.require(v, ptr, "when", "the selection rules (an object)")) {
    const std::string wp = ptr + "/when";
    if (r.object(*w, wp, "the selection rules (an object)")) {
      r.checkKeys(*w, wp, {"goalKinds", "maxGoalDistance", "maxExpectedVisit"}, "selection rules");
      if (const Json* x = r.require(*w, wp, "goalKinds", "a non-empty array of goal kinds")) {
        (void)r.choices<common_ground::GoalKind>(*x, wp + "/goalKinds", tableNames(common_ground::detail::kGoalNames), kParseGoal,
                                          "goal kind", p.goalKinds);
      }
      if (const Json* x = Reader::optional(*w, "maxGoalDistance")) {
        (void)r.number(*x, wp + "/maxGoalDistance", 0.0, 1e6, true, "m", p.maxGoalDistance);
      }
      if (const Json* x = Reader::optional(*w, "maxExpectedVisit")) {
        (void)r.number(*x, wp + "/maxExpectedVisit", 0.0, kMaxVisitDuration, true, "s", p.maxExpectedVisit);
      }
    }
  }
  if (const Json* x = Reader::optional(v, "description")) {
    (void)r.string(*x, ptr + "/description", "a string", p.description, false);
  }
  return p;
}

core::Result<std::string> readText(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return core::Diagnostic{path, 0, 0, "", std::string("cannot open file: ") + std::strerror(errno), what, ""};
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) return core::Diagnostic{path, 0, 0, "", "cannot read file", what, ""};
  return text.str();
}

}  // namespace

core::Result<common_ground::MicroBehaviourDb> parseMicroBehaviours(std::string_view text, const std::string& source) {
  try {
    auto doc = JsonDocument::parse(text, source);
    if (!doc.ok()) return std::move(doc).takeErrors();
    core::Diagnostics diags;
    Reader r(doc.value(), diags);
    common_ground::MicroBehaviourDb db;
    const Json* list = r.top({"version", "behaviours"}, "behaviours", "a micro-behaviour database");
    if (list) {
      std::set<std::string> seen;
      for (std::size_t i = 0; i < list->size(); ++i) {
        const std::string ptr = "/behaviours/" + std::to_string(i);
        auto b = readBehaviour(r, (*list)[i], ptr);
        if (!b.name.empty() && !seen.insert(b.name).second) {
          r.error(ptr + "/name", "duplicate behaviour name " + quoteName(b.name), "a name used once in the file");
        }
        db.behaviours.push_back(std::move(b));
      }
      std::vector<std::string> all(seen.begin(), seen.end());
      for (std::size_t i = 0; i < db.behaviours.size(); ++i) {
        const auto& resp = db.behaviours[i].responses;
        for (std::size_t k = 0; k < resp.size(); ++k) {
          if (seen.count(resp[k])) continue;
          const std::string match = core::closestMatch(resp[k], all);
          r.error("/behaviours/" + std::to_string(i) + "/responses/" + std::to_string(k),
                  "unknown behaviour " + quoteName(resp[k]), "a behaviour name from /behaviours",
                  match.empty() ? "" : "did you mean " + quoteName(match) + "?");
        }
      }
    }
    if (!diags.empty()) return diags;
    return db;
  } catch (const std::exception& e) {
    return core::Diagnostic{source, 0, 0, "", std::string("internal error: ") + e.what(), "", ""};
  }
}

core::Result<common_ground::MacroPlanDb> parseMacroPlans(std::string_view text, const std::string& source,
                                                  const common_ground::MicroBehaviourDb& micro) {
  try {
    auto doc = JsonDocument::parse(text, source);
    if (!doc.ok()) return std::move(doc).takeErrors();
    core::Diagnostics diags;
    Reader r(doc.value(), diags);
    common_ground::MacroPlanDb db;
    const Json* list = r.top({"version", "failurePlan", "plans"}, "plans", "a macro-plan database");
    if (const Json* root = &doc.value().root(); root->is_object()) {
      if (const Json* f = Reader::optional(*root, "failurePlan")) {
        (void)r.choice<common_ground::PlanKind>(*f, "/failurePlan", tableNames(common_ground::detail::kPlanNames), kParsePlan,
                                         "plan kind", db.failurePlan);
      }
    }
    if (list) {
      std::set<std::string> seen;
      for (std::size_t i = 0; i < list->size(); ++i) {
        const std::string ptr = "/plans/" + std::to_string(i);
        auto p = readPlan(r, (*list)[i], ptr, micro);
        if (!p.name.empty() && !seen.insert(p.name).second) {
          r.error(ptr + "/name", "duplicate plan name " + quoteName(p.name), "a name used once in the file");
        }
        db.plans.push_back(std::move(p));
      }
      if (db.plans.empty()) r.error("/plans", "no plans", "at least one macro-plan");
    }
    if (!diags.empty()) return diags;
    return db;
  } catch (const std::exception& e) {
    return core::Diagnostic{source, 0, 0, "", std::string("internal error: ") + e.what(), "", ""};
  }
}

core::Result<common_ground::MicroBehaviourDb> loadMicroBehaviours(const std::string& path) {
  auto text = readText(path, "a readable micro-behaviour database");
  if (!text.ok()) return std::move(text).takeErrors();
  return parseMicroBehaviours(text.value(), path);
}

core::Result<common_ground::MacroPlanDb> loadMacroPlans(const std::string& path, const common_ground::MicroBehaviourDb& micro) {
  auto text = readText(path, "a readable macro-plan database");
  if (!text.ok()) return std::move(text).takeErrors();
  return parseMacroPlans(text.value(), path, micro);
}

}  // namespace throng::io
