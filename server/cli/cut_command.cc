#include "cli/cut_command.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>
#include <utility>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "cli/command_args.h"
#include "cli/json_output.h"
#include "cut/crack_cutter.h"
#include "geometry/tet_measures.h"
#include "lab/crack_fidelity.h"
#include "lab/standard_scenes.h"
#include "mesh/connected_components.h"
#include "mesh/cut_mesh_check.h"
#include "mesh/cut_surface.h"
#include "mesh/face_tiling.h"
#include "mesh/io/mesh_file.h"
#include "mesh/io/vtu_writer.h"
#include "mesh/mesh_quality.h"
#include "mesh/mesh_validation.h"
#include "sim/blade_messages.h"
#include "sim/simulation.h"

namespace kerf::cli {
namespace {

constexpr absl::string_view kCutUsage =
    "kerf cut MESH --path PATH.json --out OUT.vtu [--progressive|--deferred] [--check every|end] "
    "[--uncovered OUT.csv] [--overcut OUT.csv] [--lagging OUT.csv] "
    "[--min-temporary-height F] [--snap F] [--trace OUT.jsonl] [--dump-every-pose DIR] [--json]";

double TotalRestVolume(const mesh::TetMesh& m) {
  double volume = 0;
  for (const mesh::TetId t : m.tets()) volume += mesh::RestVolume(m, t);
  return volume;
}

// The crack faces farther than the tolerance from the swept surface, one row each: corners,
// each corner's and the middle's distance from the sweep (in local edges), the local edge.
absl::Status WriteOvercutCsv(const lab::FidelityMeter& fidelity, const lab::CrackFaces& crack,
                             const std::string& path) {
  std::string csv = "x0,y0,z0,x1,y1,z1,x2,y2,z2,d0,d1,d2,dmiddle,edge\n";
  for (const lab::FidelityMeter::FaceDistance& face : fidelity.Overcut(crack)) {
    for (const Eigen::Vector3d& p : face.triangle) {  // exact, to find the face in OUT.vtu
      absl::StrAppendFormat(&csv, "%.17g,%.17g,%.17g,", p.x(), p.y(), p.z());
    }
    for (const double d : face.distance) absl::StrAppend(&csv, d, ",");
    absl::StrAppend(&csv, face.edge, "\n");
  }
  return mesh::WriteTextFile(path, csv);
}

// The VTU of a cut mesh with the arrays kerf cut writes.
std::string CutMeshVtu(const mesh::TetMesh& m, const cut::CrackCutter& cutter,
                       std::uint32_t original_vertices) {
  mesh::VtuExtraArrays extra;
  std::vector<std::int64_t> source_vertex;
  for (const mesh::VertexId v : m.vertices()) {
    const std::uint32_t index = mesh::Index(v);
    source_vertex.push_back(index < original_vertices ? std::int64_t{index} : -1);
  }
  std::vector<std::int64_t> source_tet;
  for (const mesh::TetId t : m.tets()) source_tet.push_back(mesh::Index(cutter.SourceTet(t)));
  extra.point_data.push_back(mesh::RestPositionArray(m));
  extra.point_data.push_back({"source_vertex", 1, std::move(source_vertex)});
  extra.cell_data.push_back({"source_tet", 1, std::move(source_tet)});
  return mesh::FormatVtu(m, extra);
}

}  // namespace

absl::StatusOr<mesh::TetMesh> LoadMeshOrScene(absl::string_view name) {
  const bool file = absl::EndsWith(name, ".textproto");
  absl::StatusOr<sim::Scene> scene =
      file ? sim::LoadScene(name) : lab::StandardScene(name, /*liver_mesh_path=*/"");
  if (!file && absl::IsNotFound(scene.status())) return mesh::ReadMeshFile(name);
  if (!scene.ok()) return scene.status();
  return MeshOfScene(*std::move(scene));
}

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

namespace {

// The checks after a pose (every pose with --check every, else after the withdrawal only):
// validity, conformity and volume, the step's coverage, and the trace and dump files.
class PoseChecks {
 public:
  PoseChecks(mesh::TetMesh* m, const cut::CrackCutter* cutter,
             const std::vector<cut::BladePose>& poses, lab::FidelityMeter* fidelity,
             const CutOptions& options, kerf::v1::CutReport* report)
      : m_(m),
        cutter_(cutter),
        poses_(poses),
        fidelity_(fidelity),
        options_(options),
        report_(report),
        original_vertices_(m->vertex_index_bound()),
        volume_(TotalRestVolume(*m)),
        uncut_(*m) {
    if (options.check == CheckWhen::kEveryPose) {
      incremental_.emplace(
          uncut_, m_, [cutter](mesh::TetId t) { return cutter->SourceTet(t); },
          [cutter](mesh::VertexId v) { return cutter->PartedFrom(v); });
    }
  }

