// kerf cut MESH --path PATH.json --out OUT.vtu [--progressive|--deferred] [--check every|end]
// [--uncovered OUT.csv] [--overcut OUT.csv] [--min-temporary-height F] [--snap F]
// [--trace OUT.jsonl] [--dump-every-pose DIR] [--json]: applies a blade path to a mesh file or a
// scene (its initial state: rest, or the static solution of a STATIC scene) and writes the result.
// OUT.vtu has the current positions as points, the point arrays rest_position and source_vertex
// (the original vertex id, -1 for a vertex the cut made) and the cell array source_tet (the
// original tet each tet came from).
#pragma once

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "cut/blade.h"
#include "cut/crack_cutter.h"
#include "kerf/v1/cut_report.pb.h"
#include "mesh/tet_mesh.h"
#include "sim/scene.h"

namespace kerf::cli {

absl::StatusOr<std::string> RunCutCommand(const std::vector<absl::string_view>& args);

// When kerf cut checks the mesh (valid, conforming, volume kept) and measures each step's
// coverage. Unset on the command line: at the end, or every pose when a trace or dump asks for
// every pose.
enum class CheckWhen { kEnd, kEveryPose };

struct CutOptions {
  CheckWhen check = CheckWhen::kEnd;
  cut::CutMode mode = cut::CutMode::kProgressive;
  double min_temporary_height = cut::kDefaultMinTemporaryHeight;  // see cut::CrackCutterOptions
  double snap_fraction = cut::kDefaultCrackSnapFraction;          // see cut::CrackCutterOptions
  // Non-empty: the cut mesh as VTU (current positions as points; the arrays rest_position,
  // source_vertex and source_tet).
  std::string out_path;
  // Non-empty: the swept surface's samples no crack face covers, as CSV (x, y, z, local edge).
  std::string uncovered_path;
  // Non-empty: the crack faces farther than the tolerance from the swept surface, as CSV (the
  // corners, the distance of each and of the middle in local edges, the local edge).
  std::string overcut_path;
  // Non-empty (checks every pose): each pose's own samples no crack face covers after it, as CSV
  // (pose, x, y, z, local edge, the tissue's tet holding it, whether it is below the surface).
  std::string lagging_path;
  // Non-empty: one JSON line per pose (and one after the blade is withdrawn): the Table 1
  // cases of the tets the blade is in, tets alive, valid, and the step's coverage.
  std::string trace_path;
  // Non-empty: the mesh after every pose as DIR/pose-NNNN.vtu (arrays as OUT.vtu), and after
  // the blade is withdrawn as DIR/withdrawn.vtu. The folder is made if needed.
  std::string dump_directory;
};

// Cuts `mesh` along `poses` (then withdraws the blade), checks the mesh (after every pose, or
// once withdrawn: options.check), measures where the cut is against the blade's path
// (lab::FidelityMeter, for a mesh at rest) and reports what the cut did. The blade limits scale
// with the mesh: at most twice its size long, a quarter of it per pose.
absl::StatusOr<kerf::v1::CutReport> CutAlongPath(mesh::TetMesh* mesh,
                                                 const std::vector<cut::BladePose>& poses,
                                                 absl::string_view path_name,
                                                 const CutOptions& options = {});

// The blade limits for a mesh of this size (bounding-box diagonal, in its length unit).
cut::BladeLimits LimitsForMeshSize(double diagonal);

// The mesh of a scene (a standard one by name, see lab::StandardScene, or a .textproto file) in
// its initial state, or of a mesh file.
absl::StatusOr<mesh::TetMesh> LoadMeshOrScene(absl::string_view name);

// A copy of a scene's mesh in the scene's initial state (rest, or the static solution of a
// STATIC scene).
absl::StatusOr<mesh::TetMesh> MeshOfScene(sim::Scene scene);

}  // namespace kerf::cli
