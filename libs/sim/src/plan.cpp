// plan — budgeted path planning (requests in stable id order, so deterministic): agents that
// asked for a path submit a request to the nav::PathQueue; the queue spends at most
// kPathIterationsPerTick node expansions, searching on the workers ahead of the requests' turn
// (the same results and completion ticks on any number of threads); finished paths are handed to
// their agents. Until its path
// arrives an agent walks straight at its target (as DetourCrowd does); on a multi-level world it
// searches with its population's stair cost (the queue's cost class). Reads PlanInput (positions,
// targets, floor heights, ids, populations, goals for events); writes PlanOutput (needPath, tickets, corners,
// the queue, PathPartial events) — phases.hpp.
#include <algorithm>
#include <vector>

#include "phases.hpp"

namespace throng::sim {
namespace {

/// Rows per chunk of the scan for finished requests.
constexpr std::size_t kScanGrain = 4096;

/// Hands row's finished (or expired) request to it.
void serve(const PlanInput& in, const PlanOutput& out, nav::PathQueue& queue, std::uint32_t row) {
  const nav::PathTicket t = out.ticket[row];
  const nav::TicketState state = queue.state(t);
  out.ticket[row] = 0;
  if (state != nav::TicketState::Done) return;  // expired: the progress check will ask again
  nav::PathResult result = queue.take(t);
  if (result.status == nav::PathStatus::Failed) return;
  if (result.status == nav::PathStatus::Partial) {
    out.events.push_back({in.tick, in.id[row], EventKind::PathPartial, in.goals.currentGoalPoint(row), 0});
  }
  out.corners[row].assign(result.corners);
  if (!out.cornerZ.empty()) out.cornerZ[row] = std::move(result.heights);
}

}  // namespace

void plan(const PlanInput& in, const PlanOutput& out) {
  const std::size_t n = in.id.size();
  const bool levels = !in.posZ.empty();
  nav::PathQueue& queue = out.pathQueue;
  // Requests in ascending id order, whatever the order of the rows (row_order.cpp): who is served
  // first under the budget must not depend on where an agent's row is.
  std::vector<std::uint64_t> asking;  // (id << 32) | row: sorted without reading ids again
  for (std::size_t row = 0; row < n; ++row) {
    if (out.needPath[row]) asking.push_back(static_cast<std::uint64_t>(in.id[row]) << 32 | row);
  }
  if (!std::is_sorted(asking.begin(), asking.end())) std::sort(asking.begin(), asking.end());
  for (const std::uint64_t entry : asking) {
    const auto row = static_cast<std::uint32_t>(entry);
    out.needPath[row] = 0;
    const core::Vec2 from{in.posX[row], in.posY[row]}, to{in.targetX[row], in.targetY[row]};
    out.ticket[row] = levels ? queue.request(from, in.posZ[row], to, in.targetZ[row], in.population[row])
                             : queue.request(from, to);
  }
  queue.update(kPathIterationsPerTick, in.tasks);
  // The rows whose request is no longer pending, found chunk by chunk on the workers (state() only
  // reads the queue; at 100,000 wandering agents tens of thousands of rows wait for a path and the
  // serial scan was about a millisecond a tick), then served in row order as before.
  std::vector<std::vector<std::uint32_t>> ended(core::TaskSystem::chunkCount(n, kScanGrain));
  const auto scan = [&](std::size_t begin, std::size_t end) {
    std::vector<std::uint32_t>& rows = ended[begin / kScanGrain];
    for (std::size_t row = begin; row < end; ++row) {
      const nav::PathTicket t = out.ticket[row];
      if (t != 0 && queue.state(t) != nav::TicketState::Pending) rows.push_back(static_cast<std::uint32_t>(row));
    }
  };
  if (in.tasks != nullptr) {
    in.tasks->parallelFor(n, kScanGrain, scan);
  } else {
    for (std::size_t begin = 0; begin < n; begin += kScanGrain) scan(begin, std::min(n, begin + kScanGrain));
  }
  for (const std::vector<std::uint32_t>& rows : ended) {
    for (const std::uint32_t row : rows) serve(in, out, queue, row);
  }
}

}  // namespace throng::sim
