// A box filled with a lattice of cubes, six conforming tets per cube.
#pragma once

#include <Eigen/Core>

#include "absl/status/statusor.h"
#include "mesh/tet_mesh.h"

namespace kerf::mesh {

struct BoxLatticeSpec {
  int cells_x = 1;  // cubes along x; each count must be in [1, 1024]
  int cells_y = 1;
  int cells_z = 1;
  // The box's edge lengths; each must be positive and finite. Unset (zero) means one length
  // unit per cube. The box spans [0, size].
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
};

// Each cube is split into six tets around its diagonal from the low corner to the high one
// (the Kuhn split). Every cube is split the same way, so the face diagonals of neighbouring
// cubes agree and the mesh is conforming. All tets are positively oriented. `4 6 4` gives the
// paper's 576 tets. Vertices and cubes are numbered along a Z-order (Morton) curve, so that
// what is close in space is close in memory; the cube at the origin comes first, its six tets
// being tets 0-5, and vertex 0 is the corner at the origin.
// INVALID_ARGUMENT naming the field for a count or size out of range.
absl::StatusOr<TetMesh> MakeBoxLattice(const BoxLatticeSpec& spec);

}  // namespace kerf::mesh
