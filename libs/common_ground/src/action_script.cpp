// throng::common_ground action script — labels, a text rendering in the shape of Park, Peng, Quek, Cao
// Tables 3 and 5, and the script invariants (ordered, non-overlapping entries per actor). Reads an
// ActionScript (A, B and any companions); writes text.
#include "throng/common_ground/action_script.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace throng::common_ground {

std::string_view outcomeName(Outcome outcome) {
  return outcome == Outcome::Grounded ? "grounded" : "failed";
}

std::string stepLabel(const ScriptEntry& entry) {
  std::string s = std::to_string(static_cast<int>(entry.step));
  if (entry.part > 0) s += static_cast<char>('a' + (entry.part - 1) % 26);
  if (entry.attempt > 0) s += "/retry " + std::to_string(entry.attempt);
  return s;
}

std::string actorLabel(std::size_t i) {
  if (i == 0) return "A";
  if (i == 1) return "B";
  return "C" + std::to_string(i - 1);
}

namespace {

std::string formatTarget(const ScriptEntry& e) {
  char buf[96];
  switch (e.targetType) {
    case ScriptEntry::Target::None: return "-";
    case ScriptEntry::Target::Point:
      std::snprintf(buf, sizeof buf, "(%.2f, %.2f)", e.targetPoint.x, e.targetPoint.y);
      return buf;
    case ScriptEntry::Target::Agent:
      std::snprintf(buf, sizeof buf, "%s (%.2f, %.2f)", actorLabel(e.targetActor).c_str(), e.targetPoint.x,
                    e.targetPoint.y);
      return buf;
  }
  return "-";
}

}  // namespace

std::string formatScript(const ActionScript& script) {
  struct Row {
    const ScriptEntry* e;
    std::size_t actor;
  };
  std::vector<Row> rows;
  for (std::size_t a = 0; a < script.actors.size(); ++a) {
    for (const auto& e : script.actors[a]) rows.push_back({&e, a});
  }
  std::stable_sort(rows.begin(), rows.end(), [](const Row& x, const Row& y) {
    if (x.e->start != y.e->start) return x.e->start < y.e->start;
    return x.e->step < y.e->step;  // a zero-length response before the next step
  });
  std::string out = "step       actor  motion       behaviour             target              start [s]  duration [s]  plan\n";
  char buf[256];
  for (const Row& r : rows) {
    std::snprintf(buf, sizeof buf, "%-10s %-6s %-12s %-21s %-19s %9.3f  %12.3f  %s\n", stepLabel(*r.e).c_str(),
                  actorLabel(r.actor).c_str(), r.e->motion.c_str(), r.e->behaviour.c_str(),
                  formatTarget(*r.e).c_str(), r.e->start, r.e->duration,
                  std::string(planKindName(r.e->plan)).c_str());
    out += buf;
  }
  std::snprintf(buf, sizeof buf, "outcome: %s, plan: %s, t0 = %.3f s, execute at %.3f s, end %.3f s\n",
                std::string(outcomeName(script.outcome)).c_str(), std::string(planKindName(script.plan)).c_str(),
                script.startTime, script.executeTime, script.endTime);
  out += buf;
  return out;
}

std::string checkScript(const ActionScript& script) {
  constexpr double kEps = 1e-9;
  double last = script.executeTime;
  for (std::size_t a = 0; a < script.actors.size(); ++a) {
    const auto& list = script.actors[a];
    const std::string who = actorLabel(a);
    for (std::size_t i = 0; i < list.size(); ++i) {
      const ScriptEntry& e = list[i];
      if (!std::isfinite(e.start) || !std::isfinite(e.duration) || e.duration < 0.0) {
        return who + " entry " + std::to_string(i) + " has a bad start or duration";
      }
      if (e.start + kEps < script.startTime) return who + " entry " + std::to_string(i) + " starts before t0";
      if (i > 0 && e.start + kEps < list[i - 1].end()) {
        return who + " entry " + std::to_string(i) + " (" + e.behaviour + ") overlaps the previous one";
      }
      if (e.targetType == ScriptEntry::Target::Agent && e.targetActor >= script.actors.size()) {
        return who + " entry " + std::to_string(i) + " (" + e.behaviour + ") targets actor " +
               std::to_string(e.targetActor) + ", not in the script";
      }
      last = std::max(last, e.end());
    }
  }
  if (!(script.startTime <= script.executeTime + kEps)) return "executeTime is before startTime";
  if (std::abs(last - script.endTime) > kEps) return "endTime is not the end of the last entry";
  return {};
}

}  // namespace throng::common_ground
