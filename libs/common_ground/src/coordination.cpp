// throng::common_ground coordination planner — Park, Peng, Quek, Cao, Table 1 (the seven grounding
// steps), Table 3 (micro-behaviour script, A3) and Table 5 (macro-behaviour script, M2). Reads a
// CoordinationInput, the micro-behaviour and macro-plan databases and the clip lengths; writes an
// ActionScript with one list per actor (A, B, companions). The state machine is run forward in
// time: `now_` is the end of the last motion, and every response starts there (t_{k+1} = t_k +
// f^{actor}_{motion}); B and the companions answer in parallel and A goes on when the last answer
// ends. A lost response (B's only) costs the initiator one timeout, then a retry: another allowed
// micro-behaviour, else moving closer to B; a step that runs out of attempts fails the
// coordination and the fallback plan runs. In step 7 the companions take B's part.
#include "throng/common_ground/coordination.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace throng::common_ground {
namespace {

using core::Vec2;

constexpr double kPi = std::numbers::pi;

double wrapAngle(double a) {
  while (a > kPi) a -= 2.0 * kPi;
  while (a < -kPi) a += 2.0 * kPi;
  return a;
}

/// B can see A after turning toward A: hearing-only relations gain sight.
Relation withSight(Relation r) {
  switch (r) {
    case Relation::A4: return Relation::A2;
    case Relation::A3:
    case Relation::A6: return Relation::A5;
    default: return r;
  }
}

core::Diagnostic problem(std::string what, std::string expected) {
  return core::Diagnostic{"coordination", 0, 0, "", std::move(what), std::move(expected), ""};
}

struct Pose {
  Vec2 position{};
  double heading = 0.0;
  double speed = 1.0;
};

constexpr std::size_t kA = 0;  ///< script index of the initiator
constexpr std::size_t kB = 1;  ///< script index of the respondent

/// One run of the grounding state machine. Actors are script indices: 0 = A, 1 = B, 2 + k =
/// companion k.
class Planner {
 public:
  Planner(const CoordinationInput& in, const Databases& dbs, const ClipLengths& clips, const CoordinationParams& p)
      : in_(in), micro_(*dbs.micro), macro_(*dbs.macro), clips_(clips), params_(p) {
    const std::size_t n = 2 + in.companions.size();
    pose_.reserve(n);
    rng_.reserve(n);
    auto add = [&](const ActorBody& b) {
      pose_.push_back({b.position, b.heading, b.walkSpeed});
      rng_.emplace_back(in.seed, b.id, core::RngPurpose::Behaviour);
    };
    add(in.initiator);
    add(in.respondent);
    for (const Companion& c : in.companions) {
      add(c.body);
      companionRelation_.push_back(c.relation);
    }
    script_.actors.assign(n, {});
    relation_ = in.relation;
    now_ = in.startTime;
  }

  core::Result<ActionScript> run() {
    script_.startTime = in_.startTime;
    std::optional<std::size_t> planIndex;
    if (in_.forcedPlan) {
      for (std::size_t i = 0; i < macro_.plans.size(); ++i) {
        if (macro_.plans[i].kind == *in_.forcedPlan) planIndex = i;
      }
      if (!planIndex) {
        return problem("forced plan \"" + std::string(planKindName(*in_.forcedPlan)) + "\" is not in the plan database",
                       "a plan kind listed in macro_plans.json");
      }
    } else {
      planIndex = selectPlan(macro_, in_.goal, core::distance(in_.goal.position, in_.respondent.position));
    }
    bool grounded = false;
    if (planIndex) {
      plan_ = macro_.plans[*planIndex].kind;
      grounded = ground(macro_.plans[*planIndex]);
    }
    if (!errors_.empty()) return errors_;
    script_.outcome = grounded ? Outcome::Grounded : Outcome::Failed;
    script_.plan = grounded ? plan_ : macro_.failurePlan;
    plan_ = script_.plan;
    script_.executeTime = now_;
    execute(script_.plan);
    if (!errors_.empty()) return errors_;
    double end = script_.executeTime;
    for (const auto& list : script_.actors) {
      for (const auto& e : list) end = std::max(end, e.end());
    }
    script_.endTime = end;
    return std::move(script_);
  }

 private:
  // --- the grounding steps (Table 1) ---

