#include "cli/cut_command.h"

#include <limits>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "cli/command_args.h"
#include "cli/json_output.h"
#include "cut/cutter.h"
#include "geometry/tet_measures.h"
#include "mesh/connected_components.h"
#include "mesh/io/mesh_file.h"
#include "mesh/io/vtu_writer.h"
#include "mesh/mesh_quality.h"
#include "mesh/mesh_validation.h"
#include "sim/simulation.h"

namespace kerf::cli {
namespace {

constexpr absl::string_view kUsage = "kerf cut MESH --path PATH.json --out OUT.vtu [--json]";

// The mesh of a scene (an embedded name or a .textproto file) in its initial state, or of a
// mesh file.
absl::StatusOr<mesh::TetMesh> LoadMeshOrScene(absl::string_view name) {
  if (!sim::EmbeddedSceneText(name).ok() && !absl::EndsWith(name, ".textproto")) {
    return mesh::ReadMeshFile(name);
  }
  absl::StatusOr<sim::Scene> scene = sim::LoadScene(name);
  if (!scene.ok()) return scene.status();
  return MeshOfScene(*std::move(scene));
}

}  // namespace

absl::StatusOr<mesh::TetMesh> MeshOfScene(sim::Scene scene) {
  absl::StatusOr<std::unique_ptr<sim::Simulation>> simulation =
      sim::Simulation::Create(std::move(scene));
  if (!simulation.ok()) return simulation.status();
  return (*simulation)->mesh();  // a copy, in the scene's initial state
}

cut::BladeLimits LimitsForMeshSize(double diagonal) {
  cut::BladeLimits limits;
  limits.max_length = 2 * diagonal;
  limits.max_step = 0.25 * diagonal;
  limits.max_speed = std::numeric_limits<double>::max();
  return limits;
}

absl::StatusOr<kerf::v1::CutReport> CutAlongPath(mesh::TetMesh* m,
                                                 const std::vector<cut::BladePose>& poses,
                                                 absl::string_view path_name,
                                                 std::vector<mesh::TetId>* source_tets) {
  kerf::v1::CutReport report;
  report.set_path(std::string(path_name));
  report.set_poses(static_cast<std::uint32_t>(poses.size()));
  report.set_tets_before(static_cast<std::uint32_t>(m->tet_count()));
  absl::StatusOr<cut::Cutter> cutter = cut::Cutter::Create(m, mesh::MeanEdgeLength(*m));
  if (!cutter.ok()) return cutter.status();
  for (std::size_t i = 0; i < poses.size(); ++i) {
    if (absl::Status s = cutter->ApplyPose(poses[i]); !s.ok()) {
      return absl::InvalidArgumentError(absl::StrCat(path_name, ": pose ", i, ": ", s.message()));
    }
  }
  cutter->Finish();
  const cut::CutStatistics& s = cutter->statistics();
  report.set_tets_after(static_cast<std::uint32_t>(m->tet_count()));
  report.set_cut_tets(static_cast<std::uint32_t>(s.cut_tets));
  report.set_new_tets(static_cast<std::uint32_t>(s.new_tets));
  report.set_new_per_cut(s.cut_tets ? static_cast<double>(s.new_tets) / s.cut_tets : 0.0);
  report.set_case_i(static_cast<std::uint32_t>(s.tets_by_case[1]));
  report.set_case_ii(static_cast<std::uint32_t>(s.tets_by_case[2]));
  report.set_case_iii(static_cast<std::uint32_t>(s.tets_by_case[3]));
  report.set_case_iv(static_cast<std::uint32_t>(s.tets_by_case[4]));
  report.set_case_v(static_cast<std::uint32_t>(s.tets_by_case[5]));
  report.set_dropped_hits(static_cast<std::uint32_t>(s.dropped_hits));
  report.set_degenerate_hits(static_cast<std::uint32_t>(s.degenerate_hits));
  double min_angle = 0;
  std::uint32_t slivers = 0;
  bool any = false;
  for (const mesh::TetId t : m->tets()) {
    if (source_tets != nullptr) {
      if (source_tets->size() <= mesh::Index(t)) source_tets->resize(mesh::Index(t) + 1);
      (*source_tets)[mesh::Index(t)] = cutter->SourceTet(t);
    }
    if (!cutter->MadeByCut(t)) continue;
    const mesh::TetVertices& v = m->tet(t);
    const geometry::TetMeasures q =
        geometry::MeasureTet(m->rest_position(v[0]), m->rest_position(v[1]), m->rest_position(v[2]),
                             m->rest_position(v[3]));
    min_angle = any ? std::min(min_angle, q.min_dihedral_deg) : q.min_dihedral_deg;
    any = true;
    if (q.min_dihedral_deg < mesh::kDefaultSliverAngleDeg) ++slivers;
  }
  report.set_min_dihedral_deg(min_angle);
  report.set_slivers(slivers);
  report.set_components(static_cast<std::uint32_t>(mesh::FindConnectedComponents(*m).count));
  report.set_valid(mesh::FindMeshDefects(*m).empty());
  return report;
}

absl::StatusOr<std::string> RunCutCommand(const std::vector<absl::string_view>& args) {
  CommandArgs rest(args);
  const bool json = rest.TakeFlag("--json");
  absl::StatusOr<std::optional<std::vector<absl::string_view>>> path_arg =
      rest.TakeOption("--path", 1);
  if (!path_arg.ok()) return path_arg.status();
  absl::StatusOr<std::optional<std::vector<absl::string_view>>> out_arg =
      rest.TakeOption("--out", 1);
  if (!out_arg.ok()) return out_arg.status();
  absl::StatusOr<std::vector<absl::string_view>> mesh_arg = rest.TakePositionals(1, kUsage);
  if (!mesh_arg.ok()) return mesh_arg.status();
  if (!path_arg->has_value() || !out_arg->has_value()) {
    return absl::InvalidArgumentError(
        absl::StrCat("--path and --out are required\nusage: ", kUsage));
  }
  absl::StatusOr<mesh::TetMesh> m = LoadMeshOrScene((*mesh_arg)[0]);
  if (!m.ok()) return m.status();
  const absl::string_view path_file = (**path_arg)[0];
  absl::StatusOr<std::string> path_text = mesh::ReadTextFile(path_file);
  if (!path_text.ok()) return path_text.status();
  absl::StatusOr<std::vector<cut::BladePose>> poses = cut::ParseBladePathJson(
      *path_text, path_file,
      LimitsForMeshSize(mesh::MeasureBounds(*m, /*current=*/true).diagonal()));
  if (!poses.ok()) return poses.status();
  const std::uint32_t original_vertices = m->vertex_index_bound();
  std::vector<mesh::TetId> source_tets;
  absl::StatusOr<kerf::v1::CutReport> report = CutAlongPath(&*m, *poses, path_file, &source_tets);
  if (!report.ok()) return report.status();

  mesh::VtuExtraArrays extra;
  std::vector<std::int64_t> source_vertex;
  for (const mesh::VertexId v : m->vertices()) {
    source_vertex.push_back(mesh::Index(v) < original_vertices ? mesh::Index(v) : -1);
  }
  std::vector<std::int64_t> source_tet;
  for (const mesh::TetId t : m->tets())
    source_tet.push_back(mesh::Index(source_tets[mesh::Index(t)]));
  extra.point_data.push_back(mesh::RestPositionArray(*m));
  extra.point_data.push_back({"source_vertex", 1, std::move(source_vertex)});
  extra.cell_data.push_back({"source_tet", 1, std::move(source_tet)});
  if (absl::Status s = mesh::WriteTextFile((**out_arg)[0], mesh::FormatVtu(*m, extra)); !s.ok()) {
    return s;
  }
  if (json) return FormatProtoJson(*report);
  return absl::StrCat("cut ", report->cut_tets(), " of ", report->tets_before(), " tets into ",
                      report->new_tets(), " (", report->new_per_cut(), " per cut tet); ",
                      report->tets_after(), " tets, ", report->components(), " component(s), ",
                      report->valid() ? "valid" : "INVALID", "; wrote ", (**out_arg)[0], "\n");
}

}  // namespace kerf::cli
