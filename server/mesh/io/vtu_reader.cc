#include "mesh/io/vtu_reader.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <type_traits>
#include <vector>

#include "absl/strings/str_cat.h"
#include "mesh/io/base64.h"
#include "mesh/io/text_scanner.h"
#include "mesh/io/vtk_cell_types.h"
#include "mesh/io/xml_element.h"

namespace kerf::mesh {
namespace {

using internal::TextScanner;
using internal::XmlElement;

struct Encoding {
  bool header_is_64_bit = false;
  bool big_endian = false;
};

// Reads one value of VTK type `type` from little- or big-endian bytes.
template <typename T>
bool ReadScalar(absl::string_view type, const std::uint8_t* bytes, bool big_endian, T* out) {
  auto load = [&](auto tag) {
    using S = decltype(tag);
    std::uint8_t raw[sizeof(S)];
    std::memcpy(raw, bytes, sizeof(S));
    if (big_endian) std::reverse(raw, raw + sizeof(S));
    S value;
    std::memcpy(&value, raw, sizeof(S));
    *out = static_cast<T>(value);
  };
  if (type == "Float32")
    load(float{});
  else if (type == "Float64")
    load(double{});
  else if (type == "Int8")
    load(std::int8_t{});
  else if (type == "UInt8")
    load(std::uint8_t{});
  else if (type == "Int16")
    load(std::int16_t{});
  else if (type == "UInt16")
    load(std::uint16_t{});
  else if (type == "Int32")
    load(std::int32_t{});
  else if (type == "UInt32")
    load(std::uint32_t{});
  else if (type == "Int64")
    load(std::int64_t{});
  else if (type == "UInt64")
    load(std::uint64_t{});
  else
    return false;
  return true;
}

std::size_t SizeOfType(absl::string_view type) {
  if (type == "Int8" || type == "UInt8") return 1;
  if (type == "Int16" || type == "UInt16") return 2;
  if (type == "Float32" || type == "Int32" || type == "UInt32") return 4;
  if (type == "Float64" || type == "Int64" || type == "UInt64") return 8;
  return 0;
}

// The values of a <DataArray>, as T (double or std::int64_t).
template <typename T>
absl::StatusOr<std::vector<T>> DecodeDataArray(const XmlElement& array, const Encoding& encoding,
                                               const TextScanner& errors) {
  const absl::string_view name = array.Attribute("Name").value_or("(unnamed)");
  auto fail = [&](absl::string_view message) {
    return errors.ErrorAt(array.offset, absl::StrCat("DataArray ", name, ": ", message));
  };
  const absl::string_view type = array.Attribute("type").value_or("");
  const std::size_t size = SizeOfType(type);
  if (size == 0)
    return fail(absl::StrCat("expected a numeric type, found ", internal::Quoted(type)));
  const absl::string_view format = array.Attribute("format").value_or("");
  std::vector<T> values;
  if (format == "ascii") {
    TextScanner s(array.text, "");
    for (absl::string_view token = s.NextToken(); !token.empty(); token = s.NextToken()) {
      if constexpr (std::is_floating_point_v<T>) {
        double v = 0;
        if (!internal::ParseDouble(token, &v) || !std::isfinite(v)) {
          return fail(absl::StrCat("expected a finite number, found ", internal::Quoted(token)));
        }
        values.push_back(v);
      } else {
        std::int64_t v = 0;
        if (!internal::ParseInt(token, &v)) {
          return fail(absl::StrCat("expected an integer, found ", internal::Quoted(token)));
        }
        values.push_back(v);
      }
    }
    return values;
  }
  if (format != "binary") {
    return fail(absl::StrCat("format ", internal::Quoted(format),
                             " is not supported: use inline \"ascii\" or \"binary\""));
  }
  const std::optional<std::vector<std::uint8_t>> bytes = internal::Base64Decode(array.text);
  if (!bytes) return fail("invalid base64 data");
  const std::size_t header_size = encoding.header_is_64_bit ? 8 : 4;
  if (bytes->size() < header_size) return fail("binary data is shorter than its header");
  std::uint64_t byte_count = 0;
  ReadScalar(encoding.header_is_64_bit ? "UInt64" : "UInt32", bytes->data(), encoding.big_endian,
             &byte_count);
  if (byte_count > bytes->size() - header_size || byte_count % size != 0) {
    return fail(absl::StrCat("header declares ", byte_count, " bytes of ", type, " but ",
                             bytes->size() - header_size, " bytes follow"));
  }
  values.resize(byte_count / size);
  for (std::size_t i = 0; i < values.size(); ++i) {
    ReadScalar(type, bytes->data() + header_size + i * size, encoding.big_endian, &values[i]);
    if constexpr (std::is_floating_point_v<T>) {
      if (!std::isfinite(values[i])) return fail(absl::StrCat("value ", i, " is not finite"));
    }
  }
  return values;
}

const XmlElement* FindArray(const XmlElement& parent, absl::string_view name) {
  for (const XmlElement& child : parent.children) {
    if (child.name == "DataArray" && child.Attribute("Name") == name) return &child;
  }
  return nullptr;
}

}  // namespace

absl::StatusOr<TetMeshData> ParseVtu(absl::string_view text, absl::string_view source) {
  const TextScanner errors(text, source);
  if (const std::size_t at = text.find("<AppendedData"); at != absl::string_view::npos) {
    return errors.ErrorAt(at,
                          "appended data is not supported: save the VTU with inline "
                          "ascii or binary arrays");
  }
  absl::StatusOr<XmlElement> root = internal::ParseXml(text, source);
  if (!root.ok()) return root.status();
  if (root->name != "VTKFile" || root->Attribute("type") != "UnstructuredGrid") {
    return errors.ErrorAt(root->offset, "expected <VTKFile type=\"UnstructuredGrid\">");
  }
  if (const auto compressor = root->Attribute("compressor"); compressor && !compressor->empty()) {
    return errors.ErrorAt(root->offset, absl::StrCat("compressed data (", *compressor,
                                                     ") is not supported: save uncompressed"));
  }
  Encoding encoding;
  const absl::string_view header_type = root->Attribute("header_type").value_or("UInt32");
  if (header_type != "UInt32" && header_type != "UInt64") {
    return errors.ErrorAt(root->offset, absl::StrCat("expected header_type UInt32 or UInt64, "
                                                     "found ",
                                                     internal::Quoted(header_type)));
  }
  encoding.header_is_64_bit = header_type == "UInt64";
  encoding.big_endian = root->Attribute("byte_order") == "BigEndian";

  const XmlElement* grid = root->Child("UnstructuredGrid");
  if (grid == nullptr) return errors.ErrorAt(root->offset, "expected <UnstructuredGrid>");
  const XmlElement* piece = grid->Child("Piece");
  if (piece == nullptr) return errors.ErrorAt(grid->offset, "expected <Piece>");
  if (std::count_if(grid->children.begin(), grid->children.end(),
                    [](const XmlElement& e) { return e.name == "Piece"; }) > 1) {
    return errors.ErrorAt(grid->offset, "more than one <Piece> is not supported");
  }
  const XmlElement* points = piece->Child("Points");
  const XmlElement* cells = piece->Child("Cells");
  if (points == nullptr || cells == nullptr) {
    return errors.ErrorAt(piece->offset, "expected <Points> and <Cells> in <Piece>");
  }
  const XmlElement* point_array = points->Child("DataArray");
  const XmlElement* connectivity_array = FindArray(*cells, "connectivity");
  const XmlElement* offsets_array = FindArray(*cells, "offsets");
  const XmlElement* types_array = FindArray(*cells, "types");
  if (point_array == nullptr || connectivity_array == nullptr || offsets_array == nullptr ||
      types_array == nullptr) {
    return errors.ErrorAt(piece->offset,
                          "expected a points DataArray and the cell arrays "
                          "connectivity, offsets and types");
  }
  if (point_array->Attribute("NumberOfComponents").value_or("1") != "3") {
    return errors.ErrorAt(point_array->offset, "expected NumberOfComponents=\"3\" for points");
  }
  absl::StatusOr<std::vector<double>> coordinates =
      DecodeDataArray<double>(*point_array, encoding, errors);
  if (!coordinates.ok()) return coordinates.status();
  absl::StatusOr<std::vector<std::int64_t>> connectivity =
      DecodeDataArray<std::int64_t>(*connectivity_array, encoding, errors);
  if (!connectivity.ok()) return connectivity.status();
  absl::StatusOr<std::vector<std::int64_t>> offsets =
      DecodeDataArray<std::int64_t>(*offsets_array, encoding, errors);
  if (!offsets.ok()) return offsets.status();
  absl::StatusOr<std::vector<std::int64_t>> types =
      DecodeDataArray<std::int64_t>(*types_array, encoding, errors);
  if (!types.ok()) return types.status();

  if (coordinates->size() % 3 != 0) {
    return errors.ErrorAt(point_array->offset, "point coordinates are not a multiple of 3");
  }
  std::int64_t declared_points = 0;
  if (const auto n = piece->Attribute("NumberOfPoints");
      !n || !internal::ParseInt(*n, &declared_points) ||
      declared_points != static_cast<std::int64_t>(coordinates->size() / 3)) {
    return errors.ErrorAt(piece->offset, absl::StrCat("NumberOfPoints does not match the ",
                                                      coordinates->size() / 3, " points given"));
  }
  if (offsets->size() != types->size()) {
    return errors.ErrorAt(cells->offset, absl::StrCat(offsets->size(), " offsets for ",
                                                      types->size(), " cell types"));
  }
  TetMeshData data;
  const std::size_t point_count = coordinates->size() / 3;
  data.points.reserve(point_count);
  for (std::size_t i = 0; i < point_count; ++i) {
    data.points.emplace_back((*coordinates)[3 * i], (*coordinates)[3 * i + 1],
                             (*coordinates)[3 * i + 2]);
    data.point_ids.push_back(static_cast<std::int64_t>(i));
  }
  std::int64_t begin = 0;
  for (std::size_t i = 0; i < types->size(); ++i) {
    const std::int64_t end = (*offsets)[i];
    if (end < begin || end > static_cast<std::int64_t>(connectivity->size())) {
      return errors.ErrorAt(offsets_array->offset, absl::StrCat("offset ", i, " (", end,
                                                                ") is out of order or past the "
                                                                "connectivity (",
                                                                connectivity->size(), ")"));
    }
    const std::int64_t type = (*types)[i];
    if (type == internal::kVtkTetra) {
      if (end - begin != 4) {
        return errors.ErrorAt(cells->offset, absl::StrCat("tetra cell ", i, " has ", end - begin,
                                                          " points, expected 4"));
      }
      std::array<std::uint32_t, 4> tet;
      for (int c = 0; c < 4; ++c) {
        const std::int64_t index = (*connectivity)[static_cast<std::size_t>(begin + c)];
        if (index < 0 || index >= static_cast<std::int64_t>(point_count)) {
          return errors.ErrorAt(
              connectivity_array->offset,
              absl::StrCat("cell ", i, " names point ", index, " of ", point_count));
        }
        tet[c] = static_cast<std::uint32_t>(index);
      }
      data.tets.push_back(tet);
    } else if (!internal::IsLowerDimensionVtkCell(type)) {
      return errors.ErrorAt(types_array->offset,
                            absl::StrCat("cell ", i, " has type ", type,
                                         ", which is not "
                                         "supported: kerf reads tetrahedra (type 10)"));
    }
    begin = end;
  }
  return data;
}

}  // namespace kerf::mesh
