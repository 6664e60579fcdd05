#include "gjklab/experiment/cases/cloud_io.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "gjklab/exact/closed_mesh.hpp"
#include "gjklab/exact/mesh_io.hpp"
#include "gjklab/geometry/polytope.hpp"

namespace gjklab::experiment {

namespace {
/// "FILE:LINE: PROBLEM", or "FILE: PROBLEM" when the problem concerns the whole file.
std::string located(const std::string& file, int line, const std::string& problem) {
  std::string out = file;
  if (line > 0) out.append(":").append(std::to_string(line));
  return out.append(": ").append(problem);
}
}  // namespace

InputError::InputError(std::string file, int line, std::string problem)
    : std::runtime_error(located(file, line, problem)),
      file_(std::move(file)),
      line_(line),
      problem_(std::move(problem)) {}

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front())))
    s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back())))
    s.remove_suffix(1);
  return s;
}

/// Splits on white space and commas.
std::vector<std::string_view> fields(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  auto is_sep = [](char c) { return std::isspace(static_cast<unsigned char>(c)) || c == ','; };
  while (i < s.size()) {
    while (i < s.size() && is_sep(s[i]))
      ++i;
    const std::size_t start = i;
    while (i < s.size() && !is_sep(s[i]))
      ++i;
    if (i > start) out.push_back(s.substr(start, i - start));
  }
  return out;
}

bool parse_double(std::string_view s, double& out) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && end == s.data() + s.size();
}

/// Parses three coordinates from fields[first … first+2]; throws InputError.
Vec3 parse_point(const std::vector<std::string_view>& f, std::size_t first, const std::string& file,
                 int line) {
  if (f.size() < first + 3) throw InputError(file, line, "expected three coordinates");
  Vec3 p;
  for (int k = 0; k < 3; ++k) {
    if (!parse_double(f[first + k], p[k]))
      throw InputError(file, line, "not a number: '" + std::string(f[first + k]) + "'");
    if (!std::isfinite(p[k])) throw InputError(file, line, "non-finite coordinate");
  }
  return p;
}

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}

/// Lines of a text file with comments ('#' to end of line) removed and blank lines skipped,
/// each with its 1-based line number.
std::vector<std::pair<int, std::string>> content_lines(std::istream& in) {
  std::vector<std::pair<int, std::string>> out;
  std::string raw;
  for (int number = 1; std::getline(in, raw); ++number) {
    std::string_view s = raw;
    if (const auto hash = s.find('#'); hash != std::string_view::npos) s = s.substr(0, hash);
    s = trim(s);
    if (!s.empty()) out.emplace_back(number, std::string(s));
  }
  return out;
}

/// The InputError of a mesh reader's message "FILE: problem" or "FILE:LINE: problem".
InputError mesh_input_error(const std::string& file, std::string_view message) {
  if (!message.starts_with(file + ":")) return InputError(file, 0, std::string(message));
  message.remove_prefix(file.size() + 1);
  int line = 0;
  const auto [end, ec] = std::from_chars(message.data(), message.data() + message.size(), line);
  if (ec == std::errc() && end != message.data() + message.size() && *end == ':')
    message.remove_prefix(static_cast<std::size_t>(end - message.data()) + 1);
  else
    line = 0;
  return InputError(file, line, std::string(trim(message)));
}

std::vector<Vec3> read_xyz(std::istream& in, const std::string& file) {
  std::vector<Vec3> points;
  for (const auto& [number, text] : content_lines(in)) {
    const auto f = fields(text);
    if (f.size() != 3) throw InputError(file, number, "expected exactly three coordinates");
    points.push_back(parse_point(f, 0, file, number));
  }
  return points;
}

std::vector<Vec3> read_obj(std::istream& in, const std::string& file) {
  std::vector<Vec3> points;
  for (const auto& [number, text] : content_lines(in)) {
    const auto f = fields(text);
    if (!f.empty() && f[0] == "v") points.push_back(parse_point(f, 1, file, number));
  }
  return points;
}

std::vector<Vec3> read_off(std::istream& in, const std::string& file) {
  const auto lines = content_lines(in);
  std::size_t next = 0;
  if (next < lines.size() && lines[next].second.ends_with("OFF") &&
      lines[next].second.size() <= 4) {
    ++next;  // header: OFF, COFF, NOFF, …
  } else {
    throw InputError(file, lines.empty() ? 0 : lines[0].first, "missing OFF header");
  }
  if (next >= lines.size()) throw InputError(file, 0, "missing vertex/face counts");
  const auto counts = fields(lines[next].second);
  double nv = 0;
  if (counts.empty() || !parse_double(counts[0], nv) || nv < 0 || nv != std::floor(nv))
    throw InputError(file, lines[next].first, "expected the vertex count");
  if (nv > static_cast<double>(lines.size() - next - 1))
    throw InputError(file, lines[next].first,
                     "declares " + std::string(counts[0]) + " vertices, but only " +
                         std::to_string(lines.size() - next - 1) + " lines follow");
  ++next;
  std::vector<Vec3> points;
  for (std::size_t i = 0; i < static_cast<std::size_t>(nv); ++i, ++next) {
    if (next >= lines.size())
      throw InputError(file, 0,
                       "file ends after " + std::to_string(i) + " of " +
                           std::to_string(static_cast<long>(nv)) + " vertices");
    points.push_back(parse_point(fields(lines[next].second), 0, file, lines[next].first));
  }
  return points;
}

