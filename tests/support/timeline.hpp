// Timeline entries for the tests that close and open exits (closed_door_test, exit_choice_test).
#pragma once
#include <cstdint>

#include "throng/sim/scenario.hpp"

namespace throng::test {

/// A timeline entry that closes or opens exit `point` at `time` [s].
inline sim::TimelineEntry doorAt(float time, sim::TimelineAction action, std::uint32_t point) {
  sim::TimelineEntry e;
  e.time = time;
  e.action = action;
  e.point = point;
  return e;
}

}  // namespace throng::test
