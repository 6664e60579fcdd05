// The HDF5 results archive: round trip of every field and attribute, the temporary-file rule,
// refusals before any work, and a check that h5py reads the documented dtypes.
#include <catch2/catch.hpp>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <unistd.h>

#include "gjklab/experiment/archive/archive.hpp"

namespace fs = std::filesystem;
using namespace gjklab;
using namespace gjklab::experiment;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A fresh folder under the system temporary folder, removed with everything in it.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    std::random_device rd;
    path_ = fs::temp_directory_path() / ("gjklab-archive-test-" + std::to_string(::getpid()) + "-" +
                                         std::to_string(counter++) + "-" + std::to_string(rd()));
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const fs::path& path() const { return path_; }
  fs::path operator/(const std::string& name) const { return path_ / name; }

 private:
  fs::path path_;
};

fs::path tmp_of(const fs::path& p) {
  fs::path t = p;
  t += ".tmp";
  return t;
}

ArchiveHeader make_header(bool oracle) {
  ArchiveHeader h;
  h.experiment_name = "round-trip";
  h.experiment_text = "# experiment\nname = \"round-trip\"\nseed = 42\n# σ ≤ 1e-6 — ünïcödé\n";
  for (int i = 0; i < 2000; ++i)  // larger than 64 KiB: beyond the compact attribute limit
    h.experiment_text +=
        "[[family]]\nshape = \"sphere_points\"  # line " + std::to_string(i) + "\n";
  h.seed = 0xFEDCBA9876543210ULL;
  h.cases_planned = 50;
  h.start_time = "2024-05-01T12:00:00Z";
  h.provenance = {{"gjklab_version", "0.1.0"}, {"git_commit", "0123456789ab"},
                  {"compiler", "GNU 12.2.0"},  {"cxx_flags", "-O3 -DNDEBUG"},
                  {"cgal_version", "5.5.1"},   {"eigen_version", "3.4.0"},
                  {"hdf5_version", "1.10.8"},  {"gsl_version", "2.7.1"},
                  {"libccd_version", "2.1"},   {"note", "naïve — “quoted”"}};
  h.family_names = {"spheres", "boxes", "gaussian µ"};
  h.algorithm_names = {"gjk-johnson", "gjk-bool"};
  h.algorithm_options = {{{"max_iterations", "64"}, {"tolerance", "1e-12"}},
                         {{"max_iterations", "128"}}};
  h.oracle = oracle;
  h.touching_band = 2.5e-10;
  return h;
}

CaseResult make_result(std::uint64_t i, bool oracle) {
  CaseResult r;
  CaseRecord& c = r.record;
  c.case_id = 1000 + i;
  c.family = static_cast<std::uint32_t>(i % 3);
  c.shape_a = static_cast<ShapeKind>(i % 8);
  c.shape_b = static_cast<ShapeKind>((i + 3) % 8);
  c.placement = static_cast<Placement>(i % 3);
  c.vertices_a = static_cast<std::int32_t>(8 + i);
  c.vertices_b = static_cast<std::int32_t>(100 - i);
  c.scale = 0.5 + static_cast<double>(i);
  c.size = std::sqrt(3.0) * static_cast<double>(i + 1);
  c.intended_gap = i % 4 == 0 ? kNaN : (i % 2 == 0 ? 1e-7 : -0.25) * static_cast<double>(i);
  c.radius_a = i % 3 == 0 ? 0.0 : 0.125 * static_cast<double>(i);
  c.radius_b = 1.0 / static_cast<double>(i + 3);
  if (oracle) {
    ExactRecord& e = r.exact.emplace();
    e.intersect = i % 2 == 1;
    e.distance = e.intersect ? 0.0 : 1.0 / static_cast<double>(i + 1);
    e.distance2_num = std::to_string(i) + std::string(i * 7, '9');  // up to ~350 digits
    e.distance2_den = "1" + std::string(i * 5, '0');
    e.depth = i % 3 == 0 ? kNaN : 0.125 * static_cast<double>(i);
    e.hull_vertices_a = static_cast<std::int32_t>(i % 17);
    e.hull_vertices_b = static_cast<std::int32_t>(i % 11);
    e.contact = static_cast<ContactClass>(i % 3);
  }
  for (int k = 0; k < 2; ++k) {
    AlgorithmRecord& a = r.algorithms.emplace_back();
    a.intersect = (i + static_cast<std::uint64_t>(k)) % 2 == 0;
    a.distance = k == 1 ? kNaN : 1.0 / static_cast<double>(i + 2);
    a.abs_error = k == 1 ? kNaN : 1e-17 * static_cast<double>(i);
    a.rel_error = k == 1 ? kNaN : 1e-16 * static_cast<double>(i);
    a.boolean_correct = i % 5 != 0;
    a.iterations = static_cast<std::int32_t>(i * 3 + static_cast<std::uint64_t>(k));
    a.support_calls = static_cast<std::int32_t>(i * 4 + 1);
    a.termination = kAllTerminations[(i + static_cast<std::uint64_t>(k)) % kAllTerminations.size()];
    a.time_ns = i % 6 == 0 ? kNaN : 125.5 * static_cast<double>(i);
    a.failure = static_cast<FailureClass>(i % 9);
    a.depth = i % 4 == 0 ? kNaN : 0.25 * static_cast<double>(i);
    a.depth_abs_error = i % 4 == 0 ? kNaN : 1e-17 * static_cast<double>(i);
    a.depth_rel_error = i % 4 == 0 ? kNaN : 3e-18 * static_cast<double>(i);
  }
  if (i % 7 == 3) {  // some cases keep their geometry, one of them with an empty cloud
    CaseGeometry& g = r.geometry.emplace();
    for (std::uint64_t j = 0; j < 4 + i % 5; ++j)
      g.a.emplace_back(static_cast<double>(i), static_cast<double>(j),
                       -0.5 * static_cast<double>(j));
    if (i != 10)
      for (std::uint64_t j = 0; j < 3 + i % 4; ++j)
        g.b.emplace_back(1e-300 * static_cast<double>(j), 1e300, static_cast<double>(i + j));
  }
  return r;
}

