#include "cli/experiments/stability_experiment.h"

#include "absl/strings/str_format.h"
#include "lab/standard_scenes.h"

namespace kerf::cli {
namespace {

struct Integration {
  kerf::v1::Integration::Method method;
  double time_step;  // s; 0: the automatic step
  const char* name;
};
constexpr Integration kIntegrations[] = {
    {kerf::v1::Integration::SYMPLECTIC_EULER, 0, "SYMPLECTIC_EULER, 0.9 x critical, re-estimated"},
    {kerf::v1::Integration::SYMPLECTIC_EULER_SUBSTEPPED, 1e-3, "SYMPLECTIC_EULER_SUBSTEPPED, 1 ms"},
    {kerf::v1::Integration::IMPLICIT_EULER, 1e-3, "IMPLICIT_EULER, 1 ms"}};

struct StabilityCutting {
  kerf::v1::Cutting::Mode mode;
  double snap_fraction;
};
constexpr StabilityCutting kStabilityCuttings[] = {
    {kerf::v1::Cutting::PROGRESSIVE, 0},
    {kerf::v1::Cutting::PROGRESSIVE, kStabilitySnapFraction},
    {kerf::v1::Cutting::DEFERRED, 0},
    {kerf::v1::Cutting::DEFERRED, kStabilitySnapFraction}};

}  // namespace

absl::StatusOr<kerf::v1::StabilityExperiment> RunStability(const StabilityOptions& options) {
  kerf::v1::StabilityExperiment experiment;
  experiment.set_snapping(true);
  experiment.set_settle_seconds(options.live_cut.settle_seconds);
  experiment.set_slow_down(options.live_cut.slow_down);
  experiment.set_pose_rate_hz(options.live_cut.pose_rate_hz);
  experiment.set_blow_up_energy_ratio(options.live_cut.blow_up_energy_ratio);
  experiment.set_max_wall_seconds(options.live_cut.max_wall_seconds);
  std::vector<std::string> scenes = options.scenes;
  if (!options.liver_mesh_path.empty()) scenes.push_back("liver");
  for (const lab::StandardCut& cut : lab::StandardCuts(scenes)) {
    absl::StatusOr<std::vector<cut::BladePose>> path = lab::StandardPath(cut.path);
    if (!path.ok()) return path.status();
    for (const StabilityCutting& cutting : kStabilityCuttings) {
      for (const Integration& integration : kIntegrations) {
        for (const fem::ElasticLaw law :
             {fem::ElasticLaw::kLinear, fem::ElasticLaw::kCorotational}) {
          absl::StatusOr<sim::Scene> scene = lab::StandardScene(cut.scene, options.liver_mesh_path);
          if (!scene.ok()) return scene.status();
          scene->method = integration.method;
          scene->time_step = integration.time_step;
          scene->cut_mode = cutting.mode;
          scene->snap_fraction = cutting.snap_fraction;
          scene->elastic.law = law;
          absl::StatusOr<kerf::v1::LiveCutRow> row =
              lab::RunLiveCut(*std::move(scene), *path, options.live_cut);
          if (!row.ok()) return row.status();
          row->set_scene(cut.scene);
          row->set_path(cut.path);
          row->set_integration(integration.name);
          row->set_cut_mode(cutting.mode == kerf::v1::Cutting::PROGRESSIVE ? "progressive"
                                                                           : "deferred");
          row->set_snap_fraction(cutting.snap_fraction);
          row->set_law(law == fem::ElasticLaw::kLinear ? "linear" : "corotational");
          *experiment.add_rows() = *std::move(row);
        }
      }
    }
  }
  return experiment;
}

std::string FormatStability(const kerf::v1::StabilityExperiment& experiment) {
  std::string out = absl::StrFormat(
      "stability: each scene settled %g s, then cut along its path %g times slower than "
      "written, %g poses/s; blew up: energy over %g times that at the first pose; a row stops "
      "after %g s of wall time\n\n"
      "| scene | path | cutting | integration | law | blew up | after (s) | stopped after (s) | "
      "largest "
      "energy ratio | "
      "critical step at the end (us) | step (us) | sub-steps (median, max) | smallest radius "
      "ratio | smallest dihedral (deg) | cut tets | valid | wall s per simulated s "
      "|\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
      experiment.settle_seconds(), experiment.slow_down(), experiment.pose_rate_hz(),
      experiment.blow_up_energy_ratio(), experiment.max_wall_seconds());
  for (const kerf::v1::LiveCutRow& r : experiment.rows()) {
    absl::StrAppendFormat(
        &out,
        "| %s | %s | %s | %s | %s | %s | %.3f | %s | %.3g | %.3g | %.4g | %u, %u | %.3g | %.3g | "
        "%u | %s | %.3g |\n",
        r.scene(), r.path(),
        r.snap_fraction() > 0 ? absl::StrFormat("%s, snap %g", r.cut_mode(), r.snap_fraction())
                              : r.cut_mode(),
        r.integration(), r.law(), r.blew_up() ? "YES" : "no", r.blew_up_after(),
        StoppedAfterCell(r), r.largest_energy_ratio(), 1e6 * r.critical_time_step(),
        1e6 * r.time_step(), r.sub_steps_median(), r.sub_steps_max(), r.smallest_radius_ratio(),
        r.smallest_dihedral_deg(), r.cut_tets(), r.valid() ? "yes" : "NO",
        r.wall_seconds_per_simulated_second());
  }
  return out;
}

std::string StoppedAfterCell(const kerf::v1::LiveCutRow& row) {
  return row.stopped_after() > 0 ? absl::StrFormat("%.3f", row.stopped_after()) : "-";
}

}  // namespace kerf::cli
