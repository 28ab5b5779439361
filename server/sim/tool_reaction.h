// What the user holding the blade feels: the reaction of the tissue on the blade.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <span>

#include "cut/blade.h"
#include "sim/simulation.h"

namespace kerf::sim {

struct ToolReaction {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   // N, on the blade
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();  // N m, about the tip
  double length_inside = 0;                          // m of blade inside tissue
};

// Resistance to cutting per metre of blade edge inside the tissue, N/m (about 1 N for a
// 1 cm deep cut, the order measured for scalpels in soft tissue).
inline constexpr double kCuttingResistance = 100.0;

// What the blade at `pose` holds: K u at the vertices of the tets that hold it (the cut front
// pulls or pushes on it), taken from `elastic_forces` (-K u by vertex index, N: the model's
// MultiplyStiffness negated), plus the cutting resistance opposed to the tip's motion since
// `previous` (none when it has not moved). Zero when the blade touches nothing. O(tets near
// the blade).
ToolReaction MeasureToolReaction(const Simulation& simulation,
                                 std::span<const Eigen::Vector3d> elastic_forces,
                                 const cut::BladePose& pose,
                                 const std::optional<cut::BladePose>& previous);

}  // namespace kerf::sim