  absl::Status Open() {
    if (!options_.trace_path.empty()) {
      trace_ = std::fopen(options_.trace_path.c_str(), "w");
      if (trace_ == nullptr) {
        return absl::NotFoundError(absl::StrCat("cannot write ", options_.trace_path));
      }
    }
    if (!options_.dump_directory.empty()) {
      std::error_code error;
      std::filesystem::create_directories(options_.dump_directory, error);
      if (error) {
        return absl::NotFoundError(
            absl::StrCat("cannot make ", options_.dump_directory, ": ", error.message()));
      }
    }
    return absl::OkStatus();
  }
  ~PoseChecks() {
    if (trace_ != nullptr) std::fclose(trace_);
  }

  // After pose `i` (poses.size(): withdrawn).
  absl::Status After(std::size_t i) {
    const bool withdrawn = i == poses_.size();
    const double crack_area = trace_ != nullptr ? mesh::MeasureCrackArea(*m_) : 0;
    const absl::Status valid_status = Valid();
    const bool valid = valid_status.ok();
    if (!valid) {
      report_->set_invalid_poses(report_->invalid_poses() + 1);
      if (report_->first_invalid().empty()) {
        report_->set_first_invalid(absl::StrCat(withdrawn ? "withdrawal" : absl::StrCat("pose ", i),
                                                ": ", valid_status.message()));
      }
    }
    double covered = 1, covered_below = 1;
    if (!withdrawn && fidelity_ != nullptr && i > 0) {
      const lab::CrackFaces crack = fidelity_->FindCrackNearStep(*m_, i - 1);
      covered = fidelity_->StepCoverage(crack, i - 1);
      covered_below = fidelity_->StepCoverageBelowSurface(crack, i - 1);
      if (covered < 1) report_->set_poses_not_covered(report_->poses_not_covered() + 1);
      if (covered_below < 1) {
        report_->set_poses_not_covered_below_surface(report_->poses_not_covered_below_surface() +
                                                     1);
      }
      report_->set_min_step_coverage(std::min(report_->min_step_coverage(), covered));
      if (!options_.lagging_path.empty()) {
        for (const auto& s : fidelity_->StepUncovered(crack, i - 1)) {
          absl::StrAppend(&lagging_, i, ",", s.point.x(), ",", s.point.y(), ",", s.point.z(), ",",
                          s.edge, ",", s.tet, ",", s.at_surface ? 0 : 1, "\n");
        }
      }
    }
    if (withdrawn && !options_.lagging_path.empty()) {
      if (absl::Status s = mesh::WriteTextFile(options_.lagging_path, lagging_); !s.ok()) return s;
    }
    if (trace_ != nullptr) Trace(i, valid, crack_area, covered, covered_below);
    if (options_.dump_directory.empty()) return absl::OkStatus();
    char name[32];
    std::snprintf(name, sizeof name, "pose-%04zu.vtu", i);
    const std::filesystem::path file =
        std::filesystem::path(options_.dump_directory) / (withdrawn ? "withdrawn.vtu" : name);
    return mesh::WriteTextFile(file.string(), CutMeshVtu(*m_, *cutter_, original_vertices_));
  }

