// Point files: `gjklab query A B` reads each with experiment::read_point_file, which picks the
// reader by extension (.xyz and .obj: gjklab's own; .off, .ply, .stl: CGAL's, in src/exact/).
//
// Input: one byte choosing the extension, then the file's bytes. The contract: either the
// vertices (non-empty, every coordinate finite) or an InputError; any other exception would
// escape `gjklab query` (it catches InputError only) and is reported as a crash.
#include <cmath>
#include <cstdint>
#include <span>

#include "gjklab/experiment/cases/cloud_io.hpp"
#include "support.hpp"

namespace {

constexpr const char* kNames[] = {"cloud.xyz", "cloud.off", "cloud.obj", "cloud.ply",
                                  "cloud.stl", "CLOUD.OFF", "CLOUD.PLY", "CLOUD.STL"};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const char* name = kNames[data[0] % std::size(kNames)];
  const auto path = gjklab::fuzz::write_scratch_file(name, std::span(data + 1, size - 1));
  try {
    const auto cloud = gjklab::experiment::read_point_file(path);
    if (cloud.empty()) gjklab::fuzz::violated("read_point_file returned an empty cloud");
    for (const auto& p : cloud)
      if (!p.allFinite()) gjklab::fuzz::violated("read_point_file returned a non-finite point");
  } catch (const gjklab::experiment::InputError& e) {
    if (e.file() != path.string()) gjklab::fuzz::violated("InputError names another file");
  }
  return 0;
}
