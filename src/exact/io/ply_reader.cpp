#include "exact/io/ply_reader.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <charconv>
#include <cstring>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

namespace gjklab::exact::detail {

namespace {

enum class Scalar { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

struct ScalarName {
  std::string_view name;
  Scalar type;
};

constexpr std::array<ScalarName, 16> kScalarNames = {{
    {"char", Scalar::int8},
    {"int8", Scalar::int8},
    {"uchar", Scalar::uint8},
    {"uint8", Scalar::uint8},
    {"short", Scalar::int16},
    {"int16", Scalar::int16},
    {"ushort", Scalar::uint16},
    {"uint16", Scalar::uint16},
    {"int", Scalar::int32},
    {"int32", Scalar::int32},
    {"uint", Scalar::uint32},
    {"uint32", Scalar::uint32},
    {"float", Scalar::float32},
    {"float32", Scalar::float32},
    {"double", Scalar::float64},
    {"float64", Scalar::float64},
}};

std::size_t size_of(Scalar t) {
  switch (t) {
    case Scalar::int8:
    case Scalar::uint8:
      return 1;
    case Scalar::int16:
    case Scalar::uint16:
      return 2;
    case Scalar::int32:
    case Scalar::uint32:
    case Scalar::float32:
      return 4;
    case Scalar::float64:
      return 8;
  }
  return 8;
}

struct Property {
  std::string name;
  Scalar type = Scalar::float64;
  std::optional<Scalar> count_type;  ///< set for a list: the type of its item count
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

enum class Format { ascii, binary_little_endian, binary_big_endian };

struct Header {
  Format format = Format::ascii;
  std::vector<Element> elements;
};

/// Reports a problem at a header line (line > 0) or in the body (line 0).
[[noreturn]] void fail(const std::string& file, int line, const std::string& problem) {
  std::string message = file;
  if (line > 0) message.append(":").append(std::to_string(line));
  message.append(": ").append(problem);
  throw std::runtime_error(message);
}

std::vector<std::string> words_of(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string w; in >> w;)
    out.push_back(w);
  return out;
}

Scalar scalar_named(const std::string& word, const std::string& file, int line) {
  for (const ScalarName& s : kScalarNames)
    if (s.name == word) return s.type;
  fail(file, line, "unknown PLY type '" + word + "'");
}

Property property_of(const std::vector<std::string>& w, const std::string& file, int line) {
  Property p;
  if (w.size() >= 5 && w[1] == "list") {
    p.count_type = scalar_named(w[2], file, line);
    if (*p.count_type == Scalar::float32 || *p.count_type == Scalar::float64)
      fail(file, line, "a list count of floating-point type '" + w[2] + "'");
    p.type = scalar_named(w[3], file, line);
    p.name = w[4];
  } else if (w.size() >= 3 && w[1] != "list") {
    p.type = scalar_named(w[1], file, line);
    p.name = w[2];
  } else {
    fail(file, line, "expected 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'");
  }
  return p;
}

/// Reads the header up to end_header; `in` is left at the first byte of the body.
Header read_header(std::istream& in, const std::string& file) {
  Header h;
  std::string line;
  for (int number = 1; number <= 1000 && std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::vector<std::string> w = words_of(line);
    if (number == 1) {
      if (w.size() != 1 || w[0] != "ply") fail(file, 1, "not a PLY file (no 'ply' line)");
      continue;
    }
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "end_header") return h;
    if (w[0] == "format") {
      if (w.size() < 2) fail(file, number, "a format line without a format");
      if (w[1] == "ascii") {
        h.format = Format::ascii;
      } else if (w[1] == "binary_little_endian") {
        h.format = Format::binary_little_endian;
      } else if (w[1] == "binary_big_endian") {
        h.format = Format::binary_big_endian;
      } else {
        fail(file, number, "unknown PLY format '" + w[1] + "'");
      }
    } else if (w[0] == "element") {
      Element e;
      if (w.size() < 3) fail(file, number, "expected 'element NAME COUNT'");
      e.name = w[1];
      const auto [end, ec] = std::from_chars(w[2].data(), w[2].data() + w[2].size(), e.count);
      if (ec != std::errc() || end != w[2].data() + w[2].size())
        fail(file, number, "element count '" + w[2] + "' is not a non-negative integer");
      h.elements.push_back(std::move(e));
    } else if (w[0] == "property") {
      if (h.elements.empty()) fail(file, number, "a property before any element");
      h.elements.back().properties.push_back(property_of(w, file, number));
    } else {
      fail(file, number, "unknown PLY header line '" + w[0] + "'");
    }
  }
  fail(file, 0, "no end_header within the first 1000 lines of the PLY header");
}

/// The body of the file, read as numbers one at a time; every read is bounded by the bytes
/// left, and an item count by the bytes its items need.
class Body {
 public:
  Body(std::string bytes, Format format, std::string file)
      : bytes_(std::move(bytes)), format_(format), file_(std::move(file)) {}

