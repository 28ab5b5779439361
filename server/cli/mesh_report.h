// The statistics `kerf mesh info` prints, gathered from the mesh library into the
// kerf.v1.MeshReport message, and their text and JSON forms.
#pragma once

#include <string>

#include "absl/strings/string_view.h"
#include "kerf/v1/mesh_report.pb.h"
#include "mesh/tet_mesh.h"

namespace kerf::cli {

// Counts, validity, quality and histogram of a mesh. O(tets * star size).
kerf::v1::MeshReport MakeMeshReport(const mesh::TetMesh& mesh, absl::string_view source);

// Human-readable, several lines.
std::string FormatMeshReportText(const kerf::v1::MeshReport& report);
// One JSON object with the proto field names, every field present.
std::string FormatMeshReportJson(const kerf::v1::MeshReport& report);

}  // namespace kerf::cli
