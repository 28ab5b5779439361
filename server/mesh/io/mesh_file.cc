#include "mesh/io/mesh_file.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"
#include "mesh/io/abaqus_inp_reader.h"
#include "mesh/io/gmsh_msh_reader.h"
#include "mesh/io/gmsh_msh_writer.h"
#include "mesh/io/tetgen_reader.h"
#include "mesh/io/vtk_legacy_reader.h"
#include "mesh/io/vtu_reader.h"
#include "mesh/io/vtu_writer.h"

namespace kerf::mesh {
namespace {

std::string Extension(absl::string_view path) {
  return absl::AsciiStrToLower(std::filesystem::path(std::string(path)).extension().string());
}

}  // namespace

absl::StatusOr<std::string> ReadTextFile(absl::string_view path) {
  std::error_code error;
  if (std::filesystem::is_directory(std::string(path), error)) {
    return absl::InvalidArgumentError(absl::StrCat(path, ": is a directory, expected a file"));
  }
  std::ifstream in{std::string(path), std::ios::binary};
  if (!in) return absl::NotFoundError(absl::StrCat(path, ": cannot open file"));
  std::ostringstream contents;
  contents << in.rdbuf();
  if (in.bad()) return absl::DataLossError(absl::StrCat(path, ": read failed"));
  return std::move(contents).str();
}

absl::Status WriteTextFile(absl::string_view path, absl::string_view text) {
  std::ofstream out{std::string(path), std::ios::binary | std::ios::trunc};
  if (!out) return absl::PermissionDeniedError(absl::StrCat(path, ": cannot open for writing"));
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.close();
  if (!out) return absl::DataLossError(absl::StrCat(path, ": write failed"));
  return absl::OkStatus();
}

absl::StatusOr<TetMeshData> ReadMeshFileData(absl::string_view path) {
  const std::string extension = Extension(path);
  if (extension == ".node" || extension == ".ele") {
    std::filesystem::path base{std::string(path)};
    const std::string node_path = base.replace_extension(".node").string();
    const std::string ele_path = base.replace_extension(".ele").string();
    absl::StatusOr<std::string> nodes = ReadTextFile(node_path);
    if (!nodes.ok()) return nodes.status();
    absl::StatusOr<std::string> tets = ReadTextFile(ele_path);
    if (!tets.ok()) return tets.status();
    return ParseTetGen(*nodes, node_path, *tets, ele_path);
  }
  using Parser = absl::StatusOr<TetMeshData> (*)(absl::string_view, absl::string_view);
  Parser parse = nullptr;
  if (extension == ".msh") parse = &ParseGmshMsh;
  if (extension == ".vtk") parse = &ParseVtkLegacy;
  if (extension == ".vtu") parse = &ParseVtu;
  if (extension == ".inp") parse = &ParseAbaqusInpMesh;
  if (parse == nullptr) {
    return absl::InvalidArgumentError(
        absl::StrCat(path, ": unknown mesh format '", extension,
                     "'; kerf reads .msh, .vtk, .vtu, .node/.ele and .inp"));
  }
  absl::StatusOr<std::string> text = ReadTextFile(path);
  if (!text.ok()) return text.status();
  return parse(*text, path);
}

absl::StatusOr<TetMesh> ReadMeshFile(absl::string_view path) {
  absl::StatusOr<TetMeshData> data = ReadMeshFileData(path);
  if (!data.ok()) return data.status();
  return BuildTetMesh(*data);
}

absl::Status WriteMeshFile(const TetMesh& mesh, absl::string_view path) {
  const std::string extension = Extension(path);
  if (extension == ".vtu") return WriteTextFile(path, FormatVtu(mesh));
  if (extension == ".msh") return WriteTextFile(path, FormatGmshMsh4(mesh));
  return absl::InvalidArgumentError(
      absl::StrCat(path, ": cannot write '", extension, "'; kerf writes .vtu and .msh"));
}

}  // namespace kerf::mesh