  double scalar(Scalar type) {
    return format_ == Format::ascii ? ascii_number() : binary_number(type);
  }

  /// A list's item count, checked against the bytes left (each item takes at least one).
  std::uint64_t count(Scalar type) {
    const double c = scalar(type);
    if (!(c >= 0) || c != static_cast<double>(static_cast<std::uint64_t>(c)))
      fail(file_, 0, "a list count that is not a non-negative integer");
    const auto n = static_cast<std::uint64_t>(c);
    if (n > bytes_.size() - pos_) fail(file_, 0, "a list count beyond the end of the file");
    return n;
  }

  void skip(Scalar type, std::uint64_t items) {
    if (format_ != Format::ascii) {
      const std::uint64_t bytes = items * size_of(type);
      if (bytes > bytes_.size() - pos_) fail(file_, 0, "a list beyond the end of the file");
      pos_ += bytes;
      return;
    }
    for (std::uint64_t k = 0; k < items; ++k)
      ascii_number();
  }

 private:
  double ascii_number() {
    while (pos_ < bytes_.size() && std::isspace(static_cast<unsigned char>(bytes_[pos_])))
      ++pos_;
    if (pos_ == bytes_.size()) fail(file_, 0, "the file ends inside an element");
    const char* begin = bytes_.data() + pos_;
    double value = 0;
    const auto [end, ec] = std::from_chars(begin, bytes_.data() + bytes_.size(), value);
    if (ec != std::errc() ||
        (end != bytes_.data() + bytes_.size() && !std::isspace(static_cast<unsigned char>(*end))))
      not_a_number(std::string_view(begin, std::min<std::size_t>(20, bytes_.size() - pos_)));
    pos_ = static_cast<std::size_t>(end - bytes_.data());
    return value;
  }

  [[noreturn]] void not_a_number(std::string_view text) const {
    std::string problem = "'";
    problem.append(text).append("' is not a number");
    fail(file_, 0, problem);
  }

  double binary_number(Scalar type) {
    const std::size_t n = size_of(type);
    if (n > bytes_.size() - pos_) fail(file_, 0, "the file ends inside an element");
    std::array<unsigned char, 8> raw{};
    std::memcpy(raw.data(), bytes_.data() + pos_, n);
    pos_ += n;
    const bool swap =
        (format_ == Format::binary_big_endian) == (std::endian::native == std::endian::little);
    if (swap) std::reverse(raw.begin(), raw.begin() + static_cast<std::ptrdiff_t>(n));
    return value_of(type, raw);
  }

  static double value_of(Scalar type, const std::array<unsigned char, 8>& raw) {
    const auto read = [&raw](auto value) {
      std::memcpy(&value, raw.data(), sizeof value);
      return static_cast<double>(value);
    };
    switch (type) {
      case Scalar::int8:
        return read(std::int8_t{});
      case Scalar::uint8:
        return read(std::uint8_t{});
      case Scalar::int16:
        return read(std::int16_t{});
      case Scalar::uint16:
        return read(std::uint16_t{});
      case Scalar::int32:
        return read(std::int32_t{});
      case Scalar::uint32:
        return read(std::uint32_t{});
      case Scalar::float32:
        return read(float{});
      case Scalar::float64:
        return read(double{});
    }
    return 0;
  }

