// Degenerate and adversarial families: exact contact, flat and collinear clouds, duplicates,
// slivers, scale disparity, offsets and cases read from a file — checked with the exact oracle.
#include <catch2/catch.hpp>

#include <unistd.h>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include "gjklab/exact/oracle.hpp"
#include "gjklab/experiment/cases/cloud_io.hpp"
#include "gjklab/experiment/config/config.hpp"
#include "gjklab/experiment/cases/families.hpp"

using namespace gjklab;
using namespace gjklab::experiment;

namespace {

ExperimentConfig parse(const std::string& families, const std::string& source = "deg.toml") {
  return parse_experiment("name = \"deg\"\nseed = 5\ncases = 100\n" + families +
                              "\n[[algorithm]]\nname = \"gjk-johnson\"\n",
                          source);
}

}  // namespace

TEST_CASE("contact families touch exactly, for every contact type", "[unit][families]") {
  for (const char* type :
       {"face-face", "edge-edge", "vertex-face", "edge-face", "vertex-edge", "vertex-vertex"}) {
    const auto config = parse(std::string("[[family]]\nshape = \"contact\"\ncontact = \"") + type +
                              "\"\nscale = 0.25\n[family.placement]\nmode = \"touching\"\n");
    for (std::uint64_t i = 0; i < 8; ++i) {
      const GeneratedCase c = generate_case(config, i);
      INFO(type << " case " << i);
      CHECK(c.record.placement == Placement::touching);
      const auto exact = exact::solve(c.a, c.b, {.depth = true});
      CHECK(exact.intersect);
      CHECK(exact.distance_squared.is_zero());
      // Contact, not overlap: the Minkowski difference has the origin on its boundary.
      CHECK(exact.depth_squared->is_zero());
    }
  }
}

TEST_CASE("contact families separated or penetrating by epsilon", "[unit][families]") {
  const auto config = parse(
      "[[family]]\nshape = \"contact\"\ncontact = \"any\"\n"
      "[family.placement]\nmode = \"mixed\"\ngap = [1e-6, 1e-3]\ndepth = [1e-6, 1e-3]\n");
  int separated = 0, penetrating = 0;
  std::set<ShapeKind> shapes;
  for (std::uint64_t i = 0; i < 40; ++i) {
    const GeneratedCase c = generate_case(config, i);
    const auto exact = exact::solve(c.a, c.b);
    const double eps = std::abs(c.record.intended_gap);
    INFO("case " << i << " intended gap " << c.record.intended_gap);
    REQUIRE(eps >= 1e-6);
    if (c.record.placement == Placement::separated) {
      ++separated;
      CHECK_FALSE(exact.intersect);
      // The gap along the contact normal is the distance (up to the rounding of the shift).
      CHECK(exact.distance == Approx(eps * c.record.size).epsilon(1e-6));
    } else {
      ++penetrating;
      CHECK(exact.intersect);
    }
    shapes.insert(c.record.shape_b);
  }
  CHECK(separated > 5);
  CHECK(penetrating > 5);
  CHECK(shapes.size() >= 2);  // "any" draws several contact types
}

TEST_CASE("parallel-edges contact: ridges at a small angle cross at the origin",
          "[unit][families]") {
  const auto config = parse(
      "[[family]]\nshape = \"contact\"\ncontact = \"parallel-edges\"\nangle = [1e-9, 1e-2]\n"
      "[family.placement]\nmode = \"separated\"\ngap = 1e-4\n");
  for (std::uint64_t i = 0; i < 10; ++i) {
    const GeneratedCase c = generate_case(config, i);
    const auto exact = exact::solve(c.a, c.b);
    CHECK_FALSE(exact.intersect);
    CHECK(exact.distance == Approx(1e-4 * c.record.size).epsilon(1e-6));
  }
}

