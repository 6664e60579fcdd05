// The queries themselves: `gjklab query` runs the selected algorithms of the registry
// (experiment::run_algorithm) on a pair of point clouds, optionally sphere-swept.
//
// Input: a compact encoding of two small adversarial clouds (decode_pair below): huge, tiny,
// subnormal, repeated, nearly equal and flat coordinates, with optional radii, an exact depth
// request and an iteration bound, as a user can give them with --radius-a/-b, --depth and
// --max-iterations; then one byte choosing the query (select_queries below): one registered
// algorithm, or the exact pair (`exact` and `gjk-certified`, with the QP alone). An input
// without that byte chooses by a hash of its bytes. Every algorithm is reached across inputs;
// one input runs one query, because the exact arithmetic is almost all of the cost (measured
// over the corpus under ASan: `exact`, `gjk-certified` and the QP alone 85 % of the time,
// `sat` 12 %, the 16 other algorithms together 2 %): running it on every input would keep
// every input at about its earlier cost, and every algorithm at the same few inputs. With
// GJKLAB_FUZZ_QUERY_ALL set, every input runs every algorithm and the exact pair (the
// target's earlier form), e.g. to replay a corpus with all checks at once.
// Properties, each a trap when violated:
//  - the algorithm run answers with a termination (a value of the enum), and an answer
//    reported as converged has no NaN in it and no negative distance or depth;
//  - the exact pair: `exact` and `gjk-certified` answer the pair (the properties above), with
//    the same exact rationals (intersect, squared distance, squared depth) as each other and
//    as the oracle's QP alone (exact::solve_swept with the certificates off), the independent
//    path, whenever a certificate gave part of the answer (otherwise that answer already is
//    the QP's).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "gjklab/exact/oracle.hpp"
#include "gjklab/experiment/cases/cloud_io.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"
#include "support.hpp"

namespace {

using gjklab::Polytope;
using gjklab::SweptRadii;
using gjklab::Vec3;
using gjklab::fuzz::violated;
namespace experiment = gjklab::experiment;
namespace exact = gjklab::exact;

/// Reads the input byte by byte; past the end it gives zeros.
class ByteReader {
 public:
  explicit ByteReader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}
  std::uint8_t byte() { return pos_ < bytes_.size() ? bytes_[pos_++] : 0; }
  bool at_end() const { return pos_ >= bytes_.size(); }
  double raw_double() {
    std::uint64_t bits = 0;
    for (int k = 0; k < 8; ++k)
      bits |= std::uint64_t{byte()} << (8 * k);
    double x;
    std::memcpy(&x, &bits, sizeof x);
    return x;
  }

 private:
  std::span<const std::uint8_t> bytes_;
  std::size_t pos_ = 0;
};

constexpr double kMax = std::numeric_limits<double>::max();

/// Values that break floating-point code: the extremes, subnormals, one ulp above 1, square
/// roots of the extremes (whose squares overflow or underflow), and plain ones.
constexpr double kPalette[] = {
    0,       1,           0.5,     0.1,    1.0 / 3, 3,      7,
    1e-8,    1e-12,       1e-100,  1e-154, 1e-300,  5e-324, 2.2250738585072014e-308,
    0x1p-52, 1 + 0x1p-52, 0x1p53,  1e8,    1e16,    1e100,  1e154,
    1e200,   1e300,       1.5e308, kMax,   1e-7,    1e-200, 0x1p-1074 * 3};

/// Exponents for small integers scaled by a power of two (exact, so flat and collinear
/// configurations stay exact).
constexpr int kExponents[] = {0,   -1,   -2,   -10,   -26,   -52,  10, 26, 52, 100, -100,
                              500, -500, 1000, -1000, -1070, 1020, 3,  -3, 20, -20, 60,
                              -60, 200,  -200, 300,   -300,  0,    0,  0,  0,  0};

double decode_any(ByteReader& in, const std::vector<double>& earlier) {
  const std::uint8_t tag = in.byte();
  const double previous = earlier.empty() ? 0.0 : earlier.back();
  switch (tag % 8) {
    case 0:
      return in.raw_double();
    case 1: {
      const double x = kPalette[in.byte() % std::size(kPalette)];
      return (tag & 8) ? -x : x;
    }
    case 2:
      return std::ldexp(static_cast<std::int8_t>(in.byte()), kExponents[(tag >> 3) % 32]);
    case 3:
      return previous;
    case 4:
      return earlier.empty() ? 0.0 : earlier[in.byte() % earlier.size()];
    case 5: {
      // A few ulps away from the previous coordinate: nearly coincident points.
      const int steps = static_cast<std::int8_t>(in.byte()) % 8;
      double x = previous;
      for (int k = 0; k < std::abs(steps); ++k)
        x = std::nextafter(x, steps > 0 ? kMax : -kMax);
      return x;
    }
    case 6:
      return -previous;
    default:
      return static_cast<std::int8_t>(in.byte());
  }
}

