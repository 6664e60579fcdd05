// Reading point clouds and cases from files: .xyz, .off and .obj vertex lists, and the
// JSON-lines case format of `gjklab query --cases`.
//
// JSON-lines format, one case per line:
//   {"id": "name", "a": [[x, y, z], ...], "b": [[x, y, z], ...]}
// Coordinates are JSON numbers; 17 significant digits round-trip a double exactly. A side may
// be a closed triangle mesh in place of a point list (a non-convex solid):
//   "a": {"vertices": [[x, y, z], ...], "faces": [[i, j, k], ...]}
// with faces counter-clockwise seen from outside, validated as exact/closed_mesh.hpp says.
#pragma once

#include <filesystem>
#include <optional>

#include <nlohmann/json.hpp>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "gjklab/geometry/triangle_mesh.hpp"
#include "gjklab/geometry/types.hpp"

namespace gjklab::experiment {

/// A problem with an input file, located by file and line (line 0: the file as a whole).
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, int line, std::string problem);
  const std::string& file() const { return file_; }
  int line() const { return line_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string file_;
  int line_;
  std::string problem_;
};

/// One pair of point clouds to query.
struct PointCase {
  std::string id;
  std::vector<Vec3> a, b;
  /// Sphere-swept shapes: optional "radius_a" and "radius_b" of a cases line (length units,
  /// finite and >= 0; 0 when absent).
  double radius_a = 0;
  double radius_b = 0;
  /// A side given as a closed mesh (then `a` or `b` holds its vertices): validated, never
  /// repaired. A case with a mesh side has no radii.
  std::optional<TriangleMesh> mesh_a, mesh_b;
};

/// A line of a cases file that could not be read, with the id if one was found.
struct CaseError {
  std::string id;
  int line = 0;
  std::string problem;
};

using CaseOrError = std::variant<PointCase, CaseError>;

/// Reads the vertices of a .xyz (x y z per line), .off, .obj, .ply or .stl file (the last two
/// ASCII or binary, with CGAL's readers). Throws InputError naming
/// the file and line for a missing file, an unknown extension, a malformed line, a non-finite
/// coordinate or an empty cloud.
std::vector<Vec3> read_point_file(const std::filesystem::path& path);

/// Parses one JSON line into a case; problems are returned as a CaseError (never thrown).
/// `line` is used for the default id ("line N") and in errors.
CaseOrError parse_case_line(std::string_view text, int line);

/// Checks one cloud of a case the way a cases line is checked (`name` is "a" or "b"): throws
/// std::invalid_argument with the message `gjklab query --cases` reports, e.g.
/// "cloud a: empty point cloud" or "cloud b point 3: non-finite coordinate".
void check_case_cloud(std::span<const Vec3> cloud, const char* name);

/// Checks a case's "radius_a" or "radius_b" (finite, >= 0); throws std::invalid_argument
/// "radius_a: expected a finite number >= 0, got -1".
void check_case_radius(double radius, const char* key);

/// Reads every non-blank line of a cases file. Throws InputError if the file cannot be opened.
std::vector<CaseOrError> read_cases_file(const std::filesystem::path& path);

/// The JSON line of a case, with every coordinate written to round-trip exactly.
std::string case_to_json_line(const PointCase& c);

/// Deepest nesting of arrays and objects a cases line may have (the deepest valid case nests
/// 3 levels: {"a": [[x, y, z], …]}); deeper lines are rejected before they are parsed.
inline constexpr int kMaxJsonDepth = 32;

/// One JSON value as one output line, safe for any bytes: strings that are not valid UTF-8
/// (a case id or a file name read from disk) have each invalid byte replaced by U+FFFD rather
/// than making the whole line, and the program, fail.
/// One side of a cases line: the cloud as [[x, y, z], …], or a mesh as {"vertices", "faces"}
/// (Json: nlohmann::json or nlohmann::ordered_json).
template <class Json>
Json case_side_json(const std::vector<Vec3>& cloud, const std::optional<TriangleMesh>& mesh) {
  auto points = [](const std::vector<Vec3>& pts) {
    Json arr = Json::array();
    for (const Vec3& p : pts)
      arr.push_back({p.x(), p.y(), p.z()});
    return arr;
  };
  if (!mesh) return points(cloud);
  Json faces = Json::array();
  for (const MeshFace& f : mesh->faces)
    faces.push_back({f[0], f[1], f[2]});
  return Json{{"vertices", points(mesh->vertices)}, {"faces", faces}};
}

std::string json_line(const nlohmann::json& j);
std::string json_line(const nlohmann::ordered_json& j);  ///< keys in insertion order

}  // namespace gjklab::experiment