TEST_CASE("flat and collinear clouds stay exactly flat under axis rotations", "[unit][families]") {
  const auto config = parse(
      "[[family]]\nshape = \"flat_points\"\nvertices = 20\nrotate = \"axes\"\n"
      "[[family]]\nshape = \"collinear_points\"\nvertices = 9\nrotate = \"axes\"\n"
      "[[family]]\nshape = \"duplicate_points\"\nvertices = 12\n"
      "[[family]]\nshape = \"single_point\"\n");
  std::set<std::uint32_t> seen;
  for (std::uint64_t i = 0; i < 60; ++i) {
    const GeneratedCase c = generate_case(config, i);
    seen.insert(c.record.family);
    const int hull = exact::hull_vertex_count(c.a);
    INFO("case " << i << " family " << c.record.family);
    switch (c.record.family) {
      case 0: {
        // One coordinate is the same for every point: exactly coplanar in an axis plane.
        bool flat = false;
        for (int k = 0; k < 3; ++k) {
          bool same = true;
          for (const Vec3& p : c.a)
            same = same && p[k] == c.a[0][k];
          flat = flat || same;
        }
        CHECK(flat);
        CHECK(hull >= 3);
        break;
      }
      case 1:
        CHECK(hull == 2);
        break;
      case 2:
        CHECK(hull <= 3);
        break;
      case 3:
        CHECK(c.a.size() == 1);
        CHECK(hull == 1);
        break;
    }
  }
  CHECK(seen.size() == 4);
}

TEST_CASE("slivers, scale disparity and offsets", "[unit][families]") {
  const auto config = parse(
      "[[family]]\nname = \"slivers\"\nshape = \"sliver\"\naspect = [1e5, 1e6]\nrotate = false\n"
      "[[family]]\nname = \"disparity\"\nshape = \"cube_points\"\nvertices = 8\nscale = 1e4\n"
      "scale_b = 1e-8\n"
      "[[family]]\nname = \"far\"\nshape = \"box\"\noffset = [1e8, 1e9]\n");
  for (std::uint64_t i = 0; i < 30; ++i) {
    const GeneratedCase c = generate_case(config, i);
    INFO("case " << i);
    if (c.record.family == 0) {
      // Extent along z is 1/aspect.
      double lo = INFINITY, hi = -INFINITY;
      for (const Vec3& p : c.a)
        lo = std::min(lo, p.z()), hi = std::max(hi, p.z());
      CHECK(hi - lo <= 1e-5);
      CHECK(hi - lo >= 1e-6 * (1 - 1e-12));
    } else if (c.record.family == 1) {
      CHECK(pair_size(c.a, c.a) > 1e3 * pair_size(c.b, c.b) * 1e4);
    } else {
      CHECK(c.a[0].norm() > 0.9e8);
    }
  }
}

TEST_CASE("file family: pairs read from a cases file, in order, exactly", "[unit][families]") {
  const auto dir =
      std::filesystem::temp_directory_path() / ("gjklab-file-family-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  {
    std::ofstream f(dir / "pairs.jsonl");
    f << case_to_json_line({"p0", {Vec3(0.1, 0.2, 0.3)}, {Vec3(1, 1, 1), Vec3(2, 2, 2)}}) << "\n";
    f << case_to_json_line({"p1", {Vec3(0, 0, 0)}, {Vec3(0, 0, 1e-300)}}) << "\n";
  }
  const std::string experiment = (dir / "exp.toml").string();
  const auto config = parse("[[family]]\nshape = \"file\"\npath = \"pairs.jsonl\"\n", experiment);
  const GeneratedCase c0 = generate_case(config, 0), c1 = generate_case(config, 1),
                      c2 = generate_case(config, 2);
  CHECK(c0.a[0] == Vec3(0.1, 0.2, 0.3));
  CHECK(c1.b[0] == Vec3(0, 0, 1e-300));
  CHECK(c2.a == c0.a);
  CHECK(c0.record.placement == Placement::as_given);
  CHECK(c0.record.shape_a == ShapeKind::from_file);

  // A bad line in the cases file is a config error naming both files.
  {
    std::ofstream f(dir / "bad.jsonl");
    f << "{\"id\": \"x\", \"a\": [], \"b\": [[0,0,0]]}\n";
  }
  CHECK_THROWS_WITH(parse("[[family]]\nshape = \"file\"\npath = \"bad.jsonl\"\n", experiment),
                    Catch::Contains("exp.toml:6: key 'family[0].path'") &&
                        Catch::Contains("bad.jsonl:1: case 'x': cloud a: empty point cloud"));
  std::filesystem::remove_all(dir);
}
