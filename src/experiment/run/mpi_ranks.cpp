// Ranks on MPI. Compiled with GJKLAB_HAVE_MPI only when CMake found an MPI library; without it
// the same functions say that the build has none, so nothing else depends on the choice.
#include <algorithm>
#include <cstdlib>
#include <string>

#include "gjklab/experiment/run/ranks.hpp"

#ifdef GJKLAB_HAVE_MPI
// The C interface only: Open MPI's mpi.h otherwise pulls in its deprecated C++ bindings,
// whose symbols live in a library the build does not link.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>

#include <limits>
#endif

namespace gjklab::experiment {

int launched_ranks() {
  // Open MPI's mpirun sets OMPI_COMM_WORLD_SIZE; PMIx launchers (srun --mpi=pmix) set PMIX_RANK
  // and PMI-1/2 launchers (MPICH's hydra, srun --mpi=pmi2) PMI_RANK, the size in PMI_SIZE or
  // Slurm's SLURM_STEP_NUM_TASKS. Tasks of a plain srun get no rank: they are separate runs.
  auto number = [](const char* name) {
    const char* v = std::getenv(name);
    return v ? std::max(1, std::atoi(v)) : 0;
  };
  if (const int n = number("OMPI_COMM_WORLD_SIZE")) return n;
  if (!std::getenv("PMIX_RANK") && !std::getenv("PMI_RANK")) return 0;
  if (const int n = number("PMI_SIZE")) return n;
  if (const int n = number("SLURM_STEP_NUM_TASKS")) return n;
  return 1;
}

#ifdef GJKLAB_HAVE_MPI

namespace {

void check(int code, const char* what) {
  if (code == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  MPI_Error_string(code, text, &length);
  throw std::runtime_error(std::string(what) + ": " + std::string(text, length));
}

int as_count(std::size_t n) {
  // MPI counts are ints: one rank's share of a round is far below 2 GB.
  if (n > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw std::runtime_error("an MPI message of " + std::to_string(n) +
                             " bytes is too long (use a smaller --checkpoint)");
  return static_cast<int>(n);
}

class MpiRanks final : public Ranks {
 public:
  MpiRanks() {
    int provided = 0;
    check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
    // Errors come back as codes (and become exceptions) instead of aborting the job silently.
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
  }
  ~MpiRanks() override { MPI_Finalize(); }
  MpiRanks(const MpiRanks&) = delete;
  MpiRanks& operator=(const MpiRanks&) = delete;

  int rank() const override { return rank_; }
  int size() const override { return size_; }

  std::vector<std::string> gather(const std::string& bytes) override {
    const int length = as_count(bytes.size());
    std::vector<int> lengths(rank_ == 0 ? size_ : 0);
    check(MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, MPI_COMM_WORLD),
          "MPI_Gather");
    std::vector<int> offsets(lengths.size());
    std::size_t total = 0;
    for (std::size_t r = 0; r < lengths.size(); ++r) {
      offsets[r] = as_count(total);
      total += static_cast<std::size_t>(lengths[r]);
    }
    as_count(total);
    std::string all(total, '\0');
    check(MPI_Gatherv(bytes.data(), length, MPI_BYTE, all.data(), lengths.data(), offsets.data(),
                      MPI_BYTE, 0, MPI_COMM_WORLD),
          "MPI_Gatherv");
    std::vector<std::string> parts;
    for (std::size_t r = 0; r < lengths.size(); ++r)
      parts.push_back(
          all.substr(static_cast<std::size_t>(offsets[r]), static_cast<std::size_t>(lengths[r])));
    return parts;
  }

  std::string broadcast(const std::string& bytes) override {
    int length = rank_ == 0 ? as_count(bytes.size()) : 0;
    check(MPI_Bcast(&length, 1, MPI_INT, 0, MPI_COMM_WORLD), "MPI_Bcast");
    std::string out = rank_ == 0 ? bytes : std::string(static_cast<std::size_t>(length), '\0');
    check(MPI_Bcast(out.data(), length, MPI_BYTE, 0, MPI_COMM_WORLD), "MPI_Bcast");
    return out;
  }

  [[noreturn]] void abort(int status) override {
    MPI_Abort(MPI_COMM_WORLD, status);
    std::_Exit(status);  // MPI_Abort does not return; this keeps [[noreturn]] true if it did
  }

 private:
  int rank_ = 0;
  int size_ = 1;
};

}  // namespace

bool built_with_mpi() {
  return true;
}

std::unique_ptr<Ranks> join_mpi_job() {
  return std::make_unique<MpiRanks>();
}

std::string mpi_library_version() {
  // One of the few MPI calls allowed before MPI_Init.
  char text[MPI_MAX_LIBRARY_VERSION_STRING];
  int length = 0;
  if (MPI_Get_library_version(text, &length) != MPI_SUCCESS) return "unknown";
  std::string v(text, static_cast<std::size_t>(length));
  v = v.substr(0, v.find_first_of(",\r\n"));
  while (!v.empty() && (v.back() == ',' || v.back() == ' '))
    v.pop_back();
  return v;
}

#else

bool built_with_mpi() {
  return false;
}

std::unique_ptr<Ranks> join_mpi_job() {
  throw std::runtime_error(
      "this gjklab was built without MPI (install an MPI library, e.g. Debian's "
      "libopenmpi-dev, and configure again)");
}

std::string mpi_library_version() {
  return {};
}

#endif

}  // namespace gjklab::experiment
