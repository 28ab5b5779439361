#include "cli/mesh_commands.h"

#include "absl/strings/str_cat.h"
#include "cli/command_args.h"
#include "cli/mesh_report.h"
#include "mesh/box_lattice.h"
#include "mesh/io/mesh_file.h"

namespace kerf::cli {
namespace {

absl::StatusOr<std::string> Info(CommandArgs args) {
  const bool json = args.TakeFlag("--json");
  absl::StatusOr<std::vector<absl::string_view>> files =
      args.TakePositionals(1, "kerf mesh info FILE [--json]");
  if (!files.ok()) return files.status();
  absl::StatusOr<mesh::TetMesh> mesh = mesh::ReadMeshFile((*files)[0]);
  if (!mesh.ok()) return mesh.status();
  const kerf::v1::MeshReport report = MakeMeshReport(*mesh, (*files)[0]);
  return json ? FormatMeshReportJson(report) : FormatMeshReportText(report);
}

absl::StatusOr<std::string> Lattice(CommandArgs args) {
  constexpr absl::string_view kLatticeUsage =
      "kerf mesh lattice NX NY NZ [--size X Y Z] --out FILE";
  absl::StatusOr<std::optional<std::vector<absl::string_view>>> size = args.TakeOption("--size", 3);
  if (!size.ok()) return size.status();
  absl::StatusOr<std::optional<std::vector<absl::string_view>>> out = args.TakeOption("--out", 1);
  if (!out.ok()) return out.status();
  if (!out->has_value()) {
    return absl::InvalidArgumentError(
        absl::StrCat("--out FILE is required\nusage: ", kLatticeUsage));
  }
  absl::StatusOr<std::vector<absl::string_view>> counts = args.TakePositionals(3, kLatticeUsage);
  if (!counts.ok()) return counts.status();

  mesh::BoxLatticeSpec spec;
  int* cells[3] = {&spec.cells_x, &spec.cells_y, &spec.cells_z};
  for (int axis = 0; axis < 3; ++axis) {
    absl::StatusOr<int> n =
        ParseIntArg((*counts)[axis], absl::StrCat("N", absl::string_view("XYZ").substr(axis, 1)));
    if (!n.ok()) return n.status();
    *cells[axis] = *n;
    if (size->has_value()) {
      absl::StatusOr<double> length = ParseDoubleArg(
          (**size)[axis], absl::StrCat("--size ", absl::string_view("XYZ").substr(axis, 1)));
      if (!length.ok()) return length.status();
      spec.size[axis] = *length;
    }
  }
  absl::StatusOr<mesh::TetMesh> mesh = mesh::MakeBoxLattice(spec);
  if (!mesh.ok()) return mesh.status();
  if (auto st = mesh::WriteMeshFile(*mesh, (**out)[0]); !st.ok()) return st;
  return absl::StrCat("wrote ", (**out)[0], ": ", mesh->vertex_count(), " vertices, ",
                      mesh->tet_count(), " tets\n");
}

absl::StatusOr<std::string> Convert(CommandArgs args) {
  absl::StatusOr<std::vector<absl::string_view>> files =
      args.TakePositionals(2, "kerf mesh convert IN OUT");
  if (!files.ok()) return files.status();
  absl::StatusOr<mesh::TetMesh> mesh = mesh::ReadMeshFile((*files)[0]);
  if (!mesh.ok()) return mesh.status();
  if (auto st = mesh::WriteMeshFile(*mesh, (*files)[1]); !st.ok()) return st;
  return absl::StrCat("wrote ", (*files)[1], ": ", mesh->vertex_count(), " vertices, ",
                      mesh->tet_count(), " tets\n");
}

}  // namespace

absl::StatusOr<std::string> RunMeshCommand(const std::vector<absl::string_view>& args) {
  if (args.empty()) return absl::InvalidArgumentError(absl::StrCat("usage: ", kMeshUsage));
  const absl::string_view verb = args[0];
  CommandArgs rest({args.begin() + 1, args.end()});
  if (verb == "info") return Info(std::move(rest));
  if (verb == "lattice") return Lattice(std::move(rest));
  if (verb == "convert") return Convert(std::move(rest));
  return absl::InvalidArgumentError(
      absl::StrCat("unknown mesh command '", verb, "'\nusage: ", kMeshUsage));
}

absl::StatusOr<std::string> RunDemoCommand(const std::vector<absl::string_view>& args) {
  CommandArgs rest(args);
  const bool json = rest.TakeFlag("--json");
  if (auto none = rest.TakePositionals(0, "kerf demo [--json]"); !none.ok()) return none.status();
  mesh::BoxLatticeSpec spec;
  spec.cells_x = 4;
  spec.cells_y = 6;
  spec.cells_z = 4;
  absl::StatusOr<mesh::TetMesh> mesh = mesh::MakeBoxLattice(spec);
  if (!mesh.ok()) return mesh.status();
  const kerf::v1::MeshReport report =
      MakeMeshReport(*mesh, "lattice 4 6 4 (the paper's experiment, 576 tets)");
  return json ? FormatMeshReportJson(report) : FormatMeshReportText(report);
}

}  // namespace kerf::cli
