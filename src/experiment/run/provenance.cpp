#include "gjklab/experiment/run/provenance.hpp"

#include <gsl/gsl_version.h>
#include <hdf5.h>

#include <Eigen/Core>

#include "gjklab/build_info.hpp"
#include "gjklab/exact/oracle.hpp"
#include "gjklab/experiment/run/ranks.hpp"
#include "gjklab/peers/libccd.hpp"
#ifdef GJKLAB_HAVE_FCL
#include "gjklab/peers/fcl.hpp"
#endif
#ifdef GJKLAB_HAVE_BULLET
#include "gjklab/peers/bullet.hpp"
#endif

namespace gjklab::experiment {

namespace {
std::string hdf5_version() {
  unsigned major = 0, minor = 0, release = 0;
  H5get_libversion(&major, &minor, &release);
  return std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(release);
}

/// The optional peer libraries this build includes, e.g. "fcl bullet" ("none" without any).
std::string optional_peers() {
  std::string peers;
#ifdef GJKLAB_HAVE_FCL
  peers += "fcl ";
#endif
#ifdef GJKLAB_HAVE_BULLET
  peers += "bullet ";
#endif
  if (peers.empty()) return "none";
  peers.pop_back();
  return peers;
}

}  // namespace

std::vector<std::pair<std::string, std::string>> build_provenance() {
  std::vector<std::pair<std::string, std::string>> p = {
      {"gjklab_version", build_info::version},
      {"git_commit", build_info::git_commit},
      {"compiler", build_info::compiler},
      {"build_type", build_info::build_type},
      {"cxx_flags", build_info::cxx_flags},
      {"cgal_version", exact::cgal_version()},
      {"eigen_version", std::to_string(EIGEN_WORLD_VERSION) + "." +
                            std::to_string(EIGEN_MAJOR_VERSION) + "." +
                            std::to_string(EIGEN_MINOR_VERSION)},
      {"hdf5_version", hdf5_version()},
      {"gsl_version", GSL_VERSION},
      {"libccd_version", peers::libccd_version()},
      {"optional_peers", optional_peers()},
  };
  // Distributed runs: the MPI library this build joins jobs with (absent without MPI).
  if (const std::string mpi = mpi_library_version(); !mpi.empty())
    p.emplace_back("mpi_version", mpi);
#ifdef GJKLAB_HAVE_FCL
  p.emplace_back("fcl_version", peers::fcl_version());
  p.emplace_back("fcl_settings", peers::fcl_settings());
#endif
#ifdef GJKLAB_HAVE_BULLET
  p.emplace_back("bullet_version", peers::bullet_version());
#endif
  return p;
}

}  // namespace gjklab::experiment
