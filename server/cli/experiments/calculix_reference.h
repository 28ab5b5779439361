// The converged reference of an accuracy bar (lab/accuracy_bar.h): CalculiX (`ccx`, installed
// by scripts/setup) on quadratic tets (C3D10, which do not lock as linear tets do at
// nu = 0.45) of the same lattice, with the same held faces and load. The twist is solved
// geometrically non-linear (NLGEOM: large rotation, as the corotational model assumes), the
// cantilever and the tension linear (as the paper's model). On the cantilever at n = 6 it
// gives 0.18708, within 0.6% of the extrapolated 0.1882 of ../shared/design/accuracy.md.
#pragma once

#include <Eigen/Core>

#include "absl/status/statusor.h"
#include "lab/accuracy_bar.h"

namespace kerf::cli {

// The bar's quantity (see lab::BarLoad) at resolution n (even, in [2, 64]), solved by ccx in
// a temporary folder that is removed afterwards. FAILED_PRECONDITION if ccx is not installed;
// INTERNAL with the end of its log if it fails or prints no result.
absl::StatusOr<Eigen::Vector3d> CalculixReference(lab::BarLoad load, int n);

}  // namespace kerf::cli
