// Structural checks of a tet mesh, reporting each defect precisely.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "mesh/mesh_ids.h"
#include "mesh/tet_mesh.h"

namespace kerf::mesh {

enum class MeshDefectKind {
  kNonPositiveVolume,  // a tet whose rest volume is <= 0 (flat or inverted)
  kRepeatedVertex,     // a tet naming one vertex twice
  kOverSharedFace,     // a triangle that is a face of three or more tets
  kDanglingVertex,     // a live vertex that no tet uses
};

struct MeshDefect {
  MeshDefectKind kind;
  // Which elements: the tet (volume, repeated vertex), the face's three vertices and the tets
  // sharing it, or the vertex. Unused fields are empty.
  std::vector<TetId> tets;
  std::vector<VertexId> vertices;
  double rest_volume = 0;  // kNonPositiveVolume only
  std::string message;     // one line naming the elements and the values
};

// Every defect in the mesh; empty for a valid mesh. Each over-shared face is reported once.
// O(tets * star size).
std::vector<MeshDefect> FindMeshDefects(const TetMesh& mesh);
// The defects of the live tets among `tets` (their volume, vertices and faces) and of the live
// vertices among `vertices` (used by no tet): after a change, those it added and those around
// what it removed are all that can have become defective. O((tets + vertices) * star size).
std::vector<MeshDefect> FindMeshDefectsAmong(const TetMesh& mesh, std::span<const TetId> tets,
                                             std::span<const VertexId> vertices);

// OK for a valid mesh, else FAILED_PRECONDITION naming the defect count and the first few.
absl::Status ValidateMesh(const TetMesh& mesh);
// The same for FindMeshDefectsAmong.
absl::Status ValidateMeshAmong(const TetMesh& mesh, std::span<const TetId> tets,
                               std::span<const VertexId> vertices);

}  // namespace kerf::mesh