std::vector<CaseResult> make_results(std::size_t n, bool oracle) {
  std::vector<CaseResult> rs;
  for (std::uint64_t i = 0; i < n; ++i)
    rs.push_back(make_result(i, oracle));
  return rs;
}

bool same(double x, double y) {
  return (std::isnan(x) && std::isnan(y)) || x == y;
}

void check_same_header(const ArchiveHeader& x, const ArchiveHeader& y) {
  CHECK(x.experiment_name == y.experiment_name);
  CHECK(x.experiment_text == y.experiment_text);
  CHECK(x.seed == y.seed);
  CHECK(x.cases_planned == y.cases_planned);
  CHECK(x.start_time == y.start_time);
  CHECK(x.provenance == y.provenance);
  CHECK(x.family_names == y.family_names);
  CHECK(x.algorithm_names == y.algorithm_names);
  CHECK(x.algorithm_options == y.algorithm_options);
  CHECK(x.oracle == y.oracle);
  CHECK(x.touching_band == y.touching_band);
}

void check_same_result(const CaseResult& x, const CaseResult& y) {
  INFO("case " << x.record.case_id);
  CHECK(x.record.case_id == y.record.case_id);
  CHECK(x.record.family == y.record.family);
  CHECK(x.record.shape_a == y.record.shape_a);
  CHECK(x.record.shape_b == y.record.shape_b);
  CHECK(x.record.placement == y.record.placement);
  CHECK(x.record.vertices_a == y.record.vertices_a);
  CHECK(x.record.vertices_b == y.record.vertices_b);
  CHECK(same(x.record.scale, y.record.scale));
  CHECK(same(x.record.size, y.record.size));
  CHECK(same(x.record.intended_gap, y.record.intended_gap));
  CHECK(same(x.record.radius_a, y.record.radius_a));
  CHECK(same(x.record.radius_b, y.record.radius_b));

  REQUIRE(x.exact.has_value() == y.exact.has_value());
  if (x.exact) {
    CHECK(x.exact->intersect == y.exact->intersect);
    CHECK(same(x.exact->distance, y.exact->distance));
    CHECK(x.exact->distance2_num == y.exact->distance2_num);
    CHECK(x.exact->distance2_den == y.exact->distance2_den);
    CHECK(same(x.exact->depth, y.exact->depth));
    CHECK(x.exact->hull_vertices_a == y.exact->hull_vertices_a);
    CHECK(x.exact->hull_vertices_b == y.exact->hull_vertices_b);
    CHECK(x.exact->contact == y.exact->contact);
  }

  REQUIRE(x.algorithms.size() == y.algorithms.size());
  for (std::size_t k = 0; k < x.algorithms.size(); ++k) {
    INFO("algorithm " << k);
    const AlgorithmRecord& a = x.algorithms[k];
    const AlgorithmRecord& b = y.algorithms[k];
    CHECK(a.intersect == b.intersect);
    CHECK(same(a.distance, b.distance));
    CHECK(same(a.abs_error, b.abs_error));
    CHECK(same(a.rel_error, b.rel_error));
    CHECK(a.boolean_correct == b.boolean_correct);
    CHECK(a.iterations == b.iterations);
    CHECK(a.support_calls == b.support_calls);
    CHECK(a.termination == b.termination);
    CHECK(same(a.time_ns, b.time_ns));
    CHECK(a.failure == b.failure);
    CHECK(same(a.depth, b.depth));
    CHECK(same(a.depth_abs_error, b.depth_abs_error));
    CHECK(same(a.depth_rel_error, b.depth_rel_error));
  }

  REQUIRE(x.geometry.has_value() == y.geometry.has_value());
  if (x.geometry) {
    CHECK(x.geometry->a == y.geometry->a);
    CHECK(x.geometry->b == y.geometry->b);
  }
}

