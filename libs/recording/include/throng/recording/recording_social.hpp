// throng::recording Common Ground recording readers — read what the recorder wrote about the social model
// (Park, Peng, Quek, Cao): the coordinations (`throng_coordinations`), the per-character action
// scripts (`throng_script`, the shape of the paper's Tables 3 and 5), an agent's trajectory, and
// the evaluation metrics of docs/social-metrics.md (arrival rate at destinations over time,
// congestion at key points, group cohesion, coordination statistics). Files are opened read-only;
// a missing table, a bad enum text or a malformed row gives a diagnostic naming the file, the
// table and the row. A recording without the Common Ground tables (written before they existed)
// gives "no Common Ground data in FILE".
#pragma once
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "throng/core/result.hpp"

namespace throng::recording {

/// One row of `throng_coordinations`: a Common Ground interaction or a lone visit.
struct CoordinationInfo {
  std::uint32_t id = 0;
  std::uint32_t group = 0;                  ///< stable group id
  std::uint32_t initiator = 0;              ///< stable id of A
  std::vector<std::uint32_t> respondents;   ///< B first, then the companions C1, C2, ...; empty when alone
  std::uint32_t goalPoint = 0;              ///< index into throng_points
  std::string goalPointId;                  ///< throng_points.id ("" when the point is unknown)
  std::string goalCategory;                 ///< throng_points.category ("" when none)
  std::string goalKind;                     ///< "personal" / "shared"
  std::string trigger;                      ///< "need" / "attraction"
  std::string relation;                     ///< "A1".."A6"; "" when alone
  std::string plan;                         ///< "divide_and_proceed", "divide_and_wait", "detour_together", "resume"
  std::string outcome;                      ///< "grounded" / "failed" / "alone"
  std::uint32_t retries = 0;                ///< grounding attempts beyond the first, over all steps
  double start = 0.0;                       ///< t_0 [s] (NaN when not recorded)
  double execute = 0.0;                     ///< t_8: the macro-plan (or fallback) starts [s]
  double end = 0.0;                         ///< the last actor left the script [s]
  /// False: the coordination had started but not ended when the recording stopped (no row in
  /// throng_coordinations; plan, outcome, goal kind, relation and t_8 are unknown).
  bool finished = true;
};

/// One row of `throng_script`: an action-script entry as the simulation carried it out.
struct ScriptEntryInfo {
  std::uint32_t coordination = 0;
  std::uint32_t agent = 0;                  ///< stable id of the character
  std::uint32_t seq = 0;                    ///< position in this character's script for the coordination
  std::string role;                         ///< "initiator" / "respondent" / "companion"
  int step = 7;                             ///< grounding step 1..7 (Park et al. Table 1; 7 = macro-plan)
  int part = 0;                             ///< proposal part of steps 4 and 5: 1 = "a", 2 = "b"; 0 otherwise
  int attempt = 0;                          ///< 0 first try, then retries
  std::string plan;                         ///< macro-plan proposed or executed
  std::string motion;                       ///< clip name, or "walk" / "turn" / "idle"
  std::string behaviour;                    ///< micro-behaviour ("wave") or macro step ("walk_to_goal")
  std::string targetType;                   ///< "none" / "point" / "agent"
  std::optional<std::uint32_t> targetAgent; ///< when targetType == "agent"
  double targetX = 0.0, targetY = 0.0;      ///< [m] target point (the agent's position for agents); NaN for none
  double plannedStart = 0.0;                ///< what the planner predicted [s] (NaN when not recorded)
  double plannedDuration = 0.0;             ///< [s]
  double start = 0.0;                       ///< when the simulation started it [s]
  double duration = 0.0;                    ///< how long it lasted [s]
};

/// "1", "4a", "5b", "2/retry 1": the step column of Tables 3 and 5.
[[nodiscard]] std::string scriptStepLabel(int step, int part, int attempt);

/// Whether the file has the Common Ground tables (false for recordings made before they existed).
core::Result<bool> hasCommonGroundData(const std::string& path);

/// Every coordination, ordered by id.
core::Result<std::vector<CoordinationInfo>> readCoordinations(const std::string& path);

/// Coordinations still running when the recording stopped: a coordination_start event with no
/// throng_coordinations row, ordered by id. Group, initiator and t_0 come from the event, the
/// goal point and trigger from the initiator's latest goal_generated event before it, the
/// respondents from the script entries recorded so far (B first, then companions by first entry).
core::Result<std::vector<CoordinationInfo>> readUnfinishedCoordinations(const std::string& path);

/// The entries of one agent, ordered by coordination, then seq.
core::Result<std::vector<ScriptEntryInfo>> readScript(const std::string& path, std::uint32_t agent);

/// Every entry of every actor of one coordination, ordered by start time (then agent, seq).
core::Result<std::vector<ScriptEntryInfo>> readCoordinationScript(const std::string& path,
                                                                  std::uint32_t coordination);

/// One recorded frame of an agent. Velocity is not recorded: it is the central difference of the
/// recorded positions (one-sided at the ends, 0 for a single frame).
struct TrackSample {
  std::uint64_t frame = 0;
  double time = 0.0;         ///< [s] throng_frames.time, else frame / fps
  double x = 0.0, y = 0.0;   ///< [m]
  double vx = 0.0, vy = 0.0; ///< [m/s]
  double oriX = 1.0, oriY = 0.0;  ///< heading, a unit vector
  int clip = -1;             ///< throng_animation clip index; -1 when not recorded
  double phase = 0.0;        ///< clip phase in [0, 1)
};

struct AgentTrack {
  std::uint32_t agent = 0;
  bool known = false;              ///< the agent appears in throng_agents or trajectory_data
  std::optional<std::uint32_t> group;
  std::string population;
  std::vector<TrackSample> samples;  ///< in frame order
  std::vector<std::string> clips;    ///< throng_clips names by index (empty when absent)
};

/// An agent's trajectory (an unknown agent gives known = false, not an error).
core::Result<AgentTrack> readAgentTrack(const std::string& path, std::uint32_t agent);

struct MetricsOptions {
  double radius = 2.0;           ///< congestion disc around a key point [m] [Limit: > 0]
  double bin = 60.0;             ///< width of the arrival-rate bins [s] [Limit: > 0]
  double cohesionRadius = 3.0;   ///< "together": every member within this of the centroid [m] [Limit: > 0]
  std::size_t worstPoints = 5;   ///< how many of the most congested points to list
  /// Called during the trajectory pass with the fraction done, [0, 1]; may be empty.
  std::function<void(double)> progress;
};

/// Arrivals in one time bin [start, start + bin).
struct ArrivalBin {
  double start = 0.0;                                  ///< [s]
  std::uint64_t visits = 0;                            ///< VisitStart events, all categories
  std::map<std::string, std::uint64_t> byCategory;     ///< per point category ("" = no category)
  std::uint64_t exits = 0;                             ///< Exit events
};

/// Density around key points: agents within the radius / (π r²) [1/m²], one sample per point and frame.
struct DensityStats {
  std::string category;          ///< point category (for a point: also its id in `point`)
  std::string point;             ///< point id ("" for a category summary)
  std::uint32_t pointIndex = 0;
  std::size_t points = 0;        ///< points in the category (1 for a point)
  std::uint64_t samples = 0;     ///< point-frames
  double mean = 0.0, p95 = 0.0, max = 0.0;  ///< [1/m²]
};

struct CohesionStats {
  std::uint64_t groupFrames = 0;     ///< (group, frame) pairs with >= 2 members present
  std::uint64_t groups = 0;          ///< distinct groups that ever had >= 2 members present
  double meanDistance = 0.0;         ///< mean over group-frames of the members' mean distance to the centroid [m]
  double shareTogether = 0.0;        ///< share of group-frames with every member within cohesionRadius, [0, 1]
};

struct CoordinationStats {
  std::uint64_t total = 0;
  std::map<std::string, std::uint64_t> byPlan, byOutcome, byRelation, byTrigger;
  std::map<std::string, std::uint64_t> microBehaviours;  ///< behaviour of script entries with step 1..6
  std::uint64_t groundingSamples = 0;  ///< coordinations that were not alone
  double meanGrounding = 0.0;          ///< mean execute - start over those [s]
  double maxGrounding = 0.0;           ///< [s]
  std::uint64_t divideSamples = 0;     ///< not-alone coordinations with a divide plan
  double meanDivide = 0.0;             ///< mean end - execute over those [s]
  std::uint64_t reunited = 0;          ///< Reunited events
  std::uint64_t goalsGenerated = 0;    ///< GoalGenerated events
};

struct SocialMetrics {
  std::string path;
  std::string commonGround;      ///< metadata throng_common_ground: "on", "off", or "" when absent
  double fps = 0.0;
  std::uint64_t frames = 0;
  double duration = 0.0;         ///< (frames - 1) / fps [s]
  double radius = 0.0, bin = 0.0, cohesionRadius = 0.0;  ///< the options used

  // (a) arrival rate at designated destinations over time
  std::vector<std::string> categories;           ///< categories of key points, sorted
  std::vector<ArrivalBin> arrivals;              ///< consecutive bins from t = 0
  std::map<std::string, std::uint64_t> visitsByCategory;
  std::uint64_t visits = 0, exits = 0;
  double visitsPerMinute = 0.0, exitsPerMinute = 0.0;  ///< over the whole duration

  // (b) congestion at key points (points with a category)
  std::vector<DensityStats> congestion;          ///< per category, sorted by category
  std::vector<DensityStats> worstPoints;         ///< highest mean density first (ties: higher max)

  // (c) group cohesion, (d) coordinations
  CohesionStats cohesion;
  CoordinationStats coordinations;
};

/// Computes every metric in one ordered pass over trajectory_data (docs/social-metrics.md).
core::Result<SocialMetrics> computeMetrics(const std::string& path, const MetricsOptions& options = {});

}  // namespace throng::recording
