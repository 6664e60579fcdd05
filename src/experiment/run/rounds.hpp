// Rounds of cases for the run loop (driver.cpp): evaluated on this process's worker threads,
// or split over the ranks of a distributed run with the results sent to rank 0, which writes
// them. Private to src/experiment.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "gjklab/experiment/config/config.hpp"
#include "gjklab/experiment/run/ranks.hpp"
#include "gjklab/experiment/cases/records.hpp"

namespace gjklab::experiment {

/// True once the run has been asked to stop.
using StopCheck = std::function<bool()>;

/// A round as the writer sees it.
struct Round {
  /// The round's finished cases, in case order: all of them, or after a stop request a prefix
  /// of the round. Empty on the ranks other than 0, which do not write.
  std::vector<CaseResult> results;
  bool stop = false;  ///< the run stops after this round (on every rank alike)
};

/// Evaluates cases [first, first + count) on `threads` worker threads. On a stop request the
/// started cases are finished and the result holds exactly the first k cases (the flag is read
/// before an index is taken). Throws the first failing case's error, naming the case.
std::vector<CaseResult> evaluate_range(const ExperimentConfig& config, int threads,
                                       std::uint64_t first, std::uint64_t count,
                                       const StopCheck& stopping);

class RoundSource {
 public:
  virtual ~RoundSource() = default;
  /// Evaluates cases [first, first + count). Collective in a distributed run: every rank calls
  /// it with the same arguments, and every rank throws when any case failed (rank 0 the
  /// case's error, the others PeerFailure).
  virtual Round next(std::uint64_t first, std::uint64_t count) = 0;
  /// Distributed runs, on rank 0: seconds spent so far decoding the other ranks' results
  /// (with the writing, the job's serial part); 0 otherwise.
  virtual double decoding_seconds() const { return 0; }
};

/// This process's threads alone (ranks null), or its share over the ranks.
std::unique_ptr<RoundSource> make_rounds(const ExperimentConfig& config, int threads, Ranks* ranks,
                                         StopCheck stopping);

}  // namespace gjklab::experiment
