#include "cli/experiment_command.h"

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "cli/command_args.h"
#include "cli/cut_command.h"
#include "cli/json_output.h"
#include "cut/progressive_case_paths.h"
#include "embedded_text.h"
#include "kerf/v1/cut_report.pb.h"
#include "mesh/mesh_quality.h"

namespace kerf::cli {
namespace {

absl::StatusOr<std::string> LatticeCut(bool json) {
  absl::StatusOr<std::string> text = sim::EmbeddedSceneText("lattice-tension");
  if (!text.ok()) return text.status();
  absl::StatusOr<kerf::v1::Scene> spec = sim::ParseSceneText(*text, "lattice-tension");
  if (!spec.ok()) return spec.status();
  spec->mutable_integration()->set_method(kerf::v1::Integration::STATIC);
  kerf::v1::CutExperiment experiment;
  experiment.set_name("lattice-cut");
  experiment.set_scene("lattice-tension, at static equilibrium under 10% tension");
  for (const char* path : {"lattice-straight", "lattice-curved"}) {
    absl::StatusOr<sim::Scene> scene = sim::BuildScene(*spec, ".");
    if (!scene.ok()) return scene.status();
    absl::StatusOr<mesh::TetMesh> m = MeshOfScene(*std::move(scene));
    if (!m.ok()) return m.status();
    const std::optional<absl::string_view> json_path = FindEmbeddedText(EmbeddedBladePaths(), path);
    absl::StatusOr<std::vector<cut::BladePose>> poses = cut::ParseBladePathJson(
        *json_path, path, LimitsForMeshSize(mesh::MeasureBounds(*m, /*current=*/true).diagonal()));
    if (!poses.ok()) return poses.status();
    absl::StatusOr<kerf::v1::CutReport> report = CutAlongPath(&*m, *poses, path);
    if (!report.ok()) return report.status();
    *experiment.add_cuts() = *std::move(report);
  }
  if (json) return FormatProtoJson(experiment);
  std::string out = absl::StrCat(
      "lattice-cut: ", experiment.scene(),
      "\n\n| | cut tets | new tets | new per cut | tets after | cases i/ii/iii/iv/v | "
      "min dihedral of new (deg) | slivers | components | valid |\n|---|---|---|---|---|---|---|"
      "---|---|---|\n");
  for (const kerf::v1::CutReport& r : experiment.cuts()) {
    absl::StrAppendFormat(
        &out, "| kerf, %s | %u | %u | %.2f | %u | %u/%u/%u/%u/%u | %.1f | %u | %u | %s |\n",
        r.path(), r.cut_tets(), r.new_tets(), r.new_per_cut(), r.tets_after(), r.case_i(),
        r.case_ii(), r.case_iii(), r.case_iv(), r.case_v(), r.min_dihedral_deg(), r.slivers(),
        r.components(), r.valid() ? "yes" : "NO");
  }
  out +=
      "| Mor & Kanade 2000 | 60 | 312 | 5.2 | 954 (576 - 60 + 312 = 828) | - | - | - | - | - |\n"
      "| Bielser et al. 1999 | 110 | 1870 | 17 | - | - | - | - | - | - |\n";
  return out;
}

// Every scripted path of cut::ProgressiveCasePaths, cut progressively: how often each Table 1
// case was reached, and on which paths, and whether every intermediate mesh was valid.
absl::StatusOr<std::string> ProgressiveCases(bool json) {
  kerf::v1::CutExperiment experiment;
  experiment.set_name("progressive-cases");
  experiment.set_scene("a 6 x 2 x 2 cm lattice of 1 cm cubes, at rest");
  for (const cut::ScriptedPath& path : cut::ProgressiveCasePaths()) {
    mesh::TetMesh m = cut::ScriptedPathLattice();
    CutOptions options;
    options.mode = cut::CutMode::kProgressive;
    absl::StatusOr<kerf::v1::CutReport> report = CutAlongPath(&m, path.poses, path.name, options);
    if (!report.ok()) return report.status();
    *experiment.add_cuts() = *std::move(report);
  }
  if (json) return FormatProtoJson(experiment);
  std::string out = absl::StrCat("progressive-cases: ", experiment.scene(),
                                 "\n\n| case (Table 1) | tet-poses | paths |\n|---|---|---|\n");
  for (int k = 1; k <= cut::kProgressiveCases; ++k) {
    std::uint32_t total = 0;
    std::string names;
    for (const kerf::v1::CutReport& r : experiment.cuts()) {
      if (r.poses_by_case(k) == 0) continue;
      total += r.poses_by_case(k);
      absl::StrAppend(&names, names.empty() ? "" : ", ", r.path());
    }
    absl::StrAppendFormat(&out, "| %d | %u | %s |\n", k, total, names);
  }
  out +=
      "\n| path | poses | held | frozen | rebuilt | moved | invalid poses | cut tets | "
      "components |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const kerf::v1::CutReport& r : experiment.cuts()) {
    absl::StrAppendFormat(&out, "| %s | %u | %u | %u | %u | %u | %u | %u | %u |\n", r.path(),
                          r.poses(), r.held_poses(), r.frozen_tets(), r.rebuilt(), r.moved(),
                          r.invalid_poses(), r.cut_tets(), r.components());
  }
  return out;
}

}  // namespace

absl::StatusOr<std::string> RunExperimentCommand(const std::vector<absl::string_view>& args) {
  CommandArgs rest(args);
  const bool json = rest.TakeFlag("--json");
  absl::StatusOr<std::vector<absl::string_view>> name =
      rest.TakePositionals(1, "kerf experiment lattice-cut|progressive-cases [--json]");
  if (!name.ok()) return name.status();
  if ((*name)[0] == "lattice-cut") return LatticeCut(json);
  if ((*name)[0] == "progressive-cases") return ProgressiveCases(json);
  return absl::InvalidArgumentError(absl::StrCat("unknown experiment '", (*name)[0],
                                                 "'; there are: lattice-cut, progressive-cases"));
}

}  // namespace kerf::cli
