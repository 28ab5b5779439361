// Fuzz target for every mesh reader. The first byte picks the reader; the rest is the file.
// Whatever the input, a reader returns a mesh or an error and never crashes, hangs or leaks;
// a mesh it returns builds, validates, and survives a write and read back unchanged.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "mesh/io/abaqus_inp_reader.h"
#include "mesh/io/gmsh_msh_reader.h"
#include "mesh/io/gmsh_msh_writer.h"
#include "mesh/io/tetgen_reader.h"
#include "mesh/io/vtk_legacy_reader.h"
#include "mesh/io/vtu_reader.h"
#include "mesh/io/vtu_writer.h"
#include "mesh/mesh_validation.h"

namespace {

using kerf::mesh::TetMeshData;

void Check(bool condition) {
  if (!condition) std::abort();
}

void CheckRoundTrip(const TetMeshData& data) {
  absl::StatusOr<kerf::mesh::TetMesh> mesh = kerf::mesh::BuildTetMesh(data);
  Check(mesh.ok());
  (void)kerf::mesh::FindMeshDefects(*mesh);
  for (const bool msh : {true, false}) {
    const std::string text = msh ? kerf::mesh::FormatGmshMsh4(*mesh) : kerf::mesh::FormatVtu(*mesh);
    absl::StatusOr<TetMeshData> again =
        msh ? kerf::mesh::ParseGmshMsh(text, "again.msh") : kerf::mesh::ParseVtu(text, "again.vtu");
    Check(again.ok());
    Check(again->points == data.points);
    Check(again->tets == data.tets);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* bytes, std::size_t size) {
  if (size == 0) return 0;
  const absl::string_view text(reinterpret_cast<const char*>(bytes + 1), size - 1);
  absl::StatusOr<TetMeshData> data;
  switch (bytes[0] % 5) {
    case 0:
      data = kerf::mesh::ParseGmshMsh(text, "fuzz.msh");
      break;
    case 1:
      data = kerf::mesh::ParseVtkLegacy(text, "fuzz.vtk");
      break;
    case 2:
      data = kerf::mesh::ParseVtu(text, "fuzz.vtu");
      break;
    case 3:
      data = kerf::mesh::ParseAbaqusInpMesh(text, "fuzz.inp");
      break;
    case 4: {
      // The .node and .ele files, split at the first NUL (or all .node).
      const std::size_t split = std::min(text.find('\0'), text.size());
      data = kerf::mesh::ParseTetGen(text.substr(0, split), "fuzz.node",
                                     text.substr(std::min(split + 1, text.size())), "fuzz.ele");
      break;
    }
  }
  if (data.ok()) {
    CheckRoundTrip(*data);
  } else {
    Check(!data.status().message().empty());
  }
  return 0;
}