  bool ground(const MacroPlan& plan) {
    if (!initiate()) return false;                    // step 1
    if (!requestAttention()) return false;            // steps 2 and 3
    for (std::size_t k = 0; k < plan.proposal.size(); ++k) {  // steps 4 and 5, parts a, b, ...
      if (!proposePart(plan.proposal[k], static_cast<int>(k) + 1)) return false;
    }
    return confirm();                                 // step 6; step 7 is execute()
  }

  bool initiate() {
    if (!eligible(Intent::RequestAttention, relation_, {}).empty()) return true;  // already possible
    const auto pick = chooseBehaviour(micro_, eligible(Intent::Initiate, relation_, {}), in_.initiatorStyle, rng_[kA]);
    if (!pick) {
      moveCloser(GroundingStep::Initiate, 0);
      return errors_.empty();
    }
    play(kA, micro_.behaviours[*pick], GroundingStep::Initiate, 0, 0, nullptr);
    return errors_.empty();
  }

  bool requestAttention() {
    std::vector<std::size_t> tried;
    bool movedCloser = false;
    for (int attempt = 0; attempt < params_.maxAttempts; ++attempt) {
      auto candidates = eligible(Intent::RequestAttention, relation_, tried);
      if (candidates.empty() && !movedCloser) {
        moveCloser(GroundingStep::RequestAttention, attempt);
        movedCloser = true;
        candidates = eligible(Intent::RequestAttention, relation_, tried);
      }
      if (candidates.empty()) candidates = eligible(Intent::RequestAttention, relation_, {});  // repeat one
      const auto pick = chooseBehaviour(micro_, candidates, in_.initiatorStyle, rng_[kA]);
      if (!pick) return false;
      tried.push_back(*pick);
      const ScriptEntry* signal = play(kA, micro_.behaviours[*pick], GroundingStep::RequestAttention, 0, attempt, nullptr);
      if (!errors_.empty()) return false;
      if (respond(micro_.behaviours[*pick], Intent::GiveAttention, GroundingStep::GiveAttention, 0, attempt, signal)) {
        relation_ = withSight(relation_);
        return errors_.empty();
      }
      if (!errors_.empty()) return false;
      awaitResponse(GroundingStep::RequestAttention, 0, attempt);
    }
    return false;
  }

  bool proposePart(const std::string& name, int part) {
    const auto index = micro_.find(name);
    if (!index) {
      errors_.push_back(problem("proposal behaviour \"" + name + "\" is not in the micro-behaviour database",
                                "a behaviour name from micro_behaviours.json"));
      return false;
    }
    const MicroBehaviour& b = micro_.behaviours[*index];
    if (!allows(b, relation_)) moveCloser(GroundingStep::Propose, 0);
    if (!allows(b, relation_)) return false;
    for (int attempt = 0; attempt < params_.maxAttempts; ++attempt) {
      const ScriptEntry* gesture = play(kA, b, GroundingStep::Propose, part, attempt, nullptr);
      if (!errors_.empty()) return false;
      if (respond(b, Intent::Acknowledge, GroundingStep::Acknowledge, part, attempt, gesture)) return errors_.empty();
      if (!errors_.empty()) return false;
      awaitResponse(GroundingStep::Propose, part, attempt);
    }
    return false;
  }

  bool confirm() {
    const auto pick = chooseBehaviour(micro_, eligible(Intent::Confirm, relation_, {}), in_.initiatorStyle, rng_[kA]);
    if (!pick) return false;
    play(kA, micro_.behaviours[*pick], GroundingStep::Confirm, 0, 0, nullptr);
    return errors_.empty();
  }

  /// The responses of `signal` that have `intent` and are allowed in `r`, in the signal's order.
  std::vector<std::size_t> answers(const MicroBehaviour& signal, Intent intent, Relation r) const {
    std::vector<std::size_t> out;
    for (const auto& name : signal.responses) {
      const auto i = micro_.find(name);
      if (i && hasIntent(micro_.behaviours[*i], intent) && allows(micro_.behaviours[*i], r)) out.push_back(*i);
    }
    return out;
  }

