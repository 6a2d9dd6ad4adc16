// throng::sim::ScenarioDesc — the plain, validated description a World is built from (after
// Menge's FSMDescrip and Jolt's settings objects). io parses JSON into it and validates it; the
// simulation core never reads files. Units: metres, seconds, metres per second.
#pragma once
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "throng/core/geometry.hpp"
#include "throng/nav/navmesh.hpp"
#include "throng/common_ground/behaviour_db.hpp"
#include "throng/common_ground/coordination.hpp"
#include "throng/common_ground/sensing.hpp"
#include "throng/sim/models.hpp"

namespace throng::sim {

using core::Polygon;
using core::Vec2;

enum class PointKind : std::uint8_t {
  Interest,  ///< pass through its region
  Action,    ///< may stop there, face `orientation`, play `action` for `actionDuration`
  Exit,      ///< an agent reaching its region leaves the simulation
};

/// How a walker picks its target spot inside a goal's region (PointDesc::aim).
enum class PointAim : std::uint8_t { Spread, Lane };

/// A named place in the world. Its region is a disc (`radius` around `position`) or a polygon.
struct PointDesc {
  std::string id;
  PointKind kind = PointKind::Interest;
  Vec2 position;           ///< for polygon regions: the polygon's centroid
  float height = 0.0f;     ///< height of the floor it is on [m] (multi-level worlds; 0 on flat ones)
  float radius = 0.0f;     ///< disc region radius [m]; 0 when `polygon` is used
  Polygon polygon;         ///< polygon region; empty for a disc
  bool stop = false;       ///< Action only: agents stop here
  Vec2 orientation{1, 0};  ///< Action only: facing direction while stopped (unit vector)
  std::string action;      ///< Action only: name of the action played (a motion clip); defaults
                           ///< to the clip's name (file stem) when a clip is given
  float actionDuration = 0.0f;  ///< Action only: how long the stop lasts [s]; defaults to the
                                ///< clip's duration when a clip is given
  /// Exit only: the width of the opening it stands for [m] [Limit: 0.1..100]. Exit choice estimates
  /// its capacity as kExitSpecificFlow × width (queue time ahead = people ahead / capacity).
  float width = 1.0f;
  std::string clip;        ///< Action only: motion clip (BVH) path as written in the scenario,
                           ///< relative to its directory; empty for none. io loads the clip.
  /// How a walker aims at the region (`"aim"`): Spread (a spot spread over the region by sub-region
  /// occupancy, Musse et al. §3.1.3) or Lane (where its line along the way from its previous goal
  /// crosses the region: a checkpoint in a corridor or a ring, crossed where one walks). Interest
  /// and exit points.
  PointAim aim = PointAim::Spread;
  /// What the place is for the goal generator of the social model ("restroom", "shoes", "meeting");
  /// empty for none. Letters, digits, '_' and '-'.
  std::string category;
};

enum class SpawnKind : std::uint8_t { Polygon, Position, Point };

struct SpawnDesc {
  SpawnKind kind = SpawnKind::Polygon;
  Polygon polygon;         ///< SpawnKind::Polygon
  Vec2 position;           ///< SpawnKind::Position
  std::uint32_t point = 0; ///< SpawnKind::Point: index into ScenarioDesc::points
  float height = 0.0f;     ///< Polygon/Position: height of the floor spawned on [m] (Point: the point's own)
};

/// Following (Musse et al. §3.2.5): a group adopts another group's goals, for good (permanent)
/// or during random periods (temporary).
enum class FollowMode : std::uint8_t { None, Permanent, Temporary };

struct FollowDesc {
  FollowMode mode = FollowMode::None;
  std::uint32_t population = 0;  ///< index of the population whose group is followed
  std::uint32_t group = 0;       ///< which group of it (0-based)
  float onMin = 10.0f, onMax = 30.0f;   ///< temporary: length of a following period [s]
  float offMin = 10.0f, offMax = 30.0f; ///< temporary: length of a period on its own goals [s]
};

/// A scripted guide (Musse et al. §3.2.6): a position that moves along timed waypoints; the
/// population's groups follow it as a dynamic goal. The server sets guides through the World API.
struct GuideWaypoint {
  float time = 0.0f;  ///< [s]
  Vec2 position;
  float height = 0.0f;  ///< floor height [m] (multi-level worlds)
};

struct GuideDesc {
  std::vector<GuideWaypoint> script;  ///< ascending times; empty = not scripted
  float distance = 1.5f;              ///< how far behind the guide the group keeps [m] [Limit: >= 0]
  float release = -1.0f;              ///< time the guide lets go [s]; < 0 = holds at its last waypoint
};

/// The sociological model (Musse & Thalmann 1997, Musse et al. §3.2.1 iii): when agents of
/// different groups meet, social effects happen at these rates (per second of meeting).
struct SociologicalDesc {
  bool enabled = false;
  float meetDistance = 1.2f;        ///< agents closer than this meet [m]
  float changeGroupRate = 0.02f;    ///< an agent leaves its group and joins the other's [1/s]
  float followAgentRate = 0.02f;    ///< an agent follows the agent it met for a while [1/s]
  float followDuration = 15.0f;     ///< how long such a following lasts [s]
  float leaderChangeRate = 0.01f;   ///< a group's leadership passes to its most dominant member [1/s]
  float sociability = 1.0f;         ///< scales this population's join/follow rates [Limit: >= 0]
  float domination = 0.5f;          ///< leadership weight of its members [0, 1]
};

/// The distribution of pre-movement times (PreMovementDesc).
enum class PreMovementDistribution : std::uint8_t { None, Uniform, Normal, LogNormal };

/// Pre-movement time (RiMEA test 5, NIST TN 1822 test 1.1): each agent is present and standing from
/// the moment it appears and starts walking to its first goal after a time drawn per agent — from
/// (seed, stable agent id), so the same for any thread or rank count. Scenario key "preMovement";
/// None: agents walk at once (the default). Normal and log-normal draws are clamped to
/// [0, kMaxPreMovement].
struct PreMovementDesc {
  PreMovementDistribution distribution = PreMovementDistribution::None;
  float min = 0.0f, max = 0.0f;   ///< uniform in [min, max] [s]
  float mean = 0.0f, sd = 0.0f;   ///< normal [s]
  float mu = 0.0f, sigma = 0.0f;  ///< log-normal: the mean and standard deviation of ln(t / 1 s)

