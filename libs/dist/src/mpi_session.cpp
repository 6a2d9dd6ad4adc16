// MpiSession — MPI_Init_thread / MPI_Finalize and the run loop's small collectives (mpi_session.hpp).
#include "throng/dist/mpi_session.hpp"

#include <mpi.h>

#include <string>

namespace throng::dist {

core::Result<std::unique_ptr<MpiSession>> MpiSession::start() {
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (initialised) return core::Diagnostic{"MPI", 0, 0, "", "MPI was initialised already", "one MpiSession per process", ""};
  int provided = 0;
  if (MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
    return core::Diagnostic{"MPI", 0, 0, "", "MPI_Init_thread failed", "a process started by mpirun", ""};
  }
  // Only the thread that called MPI_Init_thread calls MPI (the tick's worker threads never do), so
  // MPI_THREAD_FUNNELED is enough; with less, worker threads could still disturb some MPIs.
  if (provided < MPI_THREAD_FUNNELED) {
    MPI_Finalize();
    return core::Diagnostic{"MPI", 0, 0, "", "this MPI gives thread level " + std::to_string(provided),
                            "MPI_THREAD_FUNNELED or more", ""};
  }
  std::unique_ptr<MpiSession> session(new MpiSession());
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  session->rank_ = static_cast<std::uint32_t>(rank);
  session->ranks_ = static_cast<std::uint32_t>(size);
  return session;
}

MpiSession::~MpiSession() { MPI_Finalize(); }

bool MpiSession::anyRank(bool flag) const {
  int mine = flag ? 1 : 0, any = 0;
  MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD);
  return any != 0;
}

double MpiSession::maxOverRanks(double value) const {
  double out = 0.0;
  MPI_Allreduce(&value, &out, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return out;
}

std::uint64_t MpiSession::sumOverRanks(std::uint64_t value) const {
  unsigned long long mine = value, out = 0;
  MPI_Allreduce(&mine, &out, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  return out;
}

}  // namespace throng::dist
