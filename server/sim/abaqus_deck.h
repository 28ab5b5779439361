// A static problem read from an Abaqus/CalculiX input deck, in the subset that
// ../shared/design/accuracy.md uses:
//   *HEADING, *NODE, *ELEMENT (TYPE=C3D4), *NSET (lists or GENERATE), *MATERIAL, *ELASTIC
//   (isotropic), *DENSITY, *SOLID SECTION (one, over every element), *STEP, *STATIC,
//   *BOUNDARY, *CLOAD, *DLOAD (GRAV), *NODE PRINT, *END STEP.
// Any other keyword or parameter value is refused by name, never ignored.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "fem/boundary_conditions.h"
#include "fem/material.h"
#include "mesh/tet_mesh.h"

namespace kerf::sim {

struct StaticDeck {
  mesh::TetMesh mesh;
  std::vector<std::int64_t> node_ids;  // the deck's id of each vertex, by vertex index
  fem::Material material;
  fem::BoundaryConditions conditions;
};

// `source` names the deck in messages ("deck.inp:12: ...").
absl::StatusOr<StaticDeck> ParseStaticDeck(absl::string_view text, absl::string_view source);

}  // namespace kerf::sim
