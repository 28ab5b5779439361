// Reading and writing mesh files by their extension.
//   read:  .msh (Gmsh 1, 2, 4), .vtk (legacy), .vtu, .node or .ele (TetGen; the other file
//          of the pair is found beside it), .inp (Abaqus/CalculiX)
//   write: .vtu (current positions), .msh (MSH 4.1, rest positions)
#pragma once

#include <string>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "mesh/io/tet_mesh_data.h"
#include "mesh/tet_mesh.h"

namespace kerf::mesh {

// The file's contents; NOT_FOUND if it cannot be opened.
absl::StatusOr<std::string> ReadTextFile(absl::string_view path);
absl::Status WriteTextFile(absl::string_view path, absl::string_view text);

// INVALID_ARGUMENT for an unknown extension; parse errors name the file and line.
absl::StatusOr<TetMeshData> ReadMeshFileData(absl::string_view path);
absl::StatusOr<TetMesh> ReadMeshFile(absl::string_view path);

// INVALID_ARGUMENT for an extension kerf does not write.
absl::Status WriteMeshFile(const TetMesh& mesh, absl::string_view path);

}  // namespace kerf::mesh