/// Writes `results` in batches of the given sizes and finishes the archive.
void write_archive(const fs::path& file, const ArchiveHeader& header,
                   const std::vector<CaseResult>& results, std::vector<std::size_t> batches,
                   bool complete = true) {
  ArchiveWriter writer(file, header, false);
  std::size_t at = 0;
  for (std::size_t b : batches) {
    writer.append(std::span<const CaseResult>(results).subspan(at, b));
    at += b;
  }
  REQUIRE(at == results.size());
  writer.finish("2024-05-01T12:34:56Z", complete);
}

std::string python() {
  return GJKLAB_PYTHON3;
}

int run(const std::string& command) {
  return std::system(command.c_str());
}

std::string shell_word(const std::string& s) {
  return "'" + s + "'";
}

void require_h5py() {
  if (run(shell_word(python()) + " -c 'import h5py, numpy' 2>/dev/null") != 0)
    FAIL(python() + " cannot import h5py and numpy (tools/setup installs python3-h5py)");
}

}  // namespace

TEST_CASE("archive round trip: every field and attribute, three batches", "[unit][archive]") {
  const TempDir dir;
  const fs::path file = dir / "run.h5";
  const ArchiveHeader header = make_header(true);
  const std::vector<CaseResult> results = make_results(50, true);
  write_archive(file, header, results, {17, 0, 20, 13});

  const Archive a = read_archive(file);
  CHECK(a.schema_version == kArchiveSchemaVersion);
  CHECK(a.complete);
  CHECK(a.end_time == "2024-05-01T12:34:56Z");
  check_same_header(a.header, header);
  REQUIRE(a.results.size() == results.size());
  for (std::size_t i = 0; i < results.size(); ++i)
    check_same_result(a.results[i], results[i]);

  // The synthetic cases cover every enum value, NaNs and geometry.
  int kept = 0;
  for (const CaseResult& r : a.results)
    kept += r.geometry ? 1 : 0;
  CHECK(kept == 7);
  CHECK(std::isnan(a.results[0].exact->depth));
  CHECK(std::isnan(a.results[0].algorithms[1].distance));
  CHECK(a.results[10].geometry->b.empty());
}

TEST_CASE("archive with the oracle off has no exact records", "[unit][archive]") {
  const TempDir dir;
  const fs::path file = dir / "no-oracle.h5";
  ArchiveHeader header = make_header(false);
  header.family_names.clear();  // an empty string array attribute is fine too
  const std::vector<CaseResult> results = make_results(12, false);
  write_archive(file, header, results, {5, 7});

  const Archive a = read_archive(file);
  check_same_header(a.header, header);
  REQUIRE(a.results.size() == 12);
  for (std::size_t i = 0; i < results.size(); ++i) {
    CHECK_FALSE(a.results[i].exact.has_value());
    check_same_result(a.results[i], results[i]);
  }
}

TEST_CASE("archive with no cases and no algorithms reads back empty", "[unit][archive]") {
  const TempDir dir;
  const fs::path file = dir / "empty.h5";
  ArchiveHeader header = make_header(true);
  header.algorithm_names.clear();
  header.algorithm_options.clear();
  header.cases_planned = 0;
  write_archive(file, header, {}, {});
  const Archive a = read_archive(file);
  CHECK(a.complete);
  CHECK(a.results.empty());
  CHECK(a.header.algorithm_names.empty());
  CHECK(a.header.algorithm_options.empty());
}

