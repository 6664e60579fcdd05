// Closed meshes: exact::read_closed_mesh, the mesh readers with faces kept (gjklab's PLY
// reader, CGAL's OFF, OBJ and STL readers in src/exact/) and every check of a closed mesh
// (exact predicates, CGAL's self-intersection and nesting tests).
//
// Input: one byte choosing the extension, then the file's bytes. The contract: either a mesh
// (at least one face, every index in range, every coordinate finite and within the limit,
// accepted again by validate_closed_mesh) or a std::runtime_error whose message starts with
// the file's name; any other exception is reported as a crash.
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>

#include "gjklab/exact/closed_mesh.hpp"
#include "support.hpp"

namespace {

constexpr const char* kNames[] = {"mesh.off", "mesh.obj", "mesh.ply", "mesh.stl",
                                  "MESH.OFF", "MESH.OBJ", "MESH.PLY", "MESH.STL"};

void check_mesh(const gjklab::TriangleMesh& mesh) {
  if (mesh.faces.empty()) gjklab::fuzz::violated("read_closed_mesh returned no face");
  for (const auto& face : mesh.faces)
    for (std::uint32_t v : face)
      if (v >= mesh.vertices.size()) gjklab::fuzz::violated("a face index out of range");
  for (const auto& p : mesh.vertices)
    if (!(p.cwiseAbs().maxCoeff() <= gjklab::exact::kMaxMeshCoordinate))
      gjklab::fuzz::violated("a coordinate non-finite or beyond the limit");
  try {
    gjklab::exact::validate_closed_mesh(mesh, "accepted mesh");
  } catch (const std::runtime_error&) {
    gjklab::fuzz::violated("validate_closed_mesh refused a mesh read_closed_mesh accepted");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const char* name = kNames[data[0] % std::size(kNames)];
  const auto path = gjklab::fuzz::write_scratch_file(name, std::span(data + 1, size - 1));
  try {
    check_mesh(gjklab::exact::read_closed_mesh(path));
  } catch (const std::runtime_error& e) {
    if (!std::string(e.what()).starts_with(path.string()))
      gjklab::fuzz::violated("a refusal that does not name the file");
  }
  return 0;
}
