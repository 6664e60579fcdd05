#include "gjklab/experiment/meshes/piece_query.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <vector>

namespace gjklab::experiment {

namespace {

/// A pair of pieces and the squared distance between their boxes (length units squared).
struct Candidate {
  double box_gap_squared;
  std::uint32_t a, b;
};

double box_gap_squared(const Polytope& a, const Polytope& b) {
  double sum = 0;
  for (int k = 0; k < 3; ++k) {
    const double gap =
        std::max({0.0, b.box_lower()[k] - a.box_upper()[k], a.box_lower()[k] - b.box_upper()[k]});
    sum += gap * gap;
  }
  return sum;
}

/// Every pair of pieces, nearest boxes first (ties in index order, so the order is fixed).
std::vector<Candidate> candidates(std::span<const Polytope> a, std::span<const Polytope> b) {
  std::vector<Candidate> out;
  out.reserve(a.size() * b.size());
  for (std::uint32_t i = 0; i < a.size(); ++i)
    for (std::uint32_t j = 0; j < b.size(); ++j)
      out.push_back({box_gap_squared(a[i], b[j]), i, j});
  std::stable_sort(out.begin(), out.end(), [](const Candidate& x, const Candidate& y) {
    return x.box_gap_squared < y.box_gap_squared;
  });
  return out;
}

/// Whether no pair at or beyond this box gap can be nearer than `best` (length units). The
/// gap's rounding (a few ulps, relative) is covered by the relative margin, so a pair whose
/// exact box gap is at most the best distance is never skipped.
bool beyond(double box_gap_squared, double best) {
  constexpr double kRelativeMargin = 1e-12;
  return box_gap_squared > best * best * (1 + kRelativeMargin);
}

/// Adds one pair's run to the union's tallies.
void tally(Outcome& total, const Outcome& pair) {
  total.iterations += pair.iterations;
  total.support_calls += pair.support_calls;
  if (total.termination == Termination::converged) total.termination = pair.termination;
  if (pair.lower_bound)
    total.lower_bound = std::min(total.lower_bound.value_or(*pair.lower_bound), *pair.lower_bound);
}

/// The deciding pair's answer becomes the union's (keeping the tallies).
void decide(PieceOutcome& out, const Outcome& pair, const Candidate& c) {
  Outcome& o = out.outcome;
  o.intersect = pair.intersect;
  o.distance = pair.distance;
  o.witness_a = pair.witness_a;
  o.witness_b = pair.witness_b;
  o.upper_bound = pair.upper_bound;
  o.exact = pair.exact;
  out.piece_a = c.a;
  out.piece_b = c.b;
}

}  // namespace

PieceOutcome run_on_pieces(const AlgorithmInfo& algorithm, std::span<const Polytope> a,
                           std::span<const Polytope> b, const AlgorithmOptions& options) {
  if (a.empty() || b.empty()) throw std::invalid_argument("a non-convex pair needs pieces");
  PieceOutcome out;
  out.piece_pairs = static_cast<std::uint64_t>(a.size()) * b.size();
  const bool boolean_only = algorithm.kind == AnswerKind::boolean;
  double best = std::numeric_limits<double>::infinity();
  for (const Candidate& c : candidates(a, b)) {
    if (boolean_only ? c.box_gap_squared > 0 : beyond(c.box_gap_squared, best)) break;
    const Outcome pair = run_algorithm(algorithm, a[c.a], b[c.b], {}, options);
    ++out.piece_pairs_tested;
    tally(out.outcome, pair);
    const double distance = pair.intersect ? 0 : pair.distance.value_or(best);
    if (pair.intersect || out.piece_a < 0 || distance < best) {
      decide(out, pair, c);
      best = distance;
    }
    if (pair.intersect) break;
  }
  return out;
}

}  // namespace gjklab::experiment
