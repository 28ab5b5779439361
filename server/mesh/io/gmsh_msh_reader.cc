#include "mesh/io/gmsh_msh_reader.h"

#include <array>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "mesh/io/tet_mesh_data_builder.h"
#include "mesh/io/text_scanner.h"

namespace kerf::mesh {
namespace {

using internal::TetMeshDataBuilder;
using internal::TextScanner;

constexpr int kTet4 = 4;
// Element types of dimension 0-2 (points, lines, triangles, quads, and their higher-order
// kinds), which a volume mesh may carry for boundaries and are skipped.
bool IsLowerDimensionType(std::int64_t type) {
  switch (type) {
    case 1:
    case 2:
    case 3:
    case 8:
    case 9:
    case 10:
    case 15:
    case 16:
    case 20:
    case 21:
    case 22:
    case 23:
    case 24:
    case 25:
    case 26:
    case 27:
    case 28:
    case 36:
    case 37:
    case 38:
    case 39:
    case 40:
    case 41:
    case 42:
    case 43:
    case 44:
    case 45:
    case 46:
    case 47:
      return true;
    default:
      return false;
  }
}

absl::Status UnsupportedType(const TextScanner& s, std::int64_t type) {
  return s.Error(absl::StrCat("element type ", type,
                              " is not supported: kerf reads linear tetrahedra (type 4); "
                              "surface and line elements are skipped"));
}

// Reads "$Section" ... up to "$EndSection"-style markers. The v1 markers are $ENDNOD/$ENDELM.
absl::Status SkipSection(TextScanner& s, absl::string_view name) {
  const std::string end = absl::StrCat("$End", name.substr(1));
  while (true) {
    const absl::string_view token = s.NextToken();
    if (token.empty()) return s.ErrorExpected(absl::StrCat("'", end, "'"));
    if (token == end) return absl::OkStatus();
  }
}

// "<id> <x> <y> <z>" lines, v1 and v2 (and v4.0's per-node lines).
absl::Status ReadNodeLines(TextScanner& s, std::int64_t count, TetMeshDataBuilder& builder) {
  for (std::int64_t i = 0; i < count; ++i) {
    absl::StatusOr<std::int64_t> id = s.NextInt("node id");
    if (!id.ok()) return id.status();
    absl::StatusOr<Eigen::Vector3d> p = internal::ReadPoint(s);
    if (!p.ok()) return p.status();
    if (auto st = builder.AddPoint(*id, *p, s, s.token_offset()); !st.ok()) return st;
  }
  return absl::OkStatus();
}

// The rest of an element line after its type: `skip_tokens` tags, then node ids.
absl::Status ReadElementNodes(TextScanner& s, std::int64_t type, int skip_tokens,
                              std::size_t offset, TetMeshDataBuilder& builder) {
  const absl::string_view line = s.NextLine();
  TextScanner rest(line, s.source());
  std::vector<std::int64_t> ids;
  for (absl::string_view token = rest.NextToken(); !token.empty(); token = rest.NextToken()) {
    std::int64_t value = 0;
    if (!internal::ParseInt(token, &value)) {
      return s.ErrorAt(offset, absl::StrCat("expected an integer in the element line, found ",
                                            internal::Quoted(token)));
    }
    ids.push_back(value);
  }
  if (type != kTet4) {
    if (IsLowerDimensionType(type)) return absl::OkStatus();
    return s.ErrorAt(offset, absl::StrCat("element type ", type,
                                          " is not supported: kerf reads linear tetrahedra "
                                          "(type 4); surface and line elements are skipped"));
  }
  if (ids.size() != static_cast<std::size_t>(skip_tokens) + 4) {
    return s.ErrorAt(offset, absl::StrCat("expected ", skip_tokens,
                                          " tags and 4 node ids for "
                                          "a tetrahedron, found ",
                                          ids.size(), " numbers"));
  }
  builder.AddTet(
      {ids[skip_tokens], ids[skip_tokens + 1], ids[skip_tokens + 2], ids[skip_tokens + 3]}, offset);
  return absl::OkStatus();
}

absl::StatusOr<TetMeshData> ParseVersion1(TextScanner& s) {
  TetMeshDataBuilder builder;
  bool have_nodes = false, have_elements = false;
  for (absl::string_view section = s.NextToken(); !section.empty(); section = s.NextToken()) {
    if (section == "$NOD") {
      absl::StatusOr<std::int64_t> count = s.NextIntIn("node count", 0, internal::kMaxItemCount);
      if (!count.ok()) return count.status();
      if (auto st = ReadNodeLines(s, *count, builder); !st.ok()) return st;
      if (auto st = s.Expect("$ENDNOD"); !st.ok()) return st;
      have_nodes = true;
    } else if (section == "$ELM") {
      absl::StatusOr<std::int64_t> count = s.NextIntIn("element count", 0, internal::kMaxItemCount);
      if (!count.ok()) return count.status();
      for (std::int64_t i = 0; i < *count; ++i) {
        // elm-number elm-type reg-phys reg-elem number-of-nodes node-number-list
        const std::size_t offset = (s.PeekToken(), s.offset());
        if (absl::StatusOr<std::int64_t> id = s.NextInt("element id"); !id.ok()) return id.status();
        absl::StatusOr<std::int64_t> type = s.NextInt("element type");
        if (!type.ok()) return type.status();
        if (auto st = ReadElementNodes(s, *type, 3, offset, builder); !st.ok()) return st;
      }
      if (auto st = s.Expect("$ENDELM"); !st.ok()) return st;
      have_elements = true;
    } else {
      return s.ErrorExpected("'$NOD' or '$ELM'");
    }
  }
  if (!have_nodes || !have_elements) return s.ErrorExpected("both $NOD and $ELM sections");
  return std::move(builder).Finish(s);
}

absl::Status ReadVersion2Elements(TextScanner& s, TetMeshDataBuilder& builder) {
  absl::StatusOr<std::int64_t> count = s.NextIntIn("element count", 0, internal::kMaxItemCount);
  if (!count.ok()) return count.status();
  for (std::int64_t i = 0; i < *count; ++i) {
    // elm-number elm-type number-of-tags <tags> node-number-list
    const std::size_t offset = (s.PeekToken(), s.offset());
    if (absl::StatusOr<std::int64_t> id = s.NextInt("element id"); !id.ok()) return id.status();
    absl::StatusOr<std::int64_t> type = s.NextInt("element type");
    if (!type.ok()) return type.status();
    absl::StatusOr<std::int64_t> tags = s.NextIntIn("tag count", 0, 64);
    if (!tags.ok()) return tags.status();
    if (auto st = ReadElementNodes(s, *type, static_cast<int>(*tags), offset, builder); !st.ok()) {
      return st;
    }
  }
  return s.Expect("$EndElements");
}

// "numEntityBlocks numItems" and, in 4.1, "minTag maxTag": returns the block count.
absl::StatusOr<std::int64_t> ReadVersion4SectionHeader(TextScanner& s, bool v41,
                                                       absl::string_view item) {
  absl::StatusOr<std::int64_t> blocks =
      s.NextIntIn(absl::StrCat(item, " block count"), 0, internal::kMaxItemCount);
  if (!blocks.ok()) return blocks.status();
  if (auto n = s.NextIntIn(absl::StrCat(item, " count"), 0, internal::kMaxItemCount); !n.ok()) {
    return n.status();
  }
  if (v41) {
    for (const char* which : {"smallest ", "largest "}) {
      if (auto tag = s.NextInt(absl::StrCat(which, item, " tag")); !tag.ok()) return tag.status();
    }
  }
  return blocks;
}

absl::Status SkipEntityDimensionAndTag(TextScanner& s) {
  for (const char* what : {"entity dimension or tag", "entity tag or dimension"}) {
    if (absl::StatusOr<std::int64_t> v = s.NextInt(what); !v.ok()) return v.status();
  }
  return absl::OkStatus();
}

absl::Status ReadVersion4Nodes(TextScanner& s, bool v41, TetMeshDataBuilder& builder) {
  absl::StatusOr<std::int64_t> blocks = ReadVersion4SectionHeader(s, v41, "node");
  if (!blocks.ok()) return blocks.status();
  for (std::int64_t b = 0; b < *blocks; ++b) {
    // 4.1: entityDim entityTag parametric numNodesInBlock; 4.0: entityTag entityDim ...
    if (auto st = SkipEntityDimensionAndTag(s); !st.ok()) return st;
    absl::StatusOr<std::int64_t> parametric = s.NextIntIn("parametric flag", 0, 0);
    if (!parametric.ok()) return parametric.status();
    absl::StatusOr<std::int64_t> count = s.NextIntIn("nodes in block", 0, internal::kMaxItemCount);
    if (!count.ok()) return count.status();
    if (!v41) {
      if (auto st = ReadNodeLines(s, *count, builder); !st.ok()) return st;
      continue;
    }
    // 4.1: all tags of the block first, then all coordinates.
    std::vector<std::int64_t> tags;
    tags.reserve(internal::ReservableCount(*count, s.text().size()));
    for (std::int64_t i = 0; i < *count; ++i) {
      absl::StatusOr<std::int64_t> tag = s.NextInt("node tag");
      if (!tag.ok()) return tag.status();
      tags.push_back(*tag);
    }
    for (const std::int64_t tag : tags) {
      absl::StatusOr<Eigen::Vector3d> p = internal::ReadPoint(s);
      if (!p.ok()) return p.status();
      if (auto st = builder.AddPoint(tag, *p, s, s.token_offset()); !st.ok()) return st;
    }
  }
  return s.Expect("$EndNodes");
}

absl::Status ReadVersion4Elements(TextScanner& s, bool v41, TetMeshDataBuilder& builder) {
  absl::StatusOr<std::int64_t> blocks = ReadVersion4SectionHeader(s, v41, "element");
  if (!blocks.ok()) return blocks.status();
  for (std::int64_t b = 0; b < *blocks; ++b) {
    // entityDim entityTag elementType numElementsInBlock (4.0: entityTag entityDim ...)
    if (auto st = SkipEntityDimensionAndTag(s); !st.ok()) return st;
    absl::StatusOr<std::int64_t> type = s.NextInt("element type");
    if (!type.ok()) return type.status();
    if (*type != kTet4 && !IsLowerDimensionType(*type)) return UnsupportedType(s, *type);
    absl::StatusOr<std::int64_t> count =
        s.NextIntIn("elements in block", 0, internal::kMaxItemCount);
    if (!count.ok()) return count.status();
    s.NextLine();  // end of the block header
    for (std::int64_t i = 0; i < *count; ++i) {
      // elementTag nodeTag...
      const std::size_t offset = (s.PeekToken(), s.offset());
      if (absl::StatusOr<std::int64_t> id = s.NextInt("element tag"); !id.ok()) return id.status();
      if (auto st = ReadElementNodes(s, *type, 0, offset, builder); !st.ok()) return st;
    }
  }
  return s.Expect("$EndElements");
}

absl::StatusOr<TetMeshData> ParseVersion2Or4(TextScanner& s) {
  // $MeshFormat was read: "version file-type data-size" then $EndMeshFormat.
  const absl::string_view version = s.NextToken();
  const bool v2 = absl::StartsWith(version, "2.");
  const bool v40 = version == "4" || version == "4.0";
  const bool v41 = version == "4.1";
  if (!v2 && !v40 && !v41) return s.ErrorExpected("MSH version 2.x, 4.0 or 4.1");
  absl::StatusOr<std::int64_t> file_type = s.NextIntIn("file type", 0, 1);
  if (!file_type.ok()) return file_type.status();
  if (*file_type != 0) return s.Error("binary MSH is not supported: save the mesh as ASCII");
  if (absl::StatusOr<std::int64_t> size = s.NextInt("data size"); !size.ok()) return size.status();
  if (auto st = s.Expect("$EndMeshFormat"); !st.ok()) return st;

  TetMeshDataBuilder builder;
  bool have_nodes = false, have_elements = false;
  for (absl::string_view section = s.NextToken(); !section.empty(); section = s.NextToken()) {
    absl::Status st;
    if (section == "$Nodes") {
      if (v2) {
        absl::StatusOr<std::int64_t> count = s.NextIntIn("node count", 0, internal::kMaxItemCount);
        if (!count.ok()) return count.status();
        st = ReadNodeLines(s, *count, builder);
        if (st.ok()) st = s.Expect("$EndNodes");
      } else {
        st = ReadVersion4Nodes(s, v41, builder);
      }
      have_nodes = true;
    } else if (section == "$Elements") {
      st = v2 ? ReadVersion2Elements(s, builder) : ReadVersion4Elements(s, v41, builder);
      have_elements = true;
    } else if (absl::StartsWith(section, "$") && !absl::StartsWith(section, "$End")) {
      st = SkipSection(s, section);  // $PhysicalNames, $Entities, $NodeData, ...
    } else {
      return s.ErrorExpected("a section such as '$Nodes' or '$Elements'");
    }
    if (!st.ok()) return st;
  }
  if (!have_nodes || !have_elements) return s.ErrorExpected("both $Nodes and $Elements sections");
  return std::move(builder).Finish(s);
}

}  // namespace

absl::StatusOr<TetMeshData> ParseGmshMsh(absl::string_view text, absl::string_view source) {
  TextScanner s(text, source);
  const absl::string_view first = s.NextToken();
  if (first == "$NOD") {
    TextScanner from_start(text, source);
    return ParseVersion1(from_start);
  }
  if (first == "$MeshFormat") return ParseVersion2Or4(s);
  return s.ErrorExpected("'$MeshFormat' (MSH 2 or 4) or '$NOD' (MSH 1)");
}

}  // namespace kerf::mesh
