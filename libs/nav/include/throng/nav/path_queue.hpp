// throng::nav::PathQueue — time-sliced path planning (after DetourPathQueue): requests queue up and
// each tick's `update` spends at most a fixed budget of search iterations, so thousands of agents
// re-planning in one tick never stall it. Results are polled by ticket; unread ones expire.
// Requests are served strictly in submission order, so the outcome is deterministic. Given a
// TaskSystem of several threads, update searches the next requests in parallel ahead of their turn
// and replays the budget over them: every result, and the update it completes in, is the same as
// on one thread.
#pragma once
#include <cstdint>
#include <cstddef>
#include <deque>
#include <memory>
#include <span>
#include <vector>

#include "throng/core/parallel.hpp"
#include "throng/nav/navmesh.hpp"

namespace throng::nav {

using PathTicket = std::uint64_t;  ///< 0 = none

enum class TicketState : std::uint8_t { Unknown, Pending, Done };

struct PathResult {
  PathStatus status = PathStatus::Failed;
  std::vector<Vec2> corners;
  std::vector<float> heights;  ///< each corner's height [m]: the floor it is on (0 on a flat mesh)
};

class PathQueue {
 public:
  explicit PathQueue(std::shared_ptr<const NavMesh> mesh, int maxNodes = 4096);
  ~PathQueue();

  /// Queues a request; returns its ticket.
  PathTicket request(Vec2 from, Vec2 to);
  /// The same with heights (they pick the levels on a layered mesh; ignored on a flat one), searched
  /// with the stair cost of `costClass` (setStairCosts; layered meshes only, where stairs exist).
  PathTicket request(Vec2 from, float fromHeight, Vec2 to, float toHeight, std::uint32_t costClass = 0);
  /// Route costs: class i searches with stairs (kStairArea) costing `stairCost[i]` times their
  /// length (level ground costs 1 per metre). Without a call: one class, stairs at cost 1. May be
  /// called at any time (more classes for populations added later); a search under way keeps its
  /// class's costs as they were when it began. [Limit: each >= 1, finite, so Detour's A* heuristic
  /// stays admissible]
  void setStairCosts(std::span<const float> stairCost);
  /// The mesh's polygon flags changed (NavMesh::setClosed): the search under way and those searched
  /// ahead start again when their turn comes, so every result is searched on the mesh as it is now,
  /// the same way on any number of threads (the budget already spent stays spent). Tickets keep
  /// their places in the queue.
  void restart();
  /// Plans on `mesh` from now on (a mesh rebuilt with more cut regions, World::insertCrowd's exits):
  /// as restart(), every request not finished is searched on it when its turn comes; finished
  /// results stay. The cost classes are kept.
  void setMesh(std::shared_ptr<const NavMesh> mesh);
  /// How many cost classes setStairCosts has set (0 before any call).
  [[nodiscard]] std::size_t costClasses() const;
  /// Runs queued searches until `iterationBudget` Detour node expansions are spent (at least one
  /// request progresses per call). Returns how many requests completed. With `tasks` of more than
  /// one thread the searches run on its workers (each with a Detour query of its own), searched
  /// whole ahead of their turn; the budget is then spent on them as the sliced search would have
  /// spent it, so which requests complete in which update, and their results, never depend on
  /// the thread count.
  int update(int iterationBudget, const core::TaskSystem* tasks = nullptr);
  /// Only reads the queue: may be called from several threads at once (not during update or take).
  [[nodiscard]] TicketState state(PathTicket ticket) const;
  /// Takes a finished result (the ticket is then forgotten). Precondition: state == Done.
  PathResult take(PathTicket ticket);
  [[nodiscard]] std::size_t pending() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace throng::nav