TEST_CASE("archive is written to FILE.tmp and renamed only when complete", "[unit][archive]") {
  const TempDir dir;
  const fs::path file = dir / "run.h5";
  const fs::path tmp = tmp_of(file);
  const ArchiveHeader header = make_header(true);
  const std::vector<CaseResult> results = make_results(9, true);

  SECTION("finish(complete) renames the temporary file") {
    ArchiveWriter writer(file, header, false);
    CHECK(writer.temporary_path() == tmp);
    CHECK(fs::exists(tmp));
    CHECK_FALSE(fs::exists(file));
    writer.append(results);
    CHECK(fs::exists(tmp));
    CHECK_FALSE(fs::exists(file));
    writer.finish("end", true);
    CHECK(fs::exists(file));
    CHECK_FALSE(fs::exists(tmp));
    const Archive a = read_archive(file);
    CHECK(a.complete);
    CHECK(a.results.size() == 9);
    CHECK_THROWS_AS(writer.finish("end", true), ArchiveError);
    CHECK_THROWS_AS(writer.append(results), ArchiveError);
  }
  SECTION("finish(incomplete) keeps the temporary name and complete = 0") {
    {
      ArchiveWriter writer(file, header, false);
      writer.append(results);
      writer.finish("interrupted", false);
    }
    CHECK_FALSE(fs::exists(file));
    REQUIRE(fs::exists(tmp));
    const Archive a = read_archive(tmp);
    CHECK_FALSE(a.complete);
    CHECK(a.end_time == "interrupted");
    CHECK(a.results.size() == 9);
  }
  SECTION("an unfinished writer leaves only the temporary file") {
    {
      ArchiveWriter writer(file, header, false);
      writer.append(std::span<const CaseResult>(results).first(4));
    }
    CHECK_FALSE(fs::exists(file));
    REQUIRE(fs::exists(tmp));
    const Archive a = read_archive(tmp);  // readable: no end time, not complete
    CHECK_FALSE(a.complete);
    CHECK(a.end_time.empty());
    REQUIRE(a.results.size() == 4);
    check_same_result(a.results[3], results[3]);
  }
  SECTION("overwrite replaces an existing archive only when the new one is complete") {
    write_archive(file, header, results, {9});
    ArchiveHeader second = header;
    second.experiment_name = "second";
    {
      ArchiveWriter writer(file, second, true);
      writer.append(results);
    }
    CHECK(read_archive(file).header.experiment_name == "round-trip");
    {
      ArchiveWriter writer(file, second, true);  // truncates the stale temporary file
      writer.append(results);
      writer.finish("end", true);
    }
    CHECK(read_archive(file).header.experiment_name == "second");
    CHECK_FALSE(fs::exists(tmp));
  }
}

TEST_CASE("archive writer refuses before creating anything", "[unit][archive]") {
  const TempDir dir;
  const ArchiveHeader header = make_header(true);

  SECTION("existing output without overwrite") {
    const fs::path file = dir / "old.h5";
    std::ofstream(file) << "previous results";
    try {
      ArchiveWriter writer(file, header, false);
      FAIL("no error");
    } catch (const ArchiveError& e) {
      CHECK(std::string(e.what()) == file.string() + " exists (use --force to overwrite)");
    }
    CHECK_FALSE(fs::exists(tmp_of(file)));
    std::ifstream in(file);
    std::string content;
    std::getline(in, content);
    CHECK(content == "previous results");
  }
  SECTION("a folder that does not exist") {
    const fs::path file = dir / "missing" / "run.h5";
    try {
      ArchiveWriter writer(file, header, false);
      FAIL("no error");
    } catch (const ArchiveError& e) {
      const std::string message = e.what();
      CHECK_THAT(message, Catch::Contains(file.string()));
      CHECK_THAT(message, Catch::Contains("does not exist"));
    }
    CHECK_FALSE(fs::exists(dir / "missing"));
  }
  SECTION("a header the layout cannot hold") {
    ArchiveHeader bad = header;
    bad.algorithm_names.push_back("a/b");
    bad.algorithm_options.push_back({});
    CHECK_THROWS_WITH(ArchiveWriter(dir / "bad.h5", bad, false),
                      Catch::Contains("a/b") && Catch::Contains("bad.h5"));
    ArchiveHeader clash = header;
    clash.provenance.emplace_back("seed", "1");
    CHECK_THROWS_WITH(ArchiveWriter(dir / "clash.h5", clash, false), Catch::Contains("seed"));
    CHECK(fs::is_empty(dir.path()));
  }
}

