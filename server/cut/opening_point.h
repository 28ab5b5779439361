// Where a shut crack face opens. A face whose three corners are on the crack and which nothing
// split (the blade swept in its plane, or its corners were snapped to) is opened at a point
// inside it: each tet beside it becomes a fan of three tets from that point over the face's
// edges. The centroid is the obvious point, but when a tet's apex sits near the plane through
// one of the face's edges, the fan tet over that edge is a sliver; a point farther from that
// edge keeps it fat.
#pragma once

#include <Eigen/Core>
#include <array>
#include <span>

namespace kerf::cut {

// The smallest dihedral angle (degrees) of the fan tets from `point` over `face`'s edges to each
// of `apexes`: what the choice below makes largest.
double SmallestFanAngleDeg(const std::array<Eigen::Vector3d, 3>& face, const Eigen::Vector3d& point,
                           std::span<const Eigen::Vector3d> apexes);

// Barycentric weights (summing to 1) on `face`'s corners of the point to open it at: among the
// centroid and six points leaning towards or away from one corner, the one whose fan tets (the
// point, an edge of the face and one of `apexes`, the fourth corners of the tets beside the
// face) have the largest smallest dihedral angle; the centroid unless another is strictly
// better. Positions are in any one length unit (the rest positions, say).
Eigen::Vector3d OpeningPointWeights(const std::array<Eigen::Vector3d, 3>& face,
                                    std::span<const Eigen::Vector3d> apexes);

}  // namespace kerf::cut
