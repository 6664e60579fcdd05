// The contact families' pairs (private to src/experiment/cases): each configuration built in
// exact contact (distance 0) from small dyadic coordinates, A below the plane z = 0 and B above.
#pragma once

#include <gsl/gsl_rng.h>

#include <vector>

#include "gjklab/experiment/config/config.hpp"
#include "gjklab/geometry/types.hpp"

namespace gjklab::experiment {

struct ContactPair {
  std::vector<Vec3> a, b;
  ShapeKind shape_a, shape_b;
};

/// The pair of contact `type` (not `none`), drawn with `r` where the family varies it.
ContactPair build_contact(ContactType type, gsl_rng* r, const FamilySpec& family);

/// The lower shape (A) of a contact family, unrotated, as the shape generators list it:
/// prism, pyramid, segment, needle, rod, wedge and plate (aspect where the shape has one).
std::vector<Vec3> contact_piece(ShapeKind kind, double aspect);

}  // namespace gjklab::experiment