  /// B and every companion answer `signal` in parallel, all starting at now_ (the signal's end).
  /// B answers with one of the signal's responses that has `intent` and is allowed in B's relation,
  /// unless the response is lost. Returns whether B responded; then now_ is the end of the last
  /// answer (B's or a companion's). Otherwise now_ stays at the signal's end and lastAnswer_ holds
  /// the companions' last end, which awaitResponse waits for.
  bool respond(const MicroBehaviour& signal, Intent intent, GroundingStep step, int part, int attempt,
               const ScriptEntry* signalEntry) {
    const double t = now_;
    double last = t;
    const auto pick = chooseBehaviour(micro_, answers(signal, intent, relation_), in_.respondentStyle, rng_[kB]);
    const bool answered = pick && responseArrives();
    if (answered) {
      play(kB, micro_.behaviours[*pick], step, part, attempt, signalEntry);
      last = now_;
    }
    for (std::size_t k = 0; k < companionRelation_.size() && errors_.empty(); ++k) {
      now_ = t;
      companionAnswer(k, signal, intent, step, part, attempt, signalEntry);
      last = std::max(last, now_);
    }
    lastAnswer_ = last;
    now_ = answered ? last : t;
    return answered;
  }

  /// Companion k answers like B, in its own relation and with its own random stream; when no
  /// answer is allowed (it cannot perceive the signal) it turns toward A, following the others'
  /// reaction. Either way it then sees A. Companions never lose responses.
  void companionAnswer(std::size_t k, const MicroBehaviour& signal, Intent intent, GroundingStep step, int part,
                       int attempt, const ScriptEntry* signalEntry) {
    const std::size_t c = 2 + k;
    Relation& rel = companionRelation_[k];
    const auto pick = chooseBehaviour(micro_, answers(signal, intent, rel), in_.respondentStyle, rng_[c]);
    if (pick) {
      play(c, micro_.behaviours[*pick], step, part, attempt, signalEntry);
    } else {
      const double t = turnDuration(c, pose_[kA].position);
      aimAtAgent(emit(c, std::string(kTurnMotion), std::string(kContagionTurn), t, step, part, attempt), kA);
    }
    rel = withSight(rel);
  }

  bool responseArrives() {
    if (in_.respondentAbsent) return false;
    if (nextResponse_ < in_.lostResponses.size()) return !in_.lostResponses[nextResponse_++];
    return true;
  }

  /// Behaviours for `intent` allowed in `r` whose target the input can supply.
  std::vector<std::size_t> eligible(Intent intent, Relation r, const std::vector<std::size_t>& exclude) const {
    auto all = allowedBehaviours(micro_, intent, r, exclude);
    std::erase_if(all, [&](std::size_t i) {
      const TargetKind t = micro_.behaviours[i].target;
      return (t == TargetKind::ViewPoint && !in_.viewPoint) || (t == TargetKind::HearingPoint && !in_.hearingPoint);
    });
    return all;
  }

  // --- motions ---

  /// The partner of actor a: B for A, A for B and for every companion.
  static std::size_t other(std::size_t a) { return a == kA ? kB : kA; }

  ScriptEntry& emit(std::size_t a, std::string motion, std::string behaviour, double duration, GroundingStep step,
                    int part, int attempt) {
    ScriptEntry e;
    e.start = now_;
    e.duration = duration;
    e.motion = std::move(motion);
    e.behaviour = std::move(behaviour);
    e.step = step;
    e.part = part;
    e.attempt = attempt;
    e.plan = plan_;
    now_ += duration;
    auto& list = script_.actors[a];
    list.push_back(std::move(e));
    return list.back();
  }

  static void aimAt(ScriptEntry& e, Vec2 point) {
    e.targetType = ScriptEntry::Target::Point;
    e.targetPoint = point;
  }
  void aimAtAgent(ScriptEntry& e, std::size_t who) {
    e.targetType = ScriptEntry::Target::Agent;
    e.targetActor = static_cast<std::uint32_t>(who);
    e.targetPoint = pose_[who].position;
  }

  double turnDuration(std::size_t a, Vec2 point) {
    Pose& p = pose_[a];
    const Vec2 d = point - p.position;
    if (core::lengthSq(d) <= 0.0f) return 0.0;
    const double want = std::atan2(d.y, d.x);
    const double angle = std::abs(wrapAngle(want - p.heading));
    p.heading = want;
    return angle / params_.turnRate;
  }

  double walkDuration(std::size_t a, Vec2 point) {
    Pose& p = pose_[a];
    const Vec2 d = point - p.position;
    const double dist = core::length(d);
    if (dist > 0.0) p.heading = std::atan2(d.y, d.x);
    p.position = point;
    return dist / p.speed;
  }

  /// Where walking toward the partner stops: touchDistance short of it (or where a is, if closer already).
  Vec2 nearPartner(std::size_t a) {
    const Vec2 from = pose_[a].position;
    const Vec2 to = pose_[other(a)].position;
    const float d = core::distance(from, to);
    if (d <= params_.touchDistance) return from;
    return to + core::normalize(from - to) * static_cast<float>(params_.touchDistance);
  }

