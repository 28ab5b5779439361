#include "mesh/io/vtk_legacy_reader.h"

#include <vector>

#include "absl/strings/ascii.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "mesh/io/tet_mesh_data_builder.h"
#include "mesh/io/text_scanner.h"
#include "mesh/io/vtk_cell_types.h"

namespace kerf::mesh {
namespace {

using internal::TextScanner;

absl::StatusOr<std::vector<std::int64_t>> ReadInts(TextScanner& s, std::int64_t count,
                                                   absl::string_view what) {
  std::vector<std::int64_t> values;
  values.reserve(internal::ReservableCount(count, s.text().size()));
  for (std::int64_t i = 0; i < count; ++i) {
    absl::StatusOr<std::int64_t> v = s.NextInt(what);
    if (!v.ok()) return v.status();
    values.push_back(*v);
  }
  return values;
}

struct Cells {
  std::vector<std::int64_t> offsets;       // cell i spans connectivity[offsets[i], offsets[i+1])
  std::vector<std::int64_t> connectivity;  // point indices
  std::size_t offset_in_text = 0;
};

// Classic: "CELLS n size" then n lines "k i1 .. ik".
absl::StatusOr<Cells> ReadClassicCells(TextScanner& s, std::int64_t n, std::int64_t size) {
  Cells cells;
  cells.offsets.reserve(internal::ReservableCount(n + 1, s.text().size()));
  cells.offsets.push_back(0);
  for (std::int64_t i = 0; i < n; ++i) {
    absl::StatusOr<std::int64_t> k = s.NextIntIn("cell point count", 0, size);
    if (!k.ok()) return k.status();
    for (std::int64_t j = 0; j < *k; ++j) {
      absl::StatusOr<std::int64_t> index = s.NextInt("point index");
      if (!index.ok()) return index.status();
      cells.connectivity.push_back(*index);
    }
    cells.offsets.push_back(static_cast<std::int64_t>(cells.connectivity.size()));
  }
  if (static_cast<std::int64_t>(cells.connectivity.size()) + n != size) {
    return s.Error(absl::StrCat("CELLS declares size ", size, " but its cells hold ",
                                cells.connectivity.size() + static_cast<std::size_t>(n),
                                " numbers"));
  }
  return cells;
}

// 5.1: "CELLS n_offsets n_connectivity", "OFFSETS <type>", offsets, "CONNECTIVITY <type>", ids.
absl::StatusOr<Cells> ReadOffsetCells(TextScanner& s, std::int64_t n_offsets,
                                      std::int64_t n_connectivity) {
  Cells cells;
  if (auto st = s.Expect("OFFSETS"); !st.ok()) return st;
  s.NextToken();  // the integer type name
  absl::StatusOr<std::vector<std::int64_t>> offsets = ReadInts(s, n_offsets, "cell offset");
  if (!offsets.ok()) return offsets.status();
  if (auto st = s.Expect("CONNECTIVITY"); !st.ok()) return st;
  s.NextToken();
  absl::StatusOr<std::vector<std::int64_t>> connectivity =
      ReadInts(s, n_connectivity, "point index");
  if (!connectivity.ok()) return connectivity.status();
  cells.offsets = *std::move(offsets);
  cells.connectivity = *std::move(connectivity);
  if (cells.offsets.empty() || cells.offsets.front() != 0 ||
      cells.offsets.back() != n_connectivity) {
    return s.Error("OFFSETS must start at 0 and end at the CONNECTIVITY size");
  }
  for (std::size_t i = 1; i < cells.offsets.size(); ++i) {
    if (cells.offsets[i] < cells.offsets[i - 1]) return s.Error("OFFSETS must not decrease");
  }
  return cells;
}

}  // namespace

absl::StatusOr<TetMeshData> ParseVtkLegacy(absl::string_view text, absl::string_view source) {
  TextScanner s(text, source);
  const absl::string_view header = s.NextLine();
  if (!absl::StartsWith(header, "# vtk DataFile Version")) {
    return s.ErrorExpected("'# vtk DataFile Version' on the first line");
  }
  const bool offsets_layout = absl::StrContains(header, "Version 5");
  s.NextLine();  // title
  const absl::string_view format = s.NextToken();
  if (format == "BINARY") return s.Error("binary VTK legacy files are not supported: use ASCII");
  if (format != "ASCII") return s.ErrorExpected("'ASCII'");
  if (auto st = s.Expect("DATASET"); !st.ok()) return st;
  if (auto st = s.Expect("UNSTRUCTURED_GRID"); !st.ok()) return st;

  TetMeshData data;
  Cells cells;
  std::vector<std::int64_t> types;
  bool have_points = false, have_cells = false, have_types = false;
  std::size_t cells_offset = 0;
  while (!(have_points && have_cells && have_types)) {
    const absl::string_view keyword = s.NextToken();
    if (keyword == "POINTS") {
      absl::StatusOr<std::int64_t> n = s.NextIntIn("point count", 0, internal::kMaxItemCount);
      if (!n.ok()) return n.status();
      s.NextToken();  // float or double
      data.points.reserve(internal::ReservableCount(*n, text.size()));
      for (std::int64_t i = 0; i < *n; ++i) {
        absl::StatusOr<Eigen::Vector3d> p = internal::ReadPoint(s);
        if (!p.ok()) return p.status();
        data.points.push_back(*p);
        data.point_ids.push_back(i);
      }
      have_points = true;
    } else if (keyword == "CELLS") {
      cells_offset = s.offset();
      absl::StatusOr<std::int64_t> a = s.NextIntIn("cell count", 0, internal::kMaxItemCount);
      if (!a.ok()) return a.status();
      absl::StatusOr<std::int64_t> b = s.NextIntIn("cell list size", 0, internal::kMaxItemCount);
      if (!b.ok()) return b.status();
      absl::StatusOr<Cells> read =
          offsets_layout ? ReadOffsetCells(s, *a, *b) : ReadClassicCells(s, *a, *b);
      if (!read.ok()) return read.status();
      cells = *std::move(read);
      have_cells = true;
    } else if (keyword == "CELL_TYPES") {
      absl::StatusOr<std::int64_t> n = s.NextIntIn("cell type count", 0, internal::kMaxItemCount);
      if (!n.ok()) return n.status();
      absl::StatusOr<std::vector<std::int64_t>> read = ReadInts(s, *n, "cell type");
      if (!read.ok()) return read.status();
      types = *std::move(read);
      have_types = true;
    } else if (keyword == "METADATA") {
      // Blocks of information keys, ended by an empty line.
      s.NextLine();
      while (s.offset() < text.size() && !absl::StripAsciiWhitespace(s.NextLine()).empty()) {
      }
    } else {
      return s.ErrorExpected("'POINTS', 'CELLS' or 'CELL_TYPES'");
    }
  }
  if (types.size() + 1 != cells.offsets.size()) {
    return s.Error(absl::StrCat("CELL_TYPES lists ", types.size(), " types for ",
                                cells.offsets.size() - 1, " cells"));
  }
  for (std::size_t i = 0; i < types.size(); ++i) {
    const std::int64_t begin = cells.offsets[i], end = cells.offsets[i + 1];
    if (types[i] != internal::kVtkTetra) {
      if (internal::IsLowerDimensionVtkCell(types[i])) continue;
      return s.ErrorAt(cells_offset, absl::StrCat("cell ", i, " has type ", types[i],
                                                  ", which is not supported: kerf reads "
                                                  "tetrahedra (type 10)"));
    }
    if (end - begin != 4) {
      return s.ErrorAt(cells_offset,
                       absl::StrCat("tetra cell ", i, " has ", end - begin, " points, expected 4"));
    }
    std::array<std::uint32_t, 4> tet;
    for (int c = 0; c < 4; ++c) {
      const std::int64_t index = cells.connectivity[static_cast<std::size_t>(begin + c)];
      if (index < 0 || index >= static_cast<std::int64_t>(data.points.size())) {
        return s.ErrorAt(cells_offset, absl::StrCat("cell ", i, " names point ", index, " of ",
                                                    data.points.size()));
      }
      tet[c] = static_cast<std::uint32_t>(index);
    }
    data.tets.push_back(tet);
  }
  return data;
}

}  // namespace kerf::mesh