/// One coordinate. The readers refuse non-finite coordinates, so the largest finite ones stand
/// in for infinities and NaNs (raw bytes, or a small integer scaled beyond the double range).
double decode_coordinate(ByteReader& in, const std::vector<double>& earlier) {
  const double x = decode_any(in, earlier);
  return std::isfinite(x) ? x : std::copysign(kMax, x);
}

std::vector<Vec3> decode_cloud(ByteReader& in, int n, std::vector<double>& earlier) {
  std::vector<Vec3> cloud;
  for (int i = 0; i < n; ++i) {
    Vec3 p;
    for (int k = 0; k < 3; ++k) {
      p[k] = decode_coordinate(in, earlier);
      earlier.push_back(p[k]);
    }
    cloud.push_back(p);
  }
  return cloud;
}

constexpr double kRadii[] = {0, 0.5, 1, 1e-8, 1e-300, 1e8, 1e150, 1e300};
constexpr int kMaxPoints = 10;  ///< per cloud: small clouds keep every input within milliseconds

struct FuzzPair {
  std::vector<Vec3> a, b;
  SweptRadii radii;
  bool depth = false;      ///< --depth
  int max_iterations = 0;  ///< --max-iterations (0: each algorithm's default)
  std::uint8_t query = 0;  ///< which query runs (select_queries)
};

/// FNV-1a of the input: the query of an input that has no byte left to choose it (every input
/// of the corpus grown before the byte existed), so that such inputs spread over all queries.
std::uint8_t hash_byte(std::span<const std::uint8_t> bytes) {
  std::uint64_t h = 14695981039346656037ull;
  for (const std::uint8_t c : bytes)
    h = (h ^ c) * 1099511628211ull;
  return static_cast<std::uint8_t>(h ^ (h >> 8) ^ (h >> 16) ^ (h >> 24));
}

FuzzPair decode_pair(std::span<const std::uint8_t> bytes) {
  ByteReader in(bytes);
  FuzzPair p;
  const int na = 1 + in.byte() % kMaxPoints;
  const int nb = 1 + in.byte() % kMaxPoints;
  const std::uint8_t flags = in.byte();
  p.depth = flags & 1;
  p.radii = {kRadii[(flags >> 1) & 7], kRadii[(flags >> 4) & 7]};
  if (flags & 0x80) p.max_iterations = 1 + in.byte() % 64;
  std::vector<double> earlier;
  p.a = decode_cloud(in, na, earlier);
  p.b = decode_cloud(in, nb, earlier);
  p.query = in.at_end() ? hash_byte(bytes) : in.byte();
  return p;
}

void check_outcome(const experiment::AlgorithmInfo& algorithm, const experiment::Outcome& o) {
  const std::string name(algorithm.name);
  if (static_cast<int>(o.termination) > static_cast<int>(gjklab::Termination::invalid_input))
    violated(name + ": a termination outside the enum");
  if (o.termination != gjklab::Termination::converged) return;
  auto bad = [](const std::optional<double>& x) { return x && std::isnan(*x); };
  auto bad_vec = [](const std::optional<Vec3>& v) { return v && v->array().isNaN().any(); };
  if (bad(o.distance) || bad(o.depth) || bad_vec(o.normal) || bad_vec(o.witness_a) ||
      bad_vec(o.witness_b))
    violated(name + ": a NaN in an answer reported as converged");
  if ((o.distance && *o.distance < 0) || (o.depth && *o.depth < 0))
    violated(name + ": a negative distance or depth reported as converged");
}

bool same(const exact::Rational& x, const exact::Rational& y) {
  return x == y;
}

/// Exact rationals of two answers agree (the depth where both have one).
void check_agree(const exact::OracleAnswer& x, const exact::OracleAnswer& y, const char* what) {
  if (x.intersect != y.intersect) violated(std::string(what) + ": intersect differs");
  if (!same(x.distance_squared, y.distance_squared))
    violated(std::string(what) + ": squared distance differs");
  if (x.depth_squared && y.depth_squared && !same(*x.depth_squared, *y.depth_squared))
    violated(std::string(what) + ": squared depth differs");
}

/// Whether a certificate gave any part of the answer. If none did, the certified path already
/// answered with the QP (and the Minkowski hull for the depth) on the same clouds: the same
/// computation as the QP alone, which could not differ. The QP alone is about half of this
/// target's time per input (measured), so it is skipped then.
bool certified_anything(const exact::OracleAnswer& x) {
  return x.method == exact::AnswerMethod::certified ||
         x.depth_method == exact::AnswerMethod::certified;
}

/// The largest binary exponent span of the nonzero coordinates of the two clouds beyond which
/// the QP alone is not run: CGAL's QP works on exact binary floats (Gmpzf), whose integers grow
/// with that span, and on a pair with coordinates from 1e-323 to 67 (a span of 1080) it ran for
/// more than 10 minutes in the release build (the certified path answered in 15 ms). 128 keeps
/// every pair of the experiments' scales checked.
constexpr int kQpExponentSpan = 128;

