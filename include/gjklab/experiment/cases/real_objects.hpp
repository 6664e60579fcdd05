// Real objects: the convex hulls of the meshes Debian ships with CGAL's data (package
// libcgal-demo: elephant, cow, bunny, armadillo, Chinese dragon, fandisk, femur, …), the shapes
// of the `real_object` family.
//
// The package installs the meshes as one archive; the first use extracts them into a cache
// folder (with tar), later uses read them from there.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "gjklab/geometry/types.hpp"

namespace gjklab::experiment {

/// The Debian package that ships the meshes, and the archive it installs them in.
inline constexpr std::string_view kRealObjectPackage = "libcgal-demo";
inline constexpr std::string_view kRealObjectArchive = "/usr/share/doc/libcgal-dev/data.tar.gz";

/// A real object that cannot be had: the package is missing, extraction failed, or the name
/// is unknown (the message says which, and lists the valid names for an unknown one).
class RealObjectError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The archive the meshes are extracted from: $GJKLAB_REAL_OBJECT_ARCHIVE when set (a copy of
/// CGAL's data elsewhere), else kRealObjectArchive.
std::filesystem::path real_object_archive();

/// The folder the meshes are extracted to: $GJKLAB_CACHE_DIR/real-objects, else
/// $XDG_CACHE_HOME/gjklab/real-objects, else $HOME/.cache/gjklab/real-objects.
std::filesystem::path real_object_cache();

/// The cache folder, filled from the package's archive if it is not yet (safe when several
/// processes start at once: each extracts into its own folder and renames it into place).
/// Throws RealObjectError naming the package when its archive is missing.
std::filesystem::path real_object_meshes();

/// The names of the real objects, sorted: each mesh file's name without its extension, once
/// (pig.off and pig.stl are one object).
std::vector<std::string> real_object_names();

/// One real object: the vertices of its mesh's convex hull, centred on their bounding box and
/// scaled so that the farthest is at distance 1 (unit size, like the generated clouds). Throws
/// RealObjectError for an unknown name, listing the valid ones.
std::vector<Vec3> real_object(std::string_view name);

}  // namespace gjklab::experiment
