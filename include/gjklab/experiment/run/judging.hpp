// How the driver turns answers into the archive's published numbers: the exact answer's
// record and contact class, each algorithm's record judged against it, the witness errors,
// and which cases keep their geometry. Plain functions of plain values, tested with hand-made
// records (tests/unit/test_measuring.cpp).
#pragma once

#include <span>

#include "gjklab/exact/oracle.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"
#include "gjklab/experiment/cases/records.hpp"

namespace gjklab::experiment {

/// The exact answer's class for an absolute band (length units: touching_band · size):
/// separated, touching (distance, or depth when computed, within the band), or intersecting.
ContactClass contact_class(const exact::OracleAnswer& answer, double band);

/// The archive's record of an exact answer, classified with the absolute band.
ExactRecord exact_record(const exact::OracleAnswer& answer, double band);

/// The algorithm's own answer, as recorded (its errors are judge()'s).
AlgorithmRecord algorithm_record(const Outcome& o);

/// Sets the record's errors and correctness against the exact answer (distance and depth
/// errors absolute and divided by the pair's size), all of them, so that a record judged again
/// (after the exact depth arrived) keeps nothing stale.
void judge(AlgorithmRecord& r, const Outcome& o, const ExactRecord& exact, double size);

/// The algorithm's witness points and, for polytopes with an exact answer, their exact errors
/// (see AlgorithmRecord); a and b are the clouds.
void add_witnesses(AlgorithmRecord& r, const Outcome& o, const exact::OracleAnswer* exact,
                   std::span<const Vec3> a, std::span<const Vec3> b);

/// Whether the exact depth must be computed to judge the answers: the pair intersects, its
/// depth was not asked for, and some answer says separated. That answer may be inside the
/// touching band, which only the depth can tell. (A query stopped by its step limit fails by
/// its termination anyway: its disagreement alone does not pay for the depth, the costliest
/// exact computation, in step-limit sweeps.)
bool needs_exact_depth(const exact::OracleAnswer& answer, std::span<const AlgorithmRecord> records);

/// A case keeps its geometry when any answer is wrong, any query did not converge, or any
/// distance error exceeds the band (relative to size).
bool worth_keeping(const CaseResult& r, double relative_band);

}  // namespace gjklab::experiment