  void moveCloser(GroundingStep step, int attempt) {
    const Vec2 target = nearPartner(kA);
    const double t = walkDuration(kA, target);
    ScriptEntry& e = emit(kA, std::string(kWalkMotion), "move_closer", t, step, 0, attempt);
    aimAtAgent(e, kB);
    e.targetPoint = target;
    relation_ = Relation::A1;
  }

  /// A idles for the response timeout, and at least until every companion has finished answering.
  void awaitResponse(GroundingStep step, int part, int attempt) {
    const double wait = std::max(params_.responseTimeout, lastAnswer_ - now_);
    ScriptEntry& e = emit(kA, std::string(kIdleMotion), "await_response", wait, step, part, attempt);
    aimAtAgent(e, kB);
  }

  /// The point a behaviour is aimed at; nullopt with agent set for partner targets.
  std::optional<Vec2> targetPoint(std::size_t a, const MicroBehaviour& b, const ScriptEntry* answered) {
    switch (b.target) {
      case TargetKind::None: return std::nullopt;
      case TargetKind::Partner: return pose_[other(a)].position;
      case TargetKind::Goal: return in_.goal.position;
      case TargetKind::Here: return pose_[a].position;
      case TargetKind::ViewPoint: return in_.viewPoint;
      case TargetKind::HearingPoint: return in_.hearingPoint;
      case TargetKind::Indicated:
        if (answered && answered->targetType != ScriptEntry::Target::None) return answered->targetPoint;
        return pose_[other(a)].position;
    }
    return std::nullopt;
  }

  void setTarget(ScriptEntry& e, std::size_t a, const MicroBehaviour& b, std::optional<Vec2> point) {
    if (b.target == TargetKind::Partner) aimAtAgent(e, other(a));
    else if (point) aimAt(e, *point);
  }

  /// Plays behaviour `b` for actor `a` at now_; returns its main entry (for Indicated answers).
  const ScriptEntry* play(std::size_t a, const MicroBehaviour& b, GroundingStep step, int part, int attempt,
                          const ScriptEntry* answered) {
    const std::optional<Vec2> point = targetPoint(a, b, answered);
    const std::size_t index = script_.actors[a].size();
    if (b.clip == kWalkMotion) {
      const Vec2 dest = b.target == TargetKind::Partner ? nearPartner(a) : point.value_or(pose_[a].position);
      const double t = walkDuration(a, dest);
      ScriptEntry& e = emit(a, b.clip, b.name, t, step, part, attempt);
      setTarget(e, a, b, point);
      e.targetPoint = dest;
    } else if (b.clip == kTurnMotion) {
      const double t = point ? turnDuration(a, *point) : 0.0;
      setTarget(emit(a, b.clip, b.name, t, step, part, attempt), a, b, point);
    } else {
      if (b.turnFirst && point) {
        const double t = turnDuration(a, *point);
        setTarget(emit(a, std::string(kTurnMotion), b.name, t, step, part, attempt), a, b, point);
      }
      const auto clip = clips_.find(b.clip);
      if (clip == clips_.end()) {
        errors_.push_back(problem("no clip length for clip \"" + b.clip + "\" (behaviour \"" + b.name + "\")",
                                  "every clip of the micro-behaviour database in the clip-length map"));
        return nullptr;
      }
      setTarget(emit(a, b.clip, b.name, clip->second, step, part, attempt), a, b, point);
    }
    if (a == kA && b.resultRelation) relation_ = *b.resultRelation;
    // The clip entry (the last one); valid until this actor's list grows again.
    auto& list = script_.actors[a];
    return list.size() > index ? &list.back() : nullptr;
  }

  // --- step 7: the macro-plan (Table 5) ---

  double visitDuration(PlanKind kind) const {
    for (const auto& p : macro_.plans) {
      if (p.kind == kind) return p.visitDuration;
    }
    return 0.0;
  }

  void walkTo(std::size_t a, Vec2 point, const char* behaviour) {
    const double t = walkDuration(a, point);
    aimAt(emit(a, std::string(kWalkMotion), behaviour, t, GroundingStep::Execute, 0, 0), point);
  }

