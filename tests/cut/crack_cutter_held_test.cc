// CrackCutter::Held: the ids the cutter names. Freed for reuse after every pose but those, the
// mesh gives removed ids to new tets and points, and the cut comes out as it does when no id is
// ever reused: nothing the cutter still names was given away.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <vector>

#include "cut/crack_cutter.h"
#include "lab/hand_paths.h"
#include "mesh/box_lattice.h"
#include "mesh/mesh_quality.h"
#include "mesh/mesh_validation.h"

namespace kerf::cut {
namespace {

using mesh::TetMesh;

// The cut's tets by their corners' rest positions, sorted: what ids do not change.
std::vector<std::array<double, 12>> Shapes(const TetMesh& m) {
  std::vector<std::array<double, 12>> shapes;
  for (const mesh::TetId t : m.tets()) {
    std::array<std::array<double, 3>, 4> corners;
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d& x = m.rest_position(m.tet(t)[k]);
      corners[k] = {x.x(), x.y(), x.z()};
    }
    std::sort(corners.begin(), corners.end());
    std::array<double, 12> shape;
    for (int k = 0; k < 12; ++k) shape[k] = corners[k / 3][k % 3];
    shapes.push_back(shape);
  }
  std::sort(shapes.begin(), shapes.end());
  return shapes;
}

struct Cut {
  std::vector<std::array<double, 12>> shapes;
  std::size_t reused = 0;  // vertices and tets added on an id that was freed
};

Cut CutAlong(const TetMesh& tissue, const std::vector<BladePose>& poses, CutMode mode, bool reuse) {
  TetMesh m = tissue;
  const double diagonal = mesh::MeasureBounds(m).diagonal();
  CrackCutter cutter = *CrackCutter::Create(
      &m, mesh::MeanEdgeLength(m),
      {.max_length = 2 * diagonal, .max_step = 0.25 * diagonal, .max_speed = 1e9}, {.mode = mode});
  Cut cut;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const std::size_t free = m.ids_free();
    EXPECT_TRUE(cutter.ApplyPose(poses[i]).ok());
    EXPECT_TRUE(mesh::FindMeshDefects(m).empty()) << "pose " << i << ": " << mesh::ValidateMesh(m);
    if (::testing::Test::HasFailure()) return cut;
    cut.reused += free - m.ids_free();  // the pose's additions took them
    if (!reuse) continue;
    const CrackCutter::HeldIds held = cutter.Held();
    m.ReuseIdsRemovedBefore(
        cutter.synced(),
        [&](mesh::VertexId v) {
          return mesh::Index(v) < tissue.vertex_index_bound() || held.vertices.contains(v);
        },
        [&](mesh::TetId t) {
          return mesh::Index(t) < tissue.tet_index_bound() || held.tets.contains(t);
        });
  }
  cutter.Finish();
  EXPECT_TRUE(mesh::FindMeshDefects(m).empty()) << mesh::ValidateMesh(m);
  cut.shapes = Shapes(m);
  return cut;
}

TEST(CrackCutterHeld, IdsReusedBetweenPosesLeaveTheCutAsItWas) {
  const TetMesh lattice = *mesh::MakeBoxLattice(
      {.cells_x = 4, .cells_y = 6, .cells_z = 4, .size = Eigen::Vector3d(0.04, 0.06, 0.04)});
  std::size_t reused = 0;
  for (const CutMode mode : {CutMode::kProgressive, CutMode::kDeferred}) {
    for (const lab::PathFamily family : {lab::PathFamily::kHand, lab::PathFamily::kThroughVertices,
                                         lab::PathFamily::kInFacePlane}) {
      for (std::uint64_t seed = 1; seed <= 2; ++seed) {
        SCOPED_TRACE(::testing::Message() << lab::PathFamilyName(family) << " seed " << seed
                                          << (mode == CutMode::kDeferred ? " deferred" : ""));
        const std::vector<BladePose> poses = lab::MakeHandPath(lattice, family, seed);
        const Cut plain = CutAlong(lattice, poses, mode, false);
        const Cut reusing = CutAlong(lattice, poses, mode, true);
        if (HasFailure()) return;
        EXPECT_EQ(reusing.shapes, plain.shapes);
        reused += reusing.reused;
      }
    }
  }
  EXPECT_GT(reused, 1000u);  // ids were given again, many times
}

}  // namespace
}  // namespace kerf::cut
