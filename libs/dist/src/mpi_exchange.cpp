// MpiExchange — the steer outputs of every rank to every rank with one MPI_Allgatherv (mpi_exchange.hpp).
#include "throng/dist/mpi_exchange.hpp"

#include <mpi.h>

#include <climits>

#include "throng/core/assert.hpp"

namespace throng::dist {

MpiExchange::MpiExchange(const MpiSession& session) : rank_(session.rank()), ranks_(session.ranks()) {
  counts_.resize(ranks_);
  offsets_.resize(ranks_);
}

void MpiExchange::allGather(std::span<const std::byte> mine, std::span<const std::size_t> sizes,
                            std::vector<std::byte>& all) {
  THRONG_ASSERT(sizes.size() == ranks_ && sizes[rank_] == mine.size());
  std::size_t total = 0;
  for (std::uint32_t r = 0; r < ranks_; ++r) {
    THRONG_ASSERT(total + sizes[r] <= static_cast<std::size_t>(INT_MAX));  // MPI counts are int: < 2 GiB a tick
    counts_[r] = static_cast<int>(sizes[r]);
    offsets_[r] = static_cast<int>(total);
    total += sizes[r];
  }
  all.resize(total);
  // MPI wants a non-const send buffer in older signatures; OpenMPI 4 takes const void*.
  MPI_Allgatherv(mine.data(), static_cast<int>(mine.size()), MPI_BYTE, all.data(), counts_.data(), offsets_.data(),
                 MPI_BYTE, MPI_COMM_WORLD);
}

}  // namespace throng::dist
