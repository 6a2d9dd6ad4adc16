// plan — budgeted path planning (serial, in row = stable id order, so deterministic): agents that
// asked for a path submit a request to the nav::PathQueue; the queue spends at most
// kPathIterationsPerTick node expansions; finished paths are handed to their agents. Until its path
// arrives an agent walks straight at its target (as DetourCrowd does).
#include <algorithm>

#include "world_impl.hpp"

namespace throng::sim {

void World::Impl::plan() {
  const std::size_t n = agents.size();
  for (std::size_t row = 0; row < n; ++row) {
    if (!agents.needPath[row]) continue;
    agents.needPath[row] = 0;
    const core::Vec2 from{agents.posX[row], agents.posY[row]}, to{agents.targetX[row], agents.targetY[row]};
    agents.ticket[row] = agents.levels ? pathQueue->request(from, agents.posZ[row], to, agents.targetZ[row])
                                       : pathQueue->request(from, to);
  }
  pathQueue->update(kPathIterationsPerTick);
  for (std::size_t row = 0; row < n; ++row) {
    const nav::PathTicket t = agents.ticket[row];
    if (t == 0) continue;
    const nav::TicketState state = pathQueue->state(t);
    if (state == nav::TicketState::Pending) continue;
    agents.ticket[row] = 0;
    if (state != nav::TicketState::Done) continue;  // expired: the progress check will ask again
    nav::PathResult result = pathQueue->take(t);
    if (result.status == nav::PathStatus::Failed) continue;
    if (result.status == nav::PathStatus::Partial) {
      pendingEvents.push_back({tick, agents.id[row], EventKind::PathPartial, currentGoalPoint(row), 0});
    }
    agents.corners[row].assign(result.corners);
  }
}

}  // namespace throng::sim
