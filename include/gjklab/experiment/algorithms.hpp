// The algorithm registry: every query algorithm by name, behind one call signature.
//
// Experiment files, `gjklab query` and benchmarks select algorithms by these names. Adding an
// algorithm is one entry in src/experiment/algorithms.cpp.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "gjklab/exact/oracle.hpp"
#include "gjklab/geometry/polytope.hpp"
#include "gjklab/gjk/options.hpp"
#include "gjklab/gjk/result.hpp"
#include "gjklab/gjk/trace.hpp"
#include "gjklab/peers/libccd.hpp"

namespace gjklab::experiment {

/// Options of every algorithm, one struct each; an experiment records all of them.
struct AlgorithmOptions {
  GjkBooleanOptions gjk_boolean;
  GjkDistanceOptions gjk_distance;  ///< gjk-johnson, gjk-johnson-backup, gjk-sv, gjk-voronoi
  GjkNesterovOptions gjk_nesterov;  ///< gjk-nesterov
  peers::LibccdOptions libccd;
  exact::OracleOptions oracle;

  /// Sets the iteration bound of every iterative algorithm at once.
  void set_max_iterations(int n);
};

/// One algorithm's answer for one pair, in the vocabulary shared by all algorithms.
struct Outcome {
  bool intersect = false;
  std::optional<double> distance;  ///< absent for boolean-only algorithms
  std::optional<Vec3> witness_a, witness_b;
  int iterations = 0;
  int support_calls = 0;
  Termination termination = Termination::converged;
  std::optional<exact::OracleAnswer> exact;  ///< the full exact answer (algorithm `exact` only)
};

enum class AnswerKind { boolean, distance, exact };

struct AlgorithmInfo {
  std::string_view name;
  AnswerKind kind;
  std::string_view description;
  Outcome (*run)(const Polytope& a, const Polytope& b, const AlgorithmOptions& options);
  /// The same query with a per-iteration trace (same arithmetic); nullptr when the algorithm
  /// cannot be traced (peers, the oracle).
  Outcome (*run_traced)(const Polytope& a, const Polytope& b, const AlgorithmOptions& options,
                        TraceRecorder& trace) = nullptr;
};

/// Every registered algorithm, in a fixed order (the default order of outputs).
std::span<const AlgorithmInfo> algorithms();
/// The algorithm with this name, or nullptr.
const AlgorithmInfo* find_algorithm(std::string_view name);
/// "gjk-bool, gjk-johnson, …": the valid names, for error messages.
std::string algorithm_names();

}  // namespace gjklab::experiment
