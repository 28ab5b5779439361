// The closest point of a triangle to a point: the test behind judging a cut against the
// blade's path (how far a crack face lies from the swept surface, and a sample of the swept
// surface from the crack).
#pragma once

#include <Eigen/Core>

namespace kerf::geometry {

// The point of triangle abc (boundary included) closest to x. A degenerate triangle (a
// segment or a point) gives the closest point of what it is.
Eigen::Vector3d ClosestPointOnTriangle(const Eigen::Vector3d& x, const Eigen::Vector3d& a,
                                       const Eigen::Vector3d& b, const Eigen::Vector3d& c);

// |x - ClosestPointOnTriangle(x, a, b, c)|, in the points' unit.
double DistanceToTriangle(const Eigen::Vector3d& x, const Eigen::Vector3d& a,
                          const Eigen::Vector3d& b, const Eigen::Vector3d& c);

}  // namespace kerf::geometry
