#include "gjklab/experiment/cases/real_objects.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <mutex>

#include "gjklab/exact/hull_features.hpp"
#include "gjklab/exact/mesh_io.hpp"

extern char** environ;

namespace gjklab::experiment {

namespace fs = std::filesystem;

namespace {

/// Extensions in order of preference when one object comes in several formats: OFF is the
/// format CGAL's data is authored in, the others are conversions of the same mesh.
constexpr std::array<std::string_view, 4> kExtensions = {".off", ".ply", ".obj", ".stl"};

std::string env(const char* name) {
  const char* value = std::getenv(name);
  return value ? value : "";
}

/// Runs `tar` to unpack the archive's data/meshes/ into `folder`; returns its exit status
/// (-1 when it could not be started). Its output goes to /dev/null: a failure is reported by
/// the caller, naming the archive.
int untar_meshes(const fs::path& folder) {
  const std::string archive = real_object_archive().string();
  const std::string target = folder.string();
  const char* argv[] = {"tar",         "xzf",          archive.c_str(),
                        "-C",          target.c_str(), "--strip-components=2",
                        "data/meshes", nullptr};
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const int spawned =
      posix_spawnp(&pid, "tar", &actions, nullptr, const_cast<char**>(argv), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return -1;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// The mesh file of each object name (the preferred extension where there are several).
std::map<std::string, fs::path> mesh_files() {
  const fs::path folder = real_object_meshes();
  std::map<std::string, fs::path> files;
  auto rank = [](const fs::path& p) {
    return std::find(kExtensions.begin(), kExtensions.end(), p.extension().string()) -
           kExtensions.begin();
  };
  for (const auto& entry : fs::directory_iterator(folder)) {
    const fs::path& p = entry.path();
    if (!entry.is_regular_file() || rank(p) == static_cast<long>(kExtensions.size())) continue;
    auto [it, inserted] = files.emplace(p.stem().string(), p);
    if (!inserted && rank(p) < rank(it->second)) it->second = p;
  }
  return files;
}

/// Centred on the bounding box, farthest point at distance 1. Mesh coordinates span from
/// millimetres to thousands of units; one size lets real objects share placements and
/// tolerances with the generated families.
void normalise(std::vector<Vec3>& points) {
  Vec3 lower = points[0], upper = points[0];
  for (const Vec3& p : points) {
    lower = lower.cwiseMin(p);
    upper = upper.cwiseMax(p);
  }
  const Vec3 centre = 0.5 * (lower + upper);
  double radius = 0;
  for (const Vec3& p : points)
    radius = std::max(radius, (p - centre).norm());
  const double scale = radius > 0 ? 1 / radius : 1;
  for (Vec3& p : points)
    p = (p - centre) * scale;
}

}  // namespace

fs::path real_object_archive() {
  if (const std::string archive = env("GJKLAB_REAL_OBJECT_ARCHIVE"); !archive.empty())
    return archive;
  return fs::path(kRealObjectArchive);
}

fs::path real_object_cache() {
  if (const std::string dir = env("GJKLAB_CACHE_DIR"); !dir.empty())
    return fs::path(dir) / "real-objects";
  if (const std::string dir = env("XDG_CACHE_HOME"); !dir.empty())
    return fs::path(dir) / "gjklab" / "real-objects";
  if (const std::string home = env("HOME"); !home.empty())
    return fs::path(home) / ".cache" / "gjklab" / "real-objects";
  return fs::temp_directory_path() / "gjklab-real-objects";
}

fs::path real_object_meshes() {
  const fs::path cache = real_object_cache();
  std::error_code ec;
  // The folder appears only by the rename below, complete, so its existence means it is whole.
  if (fs::is_directory(cache, ec)) return cache;
  const fs::path archive = real_object_archive();
  if (!fs::exists(archive, ec))
    throw RealObjectError("real objects: " + archive.string() +
                          " is missing; install the Debian package " +
                          std::string(kRealObjectPackage) + " (tools/setup does)");
  fs::create_directories(cache.parent_path(), ec);
  const fs::path partial =
      cache.parent_path() / (cache.filename().string() + ".partial." + std::to_string(getpid()));
  fs::remove_all(partial, ec);
  fs::create_directories(partial, ec);
  if (ec)
    throw RealObjectError("real objects: cannot create " + partial.string() + ": " + ec.message());
  const int status = untar_meshes(partial);
  if (status != 0) {
    fs::remove_all(partial, ec);
    throw RealObjectError("real objects: extracting the meshes of " + archive.string() + " into " +
                          cache.string() + " failed (tar exit status " + std::to_string(status) +
                          ")");
  }
  fs::rename(partial, cache, ec);
  if (ec) {
    // Another process renamed its copy first: use that one.
    fs::remove_all(partial, ec);
    if (!fs::is_directory(cache, ec))
      throw RealObjectError("real objects: cannot create " + cache.string());
  }
  return cache;
}

std::vector<std::string> real_object_names() {
  std::vector<std::string> names;
  for (const auto& [name, file] : mesh_files())
    names.push_back(name);
  return names;
}

std::vector<Vec3> real_object(std::string_view name) {
  const auto files = mesh_files();
  const auto file = files.find(std::string(name));
  if (file == files.end()) {
    std::string valid;
    for (const auto& [known, path] : files)
      valid += (valid.empty() ? "" : ", ") + known;
    throw RealObjectError("unknown real object '" + std::string(name) + "'; valid: " + valid);
  }
  // Hulls are computed once per process and mesh file: an experiment names each object once,
  // but one Python program may load many experiments.
  static std::mutex mutex;
  static std::map<fs::path, std::vector<Vec3>> hulls;
  const std::lock_guard lock(mutex);
  if (const auto found = hulls.find(file->second); found != hulls.end()) return found->second;
  // Scaled first, then the hull of the scaled points: rounding can make a vertex that was
  // barely extreme coplanar with its neighbours, and the shape is to be its hull's vertices.
  std::vector<Vec3> points = exact::read_mesh_vertices(file->second);
  normalise(points);
  std::vector<Vec3> hull = exact::hull_features(points).vertices;
  return hulls.emplace(file->second, std::move(hull)).first->second;
}

}  // namespace gjklab::experiment
