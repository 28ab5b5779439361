#include "cli/experiments/hand_cut_experiment.h"

#include <algorithm>
#include <filesystem>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_split.h"
#include "cli/cut_command.h"
#include "cli/json_output.h"
#include "lab/hand_paths.h"
#include "mesh/box_lattice.h"
#include "mesh/io/mesh_file.h"

namespace kerf::cli {
namespace {

constexpr absl::string_view kHandCutsUsage =
    "kerf experiment hand-cuts [--meshes FILE,...] [--seeds N] [--check every|end] [--json]";

struct Cutting {
  const char* name;
  cut::CutMode mode;
};
constexpr Cutting kCuttings[] = {{"progressive", cut::CutMode::kProgressive},
                                 {"deferred", cut::CutMode::kDeferred}};
constexpr lab::PathFamily kFamilies[] = {lab::PathFamily::kHand, lab::PathFamily::kThroughVertices,
                                         lab::PathFamily::kAlongEdges,
                                         lab::PathFamily::kInFacePlane};

// One table row: the cuts of one mesh, family and cutting over the seeds.
struct Row {
  std::string mesh, family, cutting;
  int paths = 0;
  double min_coverage = 1, coverage = 0, min_below = 1, below = 0, min_dihedral = 180, seconds = 0;
  std::size_t samples = 0, surface_samples = 0;
  std::size_t made = 0;  // tets the cut made, alive at the end
  std::size_t poses = 0, lagging = 0, lagging_below = 0, overcut = 0, unpaired = 0, cut_tets = 0,
              new_tets = 0, slivers = 0, under_one = 0, invalid = 0;
};

void Add(const kerf::v1::CutReport& r, Row* row) {
  ++row->paths;
  row->min_coverage = std::min(row->min_coverage, r.coverage());
  row->coverage += r.coverage();
  row->min_below = std::min(row->min_below, r.coverage_below_surface());
  row->below += r.coverage_below_surface();
  row->samples += r.swept_samples();
  row->surface_samples += r.surface_samples();
  if (r.new_tets() > 0) row->min_dihedral = std::min(row->min_dihedral, r.min_dihedral_deg());
  row->seconds += r.cut_seconds();
  row->poses += r.poses();
  row->lagging += r.poses_not_covered();
  row->lagging_below += r.poses_not_covered_below_surface();
  row->overcut += r.overcut_faces();
  row->unpaired += r.unpaired_crack_faces();
  row->cut_tets += r.cut_tets();
  row->new_tets += r.new_tets();
  row->slivers += r.slivers();
  row->made += r.tets_after() + r.cut_tets() - r.tets_before();
  row->under_one += r.new_tets_under_1deg();
  row->invalid += r.invalid_poses();
}

}  // namespace

absl::StatusOr<std::string> RunHandCutExperiment(CommandArgs* args, bool json) {
  int seeds = 3;
  CheckWhen check = CheckWhen::kEnd;
  std::vector<std::string> meshes;
  absl::StatusOr<std::optional<std::vector<absl::string_view>>> arg =
      args->TakeOption("--seeds", 1);
  if (!arg.ok()) return arg.status();
  if (arg->has_value()) {
    absl::StatusOr<int> n = ParseIntArg((**arg)[0], "--seeds");
    if (!n.ok()) return n.status();
    if (*n < 1) return absl::InvalidArgumentError("--seeds must be at least 1");
    seeds = *n;
  }
  absl::StatusOr<std::optional<absl::string_view>> when =
      args->TakeChoice("--check", {"every", "end"}, kHandCutsUsage);
  if (!when.ok()) return when.status();
  if (*when == "every") check = CheckWhen::kEveryPose;
  arg = args->TakeOption("--meshes", 1);
  if (!arg.ok()) return arg.status();
  if (arg->has_value()) {
    for (absl::string_view m : absl::StrSplit((**arg)[0], ',')) meshes.emplace_back(m);
  }
  if (absl::Status s = args->TakePositionals(0, kHandCutsUsage).status(); !s.ok()) return s;
  std::vector<std::pair<std::string, mesh::TetMesh>> tissues;
  if (meshes.empty()) {
    tissues.emplace_back(
        "lattice 4x6x4 cm",
        *mesh::MakeBoxLattice(
            {.cells_x = 4, .cells_y = 6, .cells_z = 4, .size = Eigen::Vector3d(0.04, 0.06, 0.04)}));
  }
  for (const std::string& file : meshes) {
    absl::StatusOr<mesh::TetMesh> m = LoadMeshOrScene(file);
    if (!m.ok()) return m.status();
    tissues.emplace_back(std::filesystem::path(file).filename().string(), *std::move(m));
  }
  kerf::v1::CutExperiment experiment;
  experiment.set_name("hand-cuts");
  std::vector<Row> rows;
  for (const auto& [name, tissue] : tissues) {
    absl::StrAppend(experiment.mutable_scene(), experiment.scene().empty() ? "" : ", ", name);
    for (const lab::PathFamily family : kFamilies) {
      for (const Cutting& cutting : kCuttings) {
        Row row{name, std::string(lab::PathFamilyName(family)), cutting.name};
        for (int seed = 1; seed <= seeds; ++seed) {
          mesh::TetMesh m = tissue;
          const std::vector<cut::BladePose> poses =
              lab::MakeHandPath(tissue, family, static_cast<std::uint64_t>(seed));
          CutOptions options;
          options.mode = cutting.mode;
          options.check = check;
          absl::StatusOr<kerf::v1::CutReport> report =
              CutAlongPath(&m, poses, absl::StrCat(name, " ", row.family, " seed ", seed), options);
          if (!report.ok()) return report.status();
          Add(*report, &row);
          *experiment.add_cuts() = *std::move(report);
        }
        rows.push_back(row);
      }
    }
  }
  if (json) return FormatProtoJson(experiment);
  std::string out = absl::StrCat(
      "hand-cuts: ", seeds, " seeds per family, check ",
      check == CheckWhen::kEveryPose ? "every pose" : "at the end",
      "\n\n| mesh | family | mode | coverage min / mean | at the surface | below it min / mean | "
      "overcut faces | unpaired | new per cut | min dihedral (deg) | new tets under 5 deg | "
      "under 1 deg | poses lagging (below the surface) | invalid | us per pose |\n"
      "|---|---|---|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const Row& r : rows) {
    absl::StrAppendFormat(
        &out,
        "| %s | %s | %s | %.3f / %.3f | %.1f%% | %.3f / %.3f | %u | %u | %.2f | %s | %u of %u | "
        "%u | %s | %u | %.1f |\n",
        r.mesh, r.family, r.cutting, r.min_coverage, r.coverage / r.paths,
        100.0 * r.surface_samples / std::max<std::size_t>(r.samples, 1), r.min_below,
        r.below / r.paths, r.overcut, r.unpaired,
        r.cut_tets ? static_cast<double>(r.new_tets) / r.cut_tets : 0.0,
        r.new_tets > 0 ? absl::StrFormat("%.2f", r.min_dihedral) : std::string("-"), r.slivers,
        r.made, r.under_one,
        check == CheckWhen::kEveryPose
            ? absl::StrFormat("%.1f%% (%.1f%%)",
                              100.0 * r.lagging / std::max<std::size_t>(r.poses, 1),
                              100.0 * r.lagging_below / std::max<std::size_t>(r.poses, 1))
            : std::string("-"),
        r.invalid, 1e6 * r.seconds / std::max<std::size_t>(r.poses, 1));
  }
  return out;
}

}  // namespace kerf::cli
