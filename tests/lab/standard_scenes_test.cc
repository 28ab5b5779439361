#include "lab/standard_scenes.h"

#include <gtest/gtest.h>

#include "mesh/mesh_quality.h"
#include "mesh/mesh_validation.h"
#include "support/status_message.h"

namespace kerf::lab {
namespace {

using kerf::testing::StatusMessage;

TEST(StandardScenes, ThePoorLatticeIsTheLatticeWithSliversInside) {
  absl::StatusOr<sim::Scene> lattice = sim::LoadScene("lattice-tension");
  absl::StatusOr<sim::Scene> poor = PoorQualityLatticeScene();
  ASSERT_TRUE(lattice.ok() && poor.ok()) << poor.status();
  EXPECT_EQ(poor->name, "lattice-poor");
  EXPECT_EQ(poor->mesh.tet_count(), 576u);
  EXPECT_TRUE(mesh::ValidateMesh(poor->mesh).ok()) << mesh::ValidateMesh(poor->mesh);
  const mesh::MeshQuality before = mesh::MeasureMeshQuality(lattice->mesh);
  const mesh::MeshQuality after = mesh::MeasureMeshQuality(poor->mesh);
  EXPECT_NEAR(after.total_volume, before.total_volume,
              1e-12 * before.total_volume);  // the surface did not move
  EXPECT_NEAR(before.min_dihedral_deg, 45, 1e-9);
  EXPECT_GE(after.min_dihedral_deg, 1.5);
  EXPECT_LT(after.min_dihedral_deg, 5);
  EXPECT_GE(after.min_dihedral_histogram[0], 10u);  // tets under 10 degrees
  EXPECT_LT(after.min_radius_ratio, 0.05 * before.min_radius_ratio);
  EXPECT_EQ(poor->conditions.prescribed.size(), lattice->conditions.prescribed.size());
}

TEST(StandardScenes, PathsAreInMetresAndUnknownNamesAreRefused) {
  absl::StatusOr<std::vector<cut::BladePose>> liver = StandardPath("liver-across");
  ASSERT_TRUE(liver.ok()) << liver.status();
  EXPECT_EQ(liver->size(), 75u);
  EXPECT_NEAR((liver->front().tip - liver->front().heel).norm(), 0.054, 0.001);  // 5.4 cm
  EXPECT_EQ(StatusMessage(StandardPath("nowhere")), "no blade path 'nowhere' is shipped with kerf");
  EXPECT_EQ(StatusMessage(StandardScene("nothing", "")),
            "no standard scene 'nothing'; there are: lattice-tension, lattice-tension-deferred, "
            "bar-cantilever, lattice-poor, liver");
  EXPECT_EQ(StatusMessage(StandardScene("liver", "")),
            "the liver scene needs the liver mesh's file");
  const std::vector<StandardCut> cuts = StandardCuts({"lattice-poor", "liver"});
  ASSERT_EQ(cuts.size(), 3u);
  EXPECT_EQ(cuts[1].path, "lattice-curved");
  EXPECT_EQ(cuts[2].path, "liver-across");
}

}  // namespace
}  // namespace kerf::lab
