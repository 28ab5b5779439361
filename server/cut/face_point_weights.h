// Where a blade's crossing of a face sits when it stays a point of the face (not taken at an
// edge or a corner; see crack_cutter.h). A point near an edge of the face makes the pieces fanned
// from it over that edge flat, and a point near two edges (near their corner) makes two of them
// flat, so the point is moved off the edges by a share of the face.
#pragma once

#include <Eigen/Core>

namespace kerf::cut {

// `b`, barycentric weights on a face's corners (non-negative, summing to 1), moved off the
// face's edges: the smallest weight raised to `share` (the crossing's snap share; at most a
// third is used), then every weight under share / 2 raised to it. Each raise takes from the
// other two weights in proportion to them, so the sum stays 1 (and the first raised weight may
// end a little under `share`: 0.19 at the least for a share of 0.2). Weights already off the
// edges come back as they were.
Eigen::Vector3d FacePointOffEdges(const Eigen::Vector3d& b, double share);

}  // namespace kerf::cut
