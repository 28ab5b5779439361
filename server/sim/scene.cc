#include "sim/scene.h"

#include <cmath>
#include <filesystem>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "embedded_text.h"
#include "google/protobuf/io/tokenizer.h"
#include "google/protobuf/text_format.h"
#include "mesh/box_lattice.h"
#include "mesh/io/mesh_file.h"
#include "mesh/mesh_quality.h"

namespace kerf::sim {
namespace {

Eigen::Vector3d ToEigen(const kerf::v1::Vector3& v) { return {v.x(), v.y(), v.z()}; }

class ErrorCollector : public google::protobuf::io::ErrorCollector {
 public:
  void AddError(int line, google::protobuf::io::ColumnNumber column,
                const std::string& message) override {
    if (first_.empty()) first_ = absl::StrCat(line + 1, ":", column + 1, ": ", message);
  }
  const std::string& first() const { return first_; }

 private:
  std::string first_;
};

absl::StatusOr<std::vector<mesh::VertexId>> Select(const mesh::TetMesh& mesh,
                                                   const kerf::v1::VertexSelection& selection,
                                                   const std::string& field) {
  // Positions within a billionth of the mesh's size of a boundary count as on it.
  const double tolerance = 1e-9 * mesh::MeasureBounds(mesh).diagonal();
  std::vector<mesh::VertexId> selected;
  switch (selection.selection_case()) {
    case kerf::v1::VertexSelection::kBox: {
      const Eigen::Vector3d lo = ToEigen(selection.box().min()).array() - tolerance;
      const Eigen::Vector3d hi = ToEigen(selection.box().max()).array() + tolerance;
      for (const mesh::VertexId v : mesh.vertices()) {
        const Eigen::Vector3d& p = mesh.rest_position(v);
        if ((p.array() >= lo.array()).all() && (p.array() <= hi.array()).all()) {
          selected.push_back(v);
        }
      }
      break;
    }
    case kerf::v1::VertexSelection::kHalfSpace: {
      const Eigen::Vector3d point = ToEigen(selection.half_space().point());
      Eigen::Vector3d normal = ToEigen(selection.half_space().normal());
      if (!(normal.norm() > 0) || !normal.allFinite() || !point.allFinite()) {
        return absl::InvalidArgumentError(
            absl::StrCat(field, ".half_space: normal must be non-zero and finite"));
      }
      normal.normalize();
      for (const mesh::VertexId v : mesh.vertices()) {
        if ((mesh.rest_position(v) - point).dot(normal) >= -tolerance) selected.push_back(v);
      }
      break;
    }
    case kerf::v1::VertexSelection::kIds:
      for (const std::uint32_t id : selection.ids().ids()) {
        if (!mesh.IsAlive(mesh::VertexId{id})) {
          return absl::InvalidArgumentError(absl::StrCat(field, ".ids: no vertex ", id));
        }
        selected.push_back(mesh::VertexId{id});
      }
      break;
    case kerf::v1::VertexSelection::SELECTION_NOT_SET:
      return absl::InvalidArgumentError(absl::StrCat(field, ": choose box, half_space or ids"));
  }
  if (selected.empty()) {
    return absl::InvalidArgumentError(absl::StrCat(field, " selects no vertex"));
  }
  return selected;
}

absl::StatusOr<mesh::TetMesh> BuildMesh(const kerf::v1::MeshSource& source,
                                        absl::string_view base_dir) {
  switch (source.source_case()) {
    case kerf::v1::MeshSource::kFile: {
      std::filesystem::path path(source.file());
      if (path.is_relative()) path = std::filesystem::path(std::string(base_dir)) / path;
      return mesh::ReadMeshFile(path.string());
    }
    case kerf::v1::MeshSource::kLattice: {
      const kerf::v1::BoxLattice& l = source.lattice();
      mesh::BoxLatticeSpec spec;
      spec.cells_x = l.cells_x();
      spec.cells_y = l.cells_y();
      spec.cells_z = l.cells_z();
      spec.size = ToEigen(l.size());
      absl::StatusOr<mesh::TetMesh> mesh = mesh::MakeBoxLattice(spec);
      if (!mesh.ok()) {
        return absl::InvalidArgumentError(absl::StrCat("mesh.lattice: ", mesh.status().message()));
      }
      return mesh;
    }
    case kerf::v1::MeshSource::SOURCE_NOT_SET:
      break;
  }
  return absl::InvalidArgumentError("mesh: choose file or lattice");
}

}  // namespace

fem::ElasticLaw ElasticLawOf(kerf::v1::Elasticity::Model model) {
  switch (model) {
    case kerf::v1::Elasticity::COROTATIONAL:
      return fem::ElasticLaw::kCorotational;
    case kerf::v1::Elasticity::AUTO:
      return fem::ElasticLaw::kAuto;
    default:
      return fem::ElasticLaw::kLinear;
  }
}

kerf::v1::Elasticity::Model ElasticityModelOf(fem::ElasticLaw law) {
  switch (law) {
    case fem::ElasticLaw::kCorotational:
      return kerf::v1::Elasticity::COROTATIONAL;
    case fem::ElasticLaw::kAuto:
      return kerf::v1::Elasticity::AUTO;
    case fem::ElasticLaw::kLinear:
      break;
  }
  return kerf::v1::Elasticity::LINEAR;
}

namespace {

absl::StatusOr<fem::SleepOptions> BuildSleepOptions(const kerf::v1::Sleeping& spec) {
  fem::SleepOptions sleep;
  if (spec.has_rest_speed()) sleep.rest_speed = spec.rest_speed();
  if (spec.has_wake_acceleration()) sleep.wake_acceleration = spec.wake_acceleration();
  if (spec.has_quiet_time()) sleep.quiet_time = spec.quiet_time();
  if (!(std::isfinite(sleep.rest_speed) && sleep.rest_speed >= 0)) {
    return absl::InvalidArgumentError(absl::StrCat(
        "integration.sleeping.rest_speed must be a speed >= 0 (m/s), got ", sleep.rest_speed));
  }
  if (!(std::isfinite(sleep.wake_acceleration) && sleep.wake_acceleration > 0)) {
    return absl::InvalidArgumentError(
        absl::StrCat("integration.sleeping.wake_acceleration must be positive (m/s^2), got ",
                     sleep.wake_acceleration));
  }
  if (!(std::isfinite(sleep.quiet_time) && sleep.quiet_time >= 0)) {
    return absl::InvalidArgumentError(absl::StrCat(
        "integration.sleeping.quiet_time must be a time >= 0 (s), got ", sleep.quiet_time));
  }
  return sleep;
}

absl::StatusOr<Scene> Build(const kerf::v1::Scene& spec, absl::string_view base_dir) {
  absl::StatusOr<mesh::TetMesh> mesh = BuildMesh(spec.mesh(), base_dir);
  if (!mesh.ok()) return mesh.status();
  Scene scene;
  scene.name = spec.name();
  scene.mesh = *std::move(mesh);
  scene.method = spec.integration().method();
  scene.time_step = spec.integration().time_step();
  scene.cut_mode = spec.cutting().mode();
  scene.needs = spec.needs();
  const kerf::v1::Material& m = spec.material();
  scene.material = {m.youngs_modulus(), m.poisson_ratio(), m.density(), m.mass_damping(),
                    m.stiffness_damping()};
  if (absl::Status s = fem::ValidateMaterial(scene.material); !s.ok()) {
    return absl::InvalidArgumentError(absl::StrCat("material.", s.message()));
  }
  if (!kerf::v1::Integration::Method_IsValid(scene.method)) {
    return absl::InvalidArgumentError(
        absl::StrCat("integration.method must be SYMPLECTIC_EULER, SYMPLECTIC_EULER_SUBSTEPPED, "
                     "IMPLICIT_EULER or STATIC, got ",
                     scene.method));
  }
  if (!kerf::v1::Cutting::Mode_IsValid(scene.cut_mode)) {
    return absl::InvalidArgumentError(
        absl::StrCat("cutting.mode must be DEFERRED or PROGRESSIVE, got ", scene.cut_mode));
  }
  if (spec.cutting().has_min_temporary_height()) {
    scene.min_temporary_height = spec.cutting().min_temporary_height();
    if (!(scene.min_temporary_height >= 0 && scene.min_temporary_height < 1)) {
      return absl::InvalidArgumentError(
          absl::StrCat("cutting.min_temporary_height must be a fraction in [0, 1), got ",
                       scene.min_temporary_height));
    }
  }
  if (spec.cutting().has_snap_fraction()) {
    scene.snap_fraction = spec.cutting().snap_fraction();
    if (!(scene.snap_fraction >= 0 && scene.snap_fraction < 0.5)) {
      return absl::InvalidArgumentError(
          absl::StrCat("cutting.snap_fraction must be in [0, 0.5), got ", scene.snap_fraction));
    }
  }
  if (!kerf::v1::Elasticity::Model_IsValid(spec.elasticity().model())) {
    return absl::InvalidArgumentError(absl::StrCat(
        "elasticity.model must be LINEAR, COROTATIONAL or AUTO, got ", spec.elasticity().model()));
  }
  scene.elastic.law = ElasticLawOf(spec.elasticity().model());
  if (spec.elasticity().has_auto_strain()) {
    scene.elastic.auto_strain = spec.elasticity().auto_strain();
    if (!(scene.elastic.auto_strain > 0 && scene.elastic.auto_strain < 1)) {
      return absl::InvalidArgumentError(absl::StrCat(
          "elasticity.auto_strain must be a strain in (0, 1), got ", scene.elastic.auto_strain));
    }
  }
  if (scene.cut_mode == kerf::v1::Cutting::MODE_UNSPECIFIED) {
    scene.cut_mode = kerf::v1::Cutting::PROGRESSIVE;
  }
  if (scene.method == kerf::v1::Integration::METHOD_UNSPECIFIED) {
    // Explicit integration blows up under a live progressive cut (kerf experiment live-cut).
    scene.method = scene.cut_mode == kerf::v1::Cutting::PROGRESSIVE
                       ? kerf::v1::Integration::IMPLICIT_EULER
                       : kerf::v1::Integration::SYMPLECTIC_EULER;
  }
  if (scene.method == kerf::v1::Integration::STATIC &&
      scene.elastic.law != fem::ElasticLaw::kLinear) {
    return absl::InvalidArgumentError(
        "elasticity.model must be LINEAR for a STATIC scene (the static solve is linear)");
  }
  if (spec.integration().has_sleeping()) {
    absl::StatusOr<fem::SleepOptions> sleep = BuildSleepOptions(spec.integration().sleeping());
    if (!sleep.ok()) return sleep.status();
    if (scene.method != kerf::v1::Integration::SYMPLECTIC_EULER &&
        scene.method != kerf::v1::Integration::IMPLICIT_EULER) {
      return absl::InvalidArgumentError(
          "integration.sleeping needs integration.method SYMPLECTIC_EULER or IMPLICIT_EULER");
    }
    if (scene.elastic.law != fem::ElasticLaw::kLinear) {
      return absl::InvalidArgumentError(
          "integration.sleeping needs elasticity.model LINEAR (a rotating law turns every tet "
          "each step)");
    }
    scene.sleep = *sleep;
  }
  if (!std::isfinite(scene.time_step) || scene.time_step < 0) {
    return absl::InvalidArgumentError(absl::StrCat(
        "integration.time_step must be positive (s), or 0 to choose, got ", scene.time_step));
  }
  for (int i = 0; i < spec.displacements_size(); ++i) {
    const std::string field = absl::StrCat("displacements[", i, "].vertices");
    absl::StatusOr<std::vector<mesh::VertexId>> vertices =
        Select(scene.mesh, spec.displacements(i).vertices(), field);
    if (!vertices.ok()) return vertices.status();
    const Eigen::Vector3d d = ToEigen(spec.displacements(i).displacement());
    if (!d.allFinite()) {
      return absl::InvalidArgumentError(
          absl::StrCat("displacements[", i, "].displacement must be finite"));
    }
    for (const mesh::VertexId v : *vertices) {
      for (int c = 0; c < 3; ++c) scene.conditions.prescribed.push_back({v, c, d[c]});
    }
  }
  for (int i = 0; i < spec.loads_size(); ++i) {
    absl::StatusOr<std::vector<mesh::VertexId>> vertices =
        Select(scene.mesh, spec.loads(i).vertices(), absl::StrCat("loads[", i, "].vertices"));
    if (!vertices.ok()) return vertices.status();
    const Eigen::Vector3d force = ToEigen(spec.loads(i).total_force());
    if (!force.allFinite()) {
      return absl::InvalidArgumentError(absl::StrCat("loads[", i, "].total_force must be finite"));
    }
    for (const mesh::VertexId v : *vertices) {
      scene.conditions.loads.push_back({v, force / static_cast<double>(vertices->size())});
    }
  }
  scene.conditions.gravity = ToEigen(spec.gravity());
  if (!scene.conditions.gravity.allFinite()) {
    return absl::InvalidArgumentError("gravity must be finite");
  }
  return scene;
}

}  // namespace

absl::StatusOr<kerf::v1::Scene> ParseSceneText(absl::string_view text, absl::string_view source) {
  kerf::v1::Scene scene;
  ErrorCollector errors;
  google::protobuf::TextFormat::Parser parser;
  parser.RecordErrorsTo(&errors);
  if (!parser.ParseFromString(std::string(text), &scene)) {
    return absl::InvalidArgumentError(absl::StrCat(source, ":", errors.first()));
  }
  return scene;
}

absl::StatusOr<Scene> BuildScene(const kerf::v1::Scene& spec, absl::string_view base_dir) {
  absl::StatusOr<Scene> scene = Build(spec, base_dir);
  if (!scene.ok()) {
    return absl::Status(scene.status().code(),
                        absl::StrCat("scene '", spec.name(), "': ", scene.status().message()));
  }
  return scene;
}

std::vector<std::string> EmbeddedSceneNames() {
  std::vector<std::string> names;
  for (const EmbeddedText& scene : EmbeddedScenes()) names.emplace_back(scene.name);
  return names;
}

absl::StatusOr<std::string> EmbeddedSceneText(absl::string_view name) {
  if (const auto text = FindEmbeddedText(EmbeddedScenes(), name)) return std::string(*text);
  return absl::NotFoundError(absl::StrCat("no embedded scene '", name, "' (there are: ",
                                          absl::StrJoin(EmbeddedSceneNames(), ", "), ")"));
}

absl::StatusOr<Scene> LoadScene(absl::string_view name_or_path) {
  std::string source(name_or_path);
  absl::StatusOr<std::string> text = EmbeddedSceneText(name_or_path);
  const bool embedded = text.ok();
  if (!embedded) {
    std::error_code error;
    if (!std::filesystem::exists(source, error)) return text.status();
    text = mesh::ReadTextFile(source);
    if (!text.ok()) return text.status();
  }
  absl::StatusOr<kerf::v1::Scene> spec = ParseSceneText(*text, source);
  if (!spec.ok()) return spec.status();
  // Mesh files named by a scene file are found beside it.
  const std::string folder = embedded ? "" : std::filesystem::path(source).parent_path().string();
  return BuildScene(*spec, folder.empty() ? absl::string_view(".") : absl::string_view(folder));
}

}  // namespace kerf::sim
