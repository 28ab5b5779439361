#include "mesh/io/abaqus_inp_reader.h"

#include <cmath>

#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"
#include "mesh/io/abaqus_inp_blocks.h"
#include "mesh/io/tet_mesh_data_builder.h"
#include "mesh/io/text_scanner.h"

namespace kerf::mesh {

absl::StatusOr<TetMeshData> ParseAbaqusInpMesh(absl::string_view text, absl::string_view source) {
  absl::StatusOr<std::vector<internal::InpKeywordBlock>> blocks =
      internal::ParseInpKeywordBlocks(text, source);
  if (!blocks.ok()) return blocks.status();
  const internal::TextScanner errors(text, source);
  internal::TetMeshDataBuilder builder;
  bool have_nodes = false;
  for (const internal::InpKeywordBlock& block : *blocks) {
    if (block.keyword == "NODE") {
      have_nodes = true;
      for (const internal::InpDataLine& line : block.lines) {
        std::int64_t id = 0;
        Eigen::Vector3d p;
        bool ok = line.fields.size() == 4 && internal::ParseInt(line.fields[0], &id);
        for (int axis = 0; ok && axis < 3; ++axis) {
          ok = internal::ParseDouble(line.fields[axis + 1], &p[axis]) && std::isfinite(p[axis]);
        }
        if (!ok) {
          return errors.ErrorAt(line.offset,
                                "expected a *NODE line 'id, x, y, z' with an "
                                "integer id and finite coordinates");
        }
        if (auto st = builder.AddPoint(id, p, errors, line.offset); !st.ok()) return st;
      }
    } else if (block.keyword == "ELEMENT") {
      const std::string type = absl::AsciiStrToUpper(block.Parameter("TYPE").value_or(""));
      if (type != "C3D4") {
        return errors.ErrorAt(block.offset, absl::StrCat("element type '", type,
                                                         "' is not supported: kerf reads "
                                                         "linear tetrahedra (TYPE=C3D4)"));
      }
      for (const internal::InpDataLine& line : block.lines) {
        std::array<std::int64_t, 5> ids;
        bool ok = line.fields.size() == 5;
        for (std::size_t i = 0; ok && i < 5; ++i) ok = internal::ParseInt(line.fields[i], &ids[i]);
        if (!ok) {
          return errors.ErrorAt(line.offset,
                                "expected a C3D4 line 'id, n1, n2, n3, n4' of "
                                "integers");
        }
        builder.AddTet({ids[1], ids[2], ids[3], ids[4]}, line.offset);
      }
    }
  }
  if (!have_nodes || builder.tet_count() == 0) {
    return errors.ErrorAt(text.size(), "expected *NODE and *ELEMENT, TYPE=C3D4 blocks");
  }
  return std::move(builder).Finish(errors);
}

}  // namespace kerf::mesh
