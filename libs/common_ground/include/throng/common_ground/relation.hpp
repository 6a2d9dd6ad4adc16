// throng::common_ground spatial relations — how an initiator A stands with respect to a group mate B, in
// terms of what B can perceive of A (Park, Peng, Quek, Cao, §3.2 and Figure 2: touch within the body
// radius, hearing all around up to d_h, vision along the body direction up to d_v within a field of
// view α, occluded by walls). Figure 2(b)'s drawing of the six relations is missing from our copy
// of the paper; they are derived here from the sensory model (docs/social-model.md has a picture).
// The paper's worked example uses A3: "outside the immediate perception of B".
#pragma once
#include <cstdint>
#include <string_view>

namespace throng::common_ground {

/// What B perceives of A right now.
struct Perception {
  bool touch = false;  ///< bodies within touching distance
  bool hear = false;   ///< A within B's hearing range d_h (omnidirectional)
  bool see = false;    ///< A within B's vision range d_v, inside B's field of view α, not occluded by walls
};

enum class Relation : std::uint8_t {
  A1 = 1,  ///< touching: B feels a tap, hears and may see A
  A2 = 2,  ///< B sees and hears A: face to face within talking range
  A3 = 3,  ///< outside B's perception (B neither sees nor hears A), but A sees B: A must move into
           ///< B's view (then wave) or into hearing range (then call out)
  A4 = 4,  ///< B hears A but does not see A (A behind B, or behind a wall within hearing range)
  A5 = 5,  ///< B sees A but A is beyond hearing range: gestures only (wave, point)
  A6 = 6,  ///< neither perceives the other (far, or walls between): A must walk toward B first
};

[[nodiscard]] constexpr std::string_view relationName(Relation r) {
  switch (r) {
    case Relation::A1: return "A1";
    case Relation::A2: return "A2";
    case Relation::A3: return "A3";
    case Relation::A4: return "A4";
    case Relation::A5: return "A5";
    case Relation::A6: return "A6";
  }
  return "?";
}

}  // namespace throng::common_ground
