// The processes of a distributed run (`mpirun -n N gjklab run`), as the driver sees them: a
// rank, a size and the two collectives the run needs. No MPI type appears here, so the driver
// compiles the same with or without MPI; src/experiment/run/mpi_ranks.cpp implements it on MPI
// when the build found an MPI library.
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace gjklab::experiment {

/// Cases per round (and checkpoint) of a distributed run unless --checkpoint says otherwise:
/// the archive's chunk of rows, so that each round appends whole chunks. Rounds of 512 cases,
/// the single process's default, make HDF5 decompress and recompress each partly filled chunk
/// at every append: rank 0 then writes 5 times slower and caps the job (measured on the
/// quickstart: 8 400 against 47 000 cases/s).
inline constexpr std::uint64_t kDistributedRoundCases = 4096;

class Ranks {
 public:
  virtual ~Ranks() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  /// Collective: rank 0 receives every rank's bytes in rank order (its own first); the other
  /// ranks receive an empty list.
  virtual std::vector<std::string> gather(const std::string& bytes) = 0;
  /// Collective: every rank receives rank 0's bytes (the others' argument is ignored).
  virtual std::string broadcast(const std::string& bytes) = 0;
  /// Ends every rank of the job at once (MPI_Abort): for a failure the other ranks do not
  /// know of, which would leave them waiting in a collective.
  [[noreturn]] virtual void abort(int status) = 0;

  /// Set when a failure was sent to every rank (which then all end on their own).
  bool failure_shared = false;
};

/// Thrown on the ranks other than 0 when rank 0 failed and said so: rank 0 reports the error,
/// the others only exit.
class PeerFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The number of ranks when an MPI launcher (mpirun, mpiexec, srun) started this process,
/// read from the launcher's environment; 0 when none did.
int launched_ranks();

/// Whether this build can join an MPI job.
bool built_with_mpi();

/// Joins the MPI job this process was launched in (MPI_Init_thread: only the calling thread
/// communicates; the worker threads never do); the job is left (MPI_Finalize) when the
/// returned object is destroyed. Throws std::runtime_error when the build has no MPI.
std::unique_ptr<Ranks> join_mpi_job();

/// The MPI library's own version string (MPI_Get_library_version, first line), or empty when
/// the build has no MPI.
std::string mpi_library_version();

}  // namespace gjklab::experiment
