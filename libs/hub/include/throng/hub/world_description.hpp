// throng::hub world description — what a participant receives on joining a served world (the
// Welcome message's compressed JSON): the scenario as written (geometry, points, populations — the
// same format `throng run` reads, docs/scenario-format.md), the skeleton, the motion clips with
// their lengths and where to fetch them over HTTP, and the groups. Reads the loaded scenario, the
// motion library and the World; writes a JSON text. No I/O.
#pragma once
#include <string>

#include "throng/hub/motion_library.hpp"
#include "throng/io/scenario_loader.hpp"
#include "throng/sim/world.hpp"

namespace throng::hub {

/// Version of the description's layout (its "description" key); raised on incompatible changes.
inline constexpr int kWorldDescriptionVersion = 1;

/// The description as JSON text:
///   {"description": 1, "name": ..., "dt": ..., "tickRate": ..., "scenario": {...as written...},
///    "skeleton": {"joints": [{"name", "parent", "offset": [x, y, z]}...]},
///    "clips": [{"id", "name", "duration", "loops", "url"}...],   url "/motions/<id>.bvh" or null
///    "groups": [{"id", "population", "members": [...]}...]}
[[nodiscard]] std::string describeWorld(const io::LoadedScenario& scenario, const MotionLibrary& motions,
                                        const sim::World& world, double tickRate);

}  // namespace throng::hub