  std::string bytes_;
  std::size_t pos_ = 0;
  Format format_;
  std::string file_;
};

bool is_index_list(const Property& p) {
  return p.count_type && (p.name == "vertex_indices" || p.name == "vertex_index");
}

/// Reads a face's vertex index list into `face`: each a non-negative integer (any PLY type).
/// No reserve: the count is only bounded by the bytes left, and a garbled one must fail at
/// the end of the file, not as an allocation of 8 bytes per byte left.
void read_indices(Body& body, const Property& p, std::vector<std::size_t>& face) {
  const std::uint64_t n = body.count(*p.count_type);
  for (std::uint64_t k = 0; k < n; ++k) {
    const double index = body.scalar(p.type);
    // 2^53: every integer below is exact in a double and fits std::size_t.
    if (!(index >= 0 && index < 9007199254740992.0) ||
        index != static_cast<double>(static_cast<std::uint64_t>(index)))
      throw std::runtime_error("a face index that is not a non-negative integer");
    face.push_back(static_cast<std::size_t>(index));
  }
}

/// Reads one record of `e`, keeping x, y, z in `out` (vertex element) and the vertex index
/// list in `face` (face element, faces asked for) when they are given.
void read_record(Body& body, const Element& e, Vec3* out, std::vector<std::size_t>* face) {
  for (const Property& p : e.properties) {
    if (face && is_index_list(p)) {
      read_indices(body, p, *face);
      face = nullptr;  // the first index list only
      continue;
    }
    if (p.count_type) {
      body.skip(p.type, body.count(*p.count_type));
      continue;
    }
    const double v = body.scalar(p.type);
    if (out && p.name == "x") (*out)[0] = v;
    if (out && p.name == "y") (*out)[1] = v;
    if (out && p.name == "z") (*out)[2] = v;
  }
}

bool has_coordinates(const Element& e) {
  int found = 0;
  for (const Property& p : e.properties)
    if (!p.count_type && (p.name == "x" || p.name == "y" || p.name == "z")) ++found;
  return found == 3;
}

}  // namespace

MeshSoup read_ply_mesh(const std::filesystem::path& path, bool keep_faces) {
  const std::string file = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(file, 0, "cannot open the file");
  const Header header = read_header(in, file);
  Body body(std::string(std::istreambuf_iterator<char>(in), {}), header.format, file);
  MeshSoup soup;
  bool have_vertices = false;
  bool have_faces = false;
  // Every element is read, the ones after the vertices too (and dropped), so that a file whose
  // body does not match its header is an error rather than half read.
  for (const Element& e : header.elements) {
    const bool vertices = e.name == "vertex" && !have_vertices;
    const bool faces = keep_faces && e.name == "face" && !have_faces;
    if (vertices && !has_coordinates(e))
      fail(file, 0, "the vertex element has no scalar x, y and z");
    if (faces && std::none_of(e.properties.begin(), e.properties.end(), is_index_list))
      fail(file, 0, "the face element has no list 'vertex_indices' (or 'vertex_index')");
    have_vertices = have_vertices || vertices;
    have_faces = have_faces || faces;
    std::uint64_t k = 0;
    try {
      for (; k < e.count; ++k) {
        Vec3 p = Vec3::Zero();
        std::vector<std::size_t> face;
        read_record(body, e, vertices ? &p : nullptr, faces ? &face : nullptr);
        if (vertices) soup.vertices.push_back(p);
        if (faces) soup.faces.push_back(std::move(face));
      }
    } catch (const std::runtime_error& problem) {
      std::string message = problem.what();
      if (!message.starts_with(file)) message = file + ": " + message;
      message.append(" (in ").append(e.name).append(" ").append(std::to_string(k + 1));
      message.append(" of ").append(std::to_string(e.count)).append(")");
      throw std::runtime_error(message);
    }
  }
  if (!have_vertices) fail(file, 0, "no vertex element");
  return soup;
}

std::vector<Vec3> read_ply_vertices(const std::filesystem::path& path) {
  return read_ply_mesh(path, false).vertices;
}

}  // namespace gjklab::exact::detail
