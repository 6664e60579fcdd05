// Mesh files as shapes: the vertices of OFF, OBJ, PLY and STL files, and the mesh family.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <set>

#include "gjklab/exact/mesh_io.hpp"
#include "gjklab/exact/oracle.hpp"
#include "gjklab/experiment/config/config.hpp"
#include "gjklab/experiment/cases/families.hpp"

using namespace gjklab;

namespace {
std::string mesh(const char* name) {
  return std::string(GJKLAB_TEST_DATA_DIR) + "/meshes/" + name;
}
}  // namespace

TEST_CASE("mesh files: the vertices of each format, hulls as expected", "[unit][mesh]") {
  struct Expected {
    const char* file;
    std::size_t vertices;
    int hull;
  };
  for (const Expected& e : {Expected{"tetrahedron.off", 4, 4}, Expected{"octahedron.obj", 6, 6},
                            Expected{"wedge.ply", 6, 6}, Expected{"cube.stl", 8, 8}}) {
    INFO(e.file);
    const auto cloud = exact::read_mesh_vertices(mesh(e.file));
    CHECK(cloud.size() == e.vertices);
    CHECK(exact::hull_vertex_count(cloud) == e.hull);
  }
  // The octahedron's vertices are on the axes at distance 1.
  for (const Vec3& v : exact::read_mesh_vertices(mesh("octahedron.obj")))
    CHECK(v.norm() == 1.0);
}

TEST_CASE("mesh files: bad files are errors naming the file", "[unit][mesh]") {
  CHECK_THROWS_WITH(exact::read_mesh_vertices(mesh("missing.off")),
                    Catch::Contains("missing.off: no such file"));
  CHECK_THROWS_WITH(exact::read_mesh_vertices(mesh("../tetra.xyz")),
                    Catch::Contains("not a mesh file"));
  const auto bad = std::filesystem::temp_directory_path() / "gjklab-bad-mesh.off";
  std::ofstream(bad) << "OFF\n3 1 0\n0 0 0\n1 0\n";
  CHECK_THROWS_WITH(exact::read_mesh_vertices(bad), Catch::Contains("gjklab-bad-mesh.off"));
  std::filesystem::remove(bad);
}

TEST_CASE("mesh family: shapes drawn from a folder of meshes, placed like any shape",
          "[unit][mesh][families]") {
  const std::string experiment = std::string(GJKLAB_TEST_DATA_DIR) + "/mesh_experiment.toml";
  const auto config = experiment::parse_experiment(
      "name = \"meshes\"\nseed = 3\ncases = 40\n[[family]]\nshape = \"mesh\"\npath = "
      "\"meshes\"\n[family.placement]\nmode = \"separated\"\ngap = 0.01\n"
      "[[algorithm]]\nname = \"gjk-johnson\"\n",
      experiment);
  REQUIRE(config.families[0].meshes.size() == 4);
  std::set<std::size_t> sizes;
  for (std::uint64_t i = 0; i < 40; ++i) {
    const auto c = experiment::generate_case(config, i);
    CHECK(c.record.shape_a == experiment::ShapeKind::mesh);
    sizes.insert(c.a.size());
    // Separated along the placement axis by 1% of the size: the exact distance is at least that.
    const auto exact = exact::solve(c.a, c.b);
    CHECK_FALSE(exact.intersect);
    CHECK(exact.distance >= 0.01 * c.record.size * (1 - 1e-12));
  }
  CHECK(sizes.size() >= 3);  // several meshes were drawn
  CHECK_THROWS_WITH(
      experiment::parse_experiment(
          "name = \"m\"\nseed = 1\ncases = 1\n[[family]]\nshape = \"mesh\"\n"
          "path = \"no-such-folder\"\n[[algorithm]]\nname = \"gjk-bool\"\n",
          experiment),
      Catch::Contains("key 'family[0].path'") && Catch::Contains("no-such-folder: no such file"));
}
