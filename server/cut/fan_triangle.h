// Which triangle of a fan holds a point: a face split as a fan from a point inside it over its
// boundary (cut/face_split.h), and a second point on the face, all as barycentric weights on the
// face's corners.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <span>

namespace kerf::cut {

// The index i of the fan triangle (hub, boundary[i], boundary[i + 1], cyclic) that holds `point`
// with each of its weights in that triangle at least `margin`; none where the point lies within
// that margin of the fan's edges, or outside the face. The same inputs in the same order give the
// same answer, so the two tets at a face, asking with the face's corners in one order, agree.
// O(boundary).
std::optional<int> FanTriangleHolding(std::span<const Eigen::Vector3d> boundary,
                                      const Eigen::Vector3d& hub, const Eigen::Vector3d& point,
                                      double margin);

}  // namespace kerf::cut
