// Where two triangles cross: the segment they share, for where the blade's swept surface comes
// through the tissue's surface (cut/crack_cutter_snap.cc).
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>

namespace kerf::geometry {

// The segment along which triangles abc and def cross (its two ends; equal where they meet at a
// point only), boundaries included. nullopt where they do not meet, or lie in one plane (each
// edge's crossing of the other is then IntersectSegmentTriangle's nullopt: cutting handles a
// blade in the plane of a face apart).
std::optional<std::array<Eigen::Vector3d, 2>> TrianglesCross(
    const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
    const Eigen::Vector3d& d, const Eigen::Vector3d& e, const Eigen::Vector3d& f);

}  // namespace kerf::geometry
