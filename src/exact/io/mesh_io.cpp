#include "gjklab/exact/mesh_io.hpp"

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "exact/io/mesh_soup.hpp"
#include "exact/io/ply_reader.hpp"
#include "gjklab/geometry/polytope.hpp"

namespace gjklab::exact {

namespace {
using Point = CGAL::Simple_cartesian<double>::Point_3;

std::string lower_extension(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}
/// Whitespace-separated words of a header line.
std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string w; in >> w;)
    out.push_back(w);
  return out;
}

/// A count of vertices (`what` = "vertex", "vertices") or of another PLY element a header
/// declares, checked against the file's size (every item takes at least one byte), so that a
/// corrupt count fails here with its line instead of as an allocation of gigabytes inside the
/// reader.
void check_count(const std::string& name, int line, const std::string& text,
                 std::uintmax_t file_size, const std::string& what = "vertex",
                 const std::string& plural = "vertices") {
  unsigned long long count = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), count);
  if (ec != std::errc() || end != text.data() + text.size())
    throw std::runtime_error(name + ":" + std::to_string(line) + ": " + what + " count '" + text +
                             "' is not a non-negative integer");
  if (count > file_size)
    throw std::runtime_error(name + ":" + std::to_string(line) + ": declares " + text + " " +
                             plural + ", more than the file's " + std::to_string(file_size) +
                             " bytes can hold");
}
void check_vertex_count(const std::string& name, int line, const std::string& text,
                        std::uintmax_t file_size) {
  check_count(name, line, text, file_size);
}

/// A vertex property line, "property TYPE NAME" or "property list COUNT_TYPE TYPE NAME" (words
/// after the name are ignored, as CGAL's reader ignores them): x, y and z must be scalars of a
/// floating-point type, because CGAL's reader casts them to float or double properties without
/// checking (a list, or an integer type such as int32, made it call through a null pointer).
void check_ply_coordinate_type(const std::string& name, int number,
                               const std::vector<std::string>& w) {
  const bool list = w[1] == "list";
  const std::size_t name_word = list ? 4 : 2;
  if (w.size() <= name_word) return;  // CGAL refuses the line itself
  const std::string& property = w[name_word];
  if (property != "x" && property != "y" && property != "z") return;
  const std::string where = name + ":" + std::to_string(number) + ": vertex property '" + property;
  if (list) throw std::runtime_error(where + "' is a list; coordinates must be scalars");
  const std::string& type = w[1];
  if (type != "float" && type != "float32" && type != "double" && type != "float64")
    throw std::runtime_error(where + "' has type '" + type +
                             "'; coordinates must be float or double");
}

/// The checks of a PLY header that CGAL's reader does not make (it crashed on them): the
/// element counts, every property inside an element (CGAL adds a property to the last element
/// read, with no check that there is one), and x, y, z declared as scalar properties (not
/// lists).
void check_ply_header(const std::filesystem::path& file, std::uintmax_t file_size) {
  const std::string name = file.string();
  std::ifstream in(file, std::ios::binary);
  std::string line;
  bool in_element = false;
  bool in_vertex = false;
  for (int number = 1; number <= 1000 && std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto w = words(line);
    if (w.empty()) continue;
    if (w[0] == "end_header") return;
    if (w[0] == "element") {
      in_element = true;
      in_vertex = w.size() >= 3 && w[1] == "vertex";
      if (in_vertex)
        check_vertex_count(name, number, w[2], file_size);
      else if (w.size() >= 3)  // faces and the rest: CGAL reads (and allocates) them too
        check_count(name, number, w[2], file_size, "element '" + w[1] + "'",
                    "'" + w[1] + "' elements");
    } else if (w[0] == "property" && !in_element && number > 2) {
      // Lines 1 and 2 are the "ply" and format lines, whatever they hold (CGAL's own checks).
      throw std::runtime_error(name + ":" + std::to_string(number) +
                               ": a property before any element (declare 'element NAME COUNT' "
                               "first)");
    } else if (w[0] == "property" && in_vertex && w.size() >= 2) {
      check_ply_coordinate_type(name, number, w);
    }
  }
  throw std::runtime_error(name + ": no end_header within the first 1000 lines of the PLY header");
}

/// The vertex count of an OFF header (its first count line), checked as above.
void check_off_header(const std::filesystem::path& file, std::uintmax_t file_size) {
  const std::string name = file.string();
  std::ifstream in(file, std::ios::binary);
  std::string line;
  bool header_seen = false;
  for (int number = 1; number <= 1000 && std::getline(in, line); ++number) {
    if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    auto w = words(line);
    if (w.empty()) continue;
    if (!header_seen && w[0].size() <= 4 && w[0].ends_with("OFF")) {
      header_seen = true;
      w.erase(w.begin());  // counts may follow the keyword on the same line
      if (w.empty()) continue;
    }
    check_vertex_count(name, number, w[0], file_size);
    return;
  }
}

