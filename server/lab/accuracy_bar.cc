#include "lab/accuracy_bar.h"

#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <numbers>

#include "absl/strings/str_cat.h"
#include "base/check.h"
#include "mesh/box_lattice.h"
#include "sim/simulation.h"

namespace kerf::lab {
namespace {

constexpr double kPull = 0.5;                   // kTension: 10% of the length
constexpr double kTurn = std::numbers::pi / 2;  // kTwist, at x = kBarLength
const Eigen::Vector3d kAxisPoint(0, 0.5, 0.5);  // on the bar's axis

// The displacement that turns `p` by `angle` about the bar's axis.
Eigen::Vector3d Turned(const Eigen::Vector3d& p, double angle) {
  const Eigen::Vector3d r = p - kAxisPoint;
  return Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitX()) * r - r;
}

// The vertex at rest position p (exactly: lattice vertices are computed as i * size / cells).
std::optional<mesh::VertexId> VertexAt(const mesh::TetMesh& mesh, const Eigen::Vector3d& p) {
  for (const mesh::VertexId v : mesh.vertices()) {
    if ((mesh.rest_position(v) - p).norm() < 1e-9) return v;
  }
  return std::nullopt;
}

}  // namespace

std::string BarLoadName(BarLoad load) {
  switch (load) {
    case BarLoad::kCantilever:
      return "cantilever";
    case BarLoad::kTension:
      return "tension";
    case BarLoad::kTwist:
      return "twist";
  }
  return "?";
}

std::optional<Eigen::Vector3d> HeldDisplacement(BarLoad load, const Eigen::Vector3d& p) {
  if (std::abs(p.x()) < 1e-9) return Eigen::Vector3d::Zero();
  if (std::abs(p.x() - kBarLength) > 1e-9) return std::nullopt;
  switch (load) {
    case BarLoad::kCantilever:
      return std::nullopt;
    case BarLoad::kTension:
      return Eigen::Vector3d(kPull, 0, 0);
    case BarLoad::kTwist:
      return Turned(p, kTurn);
  }
  return std::nullopt;
}

std::optional<Eigen::Vector3d> ProbePoint(BarLoad load) {
  switch (load) {
    case BarLoad::kCantilever:
      return Eigen::Vector3d(kBarLength, 0.5, 0.5);
    case BarLoad::kTension:
      return std::nullopt;
    case BarLoad::kTwist:
      return Eigen::Vector3d(kBarLength / 2, 1, 1);
  }
  return std::nullopt;
}

absl::Status CheckBarResolution(int n) {
  if (n < 2 || n > 64 || n % 2 != 0) {
    return absl::InvalidArgumentError(
        absl::StrCat("the bar's resolution must be even and in [2, 64], got ", n));
  }
  return absl::OkStatus();
}

absl::StatusOr<sim::Scene> MakeBarScene(BarLoad load, int n, kerf::v1::Integration::Method method,
                                        fem::ElasticLaw law, double mass_damping) {
  if (absl::Status s = CheckBarResolution(n); !s.ok()) return s;
  absl::StatusOr<mesh::TetMesh> lattice =
      mesh::MakeBoxLattice({.cells_x = 5 * n, .cells_y = n, .cells_z = n, .size = {5, 1, 1}});
  if (!lattice.ok()) return lattice.status();
  sim::Scene scene;
  scene.name = absl::StrCat("bar-", BarLoadName(load), "-", n);
  scene.mesh = *std::move(lattice);
  scene.material = {
      .youngs_modulus = 5000, .poisson_ratio = 0.45, .density = 1, .mass_damping = mass_damping};
  for (const mesh::VertexId v : scene.mesh.vertices()) {
    const std::optional<Eigen::Vector3d> held = HeldDisplacement(load, scene.mesh.rest_position(v));
    if (!held.has_value()) continue;
    for (int c = 0; c < 3; ++c) scene.conditions.prescribed.push_back({v, c, (*held)[c]});
  }
  if (load == BarLoad::kCantilever) scene.conditions.gravity = {0, 0, -1};
  scene.method = method;
  scene.elastic.law = law;
  return scene;
}

std::vector<Eigen::Vector3d> StartingDisplacement(BarLoad load, const mesh::TetMesh& mesh) {
  std::vector<Eigen::Vector3d> u(mesh.vertex_index_bound(), Eigen::Vector3d::Zero());
  for (const mesh::VertexId v : mesh.vertices()) {
    const Eigen::Vector3d& p = mesh.rest_position(v);
    const double share = p.x() / kBarLength;
    if (load == BarLoad::kTension) u[mesh::Index(v)] = {share * kPull, 0, 0};
    if (load == BarLoad::kTwist) u[mesh::Index(v)] = Turned(p, share * kTurn);
  }
  return u;
}

absl::StatusOr<BarSettleResult> SettleBar(BarLoad load, int n, kerf::v1::Integration::Method method,
                                          fem::ElasticLaw law, double mass_damping,
                                          double simulated_seconds) {
  absl::StatusOr<sim::Scene> scene = MakeBarScene(load, n, method, law, mass_damping);
  if (!scene.ok()) return scene.status();
  absl::StatusOr<std::unique_ptr<sim::Simulation>> created =
      sim::Simulation::Create(*std::move(scene));
  if (!created.ok()) return created.status();
  sim::Simulation& sim = **created;
  if (absl::Status s = sim.SetDisplacement(StartingDisplacement(load, sim.mesh())); !s.ok()) {
    return s;
  }
  BarSettleResult result;
  result.time_step = sim.time_step();
  const auto wall_start = std::chrono::steady_clock::now();
  while (result.simulated_seconds < simulated_seconds) {
    sim.Step();
    ++result.steps;
    result.simulated_seconds += sim.time_step();
    // A blown-up explicit run is stopped as soon as it shows (checked every 100 steps).
    if (result.steps % 100 == 0 && !std::isfinite(sim.MechanicalEnergy())) {
      result.finite = false;
      break;
    }
  }
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  const std::vector<Eigen::Vector3d>& u = sim.state().displacement;
  if (const std::optional<Eigen::Vector3d> probe = ProbePoint(load); probe.has_value()) {
    const std::optional<mesh::VertexId> v = VertexAt(sim.mesh(), *probe);
    KERF_CHECK(v.has_value());  // n is even
    result.quantity = u[mesh::Index(*v)];
  } else {
    // The force holding the face: what the body resists its displacement with there.
    std::vector<Eigen::Vector3d> f(u.size(), Eigen::Vector3d::Zero());
    sim.elastic_forces()->Force(u, f);
    result.quantity.setZero();
    for (const mesh::VertexId v : sim.mesh().vertices()) {
      if (std::abs(sim.mesh().rest_position(v).x() - kBarLength) < 1e-9) {
        result.quantity += f[mesh::Index(v)];
      }
    }
  }
  result.finite = result.finite && result.quantity.allFinite();
  return result;
}

}  // namespace kerf::lab
