// Helpers shared by the World tests in tests/sim.
#pragma once
#include <vector>

#include "throng/sim/world.hpp"

namespace throng::sim::test {

/// Steps `w` until `seconds` of simulated time or until it finishes; returns every event, in order.
inline std::vector<Event> runEvents(World& w, double seconds, int threads = 1) {
  core::TaskSystem tasks(threads);
  std::vector<Event> events;
  while (w.stats().time < seconds && !w.finished()) {
    w.step(tasks);
    const auto f = w.takeFrame();
    events.insert(events.end(), f->events.begin(), f->events.end());
  }
  return events;
}

}  // namespace throng::sim::test
