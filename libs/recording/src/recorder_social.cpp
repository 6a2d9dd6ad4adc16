// throng::recording::Recorder, Common Ground tables — writes a frame's finished coordinations
// (throng_coordinations) and played script entries (throng_script) with the statements that
// Recorder::Impl::prepareAll() prepared (recorder.cpp), on the recorder's worker thread inside the
// frame's transaction. Record fields become text with throng::common_ground's names
// (docs/recording-format.md); a time that is not finite is stored as NULL.
#include <cmath>
#include <cstdint>
#include <string>

#include "throng/common_ground/behaviour_db.hpp"
#include "throng/common_ground/relation.hpp"

#include "recorder_impl.hpp"
#include "recording_schema.hpp"

namespace throng::recording {
namespace {

using recording::bindInt;
using recording::bindText;

// Common Ground record fields as text (throng::common_ground's names; docs/recording-format.md).
const char* triggerText(sim::GoalTrigger t) {
  switch (t) {
    case sim::GoalTrigger::Need: return "need";
    case sim::GoalTrigger::Attraction: return "attraction";
  }
  return "unknown";
}

const char* outcomeText(sim::CoordinationOutcome o) {
  switch (o) {
    case sim::CoordinationOutcome::Grounded: return "grounded";
    case sim::CoordinationOutcome::Failed: return "failed";
    case sim::CoordinationOutcome::Alone: return "alone";
  }
  return "unknown";
}

const char* roleText(std::uint8_t role) {
  switch (role) {
    case 0: return "initiator";
    case 1: return "respondent";
    case 2: return "companion";
    default: return "unknown";
  }
}

const char* targetTypeText(std::uint8_t type) {
  switch (type) {
    case 0: return "none";
    case 1: return "point";
    case 2: return "agent";
    default: return "unknown";
  }
}

std::string planText(std::uint8_t plan) {
  return std::string(common_ground::planKindName(static_cast<common_ground::PlanKind>(plan)));
}

/// A REAL column that holds NULL when the value is not finite (never a write error).
void bindFinite(sqlite3_stmt* s, int i, double v) {
  if (std::isfinite(v)) sqlite3_bind_double(s, i, v); else sqlite3_bind_null(s, i);
}

}  // namespace

bool Recorder::Impl::writeSocial(const sim::Frame& f) {
  for (const sim::CoordinationRecord& c : f.coordinations) {
    sqlite3_stmt* s = insertCoordination.get();
    std::string respondents;
    for (const std::uint32_t id : c.respondents) {
      if (!respondents.empty()) respondents += ' ';
      respondents += std::to_string(id);
    }
    bindInt(s, 1, c.id);
    bindInt(s, 2, c.group);
    bindInt(s, 3, c.initiator);
    bindText(s, 4, respondents);
    bindInt(s, 5, c.goalPoint);
    bindText(s, 6, common_ground::goalKindName(static_cast<common_ground::GoalKind>(c.goalKind)));
    bindText(s, 7, triggerText(c.trigger));
    if (c.relation >= 1 && c.relation <= 6) {
      bindText(s, 8, common_ground::relationName(static_cast<common_ground::Relation>(c.relation)));
    } else {
      sqlite3_bind_null(s, 8);
    }
    bindText(s, 9, planText(c.plan));
    bindText(s, 10, outcomeText(c.outcome));
    bindInt(s, 11, c.retries);
    bindFinite(s, 12, c.start);
    bindFinite(s, 13, c.executeTime);
    bindFinite(s, 14, c.end);
    if (!run(insertCoordination)) return false;
  }
  for (const sim::ScriptRecord& r : f.script) {
    sqlite3_stmt* s = insertScript.get();
    bindInt(s, 1, r.coordination);
    bindInt(s, 2, r.agent);
    bindInt(s, 3, r.seq);
    bindText(s, 4, roleText(r.role));
    bindInt(s, 5, r.step);
    bindInt(s, 6, r.part);
    bindInt(s, 7, r.attempt);
    bindText(s, 8, planText(r.plan));
    bindText(s, 9, r.motion);
    bindText(s, 10, r.behaviour);
    bindText(s, 11, targetTypeText(r.targetType));
    if (r.targetType == 2) bindInt(s, 12, r.targetAgent); else sqlite3_bind_null(s, 12);
    if (r.targetType != 0) {
      bindFinite(s, 13, static_cast<double>(r.targetX));
      bindFinite(s, 14, static_cast<double>(r.targetY));
    } else {
      sqlite3_bind_null(s, 13);
      sqlite3_bind_null(s, 14);
    }
    bindFinite(s, 15, r.plannedStart);
    bindFinite(s, 16, r.plannedDuration);
    bindFinite(s, 17, r.start);
    bindFinite(s, 18, r.duration);
    if (!run(insertScript)) return false;
  }
  return true;
}

}  // namespace throng::recording