/// Whether `token` reads as a vertex index of [0, count): an integral, finite number.
bool is_vertex_index(const std::string& token, unsigned long long count) {
  double value = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && end == token.data() + token.size() && value >= 0 &&
         value < static_cast<double>(count) && value == std::floor(value);
}

/// The face lines of a text OFF file, checked before CGAL reads them: CGAL reads a face line's
/// entries as doubles and converts the vertex indices to an unsigned integer, which is undefined
/// for a negative, huge or non-finite number (a fuzzed file had 2e75). Every index must be a
/// vertex index; the header and counts are check_off_header's, binary files CGAL's.
void check_off_faces(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::ifstream in(file, std::ios::binary);
  std::string line;
  enum class Part { keyword, counts, vertices, faces } part = Part::keyword;
  unsigned long long vertices = 0, read = 0;
  for (int number = 1; std::getline(in, line); ++number) {
    if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    auto w = words(line);
    if (w.empty()) continue;
    if (part == Part::keyword) {
      part = Part::counts;
      if (w[0].size() <= 4 && w[0].ends_with("OFF")) {
        if (std::find(w.begin(), w.end(), "BINARY") != w.end()) return;
        w.erase(w.begin());
        if (w.empty()) continue;
      }
    }
    if (part == Part::counts) {
      const auto [end, ec] = std::from_chars(w[0].data(), w[0].data() + w[0].size(), vertices);
      if (ec != std::errc()) return;  // check_off_header refused it already
      part = vertices == 0 ? Part::faces : Part::vertices;
    } else if (part == Part::vertices) {
      if (++read == vertices) part = Part::faces;
    } else {
      unsigned long long size = 0;
      std::from_chars(w[0].data(), w[0].data() + w[0].size(), size);
      for (std::size_t k = 1; k < w.size() && k <= size; ++k)
        if (!is_vertex_index(w[k], vertices))
          throw std::runtime_error(name + ":" + std::to_string(number) + ": face index '" + w[k] +
                                   "' is not a vertex index (an integer in [0, " +
                                   std::to_string(vertices) + "))");
    }
  }
}

}  // namespace

bool is_mesh_file(const std::filesystem::path& file) {
  const std::string ext = lower_extension(file);
  return ext == ".off" || ext == ".obj" || ext == ".ply" || ext == ".stl";
}

namespace detail {

MeshSoup read_mesh_soup(const std::filesystem::path& file, bool keep_faces) {
  const std::string name = file.string();
  if (!is_mesh_file(file))
    throw std::runtime_error(name + ": not a mesh file (use .off, .obj, .ply or .stl)");
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw std::runtime_error(name + ": no such file");
  const std::uintmax_t file_size = std::filesystem::file_size(file, ec);
  if (ec) throw std::runtime_error(name + ": cannot read the file size");
  const std::string ext = lower_extension(file);
  if (ext == ".ply") {
    check_ply_header(file, file_size);
    return read_ply_mesh(file, keep_faces);
  }
  if (ext == ".off") {
    check_off_header(file, file_size);
    check_off_faces(file);
  }
  std::vector<Point> points;
  MeshSoup soup;
  bool read = false;
  try {
    read = CGAL::IO::read_polygon_soup(name, points, soup.faces);
  } catch (const std::exception& e) {
    // CGAL's readers let the standard library's exceptions through: a PLY list whose count is
    // negative (a signed type) becomes a resize to 2^64 - 1 elements and std::length_error.
    throw std::runtime_error(name + ": cannot read the mesh (" + e.what() + ")");
  }
  if (!read) throw std::runtime_error(name + ": cannot read the mesh (malformed file?)");
  // CGAL's STL reader already merges exactly equal points (a map from point to index, filled
  // in order of first appearance), so every format gives shared vertices here.
  if (!keep_faces) soup.faces.clear();
  soup.vertices.reserve(points.size());
  for (const Point& p : points)
    soup.vertices.emplace_back(p.x(), p.y(), p.z());
  return soup;
}

}  // namespace detail

std::vector<Vec3> read_mesh_vertices(const std::filesystem::path& file) {
  std::vector<Vec3> cloud = detail::read_mesh_soup(file, false).vertices;
  if (const std::string problem = describe_invalid_cloud(cloud); !problem.empty())
    throw std::runtime_error(file.string() + ": " + problem);
  return cloud;
}

std::vector<std::filesystem::path> mesh_files(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_directory(path, ec)) {
    if (!std::filesystem::exists(path, ec))
      throw std::runtime_error(path.string() + ": no such file or folder");
    return {path};
  }
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(path, ec))
    if (entry.is_regular_file() && is_mesh_file(entry.path())) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  if (files.empty())
    throw std::runtime_error(path.string() + " holds no .off, .obj, .ply or .stl file");
  return files;
}

}  // namespace gjklab::exact
