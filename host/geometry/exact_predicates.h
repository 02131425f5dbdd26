// The signs of the 2D and 3D orientation determinants of double-precision
// points, exact for every finite input: a floating-point evaluation whose
// error bound is rigorous (Shewchuk 1997, "Adaptive precision floating-point
// arithmetic and fast robust geometric predicates", the A-stage bounds of
// orient2d and orient3d, with a term for underflow) decides when it can, and
// exact integer arithmetic decides the rest.
#pragma once

#include <cstdint>

namespace snh::geometry {

// +1 when a, b, c turn counterclockwise, -1 clockwise, 0 when collinear.
int orient2d(const double a[2], const double b[2], const double c[2]);

// +1 when d lies below the plane through a, b, c (a, b, c counterclockwise
// seen from above), -1 above, 0 when the four points are coplanar: the sign
// of det[a-d; b-d; c-d].
int orient3d(const double a[3], const double b[3], const double c[3], const double d[3]);

// How many calls the floating-point filter could not decide (exact
// fallbacks) since the program started, for tests of the fallback.
uint64_t exact_predicate_fallbacks();

}  // namespace snh::geometry
