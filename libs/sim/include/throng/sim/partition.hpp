// throng::sim::StepExchange — the hook that lets several copies of one World (one per process,
// "rank") share the work of a tick and stay bit-identical (docs/scaling.md, "What is built").
// Every rank holds the whole world and runs the cheap, order-dependent phases itself; the steer
// phase is split by spatial ownership: rank r steers only the agents whose position at the start
// of the tick lies in its strip [cut[r-1], cut[r]) of x, then every rank sends the values steer
// wrote for its agents to all others (allGather) and applies theirs. The core does no I/O and
// knows nothing of MPI: libs/dist implements StepExchange with MPI, tests with threads.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace throng::sim {

/// The transport between the copies of one world. Every call is collective: all ranks make the
/// same calls in the same order (the World makes exactly one allGather per tick while set).
class StepExchange {
 public:
  virtual ~StepExchange() = default;
  /// Copies of the world taking part [>= 1].
  [[nodiscard]] virtual std::uint32_t ranks() const = 0;
  /// This copy, in [0, ranks()).
  [[nodiscard]] virtual std::uint32_t rank() const = 0;
  /// Every rank passes its block `mine`; on return `all` holds every rank's block in rank order.
  /// `sizes[r]` is the size of rank r's block [bytes], known to every rank beforehand (they all
  /// compute the same owners), so one collective suffices (MPI_Allgatherv). A transport failure
  /// is fatal (MPI aborts the job), so there is nothing to return.
  virtual void allGather(std::span<const std::byte> mine, std::span<const std::size_t> sizes,
                         std::vector<std::byte>& all) = 0;
};

/// How the steer phase is split between ranks.
struct PartitionOptions {
  /// Strip cuts are recomputed from the agents' x positions every this many ticks [>= 1], so every
  /// strip holds about the same number of agents. Deterministic: every rank sees the same positions.
  std::uint32_t rebalanceTicks = 20;
};

/// Running totals of one rank's share of the work (World::partitionStats).
struct PartitionStats {
  std::uint32_t ranks = 1;
  std::uint64_t ticks = 0;            ///< ticks stepped with the partition set
  std::uint64_t ownedAgentSteps = 0;  ///< agent-steps this rank steered
  std::uint64_t agentSteps = 0;       ///< agent-steps of the whole world in those ticks
  std::uint64_t migrations = 0;       ///< an agent's owner changed between ticks because it crossed a cut
  std::uint64_t rebalanceMoves = 0;   ///< an agent's owner changed because the cuts moved
  std::uint64_t sentBytes = 0;        ///< this rank's blocks, summed over ticks [bytes]
  std::uint64_t gatheredBytes = 0;    ///< every rank's blocks received back, summed over ticks [bytes]
};

/// Bytes a rank sends per agent it owns and per tick: the preferred and ORCA velocities (4 floats)
/// the path corner index, the heading hold and the look ahead's turn: everything steer writes.
inline constexpr std::size_t kSteerRecordBytes = 4 * sizeof(float) + sizeof(std::uint32_t) + 2 * sizeof(std::uint8_t);

}  // namespace throng::sim
