// Inputs found by the fuzz targets (fuzz/): each one crashed, corrupted memory or broke a
// documented property before its fix. The inputs are data under regression/data/fuzz/ or
// regression/data/hostile/, named after what they hold.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <string>
#include <variant>

#include "gjklab/exact/closed_mesh.hpp"
#include "gjklab/exact/mesh_io.hpp"
#include "gjklab/experiment/archive/archive.hpp"
#include "gjklab/experiment/bench/bench.hpp"
#include "gjklab/experiment/cases/cloud_io.hpp"
#include "gjklab/experiment/registry/algorithms.hpp"

using namespace gjklab;

namespace {

std::string hostile(const char* name) {
  return std::string(GJKLAB_REGRESSION_DATA_DIR) + "/hostile/" + name;
}

/// The one case of a cases file under regression/data/fuzz/.
experiment::PointCase fuzz_case(const char* name) {
  const auto cases =
      experiment::read_cases_file(std::string(GJKLAB_REGRESSION_DATA_DIR) + "/fuzz/" + name);
  REQUIRE(cases.size() == 1);
  REQUIRE(std::holds_alternative<experiment::PointCase>(cases[0]));
  return std::get<experiment::PointCase>(cases[0]);
}

/// No NaN anywhere in an answer reported as converged.
bool converged_answer_is_finite(const experiment::Outcome& o) {
  if (o.termination != Termination::converged) return true;
  auto nan = [](const std::optional<double>& x) { return x && std::isnan(*x); };
  auto nan_vec = [](const std::optional<Vec3>& v) { return v && v->array().isNaN().any(); };
  return !nan(o.distance) && !nan(o.depth) && !nan_vec(o.normal) && !nan_vec(o.witness_a) &&
         !nan_vec(o.witness_b);
}

}  // namespace

TEST_CASE(
    "PLY with a property before any element: a clear error with the line, not an access "
    "before the start of CGAL's element list",
    "[regression][hostile][fuzz]") {
  // CGAL's PLY reader adds each property to its last element, m_elements.back(), without
  // checking that there is one (undefined behaviour; UBSan: offset applied to a null pointer).
  CHECK_THROWS_WITH(exact::read_mesh_vertices(hostile("ply_property_before_element.ply")),
                    Catch::Contains("ply_property_before_element.ply:3") &&
                        Catch::Contains("property before any element"));
  CHECK_THROWS_AS(experiment::read_point_file(hostile("ply_property_before_element.ply")),
                  experiment::InputError);
}

TEST_CASE(
    "PLY declaring 4e9 faces in a 181-byte file: a clear error with the line, not an "
    "allocation of gigabytes in CGAL's reader",
    "[regression][hostile][fuzz]") {
  // As fuzzing found with other elements than vertices (whose count was already checked):
  // CGAL's reader reserves and reads every element the header declares.
  const std::string file =
      std::string(GJKLAB_REGRESSION_DATA_DIR) + "/fuzz/ply_face_count_4e9_in_181_bytes.ply";
  CHECK_THROWS_WITH(exact::read_mesh_vertices(file),
                    Catch::Contains("ply_face_count_4e9_in_181_bytes.ply:7") &&
                        Catch::Contains("declares 4000000000 'face' elements"));
}

TEST_CASE(
    "PLY with z declared int32: a clear error with the line, not a call through a null "
    "pointer in CGAL's reader",
    "[regression][hostile][fuzz]") {
  // CGAL's reader takes every coordinate property to be float or double (dynamic_cast, with
  // only a disabled assertion behind it), so an integer z was a null pointer dereference.
  CHECK_THROWS_WITH(exact::read_mesh_vertices(hostile("ply_z_as_int32.ply")),
                    Catch::Contains("ply_z_as_int32.ply:6") && Catch::Contains("int32"));
}

