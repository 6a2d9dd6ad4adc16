// throng::io social databases — the micro-behaviour database (data/social/micro_behaviours.json)
// and the macro-plan database (data/social/macro_plans.json) of the Common Ground coordination
// planner, parsed from JSON into throng::common_ground's plain structs. Reads text (or one file); writes
// nothing. Every problem is one diagnostic: file:line:column, JSON pointer, what is wrong and what
// was expected. Format: docs/social-coordination.md.
#pragma once
#include <string>
#include <string_view>

#include "throng/core/result.hpp"
#include "throng/common_ground/behaviour_db.hpp"

namespace throng::io {

inline constexpr std::size_t kMaxSocialDbEntries = 4096;  ///< behaviours or plans per file
inline constexpr double kMaxBehaviourWeight = 1000.0;     ///< weights are in (0, kMaxBehaviourWeight]
inline constexpr double kMaxVisitDuration = 86400.0;      ///< [s] visitDuration in [0, kMaxVisitDuration]

/// Parses a micro-behaviour database; checks types, names (unique, known intents, relations,
/// targets) and that every response names a behaviour of the file.
[[nodiscard]] core::Result<common_ground::MicroBehaviourDb> parseMicroBehaviours(std::string_view text,
                                                                          const std::string& source);

/// Parses a macro-plan database; `micro` is the micro-behaviour database its proposals name
/// (each must exist and have the "propose" intent).
[[nodiscard]] core::Result<common_ground::MacroPlanDb> parseMacroPlans(std::string_view text, const std::string& source,
                                                                const common_ground::MicroBehaviourDb& micro);

[[nodiscard]] core::Result<common_ground::MicroBehaviourDb> loadMicroBehaviours(const std::string& path);
[[nodiscard]] core::Result<common_ground::MacroPlanDb> loadMacroPlans(const std::string& path,
                                                               const common_ground::MicroBehaviourDb& micro);

}  // namespace throng::io
