// throng::dist::MpiSession — MPI for the life of one `throng run` launched by mpirun: initialises
// MPI (funneled: only the thread that created it calls MPI), says which rank this process is, and
// offers the few collectives the run loop needs so every rank takes the same decisions (stop on a
// signal, stop on an error). Finalises MPI when destroyed. Reads the MPI environment; no files.
#pragma once
#include <cstdint>
#include <memory>

#include "throng/core/result.hpp"

namespace throng::dist {

class MpiSession {
 public:
  /// Initialises MPI once per process. Fails (a diagnostic) when MPI cannot start or when it was
  /// started already.
  static core::Result<std::unique_ptr<MpiSession>> start();
  ~MpiSession();  ///< MPI_Finalize
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  [[nodiscard]] std::uint32_t rank() const { return rank_; }
  [[nodiscard]] std::uint32_t ranks() const { return ranks_; }
  /// Collective: true on every rank when `flag` is true on any rank.
  [[nodiscard]] bool anyRank(bool flag) const;
  /// Collective: the largest `value` over the ranks.
  [[nodiscard]] double maxOverRanks(double value) const;
  /// Collective: the sum of `value` over the ranks.
  [[nodiscard]] std::uint64_t sumOverRanks(std::uint64_t value) const;

 private:
  MpiSession() = default;
  std::uint32_t rank_ = 0;
  std::uint32_t ranks_ = 1;
};

}  // namespace throng::dist
