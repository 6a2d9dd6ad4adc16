// throng::common_ground behaviour and plan selection — the rules that pick from the databases (Park,
// Peng, Quek, Cao Tables 2 and 4): the first macro-plan whose rules hold for a goal, the
// micro-behaviours an intent may use in a relation, and the seeded choice among them by weight ×
// the actor's preference. Reads the databases; writes nothing. Declared in coordination.hpp.
#include <algorithm>
#include <cmath>

#include "throng/common_ground/coordination.hpp"

namespace throng::common_ground {

std::optional<std::size_t> selectPlan(const MacroPlanDb& db, const Goal& goal, double goalDistance) {
  for (std::size_t i = 0; i < db.plans.size(); ++i) {
    const MacroPlan& p = db.plans[i];
    if (std::find(p.goalKinds.begin(), p.goalKinds.end(), goal.kind) == p.goalKinds.end()) continue;
    if (goalDistance > p.maxGoalDistance) continue;
    if (goal.expectedVisit > p.maxExpectedVisit) continue;
    return i;
  }
  return std::nullopt;
}

std::vector<std::size_t> allowedBehaviours(const MicroBehaviourDb& db, Intent intent, Relation relation,
                                           const std::vector<std::size_t>& exclude) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < db.behaviours.size(); ++i) {
    const MicroBehaviour& b = db.behaviours[i];
    if (!hasIntent(b, intent) || !allows(b, relation)) continue;
    if (std::find(exclude.begin(), exclude.end(), i) != exclude.end()) continue;
    out.push_back(i);
  }
  return out;
}

std::optional<std::size_t> chooseBehaviour(const MicroBehaviourDb& db, const std::vector<std::size_t>& candidates,
                                           const ActorStyle& style, core::Rng& rng) {
  std::vector<double> w;
  w.reserve(candidates.size());
  double total = 0.0;
  for (const std::size_t i : candidates) {
    const MicroBehaviour& b = db.behaviours[i];
    const auto pref = style.preference.find(b.name);
    const double m = pref == style.preference.end() ? 1.0 : std::max(0.0, pref->second);
    const double wi = style.mode == SelectionMode::Uniform ? (m > 0.0 ? 1.0 : 0.0) : b.weight * m;
    w.push_back(std::isfinite(wi) ? wi : 0.0);
    total += w.back();
  }
  if (candidates.empty() || !(total > 0.0)) return std::nullopt;
  if (style.mode == SelectionMode::Best) {
    std::size_t best = 0;
    for (std::size_t k = 1; k < w.size(); ++k) {
      if (w[k] > w[best]) best = k;
    }
    return candidates[best];
  }
  double r = rng.uniform() * total;
  for (std::size_t k = 0; k < w.size(); ++k) {
    if (w[k] <= 0.0) continue;
    if (r < w[k]) return candidates[k];
    r -= w[k];
  }
  for (std::size_t k = w.size(); k-- > 0;) {  // rounding: the last positive weight
    if (w[k] > 0.0) return candidates[k];
  }
  return std::nullopt;
}

}  // namespace throng::common_ground
