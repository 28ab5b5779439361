// What the user holding the blade feels: the tissue's elastic pull at the cut front, and the
// cutting resistance against the blade's motion.
#include "sim/tool_reaction.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <algorithm>
#include <vector>

#include "sim/scene.h"
#include "sim/simulation.h"
#include "support/held_bar_scene.h"

namespace kerf::sim {
namespace {

using kerf::testing::kHeldBarScene;

// A vertical blade through the bar's whole depth at x = 33.7 mm, y in the bar.
cut::BladePose VerticalBlade(double time, double y) {
  const Eigen::Vector3d tip(0.0337, y, -0.03);
  return {time, tip, tip + Eigen::Vector3d(0, 0, 0.06)};
}

class ToolReactionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    simulation_ = *Simulation::Create(*BuildScene(*ParseSceneText(kHeldBarScene, "held-bar"), "."));
    for (int step = 0; step < 100; ++step) simulation_->Step();  // sagging: u is not zero
    ASSERT_TRUE(simulation_->ApplyBladePose(VerticalBlade(0, 0.004)).ok());
  }

  // -K u by vertex index, from the assembled global stiffness (not the model's own product).
  std::vector<Eigen::Vector3d> AssembledElasticForces() const {
    const Eigen::SparseMatrix<double> k = simulation_->model().AssembleStiffness();
    const std::vector<Eigen::Vector3d>& u = simulation_->state().displacement;
    Eigen::VectorXd flat(3 * static_cast<Eigen::Index>(u.size()));
    for (std::size_t i = 0; i < u.size(); ++i) flat.segment<3>(3 * i) = u[i];
    const Eigen::VectorXd f = -(k * flat);
    std::vector<Eigen::Vector3d> forces(u.size());
    for (std::size_t i = 0; i < u.size(); ++i) forces[i] = f.segment<3>(3 * i);
    return forces;
  }

  std::unique_ptr<Simulation> simulation_;
};

TEST_F(ToolReactionTest, TheBladeHoldsTheElasticForceOfTheTetsItIsIn) {
  const cut::BladePose pose = VerticalBlade(0.001, 0.004);
  const std::vector<Eigen::Vector3d> forces = AssembledElasticForces();
  const ToolReaction reaction = MeasureToolReaction(*simulation_, forces, pose, std::nullopt);

  std::vector<mesh::VertexId> vertices;
  for (const mesh::TetVertices& t : simulation_->cutter()->TetsHoldingBlade(pose)) {
    vertices.insert(vertices.end(), t.begin(), t.end());
  }
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  ASSERT_FALSE(vertices.empty());
  Eigen::Vector3d force = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
  for (const mesh::VertexId v : vertices) {
    const Eigen::Vector3d held = -forces[mesh::Index(v)];
    force += held;
    torque += (simulation_->mesh().current_position(v) - pose.tip).cross(held);
  }
  ASSERT_GT(force.norm(), 1e-4) << "the sagging bar pulls on the blade";
  EXPECT_LE((reaction.force - force).norm(), 1e-9 * force.norm());
  EXPECT_LE((reaction.torque - torque).norm(), 1e-9 * torque.norm());
  // The bar is 2 cm deep (sagging a few mm); the length is sampled in 32nds of 6 cm.
  EXPECT_NEAR(reaction.length_inside, 0.02, 2 * 0.06 / 32);
}

TEST_F(ToolReactionTest, TheCuttingResistanceOpposesTheBladesMotion) {
  const cut::BladePose pose = VerticalBlade(0.001, 0.004);
  const cut::BladePose before = VerticalBlade(0, 0.003);
  const std::vector<Eigen::Vector3d> forces = AssembledElasticForces();
  const ToolReaction still = MeasureToolReaction(*simulation_, forces, pose, std::nullopt);
  const ToolReaction moving = MeasureToolReaction(*simulation_, forces, pose, before);
  ASSERT_GT(moving.length_inside, 0);
  const Eigen::Vector3d resistance = moving.force - still.force;
  EXPECT_NEAR(resistance.y(), -kCuttingResistance * moving.length_inside, 1e-12);
  EXPECT_NEAR(resistance.x(), 0, 1e-12);
  EXPECT_NEAR(resistance.z(), 0, 1e-12);
}

TEST_F(ToolReactionTest, ABladeOutsideTheTissueFeelsNothing) {
  const cut::BladePose outside = VerticalBlade(0.001, 0.05);
  const ToolReaction reaction =
      MeasureToolReaction(*simulation_, AssembledElasticForces(), outside, VerticalBlade(0, 0.04));
  EXPECT_EQ(reaction.force, Eigen::Vector3d::Zero());
  EXPECT_EQ(reaction.torque, Eigen::Vector3d::Zero());
  EXPECT_EQ(reaction.length_inside, 0);
}

}  // namespace
}  // namespace kerf::sim
