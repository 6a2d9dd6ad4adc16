// protocol_bandwidth — measures the crowd frames' size on the real simulation: the `throng bench`
// random scenario (agents wandering at 1 agent/m², ORCA avoidance) run at the client's tick rate,
// one client at the centre of the square seeing every agent: the 16 nearest as near (20 joints,
// angles sampled from clip and phase), the rest within 25 m as middle, beyond as far (refreshed
// every 4th frame). Acks one frame behind: frame n is delta-coded against frame n − 1.
// Prints a markdown table: key frame size, mean delta frame size, bits per agent per tick and
// kbit/s per client. Usage: protocol_bandwidth [frames=100]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numeric>

#include "throng/bench/scenarios.hpp"
#include "throng/protocol/crowd_encoder.hpp"
#include "throng/sim/animation.hpp"
#include "throng/sim/world.hpp"

namespace {

using namespace throng;

constexpr int kNear = 16;
constexpr std::uint8_t kJoints = 20;
constexpr float kMiddleRadius = 25.0f;  // [m]

protocol::CrowdView viewOf(const sim::Frame& f, float cx, float cy) {
  protocol::CrowdView v;
  v.simTick = f.tick;
  v.jointCount = kJoints;
  std::vector<std::size_t> order(f.size());
  std::iota(order.begin(), order.end(), 0);
  auto d2 = [&](std::size_t i) { return (f.posX[i] - cx) * (f.posX[i] - cx) + (f.posY[i] - cy) * (f.posY[i] - cy); };
  std::partial_sort(order.begin(), order.begin() + std::min<std::size_t>(kNear, order.size()), order.end(),
                    [&](std::size_t a, std::size_t b) { return d2(a) < d2(b); });
  std::vector<bool> near(f.size(), false);
  for (std::size_t k = 0; k < std::min<std::size_t>(kNear, order.size()); ++k) near[order[k]] = true;
  for (std::size_t i = 0; i < f.size(); ++i) {
    protocol::AgentState a;
    a.id = f.ids[i];
    a.x = f.posX[i];
    a.y = f.posY[i];
    a.yaw = std::atan2(f.oriY[i], f.oriX[i]);
    a.clip = f.clip[i];
    a.phase = f.phase[i];
    a.tier = near[i] ? protocol::Tier::Near : d2(i) <= kMiddleRadius * kMiddleRadius ? protocol::Tier::Middle : protocol::Tier::Far;
    if (a.tier == protocol::Tier::Near) {  // a clip sampled at its phase: the same (clip, phase) gives the same pose
      const float swing = a.clip == sim::kClipWalk ? 0.5f : 0.05f;
      for (int j = 0; j < kJoints * 3; ++j) {
        a.joints.push_back(swing * std::sin(6.2831853f * a.phase + 0.7f * j) * (j % 3 == 0 ? 1.0f : 0.3f));
      }
    }
    v.agents.push_back(std::move(a));
  }
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  const int frames = argc > 1 ? std::max(1, std::atoi(argv[1])) : 100;
  std::printf("| agents in view | rate [Hz] | near/middle/far | key frame [B] | delta frame [B] | bits/agent/tick | kbit/s per client |\n");
  std::printf("|---:|---:|---|---:|---:|---:|---:|\n");
  core::TaskSystem tasks(2);
  for (const std::size_t agents : {100u, 1000u, 10000u}) {
    for (const float rate : {10.0f, 25.0f}) {
      sim::ScenarioDesc desc = bench::makeScenario(bench::Layout::Random, agents, 1);
      desc.dt = 1.0f / rate;
      auto navmesh = bench::buildNavMesh(desc);
      if (!navmesh) return 1;
      auto world = sim::World::create(desc, navmesh.value());
      if (!world) return 1;
      const float c = bench::squareSide(agents) * 0.5f;
      for (int i = 0; i < 30; ++i) world.value()->step(tasks);  // spawned, paths planned, walking
      protocol::CrowdEncoder enc;
      std::size_t keyBytes = 0, deltaBytes = 0, deltas = 0;
      std::uint32_t ack = 0;
      protocol::CrowdFrameHeader last;
      for (int n = 0; n <= frames; ++n) {
        world.value()->step(tasks);
        auto e = enc.encode(viewOf(*world.value()->takeFrame(), c, c), ack);
        if (!e) return 1;
        if (e.value().keyFrame()) {
          keyBytes = e.value().bytes.size();
        } else {
          deltaBytes += e.value().bytes.size();
          ++deltas;
        }
        last = e.value().header;
        ack = e.value().header.frameNumber;  // the client acks every frame; the next is one behind
      }
      const double perFrame = static_cast<double>(deltaBytes) / static_cast<double>(std::max<std::size_t>(deltas, 1));
      const double inView = last.nearCount + last.middleCount + last.farCount;
      std::printf("| %zu | %.0f | %u/%u/%u | %zu | %.0f | %.2f | %.1f |\n", agents, rate, last.nearCount, last.middleCount,
                  last.farCount, keyBytes, perFrame, perFrame * 8.0 / inView, perFrame * 8.0 * rate / 1000.0);
      std::fflush(stdout);
    }
  }
  return 0;
}