TEST_CASE(
    "PLY with y declared uint8 and more words on its line: the type of the third word is "
    "checked, as CGAL reads it",
    "[regression][hostile][fuzz]") {
  // "property uint8 y<VT>property float z": CGAL reads the type and the name and ignores the
  // rest; the first check took the line's last word as the name and let the uint8 y through.
  CHECK_THROWS_WITH(
      exact::read_mesh_vertices(hostile("ply_y_as_uint8_then_more_words.ply")),
      Catch::Contains("ply_y_as_uint8_then_more_words.ply:5") && Catch::Contains("uint8"));
}

TEST_CASE(
    "PLY with a face list count of -1 (signed char): a clear error, not std::length_error "
    "out of the program",
    "[regression][hostile][fuzz]") {
  // CGAL's reader resized the list to the count, here 2^64 - 1, and let std::length_error
  // through; `gjklab query` catches InputError only. gjklab's own PLY reader checks each count.
  CHECK_THROWS_WITH(exact::read_mesh_vertices(hostile("ply_face_list_count_minus_1.ply")),
                    Catch::Contains("ply_face_list_count_minus_1.ply") &&
                        Catch::Contains("list count that is not a non-negative integer") &&
                        Catch::Contains("(in face 1 of"));
  CHECK_THROWS_AS(experiment::read_point_file(hostile("ply_face_list_count_minus_1.ply")),
                  experiment::InputError);
}

TEST_CASE(
    "PLY whose face list count (1.7e8) reaches past the end of the file: a clear error, not a "
    "read of 1.7e8 items",
    "[regression][hostile][fuzz]") {
  // CGAL's reader resized the list to the count and read far past the end of the file (tens of
  // seconds, hundreds of MB), as a garbled binary file found by fuzzing made it.
  const std::string file =
      std::string(GJKLAB_REGRESSION_DATA_DIR) + "/fuzz/ply_face_list_count_1.7e8_past_the_end.ply";
  CHECK_THROWS_WITH(exact::read_mesh_vertices(file),
                    Catch::Contains("ply_face_list_count_1.7e8_past_the_end.ply") &&
                        Catch::Contains("list count beyond the end of the file") &&
                        Catch::Contains("(in face 1 of 1)"));
}

TEST_CASE(
    "OFF face index 2e75 (fuzzed), or negative: a clear error with the line, not CGAL's "
    "undefined conversion",
    "[regression][hostile][fuzz]") {
  // CGAL's OFF reader reads a face's entries as doubles and converts the indices to an unsigned
  // integer, undefined for 2e75 (found by fuzzing the closed-mesh reader) and for −3.
  const std::string dir = std::string(GJKLAB_REGRESSION_DATA_DIR) + "/fuzz/";
  for (const char* name : {"off_face_index_2e75.off", "off_face_index_negative.off"}) {
    CHECK_THROWS_WITH(exact::read_mesh_vertices(dir + name),
                      Catch::Contains(name) && Catch::Contains("is not a vertex index"));
    CHECK_THROWS_WITH(exact::read_closed_mesh(dir + name), Catch::Contains(name));
  }
  CHECK_THROWS_WITH(exact::read_mesh_vertices(dir + "off_face_index_2e75.off"),
                    Catch::Contains("off_face_index_2e75.off:11"));
}

TEST_CASE("PLY files with garbled binary headers found by fuzzing: clear errors with the line",
          "[regression][hostile][fuzz]") {
  // Each made CGAL's reader allocate or read hundreds of MB (fuzz inputs, first byte dropped).
  const std::string dir = std::string(GJKLAB_REGRESSION_DATA_DIR) + "/fuzz/";
  CHECK_THROWS_WITH(exact::read_mesh_vertices(dir + "ply_garbled_header_element_count_oom.ply"),
                    Catch::Contains("ply_garbled_header_element_count_oom.ply:4") &&
                        Catch::Contains("unknown PLY type 'vertex'"));
  CHECK_THROWS_WITH(exact::read_mesh_vertices(dir + "ply_garbled_header_list_count_hang.ply"),
                    Catch::Contains("ply_garbled_header_list_count_hang.ply:2") &&
                        Catch::Contains("unknown PLY header line"));
}