  void idle(std::size_t a, const char* behaviour, double duration, Vec2 where) {
    aimAt(emit(a, std::string(kIdleMotion), behaviour, duration, GroundingStep::Execute, 0, 0), where);
  }

  /// Step 7. B's part is played by every companion too (from its own position, at its own speed).
  void execute(PlanKind kind) {
    const double t8 = now_;
    const Vec2 goal = in_.goal.position;
    const Vec2 dest = in_.destination;
    const std::size_t n = script_.actors.size();
    switch (kind) {
      case PlanKind::DivideAndWait: {
        const Vec2 meet = pose_[kB].position;
        walkTo(kA, goal, "walk_to_goal");                      // t8
        idle(kA, "stay", visitDuration(kind), goal);           // t9
        const double back = walkDuration(kA, meet);            // t10
        ScriptEntry& r = emit(kA, std::string(kWalkMotion), "walk_to_partner", back, GroundingStep::Execute, 0, 0);
        aimAtAgent(r, kB);
        const double t11 = now_;
        for (std::size_t a = kB; a < n; ++a) {                 // B and the companions wait where they are
          now_ = t8;
          idle(a, "wait", t11 - t8, pose_[a].position);        // t8 .. t11
        }
        for (std::size_t a = kA; a < n; ++a) {                 // all resume together at t11
          now_ = t11;
          walkTo(a, dest, "resume");
        }
        break;
      }
      case PlanKind::DivideAndProceed: {
        walkTo(kA, goal, "walk_to_goal");
        idle(kA, "stay", visitDuration(kind), goal);
        walkTo(kA, in_.goal.next.value_or(dest), "walk_to_next");
        for (std::size_t a = kB; a < n; ++a) {
          now_ = t8;
          walkTo(a, dest, "walk_to_destination");
        }
        break;
      }
      case PlanKind::DetourTogether: {
        std::vector<double> arrive(n, t8);
        now_ = t8;
        walkTo(kA, goal, "lead_to_goal");
        arrive[kA] = now_;
        for (std::size_t a = kB; a < n; ++a) {                 // follow the leader
          now_ = t8;
          const double t = walkDuration(a, goal);
          ScriptEntry& f = emit(a, std::string(kWalkMotion), "follow", t, GroundingStep::Execute, 0, 0);
          aimAtAgent(f, kA);
          f.targetPoint = goal;
          arrive[a] = now_;
        }
        const double t10 = *std::max_element(arrive.begin(), arrive.end()) + visitDuration(kind);
        for (std::size_t a = kA; a < n; ++a) {
          now_ = arrive[a];
          idle(a, "stay", t10 - arrive[a], goal);
        }
        for (std::size_t a = kA; a < n; ++a) {
          now_ = t10;
          walkTo(a, dest, "resume");
        }
        break;
      }
      case PlanKind::Resume: {
        for (std::size_t a = kA; a < n; ++a) {
          now_ = t8;
          walkTo(a, dest, "resume");
        }
        break;
      }
    }
  }

  static constexpr std::string_view kContagionTurn = "turn_toward";

  const CoordinationInput& in_;
  const MicroBehaviourDb& micro_;
  const MacroPlanDb& macro_;
  const ClipLengths& clips_;
  const CoordinationParams& params_;
  std::vector<core::Rng> rng_;            ///< one behaviour stream per actor, seeded by its id
  std::vector<Pose> pose_;                ///< per actor, tracked through the script
  std::vector<Relation> companionRelation_;  ///< of A w.r.t. companion k, updated as they turn to A
  Relation relation_;                     ///< of A w.r.t. B
  double now_ = 0.0;
  double lastAnswer_ = 0.0;               ///< end of the last answer to the latest signal
  PlanKind plan_ = PlanKind::Resume;
  std::size_t nextResponse_ = 0;
  ActionScript script_;
  core::Diagnostics errors_;
};

core::Diagnostics checkParams(const CoordinationParams& p, const CoordinationInput& in, const Databases& dbs) {
  core::Diagnostics d;
  if (!dbs.micro || !dbs.macro) d.push_back(problem("missing behaviour database", "both micro and macro databases"));
  if (!(p.turnRate > 0.0 && p.turnRate <= 100.0)) d.push_back(problem("turnRate out of range", "(0, 100] rad/s"));
  if (!(p.responseTimeout >= 0.0 && p.responseTimeout <= 3600.0))
    d.push_back(problem("responseTimeout out of range", "[0, 3600] s"));
  if (p.maxAttempts < 1 || p.maxAttempts > 10) d.push_back(problem("maxAttempts out of range", "1 to 10"));
  if (!(p.touchDistance > 0.0 && p.touchDistance <= 10.0)) d.push_back(problem("touchDistance out of range", "(0, 10] m"));
  for (const ActorBody* b : {&in.initiator, &in.respondent}) {
    if (!(b->walkSpeed > 0.0f && b->walkSpeed <= 10.0f)) d.push_back(problem("walkSpeed out of range", "(0, 10] m/s"));
  }
  for (std::size_t k = 0; k < in.companions.size(); ++k) {
    const Companion& c = in.companions[k];
    const std::string who = "companion " + std::to_string(k + 1) + " ";
    if (!(c.body.walkSpeed > 0.0f && c.body.walkSpeed <= 10.0f))
      d.push_back(problem(who + "walkSpeed out of range", "(0, 10] m/s"));
    const auto r = static_cast<int>(c.relation);
    if (r < 1 || r > 6) d.push_back(problem(who + "relation out of range", "one of A1..A6"));
  }
  if (!std::isfinite(in.startTime)) d.push_back(problem("startTime is not finite", "a finite time in s"));
  return d;
}

}  // namespace