  [[nodiscard]] bool enabled() const { return distribution != PreMovementDistribution::None; }
};

/// The longest pre-movement time an agent is given [s] (the longest scenario duration).
inline constexpr float kMaxPreMovement = 1e6f;
/// Tables spawning may draw desired speeds from instead of a normal distribution (demographics.hpp).
enum class SpeedTable : std::uint8_t {
  None,         ///< the population's speedMean, speedSd, speedMin, speedMax
  WeidmannAge,  ///< scenario "weidmann-age": Weidmann 1993's speed by age, as tabulated for RiMEA test 7
};

/// Ages a speed-by-age table covers [years].
inline constexpr float kMinAge = 5.0f;
inline constexpr float kMaxAge = 80.0f;

/// Who a population is (scenario: the "demographics" form of "speed"): each agent draws an age,
/// whether it is movement-impaired, and a speed from the table's band for it.
struct DemographicsDesc {
  SpeedTable table = SpeedTable::None;
  float ageMin = kMinAge;  ///< ages drawn uniformly in [ageMin, ageMax] [years] [Limit: kMinAge..kMaxAge]
  float ageMax = kMaxAge;
  /// Share of movement-impaired people [Limit: 0..1]: speeds in RiMEA 7's reduced-mobility band,
  /// 0.46–0.76 m/s (Boyce, Shields & Silcock 1999: walking frame 0.57, manual wheelchair 0.69 m/s).
  float impaired = 0.0f;
  /// Their body radius [m] [Limit: 0.05..1]: half a wheelchair's 0.70 m width (ISO 7193).
  float impairedRadius = 0.35f;
};

/// How an agent (a group: its members decide together) picks one of its population's exits.
enum class ExitRule : std::uint8_t {
  Nearest,     ///< shortest walking distance (stairs priced as in route choice)
  Quickest,    ///< walking time + the queue ahead at the exit / the exit's capacity
  Allocation,  ///< drawn once by fixed shares (a probabilistic split), never re-evaluated
};

/// How a group picks among the points of a goal choice (scenario: a "goals" entry {"choose": [...]}).
enum class GoalSplit : std::uint8_t {
  Shares,         ///< drawn by fixed shares (a probabilistic split), per group
  LeastTargeted,  ///< the option the fewest agents head for at that moment (JuPedSim's least-targeted
                  ///< transition), ties to the first listed
};

/// A choice among waypoints (JuPedSim's journeys: a stage with a split to several next stages):
/// goal `slot` of the population's list is one of `options`, picked by each group when its first
/// member reaches that slot, for the whole group.
struct GoalChoiceDesc {
  std::uint32_t slot = 0;              ///< index into PopulationDesc::goals (which holds options.front() until chosen)
  std::vector<std::uint32_t> options;  ///< point indices (interest or action points), at least 2, each once
  GoalSplit split = GoalSplit::Shares;
  std::vector<float> shares;           ///< Shares: one share >= 0 per option (normalised; empty: equal shares)
};

/// Specific flow through a short bottleneck [persons/(m·s)]: the capacity of an exit of width w is
/// this × w (Kretz, Grünebohm, Schreckenberg, J. Stat. Mech. 2006 P10014; Seyfried et al.,
/// Transportation Science 43, 395, 2009: about 1.9 for 0.8–1.2 m).
inline constexpr float kExitSpecificFlow = 1.9f;

/// Exit choice (scenario key "exitChoice"; docs/crowd-model.md "Tactical level: exit choice").
struct ExitChoiceDesc {
  ExitRule rule = ExitRule::Quickest;
  /// Nearest and Quickest: each group re-evaluates its exit this often [s] [Limit: > 0], its
  /// moment spread over the period by its id (time-sliced: 1/period of the groups a second).
  float period = 2.0f;
  /// Nearest and Quickest: a group changes exit only when the other saves more than this share of
  /// its current cost [Limit: 0..1] — so nobody flips between two nearly equal exits.
  float hysteresis = 0.2f;
  /// Allocation: one share per exit (normalised; empty: equal shares).
  std::vector<float> shares;
  /// Affiliation (Sime 1985; NIST TN 1822 test 3.3): the exits the group knows (point indices,
  /// each one of the population's exits). Empty: every exit is as familiar as any other.
  std::vector<std::uint32_t> familiar;
  /// Nearest and Quickest with `familiar`: the cost of an exit the group does not know is
  /// multiplied by this, so a familiar exit is preferred while it costs less than this many times
  /// the best unknown one [Limit: 1..100].
  float familiarity = 2.0f;
  /// Social influence (herding; NIST TN 1822 test 3.2): an exit's cost is multiplied by
  /// 1 − herding × the share of the other people within `herdingRadius` (of other groups, heading
  /// for an exit) who head for it. 0: off [Limit: 0..1).
  float herding = 0.0f;
  float herdingRadius = 5.0f;  ///< [m] [Limit: > 0 .. 50]
};

struct PopulationDesc {
  std::string id;
  std::uint32_t groups = 1;       ///< number of social groups
  std::uint32_t sizeMin = 1;      ///< group size drawn uniformly in [sizeMin, sizeMax] per group
  std::uint32_t sizeMax = 1;
  SpawnDesc spawn;
  float start = 0.0f;             ///< spawn time [s]
  std::vector<std::uint32_t> goals;  ///< indices into ScenarioDesc::points, visited in order
  /// Waypoint choices: goals whose point each group picks among several (opt-in; empty: none).
  std::vector<GoalChoiceDesc> goalChoices;
  /// Exit choice: after `goals`, each group walks to one of these exits (point indices, kind
  /// Exit), chosen by `exitChoice`. Empty: no choice (the goals are the route).
  std::vector<std::uint32_t> exits;
  ExitChoiceDesc exitChoice;
  bool wander = false;            ///< after the last goal (or with no goals): walk to random
                                  ///< points of the walkable area forever (benchmarks, ambient crowds)
  float speedMean = 1.34f;        ///< desired walking speed [m/s] (Weidmann 1993)
  float speedSd = 0.0f;           ///< standard deviation; draws are clipped to [speedMin, speedMax]
  float speedMin = 0.3f;
  float speedMax = 2.5f;
  float radius = 0.2f;            ///< body radius [m]
  PreMovementDesc preMovement;    ///< waiting before walking off (none by default)
  /// Speeds by age and impairment instead of speedMean… (table None: not used).
  DemographicsDesc demographics;
  /// The largest body among its members [m]: radius, or impairedRadius when some are impaired.
  [[nodiscard]] float largestRadius() const {
    return demographics.table != SpeedTable::None && demographics.impaired > 0.0f && demographics.impairedRadius > radius
               ? demographics.impairedRadius
               : radius;
  }
  /// Walking on stairs and steep ramps (navmesh area nav::kStairArea: ground steeper than
  /// nav::NavMeshConfig::stairSlopeDeg, 15°): the speed along the slope is this factor times the
  /// desired speed, up and down (docs/crowd-model.md, "Tactical level: stairs"). Defaults: Weidmann
  /// 1993's horizontal stair speeds (0.610 m/s up, 0.694 m/s down) along a 30° stair (/ cos 30°) over
  /// his level mean 1.34 m/s; within Fruin 1971's ranges (0.49–0.67 m/s up, 0.60–1.01 m/s down).
  /// Route choice prices stairs at the mean of 1/up and 1/down per metre. [Limit: (0, 1]]
  float stairUp = 0.53f;
  float stairDown = 0.60f;
  /// Of the groups for whom a lift or escalator reaches a goal on another floor, the share that
  /// weighs the stairs by time like any other way and climbs (or descends) them when that is quicker;
  /// the rest ride, however long it takes, unless no ride reaches the goal (transport_choice.cpp).
  /// Drawn per group and goal. Defaults: the shares of people who took the stairs rather than the
  /// escalator beside them in Montreal's shopping centres, 20.3 % going up and 31.1 % going down
  /// (Zacharias & Ling 2014, Environment and Behavior 47(6); 33,793 people counted; Beijing: 25.4 %
  /// and 32.8 %, Zacharias & Ling 2015, Preventive Medicine Reports 2). [Limit: [0, 1]]
  float stairClimbUp = 0.203f;
  float stairClimbDown = 0.311f;
  /// Lifts and escalators chosen by oneself (docs/crowd-model.md, "Choosing a lift, an escalator or
  /// the stairs"): on the way to a goal that is no transport's stop, a group rides whichever of the
  /// scenario's transports makes the way there quickest (walking, waiting and riding), if that beats
  /// walking (to a goal on another floor, whenever a ride goes there unless the group is one of the
  /// climbers: stairClimbUp/Down); false: its people walk unless their goals name a stop.
  bool useTransports = true;
  /// The fractional effective dose (smoke's carbon monoxide, coDosePerSecond) at which its people
  /// are incapacitated: they stop where they are and stay, an obstacle to the others. ISO 13571:2012
  /// takes FED 1 for the median person and 0.3 to protect susceptible people. [Limit: (0, 10]]
  float incapacitationDose = 1.0f;
  // The Musse crowd model.
  /// Paths between goals: navmesh corners (straight segments), or Bézier curves (Musse et al.
  /// §3.2.2) checked inside the walkable surface, falling back to the navmesh where none fits.
  bool bezierPaths = false;
  /// Goals chosen automatically per group (§3.1.2 "paths automatic reconstruction"): a random
  /// final action point, a Bézier curve from the group's spawn to it, and every interest point the
  /// curve passes near (within autoNearDistance) becomes a goal on the way. `goals` is then ignored.
  bool autoGoals = false;
  float autoNearDistance = 3.0f;  ///< [m]
  bool flocking = true;           ///< groups of 2+ walk together and wait for each other (§3.2.3)
  float waitTimeout = 30.0f;      ///< a member waits at most this long for the missing ones [s]
  float groupSpacing = 0.75f;     ///< lateral distance between members walking abreast [m]
  FollowDesc follow;
  GuideDesc guide;
  SociologicalDesc sociological;
  /// Common Ground goal generator: categories of places (PointDesc::category) its members may be
  /// attracted by; each agent draws `interestsPerAgent` of them (seeded, without repetition).
  std::vector<std::string> interests;
  std::uint32_t interestsPerAgent = 2;
  /// The operational (avoidance) model its members walk with and its parameters (models.hpp):
  /// scenario key "model"; ORCA with its defaults unless the scenario names another.
  ModelDesc model;
  /// Common Ground: its members' preference for micro-behaviours (name → multiplier of the
  /// database weight, >= 0; 0 = never). Names must exist in the micro-behaviour database.
  std::map<std::string, double, std::less<>> preferences;
};

/// Tunables of the operational model; every value has units and limits (after Recast's rcConfig).
struct SteeringDesc {
  float timeHorizon = 2.0f;          ///< ORCA time horizon for agents [s] [Limit: > 0]
  float timeHorizonObstacle = 0.5f;  ///< ORCA time horizon for walls [s] [Limit: > 0]
  float neighbourDistance = 3.0f;    ///< radius for neighbour search [m] [Limit: > 0]
  std::uint32_t maxNeighbours = 10;  ///< nearest agents considered by ORCA [Limit: >= 1]
  float accelerationTime = 0.5f;     ///< relaxation time towards preferred velocity [s] [Limit: >= dt]
  /// Density-dependent detection range (Musse et al. §3.2.4): where the local density is at least
  /// `denseThreshold`, neighbours are searched only within `denseNeighbourDistance` (d < D =
  /// neighbourDistance). 0 disables.
  float denseNeighbourDistance = 1.5f;  ///< d [m]
  float denseThreshold = 2.0f;          ///< [agents/m²]
  /// Multiresolution: agents farther than this from every viewer (World::setViewers) steer with a
  /// cheaper method (4 neighbours, no wall half-planes; the navmesh still holds them). 0 = off.
  float lodDistance = 0.0f;             ///< [m]
  // The preferred velocity (steer phase, every model): following the path, arriving, formation,
  // deadlock breaking. Defaults are throng's, chosen on the bundled scenarios (docs/crowd-model.md).
  float cornerReach = 0.5f;        ///< distance at which a path corner counts as passed [m] [Limit: > 0, <= 5]
  std::uint32_t levelLookAhead = 3;///< corners looked ahead for one in sight on multi-level worlds [Limit: 1..16]
  float arrivalTime = 0.5f;        ///< approaching a stop, agents slow down over this time [s] [Limit: > 0, <= 10]
  float formationSpeedUp = 1.25f;  ///< members catching up may walk this much faster than their speed [Limit: 1..3]
  float stuckPatience = 1.0f;      ///< wanting to walk but barely moving this long starts deadlock breaking [s] [Limit: > 0, <= 60]
  float stuckAttempt = 0.8f;       ///< length of one deadlock-breaking attempt (a new direction each) [s] [Limit: > 0, <= 60]
};

/// A stochastic goal of the goal generator (Park et al. §3.3): at `rate` per agent and second an
/// agent wants the nearest place of `category` (a restroom visit).
struct NeedDesc {
  std::string category;
  float rate = 0.0005f;       ///< [1/s per agent] [Limit: >= 0]
  float expectedVisit = 120.0f;  ///< what the macro-plan rules compare [s] [Limit: >= 0]
  common_ground::GoalKind kind = common_ground::GoalKind::Personal;
};

/// Environmentally driven goals: an agent that sees a place of a category among its interests
/// (PopulationDesc::interests) wants it with `probability` (one draw per agent and place).
struct AttractionDesc {
  float probability = 0.1f;      ///< [0, 1]
  float expectedVisit = 60.0f;   ///< [s] [Limit: >= 0]
  float checkPeriod = 0.5f;      ///< how often an agent looks around [s] [Limit: > 0]
};

/// The Common Ground model (Park, Peng, Quek, Cao; docs/social-model.md). io loads the databases
/// and clip lengths; the simulation only reads them.
struct CommonGroundDesc {
  bool enabled = false;          ///< the section is present: goals are generated
  bool commonGround = true;      ///< groups coordinate before they divide; off: the agent just goes
  common_ground::SensoryParams senses;
  std::vector<NeedDesc> needs;
  AttractionDesc attraction;
  common_ground::CoordinationParams coordination;
  /// Each response B owes is missed with this probability (distraction, noise): A times out and
  /// tries again, another way or closer; drawn per coordination (seeded). [0, 1]
  float missProbability = 0.1f;
  float cooldown = 60.0f;        ///< an agent gets no new goal this long after a visit [s] [Limit: >= 0]
  std::string microPath;         ///< micro-behaviour database as written (relative to the scenario); empty = built in
  std::string macroPath;         ///< macro-plan database as written; empty = built in
  std::string motions = "motions";  ///< directory of the clips (<clip>.bvh), relative to the scenario
  common_ground::MicroBehaviourDb micro;
  common_ground::MacroPlanDb macro;
  common_ground::ClipLengths clipLengths;  ///< every clip the micro-behaviour database plays, from BVH files
};

/// A crowd added to a running world (World::insertCrowd, a scenario's timeline): new points and
/// populations, parsed from a crowd file (io::parseCrowd, docs/scenario-format.md "Crowd files").
/// Point indices in its populations (goals, a spawn point) below `basePoints` name the world's
/// points; from `basePoints` on they name this crowd's own `points` (index - basePoints). The
/// world only ever appends points, so indices below basePoints stay valid. A "follow" population
/// index works the same way with `basePopulations`.
struct CrowdDesc {
  std::string id;                           ///< unique among the world's crowds; removeCrowd names it
  std::vector<PointDesc> points;            ///< new points; ids unique in the world
  std::vector<PopulationDesc> populations;  ///< ids unique in the world; `start` is relative to the insertion [s]
  std::uint32_t basePoints = 0;             ///< the world's point count the indices were resolved against
  std::uint32_t basePopulations = 0;        ///< the world's population count likewise

