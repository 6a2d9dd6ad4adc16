// throng::recording recording scenario tables — writes the scenario's points and populations into
// `throng_points` and `throng_populations` (see recording_schema.hpp, docs/recording-format.md)
// when a recording is created. Reads the ScenarioDesc; writes rows in the caller's transaction.
#include "recording_scenario.hpp"

#include "throng/sim/animation.hpp"

#include "recording_schema.hpp"
#include "recording_text.hpp"
#include "walkable_area_wkt.hpp"

namespace throng::recording {
namespace {

const char* pointKindText(sim::PointKind kind) {
  switch (kind) {
    case sim::PointKind::Interest: return "interest";
    case sim::PointKind::Action: return "action";
    case sim::PointKind::Exit: return "exit";
  }
  return "unknown";
}

std::string jsonString(std::string_view s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      static const char* kHex = "0123456789abcdef";
      out += "\\u00";
      out += kHex[(c >> 4) & 0xf];
      out += kHex[c & 0xf];
    } else {
      out += c;
    }
  }
  return out + "\"";
}

/// Steps once and resets for the next row.
bool step(const Statement& s) {
  const int rc = sqlite3_step(s.get());
  sqlite3_reset(s.get());
  sqlite3_clear_bindings(s.get());
  return rc == SQLITE_DONE;
}

}  // namespace

std::string writeScenarioTables(sqlite3* db, const sim::ScenarioDesc& scenario) {
  {
    // The motion clips that throng_animation's `clip` column indexes.
    Statement clip(db, "INSERT INTO throng_clips VALUES(?, ?, ?, ?, ?)");
    if (!clip.ok()) return sqlite3_errmsg(db);
    const std::vector<sim::ClipInfo> clips = sim::animationClips(scenario);
    for (std::size_t i = 0; i < clips.size(); ++i) {
      sqlite3_stmt* s = clip.get();
      bindInt(s, 1, static_cast<std::int64_t>(i));
      bindText(s, 2, clips[i].name);
      bindText(s, 3, clips[i].file);
      bindReal(s, 4, floatAsDecimal(clips[i].duration));
      bindInt(s, 5, clips[i].loops ? 1 : 0);
      if (!step(clip)) return sqlite3_errmsg(db);
    }
  }
  {
    Statement pt(db, "INSERT INTO throng_points VALUES(?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
    if (!pt.ok()) return sqlite3_errmsg(db);
    for (std::size_t i = 0; i < scenario.points.size(); ++i) {
      const sim::PointDesc& p = scenario.points[i];
      sqlite3_stmt* s = pt.get();
      bindInt(s, 1, static_cast<std::int64_t>(i));
      bindText(s, 2, p.id);
      bindText(s, 3, pointKindText(p.kind));
      bindReal(s, 4, floatAsDecimal(p.position.x));
      bindReal(s, 5, floatAsDecimal(p.position.y));
      bindReal(s, 6, floatAsDecimal(p.radius));
      if (p.polygon.empty()) sqlite3_bind_null(s, 7); else bindText(s, 7, polygonWkt(p.polygon));
      bindInt(s, 8, p.stop ? 1 : 0);
      bindReal(s, 9, floatAsDecimal(p.orientation.x));
      bindReal(s, 10, floatAsDecimal(p.orientation.y));
      bindText(s, 11, p.action);
      bindReal(s, 12, floatAsDecimal(p.actionDuration));
      if (p.category.empty()) sqlite3_bind_null(s, 13); else bindText(s, 13, p.category);
      if (!step(pt)) return sqlite3_errmsg(db);
    }
  }
  {
    Statement pop(db, "INSERT INTO throng_populations VALUES(?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
    if (!pop.ok()) return sqlite3_errmsg(db);
    for (std::size_t i = 0; i < scenario.populations.size(); ++i) {
      const sim::PopulationDesc& p = scenario.populations[i];
      sqlite3_stmt* s = pop.get();
      std::string goals = "[";
      for (std::size_t g = 0; g < p.goals.size(); ++g) {
        if (g > 0) goals += ",";
        const std::uint32_t idx = p.goals[g];
        goals += idx < scenario.points.size() ? jsonString(scenario.points[idx].id) : std::to_string(idx);
      }
      goals += "]";
      bindInt(s, 1, static_cast<std::int64_t>(i));
      bindText(s, 2, p.id);
      bindInt(s, 3, p.groups);
      bindInt(s, 4, p.sizeMin);
      bindInt(s, 5, p.sizeMax);
      bindReal(s, 6, floatAsDecimal(p.start));
      bindReal(s, 7, floatAsDecimal(p.speedMean));
      bindReal(s, 8, floatAsDecimal(p.speedSd));
      bindReal(s, 9, floatAsDecimal(p.speedMin));
      bindReal(s, 10, floatAsDecimal(p.speedMax));
      bindReal(s, 11, floatAsDecimal(p.radius));
      bindInt(s, 12, p.wander ? 1 : 0);
      bindText(s, 13, goals);
      switch (p.spawn.kind) {
        case sim::SpawnKind::Polygon:
          bindText(s, 14, "polygon");
          bindText(s, 15, polygonWkt(p.spawn.polygon));
          break;
        case sim::SpawnKind::Position:
          bindText(s, 14, "position");
          bindText(s, 15, "POINT (" + shortestText(floatAsDecimal(p.spawn.position.x)) + " " +
                              shortestText(floatAsDecimal(p.spawn.position.y)) + ")");
          break;
        case sim::SpawnKind::Point:
          bindText(s, 14, "point");
          if (p.spawn.point < scenario.points.size()) {
            const core::Vec2 at = scenario.points[p.spawn.point].position;
            bindText(s, 15, "POINT (" + shortestText(floatAsDecimal(at.x)) + " " +
                                shortestText(floatAsDecimal(at.y)) + ")");
          } else {
            sqlite3_bind_null(s, 15);
          }
          break;
      }
      if (!step(pop)) return sqlite3_errmsg(db);
    }
  }
  return {};
}

std::string modelsJson(const sim::ScenarioDesc& scenario) {
  std::string out = "{";
  for (std::size_t i = 0; i < scenario.populations.size(); ++i) {
    const sim::ModelDesc& m = scenario.populations[i].model;
    const sim::ModelInfo& info = sim::modelInfo(m.kind);
    out += (i ? ", " : "") + jsonString(scenario.populations[i].id) + ": {\"name\": " + jsonString(info.name);
    for (std::size_t k = 0; k < info.parameters.size(); ++k) {
      out += ", " + jsonString(info.parameters[k].key) + ": " + shortestText(floatAsDecimal(m.values[k]));
    }
    out += "}";
  }
  return out + "}";
}

}  // namespace throng::recording
