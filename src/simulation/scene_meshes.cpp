#include "scene_meshes.hpp"

#include <exception>
#include <stdexcept>
#include <string>

#include "gjklab/exact/closed_mesh.hpp"
#include "gjklab/exact/mesh_io.hpp"
#include "gjklab/experiment/meshes/decompositions.hpp"

namespace gjklab::simulation {

namespace {

/// The decomposition of `decomposition` with the options of `decomposition_options` (each
/// value an integer, a number or a boolean, checked by the registry).
const experiment::DecompositionInfo& decomposition_of(const SceneTable& t,
                                                      experiment::DecompositionOptions& options) {
  const std::string name = t.string("decomposition", "");
  const experiment::DecompositionInfo* d = nullptr;
  try {
    d = &experiment::decomposition_named(name);
  } catch (const std::invalid_argument& e) {
    t.fail("decomposition", e.what());
  }
  const SceneTable opts = t.child("decomposition_options");
  for (const auto& [key, node] : opts.raw()) {
    const std::string k(key.str());
    std::string text;
    if (const auto i = node.value_exact<std::int64_t>())
      text = std::to_string(*i);
    else if (const auto b = node.value_exact<bool>())
      text = *b ? "true" : "false";
    else if (node.is_floating_point())
      text = experiment::round_trip(*node.value<double>());
    else
      opts.fail(k, "expected an integer, a number or true/false");
    try {
      experiment::set_decomposition_option(*d, options, k, text);
    } catch (const std::invalid_argument& e) {
      opts.fail(k, e.what());
    }
  }
  return *d;
}

/// `file` read as a closed mesh and scaled; a ConfigError at `path` (or `size`, when only the
/// scaled mesh fails the checks) naming the file.
TriangleMesh closed_mesh(const SceneTable& t, const std::filesystem::path& file,
                         const Vec3& scale) {
  TriangleMesh mesh;
  try {
    mesh = exact::read_closed_mesh(file);
  } catch (const std::runtime_error& e) {
    t.fail("path", e.what());
  }
  if (scale == Vec3::Ones()) return mesh;
  for (Vec3& v : mesh.vertices)
    v = v.cwiseProduct(scale);
  // A positive scaling keeps a valid mesh valid, but rounding may make a thin face flat.
  try {
    exact::validate_closed_mesh(mesh, file.string() + " scaled by `size`");
  } catch (const std::runtime_error& e) {
    t.fail("size", e.what());
  }
  return mesh;
}

/// `message` starting with the file's name (the registry's messages mostly do already).
std::string naming(const std::filesystem::path& file, const std::string& message) {
  const std::string name = file.string();
  return message.rfind(name, 0) == 0 ? message : name + ": " + message;
}

}  // namespace

std::vector<std::filesystem::path> mesh_paths(const SceneTable& t) {
  const std::string path = t.string("path", "");
  if (path.empty()) t.fail("path", "missing (shape = \"mesh\" needs a mesh file or a folder)");
  std::filesystem::path resolved(path);
  if (resolved.is_relative()) resolved = std::filesystem::path(t.file()).parent_path() / resolved;
  try {
    return exact::mesh_files(resolved);
  } catch (const std::runtime_error& e) {
    t.fail("path", e.what());
  }
}

std::vector<std::shared_ptr<const scene::CompoundShape>> mesh_compounds(const SceneTable& t,
                                                                        const Vec3& scale) {
  experiment::DecompositionOptions options;
  const experiment::DecompositionInfo& d = decomposition_of(t, options);
  std::vector<std::shared_ptr<const scene::CompoundShape>> out;
  for (const std::filesystem::path& file : mesh_paths(t)) {
    const TriangleMesh mesh = closed_mesh(t, file, scale);
    experiment::Decomposition pieces;
    try {
      pieces = d.decompose(mesh, file.string(), options);
    } catch (const std::exception& e) {
      t.fail("decomposition", naming(file, e.what()));
    }
    try {
      out.push_back(scene::make_compound_shape(mesh, pieces.pieces));
    } catch (const std::invalid_argument& e) {
      t.fail("decomposition", naming(file, std::string(d.name) + " decomposition: " + e.what()));
    }
  }
  return out;
}

}  // namespace gjklab::simulation
