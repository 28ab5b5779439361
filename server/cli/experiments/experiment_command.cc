#include "cli/experiments/experiment_command.h"

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_split.h"
#include "cli/command_args.h"
#include "cli/cut_command.h"
#include "cli/experiments/hand_cut_experiment.h"
#include "cli/experiments/stability_experiment.h"
#include "cli/experiments/tradeoff_experiment.h"
#include "cli/json_output.h"
#include "embedded_text.h"
#include "kerf/v1/cut_report.pb.h"
#include "kerf/v1/live_cut_report.pb.h"
#include "lab/live_cut.h"
#include "lab/progressive_case_paths.h"
#include "lab/standard_scenes.h"
#include "mesh/mesh_quality.h"
#include "sim/blade_messages.h"

namespace kerf::cli {
namespace {

constexpr absl::string_view kExperimentUsage =
    "kerf experiment lattice-cut|progressive-cases|live-cut [--json]\n"
    "       kerf experiment tradeoff [--resolutions N,N,...] [--reference-resolution N] "
    "[--seconds S] [--json]\n"
    "       kerf experiment stability [--liver FILE] [--scenes NAME,...] [--slow-down X] [--json]";

absl::StatusOr<std::string> LatticeCut(bool json) {
  absl::StatusOr<std::string> text = sim::EmbeddedSceneText("lattice-tension");
  if (!text.ok()) return text.status();
  absl::StatusOr<kerf::v1::Scene> spec = sim::ParseSceneText(*text, "lattice-tension");
  if (!spec.ok()) return spec.status();
  spec->mutable_integration()->set_method(kerf::v1::Integration::STATIC);
  kerf::v1::CutExperiment experiment;
  experiment.set_name("lattice-cut");
  experiment.set_scene("lattice-tension, at static equilibrium under 10% tension");
  // Each path cut as by default (progressive), then deferred.
  CutOptions by_default;
  by_default.check = CheckWhen::kEveryPose;
  CutOptions deferred = by_default;
  deferred.mode = cut::CutMode::kDeferred;
  for (const char* path : {"lattice-straight", "lattice-curved"}) {
    for (const CutOptions& options : {by_default, deferred}) {
      absl::StatusOr<sim::Scene> scene = sim::BuildScene(*spec, ".");
      if (!scene.ok()) return scene.status();
      absl::StatusOr<mesh::TetMesh> m = MeshOfScene(*std::move(scene));
      if (!m.ok()) return m.status();
      const std::optional<absl::string_view> json_path =
          FindEmbeddedText(EmbeddedBladePaths(), path);
      absl::StatusOr<std::vector<cut::BladePose>> poses = sim::ParseBladePathJson(
          *json_path, path,
          LimitsForMeshSize(mesh::MeasureBounds(*m, /*current=*/true).diagonal()));
      if (!poses.ok()) return poses.status();
      absl::StatusOr<kerf::v1::CutReport> report = CutAlongPath(&*m, *poses, path, options);
      if (!report.ok()) return report.status();
      *experiment.add_cuts() = *std::move(report);
    }
  }
  if (json) return FormatProtoJson(experiment);
  std::string out = absl::StrCat(
      "lattice-cut: ", experiment.scene(),
      "\n\n| | cut tets | new tets | new per cut | tets after | cases i/ii/iii/iv/v | "
      "min dihedral of new (deg) | slivers | components | valid |\n|---|---|---|---|---|---|---|"
      "---|---|---|\n");
  for (const kerf::v1::CutReport& r : experiment.cuts()) {
    absl::StrAppendFormat(
        &out, "| kerf, %s, %s | %u | %u | %.2f | %u | %u/%u/%u/%u/%u | %.1f | %u | %u | %s |\n",
        r.path(), r.mode(), r.cut_tets(), r.new_tets(), r.new_per_cut(), r.tets_after(), r.case_i(),
        r.case_ii(), r.case_iii(), r.case_iv(), r.case_v(), r.min_dihedral_deg(), r.slivers(),
        r.components(), r.valid() ? "yes" : "NO");
  }
  out +=
      "| Mor & Kanade 2000 | 60 | 312 | 5.2 | 954 (576 - 60 + 312 = 828) | - | - | - | - | - |\n"
      "| Bielser et al. 1999 | 110 | 1870 | 17 | - | - | - | - | - | - |\n";
  return out;
}

// Every scripted path of lab::ProgressiveCasePaths, cut progressively with the least snapping:
// how often each Table 1 case was reached, and on which paths, and whether every intermediate
// mesh was valid.
absl::StatusOr<std::string> ProgressiveCases(bool json) {
  kerf::v1::CutExperiment experiment;
  experiment.set_name("progressive-cases");
  experiment.set_scene("a 6 x 2 x 2 cm lattice of 1 cm cubes, at rest");
  for (const lab::ScriptedPath& path : lab::ProgressiveCasePaths()) {
    mesh::TetMesh m = lab::ScriptedPathLattice();
    CutOptions options;
    options.mode = cut::CutMode::kProgressive;
    options.check = CheckWhen::kEveryPose;
    options.snap_fraction = 0;  // the least: the paths were found for crossings where they are
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
      "\n| path | poses | rebuilt | moved | invalid poses | cut tets | "
      "components |\n|---|---|---|---|---|---|---|\n";
  for (const kerf::v1::CutReport& r : experiment.cuts()) {
    absl::StrAppendFormat(&out, "| %s | %u | %u | %u | %u | %u | %u |\n", r.path(), r.poses(),
                          r.rebuilt(), r.moved(), r.invalid_poses(), r.cut_tets(), r.components());
  }
  return out;
}

// Scene lattice-tension cut along lattice-straight while it moves, per integrator and cut
// mode: explicit at the real-time step of 1 ms (no protection), explicit at 0.9 of the
// critical step re-estimated after every cut, explicit in sub-steps of 1 ms, and backward
// Euler at 1 ms.
absl::StatusOr<std::string> LiveCut(bool json) {
  const lab::LiveCutOptions options = {.max_wall_seconds = kRowWallSeconds};
  kerf::v1::LiveCutExperiment experiment;
  experiment.set_scene("lattice-tension");
  experiment.set_path("lattice-straight");
  experiment.set_settle_seconds(options.settle_seconds);
  experiment.set_slow_down(options.slow_down);
  experiment.set_pose_rate_hz(options.pose_rate_hz);
  experiment.set_blow_up_energy_ratio(options.blow_up_energy_ratio);
  experiment.set_max_wall_seconds(options.max_wall_seconds);
  const std::optional<absl::string_view> json_path =
      FindEmbeddedText(EmbeddedBladePaths(), experiment.path());
  absl::StatusOr<std::vector<cut::BladePose>> poses =
      sim::ParseBladePathJson(*json_path, experiment.path(), cut::BladeLimits{});
  if (!poses.ok()) return poses.status();
  struct Integration {
    kerf::v1::Integration::Method method;
    double time_step;  // s; 0: the scene's automatic step
    const char* name;
  };
  for (const Integration& integration :
       {Integration{kerf::v1::Integration::SYMPLECTIC_EULER, 1e-3, "SYMPLECTIC_EULER, 1 ms"},
        Integration{kerf::v1::Integration::SYMPLECTIC_EULER, 0,
                    "SYMPLECTIC_EULER, 0.9 x critical, re-estimated"},
        Integration{kerf::v1::Integration::SYMPLECTIC_EULER_SUBSTEPPED, 1e-3,
                    "SYMPLECTIC_EULER_SUBSTEPPED, 1 ms"},
        Integration{kerf::v1::Integration::IMPLICIT_EULER, 1e-3, "IMPLICIT_EULER, 1 ms"}}) {
    for (const kerf::v1::Cutting::Mode mode :
         {kerf::v1::Cutting::DEFERRED, kerf::v1::Cutting::PROGRESSIVE}) {
      absl::StatusOr<sim::Scene> scene = sim::LoadScene(experiment.scene());
      if (!scene.ok()) return scene.status();
      scene->method = integration.method;
      scene->time_step = integration.time_step;
      scene->cut_mode = mode;
      absl::StatusOr<kerf::v1::LiveCutRow> row =
          lab::RunLiveCut(*std::move(scene), *poses, options);
      if (!row.ok()) return row.status();
      row->set_integration(integration.name);
      row->set_cut_mode(mode == kerf::v1::Cutting::DEFERRED ? "deferred" : "progressive");
      *experiment.add_rows() = *std::move(row);
    }
  }
  if (json) return FormatProtoJson(experiment);
  std::string out = absl::StrFormat(
      "live-cut: %s settled %g s, then cut along %s %g times slower than written, %g poses/s; "
      "blew up: energy over %g times that at the first pose; a row stops after %g s of wall "
      "time\n\n"
      "| integration | cut | blew up | after (s) | stopped after (s) | largest energy ratio | "
      "largest speed (m/s) | "
      "smallest height (mm) | critical step (us) | step (us) | cut tets | tets after | "
      "valid | wall s per simulated s | solve iterations per step (median, max) | "
      "sub-steps per step (median, max) |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
      experiment.scene(), experiment.settle_seconds(), experiment.path(), experiment.slow_down(),
      experiment.pose_rate_hz(), experiment.blow_up_energy_ratio(), experiment.max_wall_seconds());
  for (const kerf::v1::LiveCutRow& r : experiment.rows()) {
    absl::StrAppendFormat(&out,
                          "| %s | %s | %s | %.3f | %s | %.3g | %.3g | %.3g | %.3g | %.4g | %u | %u "
                          "| %s | %.3g | %u, %u | %u, %u |\n",
                          r.integration(), r.cut_mode(), r.blew_up() ? "YES" : "no",
                          r.blew_up_after(), StoppedAfterCell(r), r.largest_energy_ratio(),
                          r.largest_speed(), 1e3 * r.smallest_height(),
                          1e6 * r.critical_time_step(), 1e6 * r.time_step(), r.cut_tets(),
                          r.tets_after(), r.valid() ? "yes" : "NO",
                          r.wall_seconds_per_simulated_second(), r.solve_iterations_median(),
                          r.solve_iterations_max(), r.sub_steps_median(), r.sub_steps_max());
  }
  return out;
}

// kerf experiment tradeoff [--resolutions N,N,...] [--reference-resolution N] [--seconds S].
absl::StatusOr<std::string> Tradeoff(CommandArgs* rest, bool json) {
  TradeoffOptions options;
  absl::StatusOr<std::optional<std::vector<absl::string_view>>> resolutions =
      rest->TakeOption("--resolutions", 1);
  if (!resolutions.ok()) return resolutions.status();
  if (resolutions->has_value()) {
    options.resolutions.clear();
    for (absl::string_view n : absl::StrSplit((**resolutions)[0], ',')) {
      absl::StatusOr<int> value = ParseIntArg(n, "--resolutions");
      if (!value.ok()) return value.status();
      options.resolutions.push_back(*value);
    }
  }
  absl::StatusOr<std::optional<std::vector<absl::string_view>>> reference =
      rest->TakeOption("--reference-resolution", 1);
  if (!reference.ok()) return reference.status();
  if (reference->has_value()) {
    absl::StatusOr<int> value = ParseIntArg((**reference)[0], "--reference-resolution");
    if (!value.ok()) return value.status();
    options.reference_resolution = *value;
  }
  absl::StatusOr<std::optional<std::vector<absl::string_view>>> seconds =
      rest->TakeOption("--seconds", 1);
  if (!seconds.ok()) return seconds.status();
  if (seconds->has_value()) {
    absl::StatusOr<double> value = ParseDoubleArg((**seconds)[0], "--seconds");
    if (!value.ok()) return value.status();
    if (!(*value > 0 && *value <= 600)) {
      return absl::InvalidArgumentError(
          absl::StrCat("--seconds must be in (0, 600], got ", *value));
    }
    options.settle_seconds = *value;
  }
  if (absl::Status s = rest->TakePositionals(0, kExperimentUsage).status(); !s.ok()) return s;
  absl::StatusOr<kerf::v1::TradeoffExperiment> experiment = RunTradeoff(options);
  if (!experiment.ok()) return experiment.status();
  return json ? FormatProtoJson(*experiment) : FormatTradeoff(*experiment);
}

// kerf experiment stability [--liver FILE] [--scenes NAME,...] [--slow-down X].
absl::StatusOr<std::string> Stability(CommandArgs* rest, bool json) {
  StabilityOptions options;
  absl::StatusOr<std::optional<std::vector<absl::string_view>>> liver =
      rest->TakeOption("--liver", 1);
  if (!liver.ok()) return liver.status();
  if (liver->has_value()) options.liver_mesh_path = std::string((**liver)[0]);
  absl::StatusOr<std::optional<std::vector<absl::string_view>>> scenes =
      rest->TakeOption("--scenes", 1);
  if (!scenes.ok()) return scenes.status();
  if (scenes->has_value()) {
    options.scenes.clear();
    for (absl::string_view name : absl::StrSplit((**scenes)[0], ',')) {
      if (name == "liver") {
        return absl::InvalidArgumentError("--scenes: the liver comes with --liver FILE");
      }
      // Built once here, so that a wrong name is refused before any run.
      if (absl::Status s = lab::StandardScene(name, "").status(); !s.ok()) return s;
      options.scenes.emplace_back(name);
    }
  }
  if (!options.liver_mesh_path.empty()) {
    if (absl::Status s = lab::LiverScene(options.liver_mesh_path).status(); !s.ok()) return s;
  }
  absl::StatusOr<std::optional<std::vector<absl::string_view>>> slow_down =
      rest->TakeOption("--slow-down", 1);
  if (!slow_down.ok()) return slow_down.status();
  if (slow_down->has_value()) {
    absl::StatusOr<double> value = ParseDoubleArg((**slow_down)[0], "--slow-down");
    if (!value.ok()) return value.status();
    if (!(*value >= 1 && *value <= 100)) {
      return absl::InvalidArgumentError(
          absl::StrCat("--slow-down must be in [1, 100], got ", *value));
    }
    options.live_cut.slow_down = *value;
  }
  if (absl::Status s = rest->TakePositionals(0, kExperimentUsage).status(); !s.ok()) return s;
  absl::StatusOr<kerf::v1::StabilityExperiment> experiment = RunStability(options);
  if (!experiment.ok()) return experiment.status();
  return json ? FormatProtoJson(*experiment) : FormatStability(*experiment);
}

}  // namespace

absl::StatusOr<std::string> RunExperimentCommand(const std::vector<absl::string_view>& args) {
  if (args.empty()) return absl::InvalidArgumentError(absl::StrCat("usage: ", kExperimentUsage));
  CommandArgs rest(std::vector<absl::string_view>(args.begin() + 1, args.end()));
  const bool json = rest.TakeFlag("--json");
  if (args[0] == "tradeoff") return Tradeoff(&rest, json);
  if (args[0] == "stability") return Stability(&rest, json);
  if (args[0] == "hand-cuts") return RunHandCutExperiment(&rest, json);
  if (absl::Status s = rest.TakePositionals(0, kExperimentUsage).status(); !s.ok()) return s;
  if (args[0] == "lattice-cut") return LatticeCut(json);
  if (args[0] == "progressive-cases") return ProgressiveCases(json);
  if (args[0] == "live-cut") return LiveCut(json);
  return absl::InvalidArgumentError(
      absl::StrCat("unknown experiment '", args[0],
                   "'; there are: lattice-cut, progressive-cases, live-cut, tradeoff, stability, "
                   "hand-cuts"));
}

}  // namespace kerf::cli
