// Embedding throng in another program: load a scenario file (validated, with located
// diagnostics on failure), create the world, step it on a thread pool and read each frame.
// usage: throng_embed SCENARIO.json [SECONDS]   (default 10 s of simulated time)
#include <cstdio>
#include <cstdlib>
#include <string>

#include "throng/core/parallel.hpp"
#include "throng/io/scenario_loader.hpp"
#include "throng/sim/world.hpp"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s SCENARIO.json [SECONDS]\n", argv[0]);
    return 2;
  }
  const double seconds = argc > 2 ? std::atof(argv[2]) : 10.0;
  auto loaded = throng::io::loadScenarioFile(argv[1]);
  if (!loaded) {
    std::fprintf(stderr, "%s\n", throng::core::formatAll(loaded.errors()).c_str());
    return 1;
  }
  const throng::io::LoadedScenario& scenario = loaded.value();
  auto created = throng::sim::World::create(scenario.desc, scenario.navmesh);
  if (!created) {
    std::fprintf(stderr, "%s\n", throng::core::formatAll(created.errors()).c_str());
    return 1;
  }
  auto world = std::move(created).value();
  throng::core::TaskSystem tasks(0);  // 0: every hardware thread
  const auto ticksPerSecond = static_cast<int>(1.0 / scenario.desc.dt + 0.5);
  for (int tick = 1; tick <= static_cast<int>(seconds * ticksPerSecond) && !world->finished(); ++tick) {
    world->step(tasks);
    const throng::sim::FramePtr frame = world->takeFrame();
    if (tick % ticksPerSecond == 0) std::printf("t = %5.1f s  agents %zu\n", frame->time, frame->size());
  }
  return 0;
}