/// Whether the clouds' nonzero coordinates span at most kQpExponentSpan binary orders.
bool qp_affordable(std::span<const gjklab::Vec3> a, std::span<const gjklab::Vec3> b) {
  int lowest = std::numeric_limits<int>::max(), highest = std::numeric_limits<int>::min();
  for (const auto cloud : {a, b})
    for (const gjklab::Vec3& p : cloud)
      for (int k = 0; k < 3; ++k) {
        if (p[k] == 0) continue;
        const int e = std::ilogb(p[k]);
        lowest = std::min(lowest, e);
        highest = std::max(highest, e);
      }
  return lowest > highest || highest - lowest <= kQpExponentSpan;
}

/// With GJKLAB_FUZZ_PRINT_CASE set, each input is first printed as a `gjklab query --cases`
/// line (with its options), so that a crash input becomes a regression case.
void print_case(const FuzzPair& pair, const std::vector<const experiment::AlgorithmInfo*>& run) {
  if (!std::getenv("GJKLAB_FUZZ_PRINT_CASE")) return;
  const experiment::PointCase c{"fuzz", pair.a, pair.b, pair.radii.a, pair.radii.b};
  std::string names;
  for (const auto* algorithm : run)
    names += (names.empty() ? "" : ",") + std::string(algorithm->name);
  std::printf("%s\n# depth %d, max_iterations %d, algorithms %s\n",
              experiment::case_to_json_line(c).c_str(), pair.depth ? 1 : 0, pair.max_iterations,
              names.c_str());
  std::fflush(stdout);
}

bool is_exact_pair(const experiment::AlgorithmInfo& algorithm) {
  return algorithm.name == "exact" || algorithm.name == "gjk-certified";
}

/// The algorithms one input runs. The candidates are the registered algorithms that handle the
/// pair's radii, in the registry's order; the query byte picks one of them (modulo their
/// number), and picking `exact` or `gjk-certified` runs both (the exact pair: 2 of the 19
/// choices for point pairs). With GJKLAB_FUZZ_QUERY_ALL set: every candidate.
std::vector<const experiment::AlgorithmInfo*> select_queries(const FuzzPair& pair) {
  std::vector<const experiment::AlgorithmInfo*> candidates;
  for (const experiment::AlgorithmInfo& algorithm : experiment::algorithms())
    if (experiment::handles(algorithm, pair.radii)) candidates.push_back(&algorithm);
  static const bool all = std::getenv("GJKLAB_FUZZ_QUERY_ALL") != nullptr;
  if (all || candidates.empty()) return candidates;
  const experiment::AlgorithmInfo* chosen = candidates[pair.query % candidates.size()];
  if (!is_exact_pair(*chosen)) return {chosen};
  std::vector<const experiment::AlgorithmInfo*> both;
  for (const auto* algorithm : candidates)
    if (is_exact_pair(*algorithm)) both.push_back(algorithm);
  return both;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const FuzzPair pair = decode_pair(std::span(data, size));
  const std::vector<const experiment::AlgorithmInfo*> run = select_queries(pair);
  print_case(pair, run);
  const Polytope a(pair.a), b(pair.b);
  experiment::AlgorithmOptions options;
  if (pair.max_iterations > 0) options.set_max_iterations(pair.max_iterations);
  options.oracle.depth = pair.depth;

  bool exact_pair = false;
  std::optional<exact::OracleAnswer> from_exact, from_certified;
  for (const experiment::AlgorithmInfo* algorithm : run) {
    experiment::Outcome o;
    try {
      o = experiment::run_algorithm(*algorithm, a, b, pair.radii, options);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%.*s: %s\n", static_cast<int>(algorithm->name.size()),
                   algorithm->name.data(), e.what());
      violated("an algorithm threw on two finite clouds instead of answering");
    }
    check_outcome(*algorithm, o);
    exact_pair = exact_pair || is_exact_pair(*algorithm);
    if (algorithm->name == "exact") from_exact = o.exact;
    if (algorithm->name == "gjk-certified") from_certified = o.exact;
  }
  if (!exact_pair) return 0;
  if (!from_exact || !from_certified) violated("exact or gjk-certified gave no exact answer");
  check_agree(*from_exact, *from_certified, "exact vs gjk-certified");
  if (!certified_anything(*from_certified) || !qp_affordable(pair.a, pair.b)) return 0;
  exact::OracleOptions qp_only;
  qp_only.depth = pair.depth;
  qp_only.certificates = false;
  qp_only.hull_vertices = false;
  const exact::OracleAnswer qp =
      exact::solve_swept(pair.a, pair.b, pair.radii.a, pair.radii.b, qp_only);
  check_agree(*from_certified, qp, "gjk-certified vs the QP alone");
  return 0;
}
