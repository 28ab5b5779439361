// How far the opening a cut made trails the blade: the part of the swept surface that is not
// yet an opening in the mesh, as an area, and as the tip's travel (and the poses) since the
// last pose whose swept surface is all open, to within a quarter of the largest step's area
// (each tet's crack is flat, the swept surface of a turning blade is not).
//
// The swept surface is the two triangles per step (cutting.md), clipped to the tissue before
// the cut; the opening is the crack of the cut mesh (mesh::MeasureCrackArea). Both on the
// positions the blade's path is given in (a mesh at rest, as `kerf cut` cuts it).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <optional>
#include <vector>

#include "cut/blade.h"
#include "mesh/tet_mesh.h"

namespace kerf::cut {

struct PoseLag {
  double swept_area = 0;    // m^2, the swept surface inside the tissue so far
  double open_area = 0;     // m^2, the crack open in the mesh now
  double lag_area = 0;      // m^2, swept - open, at least 0
  double lag_distance = 0;  // m, the tip's travel since the last pose swept no more than is open
  int lag_steps = 0;        // poses since then
};

class LagMeter {
 public:
  // `tissue` is the mesh before the cut.
  explicit LagMeter(const mesh::TetMesh& tissue);

  // Call after each pose was applied, with the crack open in the cut mesh then
  // (mesh::MeasureCrackArea(cut), m^2). O(tets of the tissue).
  PoseLag Measure(const BladePose& pose, double open_area);

 private:
  // The area of the triangle inside the tissue.
  double AreaInside(const std::array<Eigen::Vector3d, 3>& triangle) const;

  std::vector<std::array<Eigen::Vector3d, 4>> tets_;
  std::vector<std::array<Eigen::Vector3d, 2>> boxes_;
  double tolerance_;         // m^2: areas closer than this are equal
  double largest_step_ = 0;  // m^2, the largest area swept in one step
  std::optional<BladePose> previous_;
  std::vector<double> swept_;   // per pose so far
  std::vector<double> travel_;  // the tip's travel up to each pose
};

}  // namespace kerf::cut