 private:
  // Every pose: what changed since the last (mesh::CutMeshCheck); at the end only: the whole mesh.
  absl::Status Valid() {
    if (incremental_) return incremental_->Check();
    if (absl::Status s = mesh::ValidateMesh(*m_); !s.ok()) return s;
    const double volume = TotalRestVolume(*m_);
    if (std::abs(volume - volume_) > 1e-12 * volume_) {
      return absl::FailedPreconditionError(
          absl::StrCat("rest volume ", volume, " instead of ", volume_));
    }
    return mesh::CheckOriginalFacesTiled(
        uncut_, *m_, [&](mesh::TetId t) { return cutter_->SourceTet(t); },
        [&](mesh::VertexId v) { return cutter_->PartedFrom(v); });
  }

  void Trace(std::size_t i, bool valid, double crack_area, double covered, double covered_below) {
    const bool withdrawn = i == poses_.size();
    const cut::PoseSummary& pose = cutter_->last_pose();
    std::string cases;
    for (int k = 0; k <= cut::kProgressiveCases; ++k) {
      if (withdrawn || pose.tets_by_case[k] == 0) continue;
      absl::StrAppend(&cases, cases.empty() ? "" : ",", "\"", k, "\":", pose.tets_by_case[k]);
    }
    const std::string line = absl::StrCat(
        "{\"pose\":", i, ",\"withdrawn\":", withdrawn ? "true" : "false", ",\"cases\":{", cases,
        "},\"open_tets\":", withdrawn ? 0 : pose.open_tets,
        ",\"temporary_tets\":", withdrawn ? 0 : pose.temporary_tets, ",\"tets\":", m_->tet_count(),
        ",\"valid\":", valid ? "true" : "false", ",\"open_area\":", crack_area,
        withdrawn ? ""
                  : absl::StrCat(",\"step_coverage\":", covered,
                                 ",\"step_coverage_below_surface\":", covered_below),
        "}\n");
    std::fputs(line.c_str(), trace_);
  }

