// throng::nav (private) — Recast plumbing shared by the flat and the terrain tile builders: a
// build context that collects error messages (instead of printing them) and owning pointers for
// Recast's intermediate structures; the region and polygon tunables both use.
#pragma once
#include <Recast.h>

#include <memory>
#include <string>

#include "tile_builder.hpp"

namespace throng::nav::detail {

/// Collects Recast's error messages instead of printing them.
class CollectingContext final : public rcContext {
 public:
  CollectingContext() : rcContext(true) { enableTimer(false); }
  std::string errors;

 protected:
  void doLog(const rcLogCategory category, const char* msg, const int len) override {
    if (category != RC_LOG_ERROR) return;
    if (!errors.empty()) errors += "; ";
    errors.append(msg, static_cast<std::size_t>(len));
  }
};

struct HeightfieldDeleter { void operator()(rcHeightfield* p) const { rcFreeHeightField(p); } };
struct CompactDeleter { void operator()(rcCompactHeightfield* p) const { rcFreeCompactHeightfield(p); } };
struct ContourDeleter { void operator()(rcContourSet* p) const { rcFreeContourSet(p); } };
struct PolyMeshDeleter { void operator()(rcPolyMesh* p) const { rcFreePolyMesh(p); } };
struct DetailDeleter { void operator()(rcPolyMeshDetail* p) const { rcFreePolyMeshDetail(p); } };


// Region and polygon tunables shared by both builds.
inline constexpr float kMaxEdgeError = 1.1f;      // contour simplification [cells]
inline constexpr float kMaxEdgeLength = 12.0f;    // longest border edge [m]
inline constexpr float kMinIslandArea = 0.25f;    // isolated islands smaller than this are dropped [m²]
inline constexpr float kMergeRegionArea = 4.0f;   // regions smaller than this merge into neighbours [m²]
inline constexpr int kMaxVertsPerPoly = 6;

/// A failed tile: `what`, plus whatever Recast logged.
inline TileOutput fail(std::string what, const CollectingContext& ctx) {
  TileOutput out;
  out.error = std::move(what);
  if (!ctx.errors.empty()) out.error += " (Recast: " + ctx.errors + ")";
  return out;
}

}  // namespace throng::nav::detail
