// libFuzzer target for the social databases loader (libs/io social_db_loader): arbitrary bytes →
// parseMicroBehaviours, and → parseMacroPlans against a small fixed micro-behaviour database.
// Reads the input only. Checks that nothing crashes, throws or hangs, that rejected input has
// diagnostics naming the source, and that accepted databases are coherent (unique names,
// non-empty intents and relations, weights in range, responses and proposals resolvable).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <set>
#include <string_view>

#include "throng/io/social_db.hpp"

namespace {

void check(bool condition) {
  if (!condition) std::abort();
}

const throng::common_ground::MicroBehaviourDb& fixedMicro() {
  static const throng::common_ground::MicroBehaviourDb db = [] {
    auto r = throng::io::parseMicroBehaviours(R"({"version": 1, "behaviours": [
      {"name": "point_toward", "intents": ["propose"], "allowedIn": ["A2"], "clip": "point", "target": "goal"},
      {"name": "nod", "intents": ["acknowledge", "confirm"], "allowedIn": ["A2"], "clip": "nod"}]})",
                                              "fixed.json");
    check(r.ok());
    return r.value();
  }();
  return db;
}

void checkErrors(const throng::core::Diagnostics& errors, const char* source) {
  check(!errors.empty());
  for (const auto& d : errors) {
    check(d.source == source);
    check(!d.what.empty());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const auto micro = throng::io::parseMicroBehaviours(text, "micro.json");
  if (!micro.ok()) {
    checkErrors(micro.errors(), "micro.json");
  } else {
    std::set<std::string> names;
    for (const auto& b : micro.value().behaviours) check(names.insert(b.name).second && !b.name.empty());
    for (const auto& b : micro.value().behaviours) {
      check(!b.intents.empty() && !b.allowedIn.empty() && !b.clip.empty());
      check(b.weight > 0.0 && b.weight <= throng::io::kMaxBehaviourWeight);
      for (const auto& r : b.responses) check(names.count(r) == 1);
    }
  }
  const auto plans = throng::io::parseMacroPlans(text, "plans.json", fixedMicro());
  if (!plans.ok()) {
    checkErrors(plans.errors(), "plans.json");
  } else {
    check(!plans.value().plans.empty());
    for (const auto& p : plans.value().plans) {
      check(!p.proposal.empty() && !p.goalKinds.empty());
      check(p.visitDuration >= 0.0 && p.visitDuration <= throng::io::kMaxVisitDuration);
      check(p.maxGoalDistance > 0.0 && p.maxExpectedVisit > 0.0);
      for (const auto& name : p.proposal) check(fixedMicro().find(name).has_value());
    }
  }
  return 0;
}
