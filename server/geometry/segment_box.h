// Whether a segment meets an axis-aligned box: a cheap test before exact ones.
#pragma once

#include <Eigen/Core>

namespace kerf::geometry {

// Whether the segment p-q meets the closed box [lo, hi] (slab test). Conservative by
// `margin` (m): a segment within `margin` of the box counts as meeting it.
bool SegmentMeetsBox(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& lo,
                     const Eigen::Vector3d& hi, double margin);

}  // namespace kerf::geometry