TEST_CASE(
    "archive with one byte of /cases/shape_a's enum type flipped: an error, and the "
    "program survives libhdf5's out-of-bounds read",
    "[regression][hostile][fuzz]") {
  // Byte 9430 of a small traced archive, 0 -> 0x43: opening the dataset makes libhdf5's
  // H5T_copy read 68 MB from a 19-byte buffer (an upstream bug), which segfaults. The isolated
  // reader meets it in its child and reports the file as corrupt.
  CHECK_THROWS_AS(experiment::read_archive_isolated(
                      hostile("archive_shape_a_enum_type_byte_flipped_hdf5_overread.h5")),
                  experiment::ArchiveError);
}

TEST_CASE(
    "archive whose experiment_name attribute points into a corrupt global heap: an error "
    "after the time limit, not a read that never ends",
    "[regression][hostile][fuzz]") {
  // Found by fuzzing the archive reader: libhdf5 loops forever in H5HG_read on this file while
  // reading the root attribute experiment_name. The isolated reader's child is killed when the
  // time limit (GJKLAB_ARCHIVE_READ_SECONDS, here 2 s, then 0.5 s as the archive fuzz target
  // sets it) passes, and the file reported corrupt with the limit as given (a fractional limit
  // was once written as "0 s").
  const auto file = hostile("archive_experiment_name_global_heap_hang.h5");
  ::setenv("GJKLAB_ARCHIVE_READ_SECONDS", "2", 1);
  CHECK_THROWS_WITH(experiment::read_archive_isolated(file),
                    Catch::Contains("did not finish within 2 s"));
  ::setenv("GJKLAB_ARCHIVE_READ_SECONDS", "0.5", 1);
  CHECK_THROWS_WITH(experiment::read_archive_isolated(file),
                    Catch::Contains("did not finish within 0.5 s"));
  ::unsetenv("GJKLAB_ARCHIVE_READ_SECONDS");
}

TEST_CASE(
    "bench config with a published scene time of inf: refused with its key, not accepted as a "
    "figure",
    "[regression][fuzz]") {
  // TOML reads `inf` (and `nan`) as numbers; the loader took any number as a published time,
  // and the seed tables printed it and its ratio to the measured time.
  const std::string path =
      std::string(GJKLAB_REGRESSION_DATA_DIR) + "/fuzz/bench_published_scene_ms_inf.toml";
  CHECK_THROWS_WITH(
      experiment::bench::load_bench_config(path),
      Catch::Contains(
          "bench_published_scene_ms_inf.toml:12: key 'published.scene_ms.72': must be finite"));
}

TEST_CASE("bench config with an empty list of suites: refused, not a run that measures nothing",
          "[regression][fuzz]") {
  // `suites = []` was accepted: `gjklab bench` printed its header, measured nothing, exit 0.
  const std::string path =
      std::string(GJKLAB_REGRESSION_DATA_DIR) + "/fuzz/bench_empty_suites.toml";
  CHECK_THROWS_WITH(
      experiment::bench::load_bench_config(path),
      Catch::Contains("bench_empty_suites.toml:1: key 'suites': must name at least one suite"));
}

TEST_CASE(
    "archive whose vertex table claims 2^41 rows in 98 kB: a clear error, not an allocation of "
    "48 TB",
    "[regression][fuzz]") {
  // One damaged dimension: the reader allocated the rows it read from the file (std::bad_alloc
  // from `gjklab inspect`; ASan: allocation-size-too-big). Row counts are now checked against
  // what the file can hold (deflate stores at most 1032 bytes in one) before any allocation.
  const std::string path =
      std::string(GJKLAB_REGRESSION_DATA_DIR) + "/fuzz/archive_vertex_table_2pow41_rows_in_98kB.h5";
  CHECK_THROWS_WITH(experiment::read_archive(path),
                    Catch::Contains("/geometry/") && Catch::Contains("2199023255552 rows") &&
                        Catch::Contains("more than a file of 97564 bytes can hold"));
}