  /// Most agents it may spawn: groups × largest group size, summed.
  [[nodiscard]] std::uint64_t maxAgents() const;
};

/// A scenario timeline entry: at `time` a crowd is inserted or a crowd is removed (its agents leave),
/// or an exit closes or opens again for exit choice (groups heading for a closed exit choose another;
/// fixed goals are not changed).
enum class TimelineAction : std::uint8_t { Insert, Remove, CloseExit, OpenExit };

struct TimelineEntry {
  float time = 0.0f;        ///< [s] from the start of the run
  TimelineAction action = TimelineAction::Insert;
  std::string path;         ///< Insert: the crowd file as written (relative to the scenario)
  CrowdDesc crowd;          ///< Insert: loaded and validated by io
  std::string crowdId;      ///< Remove: id of an inserted crowd
  std::uint32_t point = 0;  ///< CloseExit, OpenExit: the exit's point index
};

/// A wall (scenario key "walls"): a polyline with a thickness. io turns each of its segments into a
/// rectangle `thickness` wide, lengthened by thickness/2 at both ends so that joints are covered, and
/// appends these footprints to ScenarioDesc::obstacles: the simulation sees walls only as obstacles.
struct WallDesc {
  std::string id;          ///< optional; unique among the walls when given
  std::vector<Vec2> line;  ///< at least 2 distinct points [m]
  float thickness = 0.2f;  ///< [m] [Limit: 0.01 .. 5]; default: a plastered interior masonry wall
};

/// A measurement line or area (scenario key "measurements") for analysis (throng plot); the
/// simulation never reads it.
struct MeasurementDesc {
  std::string id;          ///< unique among the measurements
  std::vector<Vec2> line;  ///< a line: exactly 2 points, non-zero length; empty for an area
  Polygon polygon;         ///< an area: a simple polygon; empty for a line
};

/// Smoke (scenario key "smoke"; NIST TN 1822 test 2.5): a region where walking is slowed by the
/// smoke's extinction coefficient K [1/m], after Frantzich and Nilsson (2003) as FDS+Evac applies
/// it: the desired speed times max(kSmokeMinFactor, 1 + (β/α)·K), α = 0.706 m/s, β = −0.057 m²/s
/// (smokeSpeedFactor, steer.cpp). Flat worlds only. Its carbon monoxide, when given, is breathed:
/// each person in it takes up a fractional effective dose (coDosePerSecond) and is incapacitated
/// when the dose reaches its population's incapacitationDose (NIST TN 1822 test 2.6).
struct SmokeDesc {
  Polygon polygon;          ///< a simple polygon
  float extinction = 0.0f;  ///< K [1/m] [Limit: 0 .. 30]
  float co = 0.0f;          ///< carbon monoxide volume fraction [ppm] [Limit: 0 .. 100000]
};

/// The fractional effective dose of carbon monoxide taken up per second at `ppm` [1/s]: ISO
/// 13571:2012's asphyxiant FED for CO, Σ φ_CO Δt / 35 000 ppm·min (after Purser, SFPE Handbook),
/// so 1 after a minute at 35 000 ppm, after an hour at 583 ppm. Other gases (HCN, CO2, O2
/// depletion), heat and irritants are not modelled.
[[nodiscard]] inline float coDosePerSecond(float ppm) { return ppm / (35000.0f * 60.0f); }

/// What carries people between two points of the scenario without their walking (the scenario key
/// "transports"; docs/crowd-model.md, "Tactical level: lifts and escalators").
enum class TransportKind : std::uint8_t {
  /// A moving stair from stops[0] to stops[1], one way: one person steps on every `headway` seconds
  /// and rides the straight line between the two points at `speed`, standing.
  Escalator = 0,
  /// A lift car serving its stops (2 to kMaxElevatorStops): it takes up to `capacity` people
  /// waiting at a stop to the stops they ride to (doors open, each alights and then each boards in
  /// `transferTime`, doors close, it travels at `speed` with `acceleration`), going on in its
  /// direction while someone aboard or waiting is that way, then turning.
  Elevator = 1,
};

/// A lift or an escalator. People use it by having its boarding stop as a goal: arrived there they
/// queue, ride, and go on from the other stop with their next goal.
struct TransportDesc {
  std::string id;
  TransportKind kind = TransportKind::Escalator;
  /// Indices into ScenarioDesc::points: where people board and alight (an escalator: two, boarding
  /// at the first only; an elevator: 2 to kMaxElevatorStops, boarding at each); different points,
  /// each the stop of no other transport.
  std::vector<std::uint32_t> stops{0, 0};
  /// Escalator: the belt's speed [m/s] [Limit: 0.1 .. 2]; 0.5 by default (EN 115-1: at most 0.75
  /// m/s up to 30°; 0.5 is the usual rate). Elevator: the car's rated speed [m/s] [Limit: 0.1 ..
  /// 10]; 1.0 by default (the usual rate of low-rise passenger lifts, CIBSE Guide D).
  float speed = 0.5f;
  /// Escalator: seconds between two people stepping on [s] [Limit: 0.2 .. 60]; 0.8 by default
  /// (1.25 persons/s, three quarters of the 1.67/s a 1 m wide step band carries at 0.5 m/s with
  /// two people on every other step, EN 115-1's theoretical capacity; people leave gaps).
  float headway = 0.8f;
  /// Elevator: the most people in the car [Limit: 1 .. 100]; 8 by default (a 630 kg car, EN 81-20).
  std::uint32_t capacity = 8;
  /// Elevator: acceleration and deceleration [m/s²] [Limit: 0.1 .. 5]; 1.0 by default (CIBSE Guide D).
  float acceleration = 1.0f;
  /// Elevator: door opening and closing times [s] [Limit: 0 .. 60]; 2 and 3 by default (CIBSE Guide D's
  /// typical centre-opening doors).
  float doorOpenTime = 2.0f;
  float doorCloseTime = 3.0f;
  /// Elevator: one person boarding or alighting [s] [Limit: 0 .. 60]; 1.2 by default (CIBSE Guide D's
  /// passenger transfer time).
  float transferTime = 1.2f;
};

/// The most stops one elevator serves.
inline constexpr std::size_t kMaxElevatorStops = 64;

struct ScenarioDesc;
/// Where someone boarding transport `t` at its stop `from` (an index into t.stops) rides to, as an
/// index into t.stops: an escalator's top; for an elevator, its next goal `next` (a point index,
/// 0xffffffff when none) when that is one of its stops, else the stop whose floor is nearest in height
/// to that goal's (ties: the first listed), else the first stop that is not `from`.
[[nodiscard]] std::size_t rideTo(const ScenarioDesc& desc, const TransportDesc& t, std::size_t from, std::uint32_t next);

/// The longest scenario "description" [bytes].
inline constexpr std::size_t kMaxDescription = 1000;

/// Walking speed in smoke of extinction coefficient K [1/m] as a factor of the desired speed:
/// Frantzich and Nilsson (2003), v = v0 (1 + β/α · K) with α = 0.706 m/s and β = −0.057 m²/s, never
/// below 0.1 v0 (FDS+Evac's floor, Korhonen's technical reference).
[[nodiscard]] inline float smokeSpeedFactor(float extinction) {
  constexpr float kBetaOverAlpha = -0.057f / 0.706f;  // [m]
  constexpr float kSmokeMinFactor = 0.1f;
  const float f = 1.0f + kBetaOverAlpha * extinction;
  return f > kSmokeMinFactor ? f : kSmokeMinFactor;
}

/// The order of the World's agent rows. Id: ascending stable id, always. Spatial: every
/// kRowSortPeriod of simulated time the rows are re-sorted along a Hilbert curve over the
/// neighbour grid's cells, so that neighbours' rows lie near each other in memory (a million
/// agents step 1.4–1.8× faster). Auto: Spatial from kSpatialRowsMinAgents agents present, Id below.
/// Frames (World::takeFrame) list agents by ascending id in every order; agentColumns are the rows
/// as they are.
enum class RowOrder : std::uint8_t { Auto = 0, Id = 1, Spatial = 2 };
/// RowOrder::Auto sorts rows spatially from this many agents present.
inline constexpr std::size_t kSpatialRowsMinAgents = 5000;
/// Simulated time between two spatial sorts of the rows [s] (walkers move about 2.7 m).
inline constexpr float kRowSortPeriod = 2.0f;

struct ScenarioDesc {
  std::string format = "throng/1";
  std::string name;
  /// For people: what the world is and what to watch in it, a sentence or two (the viewer shows
  /// it under the name). [Limit: at most kMaxDescription bytes of UTF-8]
  std::string description;
  std::uint64_t seed = 1;
  float duration = 300.0f;   ///< [s]; a run also ends once every agent has exited
  float dt = 0.05f;          ///< simulation time step [s] [Limit: 0.001 .. 0.5]
  std::vector<Polygon> walkable;
  /// The "obstacles" of the file, followed by the footprints of its `walls` (see WallDesc).
  std::vector<Polygon> obstacles;
  std::vector<WallDesc> walls;                ///< as written; already part of `obstacles`
  std::vector<MeasurementDesc> measurements;  ///< analysis only
  std::vector<SmokeDesc> smoke;               ///< regions that slow walking (flat worlds)
  /// Multi-level worlds: 3D walking geometry (floors, stairs, ramps, solid obstacles). When it is
  /// non-empty the navmesh is built from it, `walkable` and `obstacles` are empty, and agents,
  /// points, spawns and guides carry heights. Empty: the flat 2D world of `walkable`/`obstacles`.
  nav::TerrainMesh terrain;
  /// Multi-level worlds: ground steeper than this (its mean slope over nav::kStairBaseline) is a
  /// stair (the scenario key terrain.stairSlope; nav::NavMeshConfig::stairSlopeDeg) [deg]
  /// [Limit: > 0 .. 89]
  float stairSlopeDeg = nav::NavMeshConfig{}.stairSlopeDeg;
  std::vector<PointDesc> points;
  std::vector<TransportDesc> transports;  ///< lifts and escalators between points
  std::vector<PopulationDesc> populations;
  SteeringDesc steering;
  float navCellSize = 0.0f;  ///< navmesh voxel size [m]; 0 = chosen from the geometry
  /// How the World keeps its agent rows (docs/performance.md, "Row order"): results are the same
  /// for any thread count either way. Not a scenario key (hosts and `throng bench` set it).
  RowOrder rowOrder = RowOrder::Auto;
  CommonGroundDesc social;  ///< the Common Ground model: the scenario key "social" (not the sociological model, PopulationDesc::sociological)
  /// Crowds inserted and removed at given times, ascending (stable for equal times). The World
  /// applies them at the start of the tick at or after each time (io loads the crowd files).
  std::vector<TimelineEntry> timeline;

  /// The largest body radius of any population.
  [[nodiscard]] float maxRadius() const;
  /// The radius the navmesh is eroded by: the largest of every population's radius × its model's
  /// passage ratio (ModelDesc::passageRatio; 1 for ORCA).
  [[nodiscard]] float navRadius() const;
  /// True when some point is an exit.
  [[nodiscard]] bool hasExit() const;
  /// How the navmesh of this scenario is built: eroded by navRadius(), cells of navCellSize, and
  /// every exit's region — the scenario's and those of the crowds its timeline inserts — cut into
  /// polygons of its own (nav::NavMeshConfig::cuts), so that a closed exit is a wall (World:
  /// timeline `close`, setExitOpen). io, the World and the benches use it.
  [[nodiscard]] nav::NavMeshConfig navMeshConfig() const;
};

/// An exit's region (disc or polygon, on its floor) as a navmesh cut.
[[nodiscard]] nav::CutRegion cutRegion(const PointDesc& point);

}  // namespace throng::sim