double coordinationTimeBound(const CoordinationInput& in, const Databases& dbs, const ClipLengths& clips,
                             const CoordinationParams& params) {
  double maxClip = 0.0;
  for (const auto& [name, length] : clips) maxClip = std::max(maxClip, length);
  const Vec2 a = in.initiator.position;
  const Vec2 b = in.respondent.position;
  double reach = core::distance(a, b);  // farthest A can be from B, and walk toward a point
  double walk = reach;
  for (const auto& p : {in.viewPoint, in.hearingPoint}) {
    if (!p) continue;
    reach = std::max(reach, static_cast<double>(core::distance(*p, b)));
    walk = std::max(walk, static_cast<double>(core::distance(*p, a)));
  }
  const double speed = std::min(in.initiator.walkSpeed, in.respondent.walkSpeed);
  const double walking = (walk + reach) / speed;
  // A signal is at most a turn and a clip; so is every answer (B's or a companion's, a procedural
  // turn included); a lost answer costs the timeout (A waits for the companions within it or after).
  const double motion = maxClip + 2.0 * kPi / params.turnRate;
  const double attempt = 2.0 * motion + params.responseTimeout;
  std::size_t parts = 0;
  double maxVisit = 0.0;
  if (dbs.macro) {
    for (const auto& p : dbs.macro->plans) {
      parts = std::max(parts, p.proposal.size());
      maxVisit = std::max(maxVisit, p.visitDuration);
    }
  }
  const double steps = static_cast<double>(params.maxAttempts) * static_cast<double>(1 + parts) * attempt;
  const double grounding = walking + steps + motion + walking;  // initiation, steps 2–5, confirmation, moving closer

  // Step 7, from t_8. At t_8 A is within `reach` of B; B and the companions have not moved. Every
  // plan is at most: everyone walks to the goal (M3; A's walk there in M1, M2), the longest visit,
  // A walks back to B (M2), then everyone walks on (to x_r, or A to x_q), all at the slowest speed.
  const Vec2 g = in.goal.position;
  const Vec2 r = in.destination;
  double slowest = speed;
  double toGoal = core::distance(g, b) + reach;
  double onward = std::max({static_cast<double>(core::distance(r, b)) + reach,
                            static_cast<double>(core::distance(r, g)),
                            in.goal.next ? static_cast<double>(core::distance(*in.goal.next, g)) : 0.0});
  for (const Companion& c : in.companions) {
    slowest = std::min(slowest, static_cast<double>(c.body.walkSpeed));
    toGoal = std::max(toGoal, static_cast<double>(core::distance(g, c.body.position)));
    onward = std::max(onward, static_cast<double>(core::distance(r, c.body.position)));
  }
  const double back = core::distance(g, b);
  const double execution = (toGoal + back + onward) / slowest + maxVisit;
  constexpr double kRounding = 1e-3;  // [s] float distances summed in another order
  return grounding + execution + kRounding;
}

core::Result<ActionScript> planCoordination(const CoordinationInput& in, const Databases& dbs,
                                            const ClipLengths& clips, const CoordinationParams& params) {
  if (auto d = checkParams(params, in, dbs); !d.empty()) return d;
  Planner planner(in, dbs, clips, params);
  return planner.run();
}

}  // namespace throng::common_ground