TEST_CASE(
    "archive whose contact column holds a value its enum type does not name: a clear error, "
    "not an index past the summary's table",
    "[regression][fuzz]") {
  // libhdf5 reads such a value as 255; `gjklab inspect` counted contacts in a table of three
  // (UBSan: index 255 out of bounds). Every enum column is now checked as it is read.
  const std::string path =
      std::string(GJKLAB_REGRESSION_DATA_DIR) + "/fuzz/archive_contact_enum_value_unnamed.h5";
  CHECK_THROWS_WITH(experiment::read_archive(path),
                    Catch::Contains("contact row") && Catch::Contains("outside its enum"));
}

#ifdef GJKLAB_HAVE_FCL
TEST_CASE(
    "FCL on cubes with a 1e154 vertex: NaN closest points are a numerical failure, not "
    "converged",
    "[regression][fuzz]") {
  // fcl-libccd's distance query returns a finite distance (177.76) with NaN closest points here
  // (a vertex at 1e154, whose square overflows); the adapter checked only the distance and
  // reported the NaN witnesses as converged.
  const experiment::PointCase c = fuzz_case("fcl_cubes_with_1e154_vertex_overlapping.jsonl");
  const Polytope a(c.a), b(c.b);
  for (const char* name : {"fcl-libccd", "fcl-indep"}) {
    CAPTURE(name);
    const experiment::Outcome o = experiment::run_algorithm(
        *experiment::find_algorithm(name), a, b, SweptRadii{}, experiment::AlgorithmOptions{});
    CHECK(converged_answer_is_finite(o));
  }
}

TEST_CASE(
    "FCL on vertices at 5.9e68 beside features of size 1: refused as invalid input, not a "
    "query that never returns",
    "[regression][fuzz]") {
  // fcl-libccd's collide path runs libccd's MPR, whose loops take no iteration bound: on this
  // pair (found by fuzzing the queries) `gjklab query` with the default algorithms hung.
  const experiment::PointCase c = fuzz_case("fcl_libccd_mpr_hang_vertices_at_5.9e68.jsonl");
  const Polytope a(c.a), b(c.b);
  experiment::AlgorithmOptions options;
  options.oracle.depth = true;
  for (const char* name : {"fcl-libccd", "fcl-indep"}) {
    CAPTURE(name);
    const experiment::Outcome o =
        experiment::run_algorithm(*experiment::find_algorithm(name), a, b, SweptRadii{}, options);
    CHECK(o.termination == Termination::invalid_input);
  }
}

TEST_CASE(
    "FCL on vertices at -9.9e19 beside features of size 1: refused as invalid input, not a "
    "query that never returns",
    "[regression][fuzz]") {
  // Below the former bound of 1e30 on coordinates given to FCL: fcl-libccd's collide path
  // (libccd's MPR, no iteration bound) never returned here, with or without --depth.
  const experiment::PointCase c = fuzz_case("fcl_libccd_mpr_hang_vertices_at_9.9e19.jsonl");
  const Polytope a(c.a), b(c.b);
  for (const bool depth : {false, true}) {
    experiment::AlgorithmOptions options;
    options.oracle.depth = depth;
    for (const char* name : {"fcl-libccd", "fcl-indep"}) {
      CAPTURE(name, depth);
      const experiment::Outcome o =
          experiment::run_algorithm(*experiment::find_algorithm(name), a, b, SweptRadii{}, options);
      CHECK(o.termination == Termination::invalid_input);
    }
  }
}

TEST_CASE(
    "FCL on a vertex at 1e300 against a point at -7e174: refused as invalid input, not an "
    "assertion that aborts the program",
    "[regression][fuzz]") {
  // fcl-libccd's GJK distance asserted "A is not in region 1" (its triple products overflow)
  // and Debian's FCL keeps assertions: `gjklab query` died on this pair.
  const experiment::PointCase c = fuzz_case("fcl_vertex_at_1e300_assertion_abort.jsonl");
  const Polytope a(c.a), b(c.b);
  for (const char* name : {"fcl-libccd", "fcl-indep"}) {
    CAPTURE(name);
    const experiment::Outcome o = experiment::run_algorithm(
        *experiment::find_algorithm(name), a, b, SweptRadii{}, experiment::AlgorithmOptions{});
    CHECK(o.termination == Termination::invalid_input);
  }
}
#endif
