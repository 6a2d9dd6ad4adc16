// Helpers shared by the coordination planner tests in tests/common_ground: the bundled behaviour
// databases (data/social/, loaded once) and the bundled motion library's clip lengths.
#pragma once
#include <stdexcept>

#include "throng/io/social_db.hpp"
#include "throng/common_ground/coordination.hpp"

namespace throng::common_ground::test {

struct Dbs {
  MicroBehaviourDb micro;
  MacroPlanDb macro;
};

inline const Dbs& bundled() {
  static const Dbs dbs = [] {
    auto micro = io::loadMicroBehaviours(THRONG_SOURCE_DIR "/data/social/micro_behaviours.json");
    if (!micro.ok()) throw std::runtime_error(core::formatAll(micro.errors()));
    auto macro = io::loadMacroPlans(THRONG_SOURCE_DIR "/data/social/macro_plans.json", micro.value());
    if (!macro.ok()) throw std::runtime_error(core::formatAll(macro.errors()));
    return Dbs{micro.value(), macro.value()};
  }();
  return dbs;
}

inline Databases databases() { return {&bundled().micro, &bundled().macro}; }

/// The bundled motion library's lengths (docs/motion-library.md).
inline ClipLengths clipLengths() {
  return {{"wave", 1.6}, {"nod", 0.8}, {"point_toward", 1.4}, {"point_down", 1.2}, {"call_out", 1.2},
          {"look_at", 1.2}, {"talk", 2.0}};
}

}  // namespace throng::common_ground::test
