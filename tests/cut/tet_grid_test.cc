#include "cut/tet_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "geometry/segment_box.h"
#include "mesh/box_lattice.h"
#include "mesh/mesh_quality.h"
#include "support/status_message.h"

namespace kerf::cut {
namespace {

using kerf::testing::StatusMessage;
using mesh::TetId;
using mesh::VertexId;

mesh::TetMesh Lattice() {
  return *mesh::MakeBoxLattice(
      {.cells_x = 8, .cells_y = 6, .cells_z = 5, .size = {0.08, 0.06, 0.05}});
}

// Every live tet whose current bounding box meets the query box must be a candidate.
void ExpectCandidatesCoverBruteForce(const mesh::TetMesh& m, const TetGrid& grid,
                                     std::mt19937& random) {
  std::uniform_real_distribution<double> coordinate(-0.01, 0.09), size(0, 0.01);
  for (int query = 0; query < 200; ++query) {
    const Eigen::Vector3d low(coordinate(random), coordinate(random), coordinate(random));
    const Eigen::Vector3d high = low + Eigen::Vector3d(size(random), size(random), size(random));
    const std::vector<TetId> candidates = grid.Candidates(low, high);
    const std::set<TetId> listed(candidates.begin(), candidates.end());
    ASSERT_EQ(listed.size(), candidates.size()) << "a tet listed twice";
    for (const TetId t : m.tets()) {
      Eigen::Vector3d lo = m.current_position(m.tet(t)[0]), hi = lo;
      for (const VertexId v : m.tet(t)) {
        lo = lo.cwiseMin(m.current_position(v));
        hi = hi.cwiseMax(m.current_position(v));
      }
      const bool meets = (lo.array() <= high.array()).all() && (hi.array() >= low.array()).all();
      if (meets) {
        ASSERT_TRUE(listed.count(t)) << "tet " << mesh::Index(t) << " missed";
      }
    }
    for (const TetId t : candidates) ASSERT_TRUE(m.IsAlive(t));
  }
}

TEST(TetGrid, FindsEveryTetABoxMeetsAsTheMeshDeformsAndChanges) {
  mesh::TetMesh m = Lattice();
  TetGrid grid = *TetGrid::Build(m, 0.01, 0.002);
  std::mt19937 random(4);
  ExpectCandidatesCoverBruteForce(m, grid, random);
  // Deform in small steps (some within the margin, some beyond), refreshing each time.
  std::normal_distribution<double> jitter(0, 0.0015);
  for (int step = 0; step < 20; ++step) {
    for (const VertexId v : m.vertices()) {
      m.set_current_position(
          v,
          m.current_position(v) + Eigen::Vector3d(jitter(random), jitter(random), jitter(random)));
    }
    ASSERT_TRUE(grid.Refresh().ok());
    ExpectCandidatesCoverBruteForce(m, grid, random);
  }
  // Topology changes: remove some tets, add a vertex and tets on it.
  for (std::uint32_t t = 0; t < 30; ++t) ASSERT_TRUE(m.RemoveTet(TetId{t * 7}).ok());
  const VertexId extra = m.AddVertex({0.03, 0.03, 0.03});
  const mesh::TetVertices base = m.tet(TetId{1});
  ASSERT_TRUE(m.AddTet({base[0], base[1], base[2], extra}).ok());
  ASSERT_TRUE(grid.Refresh().ok());
  EXPECT_EQ(grid.registered_tets(), m.tet_count());
  ExpectCandidatesCoverBruteForce(m, grid, random);
}

TEST(TetGrid, FindsTetsThatMovedFarOutsideTheBoundsItWasBuiltFor) {
  mesh::TetMesh m = Lattice();
  TetGrid grid = *TetGrid::Build(m, 0.01, 0.002);
  // Stretch the mesh to three times its size about a corner: most tets leave the grid's cells
  // and count in the cells at its edge.
  for (const VertexId v : m.vertices()) m.set_current_position(v, 3 * m.current_position(v));
  ASSERT_TRUE(grid.Refresh().ok());
  for (const TetId t : m.tets()) {
    Eigen::Vector3d lo = m.current_position(m.tet(t)[0]), hi = lo;
    for (const VertexId v : m.tet(t)) {
      lo = lo.cwiseMin(m.current_position(v));
      hi = hi.cwiseMax(m.current_position(v));
    }
    const Eigen::Vector3d centre = 0.5 * (lo + hi);
    const std::vector<TetId> near = grid.Candidates(centre, centre);
    ASSERT_NE(std::find(near.begin(), near.end(), t), near.end()) << mesh::Index(t);
  }
}

TEST(TetGrid, MakesCellsLargerRatherThanMoreThanOnePerTet) {
  mesh::TetMesh m = Lattice();  // 1440 tets over 8 x 6 x 5 cm
  // A stray vertex 1 m away (used by no tet) stretches the bounds.
  (void)m.AddVertex({1.0, 1.0, 1.0});
  const TetGrid grid = *TetGrid::Build(m, 0.001, 0.0002);
  EXPECT_GT(grid.cell_size(), 0.001);
  const double cells_per_axis = 1.0 / grid.cell_size() + 3;
  EXPECT_LE(cells_per_axis * cells_per_axis * cells_per_axis, 4096 * 1.25 * 1.25 * 1.25 * 1.1);
}

TEST(TetGrid, RefreshOnlyTouchesTetsAroundVerticesThatMovedBeyondTheMargin) {
  mesh::TetMesh m = Lattice();
  TetGrid grid = *TetGrid::Build(m, 0.01, 0.002);
  ASSERT_TRUE(grid.Refresh().ok());
  EXPECT_EQ(grid.last_refresh_count(), 0u);
  // Move one vertex within the margin: nothing; beyond it: only the tets around it.
  const VertexId v{100};
  m.set_current_position(v, m.current_position(v) + Eigen::Vector3d(0.001, 0, 0));
  ASSERT_TRUE(grid.Refresh().ok());
  EXPECT_EQ(grid.last_refresh_count(), 0u);
  m.set_current_position(v, m.current_position(v) + Eigen::Vector3d(0.002, 0, 0));
  ASSERT_TRUE(grid.Refresh().ok());
  EXPECT_EQ(grid.last_refresh_count(), m.TetsAround(v).size());
}

TEST(TetGrid, RefreshTopologyFollowsVerticesTheMeshMoved) {
  // A temporary point of a progressive cut moves with the blade (TetMesh::MoveVertex) between
  // physics steps: the tets around it are found where it went, without a full Refresh.
  mesh::TetMesh m = Lattice();
  TetGrid grid = *TetGrid::Build(m, 0.01, 0.002);
  const VertexId v{100};
  const Eigen::Vector3d there = m.current_position(v) + Eigen::Vector3d(0.006, 0.004, 0);
  ASSERT_TRUE(m.MoveVertex(v, there, there).ok());
  ASSERT_TRUE(grid.RefreshTopology().ok());
  EXPECT_EQ(grid.last_refresh_count(), m.TetsAround(v).size());
  const std::vector<TetId> near = grid.Candidates(there, there);
  for (const TetId t : m.TetsAround(v)) {
    EXPECT_NE(std::find(near.begin(), near.end(), t), near.end()) << mesh::Index(t);
  }
}

TEST(TetGrid, QueriesListFewTetsOfALargeMesh) {
  const mesh::TetMesh m = Lattice();  // 1440 tets
  const TetGrid grid = *TetGrid::Build(m, 0.01, 0.001);
  const std::vector<TetId> near = grid.Candidates({0.041, 0.031, 0.021}, {0.042, 0.032, 0.022});
  EXPECT_GT(near.size(), 0u);
  EXPECT_LT(near.size(), 200u);
}

// A query for a segment across the mesh's diagonal: every tet whose box meets the segment is
// listed, and the cells away from it are skipped (the box query lists most of the mesh).
TEST(TetGrid, ANarrowedQueryFollowsTheRegionNotItsBox) {
  const mesh::TetMesh m = Lattice();  // 1440 tets
  const TetGrid grid = *TetGrid::Build(m, 0.01, 0.001);
  const Eigen::Vector3d a(0.001, 0.001, 0.001), b(0.079, 0.059, 0.049);
  const auto meets = [&](const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
    return geometry::SegmentMeetsBox(a, b, lo, hi, 0);
  };
  const std::vector<TetId> narrowed = grid.Candidates(a, b, meets);
  const std::set<TetId> listed(narrowed.begin(), narrowed.end());
  ASSERT_EQ(listed.size(), narrowed.size()) << "a tet listed twice";
  int meeting = 0;
  for (const TetId t : m.tets()) {
    const mesh::Bounds box = mesh::MeasureTetBounds(m, t, /*current=*/true);
    if (!meets(box.low, box.high)) continue;
    ++meeting;
    EXPECT_TRUE(listed.count(t)) << "tet " << mesh::Index(t) << " missed";
  }
  EXPECT_GT(meeting, 20);
  EXPECT_LT(narrowed.size(), 10u * static_cast<std::size_t>(meeting));
  EXPECT_GT(grid.Candidates(a, b).size(), 1000u);
}

TEST(TetGrid, RefusesBadParameters) {
  const mesh::TetMesh m = Lattice();
  EXPECT_EQ(StatusMessage(TetGrid::Build(m, 0, 0.001)),
            "cell_size must be positive and finite (m), got 0");
  EXPECT_EQ(StatusMessage(TetGrid::Build(m, 0.01, -1)),
            "margin must be non-negative and finite (m), got -1");
}

}  // namespace
}  // namespace kerf::cut
