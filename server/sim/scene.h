// A simulation scene: a kerf.v1.Scene message (proto/kerf/v1/scene.proto) made concrete and
// checked: the mesh built, the material validated, the conditions turned into per-vertex
// prescriptions and loads.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "cut/crack_cutter.h"
#include "fem/boundary_conditions.h"
#include "fem/elastic_forces.h"
#include "fem/material.h"
#include "fem/sleeping_vertices.h"
#include "kerf/v1/scene.pb.h"
#include "mesh/tet_mesh.h"

namespace kerf::sim {

struct Scene {
  std::string name;
  mesh::TetMesh mesh;
  fem::Material material;
  fem::BoundaryConditions conditions;
  kerf::v1::Integration::Method method = kerf::v1::Integration::IMPLICIT_EULER;
  double time_step = 0;   // s; 0 chooses (see kerf.v1.Integration.time_step)
  kerf::v1::Needs needs;  // carried for the service; the simulation itself needs no output
  kerf::v1::Cutting::Mode cut_mode = kerf::v1::Cutting::PROGRESSIVE;
  double min_temporary_height = cut::kDefaultMinTemporaryHeight;  // see kerf.v1.Cutting
  double snap_fraction = cut::kDefaultCrackSnapFraction;          // see kerf.v1.Cutting
  fem::ElasticOptions elastic;                                    // see kerf.v1.Elasticity
  std::optional<fem::SleepOptions> sleep;  // set: vertices at rest sleep (kerf.v1.Sleeping)
  // What the cutter refuses as a blade (too long, a teleport, too fast); a session sets the
  // limits it checks poses against, so the two agree.
  cut::BladeLimits blade_limits;
};

// The law a scene's elasticity names (MODEL_UNSPECIFIED: linear), and back.
fem::ElasticLaw ElasticLawOf(kerf::v1::Elasticity::Model model);
kerf::v1::Elasticity::Model ElasticityModelOf(fem::ElasticLaw law);

// Parses protobuf text format. INVALID_ARGUMENT "source:line:column: ..." for a syntax error
// or an unknown field.
absl::StatusOr<kerf::v1::Scene> ParseSceneText(absl::string_view text, absl::string_view source);

// Builds and validates a scene. Mesh files are found relative to `base_dir`. INVALID_ARGUMENT
// naming the scene and the field for any invalid value or a selection with no vertex.
// Where conditions select the same vertex, the later one wins.
absl::StatusOr<Scene> BuildScene(const kerf::v1::Scene& spec, absl::string_view base_dir);

// A scene by the name of an embedded scene or by the path of a text-format file.
absl::StatusOr<Scene> LoadScene(absl::string_view name_or_path);

// The scenes compiled into kerf (from server/sim/scenes/).
std::vector<std::string> EmbeddedSceneNames();
// The text of an embedded scene; NOT_FOUND naming the scenes there are.
absl::StatusOr<std::string> EmbeddedSceneText(absl::string_view name);

}  // namespace kerf::sim
