// throng::sim::ScenarioDesc — the plain, validated description a World is built from (after
// Menge's FSMDescrip and Jolt's settings objects). io parses JSON into it and validates it; the
// simulation core never reads files. Units: metres, seconds, metres per second.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "throng/core/geometry.hpp"

namespace throng::sim {

using core::Polygon;
using core::Vec2;

enum class PointKind : std::uint8_t {
  Interest,  ///< pass through its region
  Action,    ///< may stop there, face `orientation`, play `action` for `actionDuration`
  Exit,      ///< an agent reaching its region leaves the simulation
};

/// A named place in the world. Its region is a disc (`radius` around `position`) or a polygon.
struct PointDesc {
  std::string id;
  PointKind kind = PointKind::Interest;
  Vec2 position;           ///< for polygon regions: the polygon's centroid
  float radius = 0.0f;     ///< disc region radius [m]; 0 when `polygon` is used
  Polygon polygon;         ///< polygon region; empty for a disc
  bool stop = false;       ///< Action only: agents stop here
  Vec2 orientation{1, 0};  ///< Action only: facing direction while stopped (unit vector)
  std::string action;      ///< Action only: name of the action played (a motion clip)
  float actionDuration = 0.0f;  ///< Action only: how long the stop lasts [s]
};

enum class SpawnKind : std::uint8_t { Polygon, Position, Point };

struct SpawnDesc {
  SpawnKind kind = SpawnKind::Polygon;
  Polygon polygon;         ///< SpawnKind::Polygon
  Vec2 position;           ///< SpawnKind::Position
  std::uint32_t point = 0; ///< SpawnKind::Point: index into ScenarioDesc::points
};

struct PopulationDesc {
  std::string id;
  std::uint32_t groups = 1;       ///< number of social groups
  std::uint32_t sizeMin = 1;      ///< group size drawn uniformly in [sizeMin, sizeMax] per group
  std::uint32_t sizeMax = 1;
  SpawnDesc spawn;
  float start = 0.0f;             ///< spawn time [s]
  std::vector<std::uint32_t> goals;  ///< indices into ScenarioDesc::points, visited in order
  bool wander = false;            ///< after the last goal (or with no goals): walk to random
                                  ///< points of the walkable area forever (benchmarks, ambient crowds)
  float speedMean = 1.34f;        ///< desired walking speed [m/s] (Weidmann 1993)
  float speedSd = 0.0f;           ///< standard deviation; draws are clipped to [speedMin, speedMax]
  float speedMin = 0.3f;
  float speedMax = 2.5f;
  float radius = 0.2f;            ///< body radius [m]
};

/// Tunables of the operational model; every value has units and limits (after Recast's rcConfig).
struct SteeringDesc {
  float timeHorizon = 2.0f;          ///< ORCA time horizon for agents [s] [Limit: > 0]
  float timeHorizonObstacle = 0.5f;  ///< ORCA time horizon for walls [s] [Limit: > 0]
  float neighbourDistance = 3.0f;    ///< radius for neighbour search [m] [Limit: > 0]
  std::uint32_t maxNeighbours = 10;  ///< nearest agents considered by ORCA [Limit: >= 1]
  float accelerationTime = 0.5f;     ///< relaxation time towards preferred velocity [s] [Limit: >= dt]
};

struct ScenarioDesc {
  std::string format = "throng/1";
  std::string name;
  std::uint64_t seed = 1;
  float duration = 300.0f;   ///< [s]; a run also ends once every agent has exited
  float dt = 0.05f;          ///< simulation time step [s] [Limit: 0.001 .. 0.5]
  std::vector<Polygon> walkable;
  std::vector<Polygon> obstacles;
  std::vector<PointDesc> points;
  std::vector<PopulationDesc> populations;
  SteeringDesc steering;
  float navCellSize = 0.0f;  ///< navmesh voxel size [m]; 0 = chosen from the geometry

  /// The largest body radius of any population (the navmesh is eroded by it).
  [[nodiscard]] float maxRadius() const;
  /// True when some point is an exit.
  [[nodiscard]] bool hasExit() const;
};

}  // namespace throng::sim
