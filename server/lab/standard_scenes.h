// The scenes and cuts stability is judged on (kerf experiment stability, and the test that no
// standard scene blows up with its defaults): the embedded scenes along the lattice paths, a
// deliberately poor-quality copy of the lattice along the same paths, and the liver of
// ../shared/meshes across, when its file is given.
#pragma once

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "cut/blade.h"
#include "sim/scene.h"

namespace kerf::lab {

// The liver mesh is in centimetres (6.5 across): scenes and paths on it are scaled by this.
inline constexpr double kLiverUnit = 0.01;  // m

// "lattice-poor": lattice-tension with each interior vertex moved by up to 0.45 of a cube's
// edge along each axis (a fixed pseudo-random sequence), each move kept only if every tet
// around it keeps a smallest dihedral angle of 1.5 degrees or more: 11 tets under 10 degrees
// (the smallest 3.5) and 43 under 20, against the lattice's 45 everywhere, radius ratios down
// to 0.011 (lattice: 0.72); the same surface, conditions and volume.
absl::StatusOr<sim::Scene> PoorQualityLatticeScene();

// "liver": the liver of `mesh_path` in centimetres, held at its left end (x under -4 cm) under
// gravity, the defaults otherwise (progressive cutting, so backward Euler; linear elasticity).
absl::StatusOr<sim::Scene> LiverScene(absl::string_view mesh_path);

// A standard scene by name: an embedded scene, "lattice-poor", or "liver" (needs
// `liver_mesh_path`). NOT_FOUND naming the scenes there are.
absl::StatusOr<sim::Scene> StandardScene(absl::string_view name, absl::string_view liver_mesh_path);

// A blade path shipped with kerf (server/lab/paths/), in metres: lattice-straight and
// lattice-curved as written, liver-across scaled by kLiverUnit. NOT_FOUND for another name.
absl::StatusOr<std::vector<cut::BladePose>> StandardPath(absl::string_view name);

struct StandardCut {
  std::string scene;
  std::string path;
};

// Every scene of `scenes` along the paths that cross it: lattice scenes (any but "liver")
// along lattice-straight and lattice-curved, "liver" along liver-across.
std::vector<StandardCut> StandardCuts(const std::vector<std::string>& scenes);

}  // namespace kerf::lab