  mesh::TetMesh* m_;
  const cut::CrackCutter* cutter_;
  const std::vector<cut::BladePose>& poses_;
  lab::FidelityMeter* fidelity_;
  const CutOptions& options_;
  kerf::v1::CutReport* report_;
  std::uint32_t original_vertices_;
  double volume_;
  mesh::TetMesh uncut_;
  std::optional<mesh::CutMeshCheck> incremental_;
  std::FILE* trace_ = nullptr;
  std::string lagging_ = "pose,x,y,z,edge,tissue_tet,below_surface\n";  // --lagging's rows
};

bool AtRest(const mesh::TetMesh& m) {
  for (const mesh::VertexId v : m.vertices()) {
    if (m.rest_position(v) != m.current_position(v)) return false;
  }
  return true;
}

void ReportStatistics(const cut::CutStatistics& s, kerf::v1::CutReport* report) {
  for (const std::size_t n : s.poses_by_case) {
    report->add_poses_by_case(static_cast<std::uint32_t>(n));
  }
  report->set_rebuilt(static_cast<std::uint32_t>(s.rebuilt));
  report->set_moved(static_cast<std::uint32_t>(s.moved));
  report->set_cut_tets(static_cast<std::uint32_t>(s.cut_tets));
  report->set_new_tets(static_cast<std::uint32_t>(s.new_tets));
  report->set_new_per_cut(s.cut_tets ? static_cast<double>(s.new_tets) / s.cut_tets : 0.0);
  report->set_case_i(static_cast<std::uint32_t>(s.tets_by_case[1]));
  report->set_case_ii(static_cast<std::uint32_t>(s.tets_by_case[2]));
  report->set_case_iii(static_cast<std::uint32_t>(s.tets_by_case[3]));
  report->set_case_iv(static_cast<std::uint32_t>(s.tets_by_case[4]));
  report->set_case_v(static_cast<std::uint32_t>(s.tets_by_case[5]));
  report->set_snapped_vertices(static_cast<std::uint32_t>(s.snapped_vertices));
  report->set_parted_vertices(static_cast<std::uint32_t>(s.parted_vertices));
  report->set_split_edge_tets(static_cast<std::uint32_t>(
      s.tets_by_case[static_cast<std::size_t>(cut::CutCase::kSplitEdge)]));
}

// The quality of the tets the cut made: the smallest dihedral angle and the slivers.
void ReportNewTetQuality(const mesh::TetMesh& m, const cut::CrackCutter& cutter,
                         kerf::v1::CutReport* report) {
  double min_angle = 0;
  std::uint32_t slivers = 0, under_one = 0;
  bool any = false;
  for (const mesh::TetId t : m.tets()) {
    if (!cutter.MadeByCut(t)) continue;
    const mesh::TetVertices& v = m.tet(t);
    const geometry::TetMeasures q = geometry::MeasureTet(
        m.rest_position(v[0]), m.rest_position(v[1]), m.rest_position(v[2]), m.rest_position(v[3]));
    min_angle = any ? std::min(min_angle, q.min_dihedral_deg) : q.min_dihedral_deg;
    any = true;
    if (q.min_dihedral_deg < mesh::kDefaultSliverAngleDeg) ++slivers;
    if (q.min_dihedral_deg < 1) ++under_one;
  }
  report->set_min_dihedral_deg(min_angle);
  report->set_slivers(slivers);
  report->set_new_tets_under_1deg(under_one);
}

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

absl::StatusOr<kerf::v1::CutReport> CutWith(cut::CrackCutter* cutter, mesh::TetMesh* m,
                                            const std::vector<cut::BladePose>& poses,
                                            absl::string_view path_name, const CutOptions& options,
                                            kerf::v1::CutReport report) {
  std::optional<lab::FidelityMeter> fidelity;
  if (AtRest(*m)) fidelity.emplace(*m);
  const std::uint32_t original_vertices = m->vertex_index_bound();
  PoseChecks checks(m, cutter, poses, fidelity ? &*fidelity : nullptr, options, &report);
  absl::Status status = checks.Open();
  const bool every = options.check == CheckWhen::kEveryPose;
  double cut_seconds = 0, check_seconds = 0;
  for (std::size_t i = 0; i < poses.size() && status.ok(); ++i) {
    const auto start = std::chrono::steady_clock::now();
    if (absl::Status s = cutter->ApplyPose(poses[i]); !s.ok()) {
      return absl::InvalidArgumentError(absl::StrCat(path_name, ": pose ", i, ": ", s.message()));
    }
    cut_seconds += SecondsSince(start);
    const auto checked = std::chrono::steady_clock::now();
    if (fidelity && i > 0) fidelity->AddStep(poses[i - 1], poses[i]);
    if (every) status = checks.After(i);
    check_seconds += SecondsSince(checked);
  }
  if (!status.ok()) return status;
  const auto start = std::chrono::steady_clock::now();
  cutter->Finish();
  cut_seconds += SecondsSince(start);
  const auto checked = std::chrono::steady_clock::now();
  status = checks.After(poses.size());
  if (!status.ok()) return status;
  if (fidelity) {
    const lab::CrackFaces crack = fidelity->FindCrack(*m);
    const lab::Fidelity f = fidelity->Measure(crack);
    if (!options.uncovered_path.empty()) {
      std::string csv = "x,y,z,edge\n";
      for (const auto& [p, edge] : fidelity->Uncovered(crack)) {
        absl::StrAppend(&csv, p.x(), ",", p.y(), ",", p.z(), ",", edge, "\n");
      }
      if (absl::Status s = mesh::WriteTextFile(options.uncovered_path, csv); !s.ok()) return s;
    }
    if (!options.overcut_path.empty()) {
      if (absl::Status s = WriteOvercutCsv(*fidelity, crack, options.overcut_path); !s.ok()) {
        return s;
      }
    }
    report.set_fidelity_measured(true);
    report.set_swept_samples(static_cast<std::uint32_t>(f.samples));
    report.set_crossed_tets(static_cast<std::uint32_t>(fidelity->crossed_tets()));
    report.set_coverage(f.coverage);
    report.set_surface_samples(static_cast<std::uint32_t>(f.surface_samples));
    report.set_coverage_below_surface(f.coverage_below_surface);
    report.set_crack_faces(static_cast<std::uint32_t>(f.crack_faces));
    report.set_unpaired_crack_faces(static_cast<std::uint32_t>(f.unpaired_faces));
    report.set_overcut_faces(static_cast<std::uint32_t>(f.overcut_faces));
    report.set_max_overcut(f.max_overcut);
  }
  check_seconds += SecondsSince(checked);
  report.set_cut_seconds(cut_seconds);
  report.set_check_seconds(check_seconds);
  if (!options.out_path.empty()) {
    status = mesh::WriteTextFile(options.out_path, CutMeshVtu(*m, *cutter, original_vertices));
    if (!status.ok()) return status;
  }
  ReportStatistics(cutter->statistics(), &report);
  report.set_tets_after(static_cast<std::uint32_t>(m->tet_count()));
  ReportNewTetQuality(*m, *cutter, &report);
  report.set_components(static_cast<std::uint32_t>(mesh::FindConnectedComponents(*m).count));
  report.set_valid(mesh::FindMeshDefects(*m).empty());
  return report;
}

}  // namespace

absl::StatusOr<kerf::v1::CutReport> CutAlongPath(mesh::TetMesh* m,
                                                 const std::vector<cut::BladePose>& poses,
                                                 absl::string_view path_name,
                                                 const CutOptions& options) {
  kerf::v1::CutReport report;
  report.set_path(std::string(path_name));
  report.set_poses(static_cast<std::uint32_t>(poses.size()));
  report.set_tets_before(static_cast<std::uint32_t>(m->tet_count()));
  report.set_mode(options.mode == cut::CutMode::kProgressive ? "progressive" : "deferred");
  report.set_check(options.check == CheckWhen::kEveryPose ? "every" : "end");
  report.set_snap_fraction(options.snap_fraction);
  report.set_min_step_coverage(1);
  const double cell_size = mesh::MeanEdgeLength(*m);
  const cut::BladeLimits limits =
      LimitsForMeshSize(mesh::MeasureBounds(*m, /*current=*/true).diagonal());
  absl::StatusOr<cut::CrackCutter> cutter =
      cut::CrackCutter::Create(m, cell_size, limits,
                               {.mode = options.mode,
                                .snap_fraction = options.snap_fraction,
                                .min_temporary_height = options.min_temporary_height});
  if (!cutter.ok()) return cutter.status();
  return CutWith(&*cutter, m, poses, path_name, options, std::move(report));
}

absl::StatusOr<std::string> RunCutCommand(const std::vector<absl::string_view>& args) {
  CommandArgs rest(args);
  const bool json = rest.TakeFlag("--json");
  CutOptions options;
  const bool deferred = rest.TakeFlag("--deferred");
  if (rest.TakeFlag("--progressive") && deferred) {
    return absl::InvalidArgumentError(
        absl::StrCat("--progressive and --deferred exclude each other\nusage: ", kCutUsage));
  }
  if (deferred) options.mode = cut::CutMode::kDeferred;
  for (auto [flag, into] : {std::pair<absl::string_view, double*>{"--min-temporary-height",
                                                                  &options.min_temporary_height},
                            {"--snap", &options.snap_fraction}}) {
    absl::StatusOr<std::optional<std::vector<absl::string_view>>> value = rest.TakeOption(flag, 1);
    if (!value.ok()) return value.status();
    if (!value->has_value()) continue;
    absl::StatusOr<double> parsed = ParseDoubleArg((**value)[0], flag);
    if (!parsed.ok()) return parsed.status();
    *into = *parsed;
  }
  for (auto [flag, into] :
       {std::pair<absl::string_view, std::string*>{"--trace", &options.trace_path},
        {"--uncovered", &options.uncovered_path},
        {"--overcut", &options.overcut_path},
        {"--lagging", &options.lagging_path},
        {"--dump-every-pose", &options.dump_directory}}) {
    absl::StatusOr<std::optional<std::vector<absl::string_view>>> value = rest.TakeOption(flag, 1);
    if (!value.ok()) return value.status();
    if (value->has_value()) *into = std::string((**value)[0]);
  }
  absl::StatusOr<std::optional<absl::string_view>> check =
      rest.TakeChoice("--check", {"every", "end"}, kCutUsage);
  if (!check.ok()) return check.status();
  if (check->has_value()) {
    options.check = **check == "every" ? CheckWhen::kEveryPose : CheckWhen::kEnd;
    if (options.check == CheckWhen::kEnd && !options.lagging_path.empty()) {
      return absl::InvalidArgumentError(
          absl::StrCat("--lagging is of every pose: it needs --check every\nusage: ", kCutUsage));
    }
  } else if (!options.trace_path.empty() || !options.dump_directory.empty() ||
             !options.lagging_path.empty()) {
    options.check = CheckWhen::kEveryPose;  // a trace, dump or lag is of every pose
  }
  absl::StatusOr<std::optional<std::vector<absl::string_view>>> path_arg =
      rest.TakeOption("--path", 1);
  if (!path_arg.ok()) return path_arg.status();
  absl::StatusOr<std::optional<std::vector<absl::string_view>>> out_arg =
      rest.TakeOption("--out", 1);
  if (!out_arg.ok()) return out_arg.status();
  absl::StatusOr<std::vector<absl::string_view>> mesh_arg = rest.TakePositionals(1, kCutUsage);
  if (!mesh_arg.ok()) return mesh_arg.status();
  if (!path_arg->has_value() || !out_arg->has_value()) {
    return absl::InvalidArgumentError(
        absl::StrCat("--path and --out are required\nusage: ", kCutUsage));
  }
  absl::StatusOr<mesh::TetMesh> m = LoadMeshOrScene((*mesh_arg)[0]);
  if (!m.ok()) return m.status();
  const absl::string_view path_file = (**path_arg)[0];
  absl::StatusOr<std::string> path_text = mesh::ReadTextFile(path_file);
  if (!path_text.ok()) return path_text.status();
  absl::StatusOr<std::vector<cut::BladePose>> poses = sim::ParseBladePathJson(
      *path_text, path_file,
      LimitsForMeshSize(mesh::MeasureBounds(*m, /*current=*/true).diagonal()));
  if (!poses.ok()) return poses.status();
  options.out_path = std::string((**out_arg)[0]);
  absl::StatusOr<kerf::v1::CutReport> report = CutAlongPath(&*m, *poses, path_file, options);
  if (!report.ok()) return report.status();
  if (json) return FormatProtoJson(*report);
  return absl::StrCat(
      report->mode(), ": cut ", report->cut_tets(), " of ", report->tets_before(), " tets into ",
      report->new_tets(), " (", report->new_per_cut(), " per cut tet); ", report->tets_after(),
      " tets, ", report->components(), " component(s), ", report->valid() ? "valid" : "INVALID",
      report->fidelity_measured()
          ? absl::StrCat("; coverage ", report->coverage(), " (", report->coverage_below_surface(),
                         " below the surface), ", report->overcut_faces(), " overcut and ",
                         report->unpaired_crack_faces(), " unpaired crack faces")
          : "",
      options.check == CheckWhen::kEveryPose
          ? absl::StrCat("; ", report->poses_not_covered(), " poses not covered at once (",
                         report->poses_not_covered_below_surface(), " below the surface)")
          : "",
      "; wrote ", (**out_arg)[0], "\n");
}

}  // namespace kerf::cli
