#include <CGAL/version.h>

#include "gjklab/exact/oracle.hpp"

namespace gjklab::exact {

std::string cgal_version() {
  return CGAL_VERSION_STR;
}

}  // namespace gjklab::exact
