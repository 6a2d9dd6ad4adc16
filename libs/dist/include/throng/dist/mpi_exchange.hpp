// throng::dist::MpiExchange — sim::StepExchange over MPI_COMM_WORLD: one MPI_Allgatherv per tick
// carries every rank's steer outputs to every rank (the sizes are known beforehand on every rank).
// Needs a live MpiSession; used from the thread that started it.
#pragma once
#include "throng/dist/mpi_session.hpp"
#include "throng/sim/partition.hpp"

namespace throng::dist {

class MpiExchange final : public sim::StepExchange {
 public:
  explicit MpiExchange(const MpiSession& session);
  [[nodiscard]] std::uint32_t ranks() const override { return ranks_; }
  [[nodiscard]] std::uint32_t rank() const override { return rank_; }
  void allGather(std::span<const std::byte> mine, std::span<const std::size_t> sizes,
                 std::vector<std::byte>& all) override;

 private:
  std::uint32_t rank_ = 0;
  std::uint32_t ranks_ = 1;
  std::vector<int> counts_, offsets_;  // MPI's int counts, reused every tick
};

}  // namespace throng::dist
