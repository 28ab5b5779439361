#include "mesh/io/tetgen_reader.h"

#include "absl/strings/str_cat.h"
#include "mesh/io/tet_mesh_data_builder.h"
#include "mesh/io/text_scanner.h"

namespace kerf::mesh {
namespace {

using internal::TextScanner;

absl::Status ReadNodes(TextScanner& s, internal::TetMeshDataBuilder& builder) {
  // <# of points> <dimension (3)> <# of attributes> <boundary markers (0 or 1)>
  absl::StatusOr<std::int64_t> count = s.NextIntIn("point count", 0, internal::kMaxItemCount);
  if (!count.ok()) return count.status();
  absl::StatusOr<std::int64_t> dimension = s.NextIntIn("dimension", 3, 3);
  if (!dimension.ok()) return dimension.status();
  absl::StatusOr<std::int64_t> attributes = s.NextIntIn("attribute count", 0, 1024);
  if (!attributes.ok()) return attributes.status();
  absl::StatusOr<std::int64_t> markers = s.NextIntIn("boundary marker flag", 0, 1);
  if (!markers.ok()) return markers.status();
  for (std::int64_t i = 0; i < *count; ++i) {
    absl::StatusOr<std::int64_t> id = s.NextInt("point id");
    if (!id.ok()) return id.status();
    absl::StatusOr<Eigen::Vector3d> p = internal::ReadPoint(s);
    if (!p.ok()) return p.status();
    for (std::int64_t a = 0; a < *attributes + *markers; ++a) {
      if (absl::StatusOr<double> x = s.NextFiniteDouble("point attribute or marker"); !x.ok()) {
        return x.status();
      }
    }
    if (auto st = builder.AddPoint(*id, *p, s, s.token_offset()); !st.ok()) return st;
  }
  if (!s.AtEnd()) {
    s.NextToken();
    return s.ErrorExpected(absl::StrCat("end of file after ", *count, " points"));
  }
  return absl::OkStatus();
}

absl::Status ReadTets(TextScanner& s, internal::TetMeshDataBuilder& builder) {
  // <# of tetrahedra> <nodes per tetrahedron> <# of attributes>
  absl::StatusOr<std::int64_t> count = s.NextIntIn("tetrahedron count", 0, internal::kMaxItemCount);
  if (!count.ok()) return count.status();
  absl::StatusOr<std::int64_t> corners = s.NextIntIn("nodes per tetrahedron", 4, 10);
  if (!corners.ok()) return corners.status();
  if (*corners != 4) {
    return s.Error(absl::StrCat(*corners,
                                "-node tetrahedra are not supported: kerf reads "
                                "linear (4-node) tetrahedra"));
  }
  absl::StatusOr<std::int64_t> attributes = s.NextIntIn("attribute count", 0, 1024);
  if (!attributes.ok()) return attributes.status();
  for (std::int64_t i = 0; i < *count; ++i) {
    const std::size_t offset = (s.PeekToken(), s.offset());
    if (absl::StatusOr<std::int64_t> id = s.NextInt("tetrahedron id"); !id.ok()) return id.status();
    std::array<std::int64_t, 4> ids;
    for (int c = 0; c < 4; ++c) {
      absl::StatusOr<std::int64_t> v = s.NextInt("corner point id");
      if (!v.ok()) return v.status();
      ids[c] = *v;
    }
    for (std::int64_t a = 0; a < *attributes; ++a) {
      if (absl::StatusOr<double> x = s.NextFiniteDouble("tetrahedron attribute"); !x.ok()) {
        return x.status();
      }
    }
    builder.AddTet(ids, offset);
  }
  if (!s.AtEnd()) {
    s.NextToken();
    return s.ErrorExpected(absl::StrCat("end of file after ", *count, " tetrahedra"));
  }
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<TetMeshData> ParseTetGen(absl::string_view node_text, absl::string_view node_source,
                                        absl::string_view ele_text, absl::string_view ele_source) {
  internal::TetMeshDataBuilder builder;
  TextScanner nodes(node_text, node_source, '#');
  if (auto st = ReadNodes(nodes, builder); !st.ok()) return st;
  TextScanner tets(ele_text, ele_source, '#');
  if (auto st = ReadTets(tets, builder); !st.ok()) return st;
  return std::move(builder).Finish(tets);
}

}  // namespace kerf::mesh