TEST_CASE("archive writer rejects results that do not match the header", "[unit][archive]") {
  const TempDir dir;
  ArchiveWriter writer(dir / "run.h5", make_header(true), false);
  std::vector<CaseResult> one_algorithm = make_results(1, true);
  one_algorithm[0].algorithms.pop_back();
  CHECK_THROWS_WITH(writer.append(one_algorithm),
                    Catch::Contains("1 algorithm records, expected 2"));
  CHECK_THROWS_WITH(writer.append(make_results(1, false)), Catch::Contains("no exact record"));
  writer.append(make_results(3, true));  // nothing was written by the refused batches
  writer.finish("end", true);
  CHECK(read_archive(dir / "run.h5").results.size() == 3);
}

TEST_CASE("read_archive names the file it cannot read", "[unit][archive]") {
  const TempDir dir;
  const fs::path missing = dir / "nothing.h5";
  CHECK_THROWS_WITH(read_archive(missing), Catch::Contains(missing.string()));
  const fs::path text = dir / "text.h5";
  std::ofstream(text) << "not hdf5\n";
  CHECK_THROWS_WITH(read_archive(text),
                    Catch::Contains(text.string()) && Catch::Contains("not an HDF5 file"));
}

TEST_CASE("h5py reads the archive with the documented dtypes", "[smoke][archive]") {
  require_h5py();
  const TempDir dir;
  const fs::path file = dir / "run.h5";
  write_archive(file, make_header(true), make_results(50, true), {25, 25});
  const std::string script = std::string(GJKLAB_TESTS_DIR) + "/archive_check.py";
  CHECK(run(shell_word(python()) + " " + shell_word(script) + " " + shell_word(file.string())) ==
        0);

  const fs::path no_oracle = dir / "no-oracle.h5";
  write_archive(no_oracle, make_header(false), make_results(5, false), {5});
  CHECK(run(shell_word(python()) + " " + shell_word(script) + " " +
            shell_word(no_oracle.string())) == 0);
}

TEST_CASE("read_archive names a missing dataset", "[smoke][archive]") {
  require_h5py();
  const TempDir dir;
  const fs::path file = dir / "run.h5";
  write_archive(file, make_header(true), make_results(5, true), {5});
  const std::string remove_depth =
      " -c 'import h5py, sys; f = h5py.File(sys.argv[1], \"r+\"); del f[\"exact/depth\"]' ";
  REQUIRE(run(shell_word(python()) + remove_depth + shell_word(file.string())) == 0);
  CHECK_THROWS_WITH(read_archive(file),
                    Catch::Contains(file.string()) && Catch::Contains("/exact/depth"));
}

TEST_CASE("an archive older than the optional columns reads their defaults", "[smoke][archive]") {
  require_h5py();
  const TempDir dir;
  const fs::path file = dir / "run.h5";
  auto results = make_results(6, true);
  for (CaseResult& r : results)
    for (AlgorithmRecord& a : r.algorithms) {
      a.rounded_exact_distance = 0.5;
      a.rounded_exact_depth = 0.25;
    }
  write_archive(file, make_header(true), results, {6});
  // The columns added after the first archives of schema version 2 (radius_* with swept
  // shapes, rounded_exact_* with the precision option), removed as an older writer lacked them.
  const std::string remove_optional =
      " -c 'import h5py, sys; f = h5py.File(sys.argv[1], \"r+\"); "
      "[f[\"cases\"].pop(k) for k in (\"radius_a\", \"radius_b\")]; "
      "[f[\"algorithms/\" + a].pop(k) for a in (\"gjk-johnson\", \"gjk-bool\") "
      "for k in (\"rounded_exact_distance\", \"rounded_exact_depth\")]' ";
  REQUIRE(run(shell_word(python()) + remove_optional + shell_word(file.string())) == 0);
  const Archive a = read_archive(file);
  REQUIRE(a.results.size() == 6);
  for (const CaseResult& r : a.results) {
    CHECK(r.record.radius_a == 0.0);
    CHECK(r.record.radius_b == 0.0);
    for (const AlgorithmRecord& ar : r.algorithms) {
      CHECK(std::isnan(ar.rounded_exact_distance));
      CHECK(std::isnan(ar.rounded_exact_depth));
    }
  }
  // A required column is never defaulted: the same removal of one fails, naming it.
  const std::string remove_required =
      " -c 'import h5py, sys; f = h5py.File(sys.argv[1], \"r+\"); "
      "del f[\"algorithms/gjk-bool/witness_error_a\"]' ";
  REQUIRE(run(shell_word(python()) + remove_required + shell_word(file.string())) == 0);
  CHECK_THROWS_WITH(read_archive(file), Catch::Contains("/algorithms/gjk-bool/witness_error_a"));
}
