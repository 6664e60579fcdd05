#include "gjklab/peers/libccd.hpp"

namespace gjklab::peers {

// libccd's headers carry no version macro: CMake passes the version its package config reports.
std::string libccd_version() {
  return GJKLAB_LIBCCD_VERSION;
}

}  // namespace gjklab::peers
