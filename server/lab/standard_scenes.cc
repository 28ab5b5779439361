#include "lab/standard_scenes.h"

#include <algorithm>
#include <cstdint>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "embedded_text.h"
#include "geometry/tet_measures.h"
#include "mesh/mesh_quality.h"
#include "sim/blade_messages.h"

namespace kerf::lab {
namespace {

// Smallest dihedral angle (degrees) of the tets around v.
double SmallestDihedralAround(const mesh::TetMesh& m, mesh::VertexId v) {
  double smallest = 180;
  for (const mesh::TetId t : m.TetsAround(v)) {
    const mesh::TetVertices& c = m.tet(t);
    const geometry::TetMeasures measures = geometry::MeasureTet(
        m.rest_position(c[0]), m.rest_position(c[1]), m.rest_position(c[2]), m.rest_position(c[3]));
    smallest = std::min(smallest, measures.signed_volume > 0 ? measures.min_dihedral_deg : 0.0);
  }
  return smallest;
}

}  // namespace

absl::StatusOr<sim::Scene> PoorQualityLatticeScene() {
  absl::StatusOr<sim::Scene> scene = sim::LoadScene("lattice-tension");
  if (!scene.ok()) return scene.status();
  scene->name = "lattice-poor";
  mesh::TetMesh& m = scene->mesh;
  const mesh::Bounds box = mesh::MeasureBounds(m);
  const double edge = 0.01;                     // the lattice's cubes, m
  std::uint64_t state = 0x9E3779B97F4A7C15ull;  // a fixed sequence: the same mesh every run
  auto uniform = [&state] {                     // in [-1, 1)
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return 2 * static_cast<double>(state >> 11) * 0x1.0p-53 - 1;
  };
  for (const mesh::VertexId v : m.vertices()) {
    const Eigen::Vector3d p = m.rest_position(v);
    const Eigen::Vector3d offset = 0.45 * edge * Eigen::Vector3d(uniform(), uniform(), uniform());
    const bool interior =
        ((p - box.low).array() > 1e-9).all() && ((box.high - p).array() > 1e-9).all();
    if (!interior) continue;
    if (absl::Status s = m.MoveVertex(v, p + offset, p + offset); !s.ok()) return s;
    if (SmallestDihedralAround(m, v) < 1.5) {
      if (absl::Status s = m.MoveVertex(v, p, p); !s.ok()) return s;
    }
  }
  return scene;
}

absl::StatusOr<sim::Scene> LiverScene(absl::string_view mesh_path) {
  absl::StatusOr<kerf::v1::Scene> spec = sim::ParseSceneText(
      absl::StrCat("name: \"liver\"\n"
                   "mesh { file: \"",
                   mesh_path,
                   "\" }\n"
                   "material { youngs_modulus: 5000 poisson_ratio: 0.45 density: 1000 "
                   "mass_damping: 20 }\n"
                   "displacements { vertices { half_space { point { x: -4 } normal { x: -1 } } } "
                   "}\n"
                   "gravity { z: -9.81 }\n"),
      "liver");
  if (!spec.ok()) return spec.status();
  absl::StatusOr<sim::Scene> scene = sim::BuildScene(*spec, ".");
  if (!scene.ok()) return scene.status();
  for (const mesh::VertexId v : scene->mesh.vertices()) {
    const Eigen::Vector3d x = kLiverUnit * scene->mesh.rest_position(v);
    if (absl::Status s = scene->mesh.MoveVertex(v, x, x); !s.ok()) return s;
  }
  return scene;
}

absl::StatusOr<sim::Scene> StandardScene(absl::string_view name,
                                         absl::string_view liver_mesh_path) {
  if (name == "lattice-poor") return PoorQualityLatticeScene();
  if (name == "liver") {
    if (liver_mesh_path.empty()) {
      return absl::InvalidArgumentError("the liver scene needs the liver mesh's file");
    }
    return LiverScene(liver_mesh_path);
  }
  const std::vector<std::string> embedded = sim::EmbeddedSceneNames();
  if (std::find(embedded.begin(), embedded.end(), name) == embedded.end()) {
    return absl::NotFoundError(absl::StrCat("no standard scene '", name,
                                            "'; there are: ", absl::StrJoin(embedded, ", "),
                                            ", lattice-poor, liver"));
  }
  return sim::LoadScene(name);
}

absl::StatusOr<std::vector<cut::BladePose>> StandardPath(absl::string_view name) {
  const std::optional<absl::string_view> text = FindEmbeddedText(EmbeddedBladePaths(), name);
  if (!text.has_value()) {
    return absl::NotFoundError(absl::StrCat("no blade path '", name, "' is shipped with kerf"));
  }
  const bool liver = name == "liver-across";
  // The liver path is in the liver's units: a 5.4 cm blade moving 1 mm a pose.
  absl::StatusOr<std::vector<cut::BladePose>> path = sim::ParseBladePathJson(
      *text, name,
      liver ? cut::BladeLimits{.max_length = 10, .max_step = 1, .max_speed = 20}
            : cut::BladeLimits{});
  if (!path.ok() || !liver) return path;
  for (cut::BladePose& pose : *path) {
    pose.tip *= kLiverUnit;
    pose.heel *= kLiverUnit;
  }
  return path;
}

std::vector<StandardCut> StandardCuts(const std::vector<std::string>& scenes) {
  std::vector<StandardCut> cuts;
  for (const std::string& scene : scenes) {
    if (scene == "liver") {
      cuts.push_back({scene, "liver-across"});
      continue;
    }
    for (const char* path : {"lattice-straight", "lattice-curved"}) cuts.push_back({scene, path});
  }
  return cuts;
}

}  // namespace kerf::lab
