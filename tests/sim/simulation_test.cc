#include "sim/simulation.h"

#include <gtest/gtest.h>

#include <limits>

#include "lab/accuracy_bar.h"
#include "sim/scene.h"
#include "support/status_message.h"

namespace kerf::sim {
namespace {

using kerf::testing::StatusMessage;

// A start near the answer: the given displacement at rest, held components at their values,
// and a wrong one refused with nothing changed.
TEST(Simulation, SetDisplacementStartsThereAtRestAndKeepsHeldValues) {
  absl::StatusOr<Scene> scene =
      lab::MakeBarScene(lab::BarLoad::kTension, 2, kerf::v1::Integration::IMPLICIT_EULER,
                        fem::ElasticLaw::kLinear, 0);
  ASSERT_TRUE(scene.ok()) << scene.status();
  absl::StatusOr<std::unique_ptr<Simulation>> sim = Simulation::Create(*std::move(scene));
  ASSERT_TRUE(sim.ok()) << sim.status();
  const std::size_t n = (*sim)->mesh().vertex_index_bound();
  EXPECT_EQ(StatusMessage((*sim)->SetDisplacement(std::vector<Eigen::Vector3d>(n - 1))),
            absl::StrCat("a displacement for ", n - 1, " vertices, the mesh has ", n, " slots"));
  std::vector<Eigen::Vector3d> bad(n, Eigen::Vector3d::Zero());
  bad[3].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(StatusMessage((*sim)->SetDisplacement(bad)),
            "the displacement of vertex 3 is not finite");

  (*sim)->Step();  // moving, then started again
  ASSERT_TRUE(
      (*sim)->SetDisplacement(std::vector<Eigen::Vector3d>(n, Eigen::Vector3d(0, 0.001, 0))).ok());
  for (std::uint32_t i = 0; i < n; ++i) {
    EXPECT_EQ((*sim)->state().velocity[i], Eigen::Vector3d::Zero());
    const Eigen::Vector3d& rest = (*sim)->mesh().rest_position(mesh::VertexId{i});
    const std::optional<Eigen::Vector3d> held = lab::HeldDisplacement(lab::BarLoad::kTension, rest);
    const Eigen::Vector3d expected = held.value_or(Eigen::Vector3d(0, 0.001, 0));
    EXPECT_EQ((*sim)->state().displacement[i], expected) << i;
    EXPECT_EQ((*sim)->mesh().current_position(mesh::VertexId{i}), rest + expected) << i;
  }
}

// A body let fall under gravity, held nowhere: its kinetic energy grows from nothing, while the
// total (gravity's potential counted) only falls, by the damping.
TEST(Simulation, TotalEnergyCountsGravitysWork) {
  const std::string text =
      "name: \"falling\"\n"
      "mesh { lattice { cells_x: 2 cells_y: 1 cells_z: 1 size { x: 0.02 y: 0.01 z: 0.01 } } }\n"
      "material { youngs_modulus: 5000 poisson_ratio: 0.45 density: 1000 mass_damping: 2 }\n"
      "gravity { z: -9.81 }\n"
      "integration { method: IMPLICIT_EULER }\n";
  absl::StatusOr<kerf::v1::Scene> spec = ParseSceneText(text, "falling");
  ASSERT_TRUE(spec.ok()) << spec.status();
  absl::StatusOr<Scene> scene = BuildScene(*spec, ".");
  ASSERT_TRUE(scene.ok()) << scene.status();
  absl::StatusOr<std::unique_ptr<Simulation>> sim = Simulation::Create(*std::move(scene));
  ASSERT_TRUE(sim.ok()) << sim.status();
  const double start = (*sim)->TotalEnergy();
  EXPECT_EQ((*sim)->MechanicalEnergy(), 0);
  double total = start;
  for (int i = 0; i < 100; ++i) {
    (*sim)->Step();
    EXPECT_LE((*sim)->TotalEnergy(), total + 1e-12) << "step " << i;
    total = (*sim)->TotalEnergy();
  }
  // 0.1 s of fall: about 1/2 m (g t)^2 of kinetic energy, 2e-6 kg here.
  EXPECT_GT((*sim)->MechanicalEnergy(), 1e-7);
  EXPECT_LT(total, start);
}

}  // namespace
}  // namespace kerf::sim
