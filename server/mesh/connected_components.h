// Connected pieces of a mesh: tets are connected when they share a vertex, so two sides of
// a cut that share no vertex are two components.
#pragma once

#include <cstdint>
#include <vector>

#include "mesh/tet_mesh.h"

namespace kerf::mesh {

struct MeshComponents {
  std::size_t count = 0;
  // Component label 0 .. count-1 of each tet, indexed by Index(tet id); dead slots hold -1.
  // Labels follow the order of each component's lowest tet id.
  std::vector<std::int32_t> tet_component;
};

// O(tets * alpha(vertices)) by union-find over vertices.
MeshComponents FindConnectedComponents(const TetMesh& mesh);

}  // namespace kerf::mesh