Vec3 json_point(const nlohmann::json& p, const char* cloud, std::size_t index) {
  const std::string where = std::string("cloud ") + cloud + " point " + std::to_string(index);
  if (!p.is_array() || p.size() != 3) throw std::invalid_argument(where + ": expected [x, y, z]");
  Vec3 v;
  for (int k = 0; k < 3; ++k) {
    if (!p[k].is_number()) throw std::invalid_argument(where + ": coordinate is not a number");
    v[k] = p[k].get<double>();
  }
  return v;
}

std::vector<Vec3> json_cloud(const nlohmann::json& j, const char* cloud) {
  if (!j.contains(cloud)) throw std::invalid_argument(std::string("missing key \"") + cloud + "\"");
  const auto& arr = j.at(cloud);
  if (!arr.is_array())
    throw std::invalid_argument(std::string("cloud ") + cloud + ": expected an array of points");
  std::vector<Vec3> out;
  out.reserve(arr.size());
  for (std::size_t i = 0; i < arr.size(); ++i)
    out.push_back(json_point(arr[i], cloud, i));
  check_case_cloud(out, cloud);
  return out;
}

std::vector<MeshFace> json_faces(const nlohmann::json& faces, const char* side) {
  const std::string where = std::string("mesh ") + side;
  if (!faces.is_array())
    throw std::invalid_argument(where + ": \"faces\" must be an array of [i, j, k]");
  std::vector<MeshFace> out;
  out.reserve(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto& face = faces[f];
    if (!face.is_array() || face.size() != 3)
      throw std::invalid_argument(where + " face " + std::to_string(f) + ": expected [i, j, k]");
    MeshFace& indices = out.emplace_back();
    for (int k = 0; k < 3; ++k) {
      if (!face[k].is_number_unsigned() || face[k].get<std::uint64_t>() > UINT32_MAX)
        throw std::invalid_argument(where + " face " + std::to_string(f) +
                                    ": a vertex index is not an integer in [0, 2^32)");
      indices[k] = face[k].get<std::uint32_t>();
    }
  }
  return out;
}

/// A side given as {"vertices": [...], "faces": [...]}: a closed mesh, validated.
TriangleMesh json_mesh(const nlohmann::json& side, const char* name) {
  const std::string where = std::string("mesh ") + name;
  for (const char* key : {"vertices", "faces"})
    if (!side.contains(key)) throw std::invalid_argument(where + ": missing key \"" + key + "\"");
  TriangleMesh mesh;
  try {
    mesh.vertices = json_cloud(side, "vertices");
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(where + ": " + e.what());
  }
  mesh.faces = json_faces(side.at("faces"), name);
  try {
    exact::validate_closed_mesh(mesh, where);
  } catch (const std::runtime_error& e) {
    throw std::invalid_argument(e.what());
  }
  return mesh;
}

/// One side of a case: a point list, or a mesh (then `mesh` is set and the vertices returned).
std::vector<Vec3> json_side(const nlohmann::json& j, const char* name,
                            std::optional<TriangleMesh>& mesh) {
  if (j.contains(name) && j.at(name).is_object()) {
    mesh = json_mesh(j.at(name), name);
    return mesh->vertices;
  }
  return json_cloud(j, name);
}

/// An optional radius of a sphere-swept shape: 0 when absent, else a finite number >= 0.
double json_radius(const nlohmann::json& j, const char* key) {
  if (!j.contains(key)) return 0;
  const auto& v = j.at(key);
  if (!v.is_number())
    throw std::invalid_argument(std::string(key) + ": expected a finite number >= 0, got " +
                                json_line(v));
  check_case_radius(v.get<double>(), key);
  return v.get<double>();
}

/// The "id" string of a line that is not valid JSON, if one can be seen ("id", optional
/// blanks, a colon, optional blanks, then a string without escapes), so that the error names
/// the case the user wrote. A plain scan: a regex engine recurses once per character and
/// overflowed the stack on a 30 000-character id.
std::optional<std::string> id_from_unparsed(std::string_view text) {
  const auto is_blank = [](char c) { return c == ' ' || c == '\t'; };
  for (std::size_t at = text.find("\"id\""); at != std::string_view::npos;
       at = text.find("\"id\"", at + 1)) {
    std::size_t i = at + 4;
    while (i < text.size() && is_blank(text[i]))
      ++i;
    if (i >= text.size() || text[i] != ':') continue;
    ++i;
    while (i < text.size() && is_blank(text[i]))
      ++i;
    if (i >= text.size() || text[i] != '"') continue;
    const std::size_t begin = i + 1;
    const std::size_t end = text.find_first_of("\"\\", begin);
    if (end == std::string_view::npos || text[end] != '"') continue;
    return std::string(text.substr(begin, end - begin));
  }
  return std::nullopt;
}

