// Scripted blade paths through a small lattice that reach each of the eleven cases of the
// paper's Table 1 (progressive cutting), with stops, reversals and withdrawals inside tets.
// `kerf experiment progressive-cases` runs them; the cutter's tests use them one case at a time.
#pragma once

#include <string>
#include <vector>

#include "cut/blade.h"
#include "mesh/tet_mesh.h"

namespace kerf::lab {

struct ScriptedPath {
  std::string name;
  std::string what;                   // in words
  std::vector<cut::BladePose> poses;  // 1 mm apart or less, 10 ms apart
  std::vector<int> expected_cases;    // Table 1 cases it reaches (what the tests check)
};

// The lattice the paths are written for: 6 x 2 x 2 cm of 1 cm cubes (6 tets each), metres.
mesh::TetMesh ScriptedPathLattice();

std::vector<ScriptedPath> ProgressiveCasePaths();

}  // namespace kerf::lab
