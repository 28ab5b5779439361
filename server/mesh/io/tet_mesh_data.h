// Plain arrays of what a mesh file holds: points and linear tets. Readers parse into this,
// writers format from it, and BuildTetMesh turns it into a TetMesh.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "mesh/tet_mesh.h"

namespace kerf::mesh {

struct TetMeshData {
  std::vector<Eigen::Vector3d> points;
  // The id each point has in its file (for messages, node sets and round trips).
  std::vector<std::int64_t> point_ids;
  // Corners of each tet as indices into `points`.
  std::vector<std::array<std::uint32_t, 4>> tets;
};

// A mesh whose vertex Index(i) is point i, at rest, and whose tet i is tets[i].
// INVALID_ARGUMENT if a tet names a point index out of range or the sizes disagree.
absl::StatusOr<TetMesh> BuildTetMesh(const TetMeshData& data);

// The live part of a mesh, renumbered densely in id order; point_ids keep the stable vertex
// ids. Positions are rest positions unless `current` is set.
TetMeshData ExtractTetMeshData(const TetMesh& mesh, bool current = false);

}  // namespace kerf::mesh
