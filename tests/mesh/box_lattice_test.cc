#include "mesh/box_lattice.h"

#include <gtest/gtest.h>

#include "mesh/boundary_surface.h"
#include "mesh/mesh_validation.h"
#include "support/find_vertex.h"
#include "support/status_message.h"

namespace kerf::mesh {
namespace {

TEST(MakeBoxLattice, PaperLatticeHas576PositiveTetsFillingTheBox) {
  BoxLatticeSpec spec;
  spec.cells_x = 4;
  spec.cells_y = 6;
  spec.cells_z = 4;
  const TetMesh mesh = *MakeBoxLattice(spec);
  EXPECT_EQ(mesh.tet_count(), 576u);
  EXPECT_EQ(mesh.vertex_count(), 5u * 7 * 5);
  double volume = 0;
  for (const TetId t : mesh.tets()) {
    const double v = RestVolume(mesh, t);
    EXPECT_NEAR(v, 1.0 / 6, 1e-12);
    volume += v;
  }
  EXPECT_NEAR(volume, 96.0, 1e-12);
  EXPECT_TRUE(ValidateMesh(mesh).ok());
}

TEST(MakeBoxLattice, IsConformingEveryInteriorFaceInTwoTets) {
  BoxLatticeSpec spec;
  spec.cells_x = 3;
  spec.cells_y = 2;
  spec.cells_z = 2;
  const TetMesh mesh = *MakeBoxLattice(spec);
  std::size_t face_slots = 0;
  for (const TetId t : mesh.tets()) {
    const TetVertices& v = mesh.tet(t);
    for (const auto& f : kTetFaces) {
      const std::size_t n = mesh.TetsAroundFace(v[f[0]], v[f[1]], v[f[2]]).size();
      ASSERT_TRUE(n == 1 || n == 2);
      ++face_slots;
    }
  }
  // Each interior face is counted twice, each boundary face once.
  const std::size_t boundary = ExtractBoundarySurface(mesh).size();
  EXPECT_EQ((face_slots - boundary) % 2, 0u);
  EXPECT_EQ(boundary, 2u * 2 * (3 * 2 + 2 * 2 + 3 * 2));
}

TEST(MakeBoxLattice, PhysicalSizeScalesTheBox) {
  BoxLatticeSpec spec;
  spec.cells_x = 5;
  spec.cells_y = 1;
  spec.cells_z = 1;
  spec.size = {5e-2, 1e-2, 1e-2};  // metres
  const TetMesh mesh = *MakeBoxLattice(spec);
  kerf::testing::VertexAt(mesh, {5e-2, 0, 0});  // the far corner is exactly at the size
  double volume = 0;
  for (const TetId t : mesh.tets()) volume += RestVolume(mesh, t);
  EXPECT_NEAR(volume, 5e-6, 1e-18);
}

TEST(MakeBoxLattice, RefusesBadSpecsByName) {
  BoxLatticeSpec spec;
  spec.cells_y = 0;
  EXPECT_EQ(kerf::testing::StatusMessage(MakeBoxLattice(spec)),
            "cells_y must be in [1, 1024], got 0");
  spec.cells_y = 1;
  spec.size = {1, -2, 1};
  EXPECT_EQ(kerf::testing::StatusMessage(MakeBoxLattice(spec)),
            "size y must be positive and finite, got -2");
  spec.size = {1, 1, std::numeric_limits<double>::quiet_NaN()};
  EXPECT_EQ(MakeBoxLattice(spec).status().code(), absl::StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace kerf::mesh
