// demographics — who walks how fast: the desired walking speed an agent (or a flocking group) is
// given when it spawns, drawn from its population's speed distribution or, when the population
// names a demographic table (PopulationDesc::demographics), from Weidmann's (1993) walking speeds
// by age as tabulated for RiMEA test 7, with a share of movement-impaired people who walk slower
// (RiMEA 7's reduced-mobility band; Boyce, Shields & Silcock 1999) in larger bodies. Draws come
// from one stream per (scenario seed, stable id, RngPurpose::Speed), so they are the same for any
// thread count and one agent's draw never shifts another's. Reads the population; writes nothing.
#pragma once
#include <cstdint>
#include <span>

#include "throng/sim/scenario.hpp"

namespace throng::sim {

/// One row of a speed-by-age table: people aged [ageMin, ageMax) walk at speeds in
/// [speedMin, speedMax] on level ground.
struct AgeSpeedBand {
  float ageMin, ageMax;      ///< [years]
  float speedMin, speedMax;  ///< [m/s]
};

/// Weidmann 1993's walking speed by age, as RiMEA test 7 tabulates it (three age bands).
[[nodiscard]] std::span<const AgeSpeedBand> weidmannAgeBands();
/// The speed band of movement-impaired people (RiMEA test 7's reduced-mobility group) [m/s].
inline constexpr float kImpairedSpeedMin = 0.46f;
inline constexpr float kImpairedSpeedMax = 0.76f;

/// What spawning draws for one agent or group.
struct Walker {
  float speed = 0.0f;     ///< desired walking speed [m/s]
  float age = 0.0f;       ///< [years]; 0 without a demographic table
  bool impaired = false;  ///< movement-impaired (a demographic table's `impaired` share)
};

/// The draw for entity `id` (an agent's or a group's stable id) of population `pop`. Without a
/// demographic table exactly the population's clipped normal speed, as before tables existed.
[[nodiscard]] Walker drawWalker(const PopulationDesc& pop, std::uint64_t seed, std::uint64_t id);

}  // namespace throng::sim
