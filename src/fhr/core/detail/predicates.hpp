// FHR core — exact geometric predicates. The paper's Proposition 1 (§4: ψ_i is one-to-one) is
// certified on the output by the sign of orient2d for every image triangle; a wrong sign from
// round-off would certify a fold. So these signs are exact for all finite double inputs:
// a floating-point evaluation with a forward error bound (Shewchuk 1997, "Adaptive precision
// floating-point arithmetic and fast robust geometric predicates", the bounds ccwerrboundA and
// o3derrboundA), and when the bound cannot decide, an exact evaluation: for orient2d with
// coordinates of moderate exponent (0 or 2^-450..2^450) a sum of error-free products (Shewchuk's
// expansions, about 100 flops; collinear points of generated meshes need it constantly),
// otherwise in GMP rationals (every double is a rational, so the determinant is computed without
// error).
#pragma once

#include <Eigen/Core>

namespace fhr {

/// Sign (+1, 0, −1) of det[b−a, c−a]: +1 iff a, b, c turn counter-clockwise. Exact.
int orient2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c);

/// Sign of det[a−d, b−d, c−d]: +1 iff d lies below the plane through a, b, c seen
/// counter-clockwise from above (Shewchuk's convention). Exact.
int orient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& d);

/// True iff the three points are exactly collinear (or coincide): (b−a) × (c−a) = 0 exactly.
bool collinear(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

}  // namespace fhr