/// The deepest nesting of arrays and objects in a JSON text, counted outside strings, up to
/// `limit` + 1 (the scan stops there).
int json_depth(std::string_view text, int limit) {
  int depth = 0, deepest = 0;
  bool in_string = false, escaped = false;
  for (const char c : text) {
    if (in_string) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        in_string = false;
      continue;
    }
    if (c == '"')
      in_string = true;
    else if (c == '[' || c == '{')
      deepest = std::max(deepest, ++depth);
    else if (c == ']' || c == '}')
      --depth;
    if (deepest > limit) break;
  }
  return deepest;
}

}  // namespace

std::vector<Vec3> read_point_file(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::ifstream in(path);
  if (!in) throw InputError(file, 0, "cannot open file");
  const std::string ext = lower_extension(path);
  std::vector<Vec3> points;
  if (ext == ".xyz" || ext == ".txt") {
    points = read_xyz(in, file);
  } else if (ext == ".off") {
    points = read_off(in, file);
  } else if (ext == ".obj") {
    points = read_obj(in, file);
  } else if (ext == ".ply" || ext == ".stl") {
    // Binary formats too (scanned objects come as PLY, CAD parts as STL): CGAL's readers,
    // behind the header checks of mesh_io.
    try {
      points = exact::read_mesh_vertices(path);
    } catch (const std::runtime_error& e) {
      throw mesh_input_error(file, e.what());
    }
  } else {
    throw InputError(
        file, 0, "unknown point file extension '" + ext + "' (use .xyz, .off, .obj, .ply or .stl)");
  }
  if (points.empty()) throw InputError(file, 0, "empty point cloud");
  return points;
}

void check_case_cloud(std::span<const Vec3> cloud, const char* name) {
  const std::string where = std::string("cloud ") + name;
  if (cloud.empty()) throw std::invalid_argument(where + ": empty point cloud");
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (!cloud[i].allFinite())
      throw std::invalid_argument(where + " point " + std::to_string(i) +
                                  ": non-finite coordinate");
}

void check_case_radius(double radius, const char* key) {
  if (!std::isfinite(radius) || !(radius >= 0)) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", radius);
    throw std::invalid_argument(std::string(key) + ": expected a finite number >= 0, got " + text);
  }
}

CaseOrError parse_case_line(std::string_view text, int line) {
  const std::string default_id = "line " + std::to_string(line);
  if (json_depth(text, kMaxJsonDepth) > kMaxJsonDepth)
    return CaseError{id_from_unparsed(text).value_or(default_id), line,
                     "JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels"};
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::out_of_range& e) {
    // nlohmann rejects numbers beyond the double range (e.g. 1e999) while parsing.
    return CaseError{id_from_unparsed(text).value_or(default_id), line,
                     std::string("non-finite coordinate: ") + e.what()};
  } catch (const nlohmann::json::exception& e) {
    return CaseError{id_from_unparsed(text).value_or(default_id), line,
                     std::string("malformed JSON: ") + e.what()};
  }
  if (!j.is_object()) return CaseError{default_id, line, "expected a JSON object"};
  PointCase c;
  c.id = default_id;
  if (j.contains("id")) {
    const auto& id = j.at("id");
    c.id = id.is_string() ? id.get<std::string>() : json_line(id);
  }
  try {
    c.a = json_side(j, "a", c.mesh_a);
    c.b = json_side(j, "b", c.mesh_b);
    c.radius_a = json_radius(j, "radius_a");
    c.radius_b = json_radius(j, "radius_b");
    if ((c.mesh_a || c.mesh_b) && (c.radius_a != 0 || c.radius_b != 0))
      throw std::invalid_argument("radius_a and radius_b sweep point clouds, not meshes");
  } catch (const std::invalid_argument& e) {
    return CaseError{c.id, line, e.what()};
  }
  return c;
}

std::vector<CaseOrError> read_cases_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(path.string(), 0, "is a folder, not a cases file");
  std::ifstream in(path);
  if (!in) throw InputError(path.string(), 0, "cannot open file");
  std::vector<CaseOrError> out;
  std::string raw;
  for (int number = 1; std::getline(in, raw); ++number) {
    if (trim(raw).empty()) continue;
    out.push_back(parse_case_line(raw, number));
  }
  return out;
}

std::string case_to_json_line(const PointCase& c) {
  // nlohmann writes the shortest decimal that reads back as the same double.
  nlohmann::json j{{"id", c.id},
                   {"a", case_side_json<nlohmann::json>(c.a, c.mesh_a)},
                   {"b", case_side_json<nlohmann::json>(c.b, c.mesh_b)}};
  if (c.radius_a != 0) j["radius_a"] = c.radius_a;
  if (c.radius_b != 0) j["radius_b"] = c.radius_b;
  return json_line(j);
}

std::string json_line(const nlohmann::json& j) {
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::string json_line(const nlohmann::ordered_json& j) {
  return j.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

}  // namespace gjklab::experiment
