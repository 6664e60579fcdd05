// `gjklab hunt`: a search for the configurations where an algorithm fails, instead of waiting
// for random sampling to meet them.
//
// Each restart takes a case of the experiment (its families and placements, case id drawn from
// the seed) and searches the pose of B around it: a rotation about B's vertex mean (rotation
// vector, radians), a translation (in units of the pair's size) and a scale of B about its mean
// (log scale). The search is a (1+1) evolution strategy with the one-fifth success rule: one
// Gaussian step per query, kept when it does not lower the score, the step size grown after a
// success and shrunk after a failure. Every candidate is judged exactly (the certified oracle,
// with the depth of intersecting pairs). The score is the objective's value, or where the
// objective is a yes/no failure, a failure scores above every non-failure and the others are
// ranked by how close the pair is to touching (−log10 of exact distance or depth over size):
// booleans and terminations go wrong near contact, so the search walks towards it.
//
// A restart ends at its first failure or after its budget of queries. A failure is shrunk
// (vertices removed, then coordinates rounded to fewer significant digits, while it still
// fails) and kept as a `gjklab query --cases` line. The same number of queries is then spent
// on plain random sampling of the experiment's cases (ids 0, 1, 2, …), so the gain of the
// search is measured, not claimed. Everything is deterministic for a seed.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gjklab/exact/oracle.hpp"
#include "gjklab/experiment/cases/cloud_io.hpp"
#include "gjklab/experiment/config/config.hpp"

namespace gjklab::experiment {

/// What the search maximises (and what counts as a failure).
enum class HuntObjective : std::uint8_t {
  wrong_boolean,  ///< a boolean that differs from the exact one outside the touching band
  error,          ///< the relative distance error; a failure above the touching band
  iterations,     ///< the iterations used; a failure at the step limit
  not_converged,  ///< any termination other than converged
  /// a `converged` answer whose proven bracket (lower_bound, upper_bound) misses the exact
  /// distance; for algorithms without a bracket, a `converged` answer that is wrong (its
  /// boolean, or its distance beyond the touching band)
  false_convergence,
};

std::string_view to_string(HuntObjective o);
/// What the objective counts as a failure (and scores), in one phrase.
std::string_view hunt_objective_meaning(HuntObjective o);
std::optional<HuntObjective> hunt_objective_from_string(std::string_view name);
/// Every objective's name, in declaration order (for the command line's choices).
std::vector<std::string> hunt_objective_names();

struct HuntOptions {
  std::string algorithm;          ///< registry name, with the experiment's options when it lists it
  std::uint64_t queries = 10000;  ///< the search's budget of algorithm queries (each judged)
  HuntObjective objective = HuntObjective::wrong_boolean;
  std::uint64_t seed = 1;
  /// The most queries one restart's local search may spend. Short restarts find the most
  /// failures per query on experiments/hunt/hunt.toml: most failures show at the first poses drawn
  /// at the restart's contact scale, and a long local search spends queries on cases that do
  /// not fail (at 2·10⁵ queries, 6 against 48: 1.5–8x more failures per query for the peers).
  int restart_queries = 6;
  int shrink_queries = 400;     ///< the most queries shrinking one failure may spend
  bool random_baseline = true;  ///< also spend the budget on random sampling
  /// A distributed hunt's part (rank `rank` of `ranks`, each with its share of `queries`): its
  /// restarts draw from their own stream of the seed (rank 0's is the single process's), and
  /// its random baseline samples case ids rank, rank + ranks, rank + 2·ranks, …
  int rank = 0;
  int ranks = 1;
};

/// One failing configuration, shrunk.
struct FoundCase {
  PointCase points;
  double objective_value = 0;
  std::uint64_t base_case = 0;  ///< the experiment case the restart started from
  std::uint64_t query = 0;      ///< the search query that found it (1-based)
  exact::OracleAnswer exact;    ///< of the shrunk pair
  bool answer_intersect = false;
  std::optional<double> answer_distance;
  Termination answer_termination = Termination::converged;
  int answer_iterations = 0;
};

struct HuntReport {
  std::string algorithm;
  HuntObjective objective = HuntObjective::wrong_boolean;
  std::uint64_t queries = 0;  ///< search queries made (shrinking not counted)
  std::uint64_t restarts = 0;
  std::uint64_t shrink_queries = 0;
  std::vector<FoundCase> found;
  std::uint64_t random_queries = 0;
  std::uint64_t random_failures = 0;
  double worst_relative_error = 0;  ///< over every judged search query with a distance
};

/// Runs the search (and the random baseline). Throws std::invalid_argument for an algorithm
/// that is not registered, or one that cannot answer the experiment's shapes.
HuntReport hunt(const ExperimentConfig& config, const HuntOptions& options);

/// The cases file line of a found case: `gjklab query --cases` reads it; "found_by" holds the
/// objective, its value, the algorithm, its answer and the exact answer.
std::string found_case_line(const FoundCase& f, const HuntReport& report);

/// The summary (failures_found, queries, random_failures, random_queries, …) as one JSON line.
std::string hunt_summary_json(const HuntReport& report);

/// The budget of queries of rank `rank` of `ranks` (the remainder goes to the first ranks).
std::uint64_t rank_queries(std::uint64_t queries, int rank, int ranks);

/// One summary of a distributed hunt from its ranks' summaries (hunt_summary_json lines, in
/// rank order): counts added, the worst error the largest. Throws std::invalid_argument for
/// summaries of different algorithms or objectives, or malformed ones.
std::string merge_hunt_summaries(const std::vector<std::string>& summaries);

}  // namespace gjklab::experiment
