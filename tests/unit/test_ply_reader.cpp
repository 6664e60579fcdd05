// gjklab's PLY reader (src/exact/io/ply_reader.cpp) through read_mesh_vertices: ASCII and both
// binary byte orders, every element read in header order, lists skipped, other properties
// ignored; the vertices come out exactly, in file order.
#include <catch2/catch.hpp>

#include <bit>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "../support/cli_run.hpp"
#include "gjklab/exact/mesh_io.hpp"

using gjklab::Vec3;
using gjklab::testing::ScratchDir;

namespace {

const std::vector<Vec3> kPoints = {{0.1, -2, 3e-7}, {1e5, 0.25, -0.5}, {-1, 1, 1}};

/// The bytes of x in the given byte order.
template <class T>
std::string bytes_of(T x, bool big_endian) {
  std::string out(sizeof x, '\0');
  std::memcpy(out.data(), &x, sizeof x);
  if (big_endian == (std::endian::native == std::endian::little))
    std::reverse(out.begin(), out.end());
  return out;
}

/// A binary PLY: a `material` element before the vertices, vertices with x, y, z as doubles
/// between an unsigned char and a list, then one face.
std::string binary_ply(bool big_endian) {
  std::string text = std::string("ply\nformat ") +
                     (big_endian ? "binary_big_endian" : "binary_little_endian") +
                     " 1.0\ncomment made by a test\nelement material 1\nproperty list uchar "
                     "float colour\nelement vertex 3\nproperty uchar flag\nproperty double x\n"
                     "property double y\nproperty double z\nproperty list ushort int tags\n"
                     "element face 1\nproperty list uchar uint vertex_indices\nend_header\n";
  text += bytes_of<std::uint8_t>(2, big_endian) + bytes_of(0.5f, big_endian) +
          bytes_of(0.75f, big_endian);
  for (const Vec3& p : kPoints) {
    text += bytes_of<std::uint8_t>(7, big_endian);
    for (int k = 0; k < 3; ++k)
      text += bytes_of(p[k], big_endian);
    text += bytes_of<std::uint16_t>(1, big_endian) + bytes_of<std::int32_t>(-4, big_endian);
  }
  text += bytes_of<std::uint8_t>(3, big_endian);
  for (std::uint32_t i = 0; i < 3; ++i)
    text += bytes_of(i, big_endian);
  return text;
}

std::vector<Vec3> read_file(const ScratchDir& dir, const std::string& name,
                            const std::string& text) {
  const std::string path = dir.file(name);
  std::ofstream(path, std::ios::binary) << text;
  return gjklab::exact::read_mesh_vertices(path);
}

}  // namespace

TEST_CASE("PLY reader: binary in both byte orders, elements before and after the vertices",
          "[unit][mesh]") {
  ScratchDir dir("ply-reader");
  CHECK(read_file(dir, "little.ply", binary_ply(false)) == kPoints);
  CHECK(read_file(dir, "big.ply", binary_ply(true)) == kPoints);
  // One byte short: the face's last index is missing.
  std::string truncated = binary_ply(false);
  truncated.pop_back();
  CHECK_THROWS_WITH(read_file(dir, "short.ply", truncated),
                    Catch::Contains("short.ply") &&
                        Catch::Contains("a list beyond the end of the file") &&
                        Catch::Contains("(in face 1 of 1)"));
}

TEST_CASE("PLY reader: ASCII with lists and extra properties", "[unit][mesh]") {
  ScratchDir dir("ply-reader-ascii");
  const std::string text =
      "ply\r\nformat ascii 1.0\r\nelement vertex 3\r\nproperty float nx\r\nproperty double x\r\n"
      "property double y\r\nproperty double z\r\nproperty list uchar int tags\r\n"
      "element face 1\r\nproperty list uchar int vertex_indices\r\nend_header\r\n"
      "9 0.1 -2 3e-7 2 5 6\r\n9 100000 0.25 -0.5 0\r\n9 -1 1 1 1 4\r\n3 0 1 2\r\n";
  CHECK(read_file(dir, "ascii.ply", text) == kPoints);
  CHECK_THROWS_WITH(read_file(dir, "word.ply", text.substr(0, text.size() - 9) + "zero 1 2\n"),
                    Catch::Contains("word.ply") && Catch::Contains("'zero") &&
                        Catch::Contains("is not a number"));
  CHECK_THROWS_WITH(read_file(dir, "nox.ply",
                              "ply\nformat ascii 1.0\nelement vertex 1\nproperty double y\n"
                              "property double z\nend_header\n1 2\n"),
                    Catch::Contains("nox.ply") && Catch::Contains("no scalar x, y and z"));
}
