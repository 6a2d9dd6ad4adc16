// CommonGroundState — the Common Ground model's state inside the World (Park et al.; docs/social-
// model.md): the point categories and which points have each, the places some population is
// interested in, each need's category, the animation clips' lengths, the coordinations being
// played, and the script entries and coordinations finished since the last frame taken. Written by
// the Common Ground pass (common_ground.cpp, common_ground_play.cpp), creation and insertion.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "throng/sim/frame.hpp"
#include "throng/sim/scenario.hpp"
#include "throng/common_ground/coordination.hpp"

namespace throng::sim {

/// One Common Ground interaction being carried out (or a lone visit): the planned action script
/// and where each actor is in it. Times of entries not yet started shift by `slip`, the overrun of
/// walks that took longer than planned (paths bend, crowds slow), so every response still starts
/// after the motion it answers.
struct ActiveCoordination {
  CoordinationRecord record;            ///< filled as it goes; published when it ends
  std::vector<std::uint32_t> actors;    ///< stable ids: [0] A, [1] B, then companions
  common_ground::ActionScript script;
  std::vector<std::uint32_t> cursor;    ///< per actor: entry being played (== size: done)
  std::vector<double> started;          ///< per actor: actual start of the current entry, < 0 not started
  std::vector<std::uint8_t> left;       ///< per actor: has left the script (resumed or gone)
  double slip = 0.0;                    ///< [s]
  double deadline = 0.0;                ///< [s] every actor is released by then, whatever happened
  bool divides = false;                 ///< a divide plan: the group waits to be whole again
  bool reunitedOnReturn = false;        ///< divide-and-wait: A walked back to B
};

struct CommonGroundState {
  std::vector<std::string> categories;        ///< distinct point categories, in point order
  std::vector<std::int32_t> pointCategory;    ///< per point: index into categories, -1 none
  std::vector<std::vector<std::uint32_t>> categoryPoints;  ///< per category: its points
  std::vector<std::int32_t> needCategory;     ///< per CommonGroundDesc::needs entry: index into categories, -1 none
  std::vector<std::uint32_t> attractionPoints;///< points with a category some population is interested in
  std::vector<float> clipDuration;            ///< per animation clip (animationClips) [s]
  std::map<std::string, std::uint16_t, std::less<>> clipIndex;  ///< animation clip name → index
  std::map<std::uint32_t, ActiveCoordination> coordinations;    ///< active, by id (start order)
  std::uint32_t nextCoordinationId = 0;
  std::vector<ScriptRecord> pendingScript;            ///< since the last frame taken
  std::vector<CoordinationRecord> pendingCoordinations;

  /// Indexes the categories of points [first, end): new categories are added in point order.
  void addPoints(const std::vector<PointDesc>& points, std::uint32_t first);
  /// The places some population is interested in and each need's category, again (after points
  /// or populations were added).
  void refreshInterests(const ScenarioDesc& desc);
  /// The index of `category`, -1 when no point has it.
  [[nodiscard]] std::int32_t categoryIndex(std::string_view category) const;
};

}  // namespace throng::sim
