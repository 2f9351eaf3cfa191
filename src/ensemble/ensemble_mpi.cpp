// The processes of a sweep: one process, or the MPI world when topple is built with MPI (TOPPLE_WITH_MPI) and the
// process was started by an MPI launcher. Only the main thread calls MPI (MPI_THREAD_FUNNELED); oneTBB's workers
// never do.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <thread>

#include "topple/ensemble/ensemble.hpp"

#if TOPPLE_HAVE_MPI
// The C API only: the deprecated C++ bindings would need libmpi_cxx.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

namespace topple::ensemble {

[[noreturn]] void SingleProcess::abort(int exit_code) { std::exit(exit_code); }

bool built_with_mpi() noexcept { return TOPPLE_HAVE_MPI != 0; }

bool launched_by_mpi() noexcept {
  // Open MPI's mpirun/mpiexec (OMPI_*), PMIx launchers (srun --mpi=pmix, prterun), PMI-1/2 (Hydra, srun --mpi=pmi2).
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"}) {
    if (std::getenv(name) != nullptr) return true;
  }
  return false;
}

#if TOPPLE_HAVE_MPI
namespace {

void check(int code, const char* what) {
  if (code != MPI_SUCCESS) throw std::runtime_error(std::string("MPI error in ") + what);
}

class MpiWorld final : public Cluster {
 public:
  MpiWorld() {
    int provided = 0;
    check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
    check(MPI_Comm_rank(MPI_COMM_WORLD, &rank_), "MPI_Comm_rank");
    check(MPI_Comm_size(MPI_COMM_WORLD, &size_), "MPI_Comm_size");
  }
  ~MpiWorld() override { MPI_Finalize(); }

  [[nodiscard]] int rank() const noexcept override { return rank_; }
  [[nodiscard]] int size() const noexcept override { return size_; }

  /// A barrier that sleeps while it waits: a rank that has finished its chunks must not spin on a core that another
  /// rank's threads may be using (ranks bound to none, or oversubscribed).
  void barrier() override {
    MPI_Request request = MPI_REQUEST_NULL;
    check(MPI_Ibarrier(MPI_COMM_WORLD, &request), "MPI_Ibarrier");
    int done = 0;
    auto pause = std::chrono::microseconds(50);
    while (true) {
      check(MPI_Test(&request, &done, MPI_STATUS_IGNORE), "MPI_Test");
      if (done != 0) break;
      std::this_thread::sleep_for(pause);
      pause = std::min(pause * 2, std::chrono::microseconds(20'000));
    }
  }

  void broadcast(std::vector<std::uint64_t>& values, int root) override {
    unsigned long long n = values.size();
    check(MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, root, MPI_COMM_WORLD), "MPI_Bcast");
    values.resize(static_cast<std::size_t>(n));
    // In pieces of at most 2^30 values (MPI counts are int).
    std::size_t offset = 0;
    while (offset < values.size()) {
      const std::size_t piece = std::min<std::size_t>(values.size() - offset, std::size_t{1} << 30);
      check(MPI_Bcast(values.data() + offset, static_cast<int>(piece), MPI_UINT64_T, root, MPI_COMM_WORLD),
            "MPI_Bcast");
      offset += piece;
    }
  }

  [[nodiscard]] std::vector<std::uint64_t> all_gather(std::uint64_t value) override {
    std::vector<std::uint64_t> out(static_cast<std::size_t>(size_));
    check(MPI_Allgather(&value, 1, MPI_UINT64_T, out.data(), 1, MPI_UINT64_T, MPI_COMM_WORLD), "MPI_Allgather");
    return out;
  }

  [[noreturn]] void abort(int exit_code) override {
    MPI_Abort(MPI_COMM_WORLD, exit_code);
    std::_Exit(exit_code);
  }

 private:
  int rank_ = 0;
  int size_ = 1;
};

}  // namespace
#endif

std::unique_ptr<Cluster> join_cluster() {
#if TOPPLE_HAVE_MPI
  if (launched_by_mpi()) return std::make_unique<MpiWorld>();
#endif
  return std::make_unique<SingleProcess>();
}

}  // namespace topple::ensemble
