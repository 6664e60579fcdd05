// The real_object family: convex hulls of the meshes of Debian's libcgal-demo, at unit size.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <set>

#include "gjklab/exact/oracle.hpp"
#include "gjklab/experiment/config/config.hpp"
#include "gjklab/experiment/cases/families.hpp"
#include "gjklab/experiment/cases/real_objects.hpp"

using namespace gjklab;
namespace ex = gjklab::experiment;

namespace {

std::string experiment_with(const std::string& family_keys) {
  return "name = \"real\"\nseed = 4\ncases = 30\n[[family]]\n" + family_keys +
         "\n[family.placement]\nmode = \"random\"\nspread = 0.4\n"
         "[[algorithm]]\nname = \"gjk-johnson\"\n";
}

/// Sets an environment variable for the scope, restoring the old value after.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() {
    if (old_)
      setenv(name_, old_->c_str(), 1);
    else
      unsetenv(name_);
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

}  // namespace

TEST_CASE("real_object family: named objects are their hulls at unit size",
          "[unit][families][real_object]") {
  const auto config = ex::parse_experiment(
      experiment_with("shape = \"real_object\"\nobjects = [\"elephant\", \"cow\", \"fandisk\"]"),
      "real.toml");
  const ex::FamilySpec& family = config.families[0];
  REQUIRE(family.objects == std::vector<std::string>{"elephant", "cow", "fandisk"});
  REQUIRE(family.meshes.size() == 3);
  CHECK(family.name == "real_object");
  for (const auto& hull : family.meshes) {
    // Every point is a hull vertex (interior mesh vertices are gone) ...
    CHECK(exact::hull_vertex_count(hull) == static_cast<int>(hull.size()));
    CHECK(hull.size() > 20);
    // ... and the farthest from the bounding box's centre is at distance 1.
    Vec3 lower = hull[0], upper = hull[0];
    for (const Vec3& p : hull) {
      lower = lower.cwiseMin(p);
      upper = upper.cwiseMax(p);
    }
    double radius = 0;
    for (const Vec3& p : hull)
      radius = std::max(radius, (p - 0.5 * (lower + upper)).norm());
    CHECK(radius == Approx(1.0).epsilon(1e-14));
    CHECK((lower + upper).norm() < 1e-12);
  }
}

TEST_CASE("real_object family: cases are rotated objects, separated and overlapping",
          "[unit][families][real_object]") {
  const auto config = ex::parse_experiment(
      experiment_with("shape = \"real_object\"\nobjects = [\"elephant\", \"cow\"]"), "real.toml");
  const std::set<std::size_t> hull_sizes = {config.families[0].meshes[0].size(),
                                            config.families[0].meshes[1].size()};
  int separated = 0, overlapping = 0;
  std::set<double> first_coordinates;
  for (std::uint64_t i = 0; i < 30; ++i) {
    const ex::GeneratedCase c = ex::generate_case(config, i);
    CHECK(hull_sizes.count(c.a.size()) == 1);
    CHECK(hull_sizes.count(c.b.size()) == 1);
    CHECK(c.record.shape_a == ex::ShapeKind::mesh);
    first_coordinates.insert(c.a[0].x());
    const bool intersect = exact::solve(c.a, c.b).intersect;
    separated += !intersect;
    overlapping += intersect;
  }
  // Random rotations: the same object never comes out the same way twice.
  CHECK(first_coordinates.size() == 30);
  CHECK(separated > 5);
  CHECK(overlapping > 5);
}

TEST_CASE("real_object family: \"all\" is every object of the package",
          "[unit][families][real_object]") {
  const auto names = ex::real_object_names();
  CHECK(names.size() > 100);
  CHECK(std::is_sorted(names.begin(), names.end()));
  for (const char* known : {"elephant", "cow", "armadillo", "bunny00", "femur", "pig"})
    CHECK(std::count(names.begin(), names.end(), known) == 1);
}

TEST_CASE("real_object family: mistakes are errors naming the key and the choices",
          "[unit][families][real_object]") {
  CHECK_THROWS_WITH(
      ex::parse_experiment(
          experiment_with("shape = \"real_object\"\nobjects = [\"elephant\", \"unicorn\"]"),
          "real.toml"),
      Catch::Contains(
          "real.toml:6: key 'family[0].objects': unknown real object 'unicorn'; valid: ") &&
          Catch::Contains("elephant") && Catch::Contains("cow"));
  CHECK_THROWS_WITH(ex::parse_experiment(experiment_with("shape = \"real_object\""), "real.toml"),
                    Catch::Contains("key 'family[0].objects': missing"));
  CHECK_THROWS_WITH(
      ex::parse_experiment(experiment_with("shape = \"real_object\"\nobjects = []"), "real.toml"),
      Catch::Contains("key 'family[0].objects': expected \"all\" or a non-empty array"));
  CHECK_THROWS_WITH(
      ex::parse_experiment(experiment_with("shape = \"real_object\"\nobjects = [\"cow\", 3]"),
                           "real.toml"),
      Catch::Contains("key 'family[0].objects': expected object names (strings)"));
  CHECK_THROWS_WITH(
      ex::parse_experiment(experiment_with("shape = \"box\"\nobjects = [\"cow\"]"), "real.toml"),
      Catch::Contains("key 'family[0].objects': applies only to shape = \"real_object\""));
}

TEST_CASE("real_object family: without the package, the error names it",
          "[unit][families][real_object]") {
  const auto cache = std::filesystem::temp_directory_path() / "gjklab-real-object-test-cache";
  std::filesystem::remove_all(cache);
  const ScopedEnv cache_dir("GJKLAB_CACHE_DIR", cache.string());
  const ScopedEnv archive("GJKLAB_REAL_OBJECT_ARCHIVE", "/nonexistent/data.tar.gz");
  CHECK_THROWS_WITH(
      ex::parse_experiment(experiment_with("shape = \"real_object\"\nobjects = [\"cow\"]"),
                           "real.toml"),
      Catch::Contains("key 'family[0].objects': real objects: /nonexistent/data.tar.gz is missing; "
                      "install the Debian package libcgal-demo"));
  CHECK_FALSE(std::filesystem::exists(cache / "real-objects"));
}

TEST_CASE("real_object family: the cache is extracted once, then read",
          "[unit][families][real_object]") {
  const auto cache = std::filesystem::temp_directory_path() / "gjklab-real-object-test-fresh";
  std::filesystem::remove_all(cache);
  const ScopedEnv cache_dir("GJKLAB_CACHE_DIR", cache.string());
  const auto folder = ex::real_object_meshes();
  CHECK(folder == cache / "real-objects");
  CHECK(std::filesystem::exists(folder / "elephant.off"));
  // No partial folder is left behind, and a second call reuses the folder.
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(cache))
    ++entries;
  CHECK(entries == 1);
  CHECK(ex::real_object_meshes() == folder);
  CHECK(ex::real_object("tetrahedron").size() == 4);
  std::filesystem::remove_all(cache);
}
