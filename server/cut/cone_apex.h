// Where a cone splitting a tet by its crack (cut/crack_split.h, SplitAsCone) has its apex: a
// point inside, near where the blade went, whose pieces are as round as the faces' triangles
// allow.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <vector>

#include "cut/crack_split.h"
#include "mesh/mesh_ids.h"

namespace kerf::cut {

// The barycentric weights of a cone's apex for good. Where the crack has an inner part: of points
// on the plane that fits its trace points (their middle, the tet's middle projected on that
// plane, points between, then a short pattern search on the plane), each pulled inside along the
// plane where it can be, the one whose cone's smallest dihedral angle is largest among those
// near where the blade went, so the crack's faces stay on the swept surface and its pieces are
// as round as the faces' triangles allow. Where it has none, the same search from the tet's
// middle, anywhere inside. About 20 cones are tried. `rest` gives rest positions.
// Near where the blade went: `near_path`, where given, says whether an apex (barycentric) lies
// within kApexReach of the surface the blade swept; otherwise within kApexReach of the crack's
// plane. Where no candidate is near (the swept surface bends away from the plane of the traces,
// snapped corners among them; a blade that clipped the tet's corner), points where the blade went
// inside the tet (`on_path`, barycentric, asked for only then; at most kOnPathCandidates of them,
// spread evenly), pulled inside by kOnPathApexMargin, are tried wherever they lie off the plane.
// Where none is near either, the best of those no farther off the plane than the first (the
// middle of the trace points, pulled inside).
using ApexNearPath = std::function<bool(const Eigen::Vector4d&)>;
using ApexOnPath = std::function<std::vector<Eigen::Vector4d>()>;
inline constexpr int kOnPathCandidates = 32;
// How far inside (barycentric) a point where the blade went is pulled as a candidate: less than
// kApexMargin, so one in a tet the blade clipped near a corner stays near the path (measured in
// docs/cutting-fidelity.md, "A cone's apex where the blade went").
inline constexpr double kOnPathApexMargin = 0.1;
Eigen::Vector4d ConeApexWeights(const TetCrack& crack,
                                const std::function<Eigen::Vector3d(mesh::VertexId)>& rest,
                                const ApexNearPath& near_path = nullptr,
                                const ApexOnPath& on_path = nullptr);

// The smallest dihedral angle (degrees) of the cone with its apex at barycentric `weights`, on
// rest positions.
double SmallestConeAngle(const TetCrack& crack,
                         const std::function<Eigen::Vector3d(mesh::VertexId)>& rest,
                         const Eigen::Vector4d& weights);

// The apex (barycentric) of the cone to split the tet by for good instead of `split`, a split
// without a new point: where `split` has pieces under `degrees` and the best cone
// (ConeApexWeights) has fewer. Its face triangles are the same, so the tets beside it agree.
// nullopt otherwise (a whole tet, no piece under `degrees`, or no cone with fewer).
std::optional<Eigen::Vector4d> ConeApexWithFewerSlivers(
    const TetCrack& crack, const CrackSplit& split,
    const std::function<Eigen::Vector3d(mesh::VertexId)>& rest, double degrees,
    const ApexNearPath& near_path = nullptr, const ApexOnPath& on_path = nullptr);

// A cone's apex is kept at least this far (barycentric) from the tet's faces.
inline constexpr double kApexMargin = 0.15;
// An apex near where the blade went lies within this share of its tet's mean edge of the surface
// the blade swept (or of the crack's plane): the cone's crack faces then stay within the fidelity
// meter's tolerance (0.25 l, lab/crack_fidelity.h) of the blade's path.
inline constexpr double kApexReach = 0.22;
// Barycentric weights (summing to 1) moved towards `towards` (weights each at least kApexMargin;
// by default the tet's middle) until each is at least kApexMargin.
Eigen::Vector4d PulledInside(const Eigen::Vector4d& weights,
                             const Eigen::Vector4d& towards = Eigen::Vector4d::Constant(0.25),
                             double margin = kApexMargin);

}  // namespace kerf::cut
