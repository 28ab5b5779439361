#include "cut/cutter.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <random>

#include "cut/progressive_case_paths.h"
#include "geometry/tet_measures.h"
#include "mesh/boundary_surface.h"
#include "mesh/connected_components.h"
#include "mesh/face_tiling.h"
#include "mesh/io/mesh_file.h"
#include "mesh/mesh_quality.h"
#include "mesh/mesh_validation.h"
#include "support/shared_meshes.h"
#include "support/status_message.h"

namespace kerf::cut {
namespace {

using kerf::testing::StatusMessage;
using mesh::TetMesh;
using mesh::VertexId;

// A 6 x 2 x 2 cm bar of 6 x 2 x 2 cubes.
TetMesh Bar() { return ScriptedPathLattice(); }

double RestVolume(const TetMesh& m) {
  double volume = 0;
  for (const mesh::TetId t : m.tets()) volume += mesh::RestVolume(m, t);
  return volume;
}

double BoundaryArea(const TetMesh& m) {
  double area = 0;
  for (const auto& tri : mesh::ExtractBoundarySurface(m)) {
    const Eigen::Vector3d& a = m.rest_position(tri.vertices[0]);
    area +=
        0.5 *
        (m.rest_position(tri.vertices[1]) - a).cross(m.rest_position(tri.vertices[2]) - a).norm();
  }
  return area;
}

// Sweeps a blade from `start` to `end` (tip and heel move together) in steps of 2 mm, 10 ms
// apart, checking after every pose that the mesh is valid and keeps its volume.
void Sweep(Cutter& cutter, const TetMesh& m, const Eigen::Vector3d& tip_start,
           const Eigen::Vector3d& heel_start, const Eigen::Vector3d& travel, double* time) {
  const double volume = RestVolume(m);
  const int steps = std::max(1, static_cast<int>(std::ceil(travel.norm() / 0.002)));
  for (int k = 0; k <= steps; ++k) {
    const Eigen::Vector3d shift = travel * (static_cast<double>(k) / steps);
    ASSERT_TRUE(cutter.ApplyPose({*time, tip_start + shift, heel_start + shift}).ok());
    *time += 0.01;
    ASSERT_TRUE(mesh::FindMeshDefects(m).empty()) << mesh::ValidateMesh(m);
    ASSERT_NEAR(RestVolume(m), volume, 1e-12 * volume);
  }
}

TEST(Cutter, AThroughCutSeparatesTheBarOnTheBladePlane) {
  TetMesh m = Bar();
  const std::uint32_t original_vertices = m.vertex_index_bound();
  const double volume = RestVolume(m);
  Cutter cutter = *Cutter::Create(&m, 0.01, {}, CutMode::kDeferred);
  double time = 0;
  // The blade spans the bar's depth (z) and crosses it along y at x = 33.7 mm.
  Sweep(cutter, m, {0.0337, -0.005, -0.005}, {0.0337, -0.005, 0.025}, {0, 0.03, 0}, &time);
  cutter.Finish();
  EXPECT_EQ(cutter.waiting_tets(), 0u);
  EXPECT_TRUE(mesh::FindMeshDefects(m).empty()) << mesh::ValidateMesh(m);
  EXPECT_NEAR(RestVolume(m), volume, 1e-12 * volume);
  EXPECT_EQ(mesh::FindConnectedComponents(m).count, 2u);  // no vertex shared across the cut
  for (const VertexId v : m.vertices()) {
    if (mesh::Index(v) >= original_vertices) {
      EXPECT_NEAR(m.rest_position(v).x(), 0.0337, 1e-12);  // on the blade's plane
    }
  }
  const CutStatistics& s = cutter.statistics();
  EXPECT_GT(s.cut_tets, 0u);
  EXPECT_EQ(s.tets_by_case[static_cast<int>(CutCase::kOneCornerOff)] +
                s.tets_by_case[static_cast<int>(CutCase::kTwoAndTwo)],
            s.cut_tets);
  EXPECT_LE(static_cast<double>(s.new_tets) / static_cast<double>(s.cut_tets), 6.0);
  EXPECT_EQ(s.dropped_hits, 0u);
}

TEST(Cutter, ASecondCutAcrossTheFirstCutsItsNewTets) {
  TetMesh m = Bar();
  const double volume = RestVolume(m);
  Cutter cutter = *Cutter::Create(&m, 0.01, {}, CutMode::kDeferred);
  double time = 0;
  Sweep(cutter, m, {0.0337, -0.005, -0.005}, {0.0337, -0.005, 0.025}, {0, 0.03, 0}, &time);
  cutter.Finish();
  const std::size_t first = cutter.statistics().cut_tets;
  // Now along x at y = 11.3 mm, through the whole bar and the first cut.
  Sweep(cutter, m, {-0.005, 0.0113, -0.005}, {-0.005, 0.0113, 0.025}, {0.07, 0, 0}, &time);
  cutter.Finish();
  EXPECT_GT(cutter.statistics().cut_tets, first);
  EXPECT_TRUE(mesh::FindMeshDefects(m).empty()) << mesh::ValidateMesh(m);
  EXPECT_NEAR(RestVolume(m), volume, 1e-12 * volume);
  EXPECT_EQ(mesh::FindConnectedComponents(m).count, 4u);
}

TEST(Cutter, ABladeWhoseTipStaysInsideLeavesACrack) {
  TetMesh m = Bar();
  const double volume = RestVolume(m);
  const double area = BoundaryArea(m);
  Cutter cutter = *Cutter::Create(&m, 0.01, {}, CutMode::kDeferred);
  double time = 0;
  // The tip runs 9.3 mm deep (the bar is 20 mm deep); the heel stays above the bar.
  Sweep(cutter, m, {0.0337, -0.005, 0.0107}, {0.0337, -0.005, 0.03}, {0, 0.03, 0}, &time);
  cutter.Finish();
  EXPECT_TRUE(mesh::FindMeshDefects(m).empty()) << mesh::ValidateMesh(m);
  EXPECT_NEAR(RestVolume(m), volume, 1e-12 * volume);
  EXPECT_EQ(mesh::FindConnectedComponents(m).count, 1u);
  const CutStatistics& s = cutter.statistics();
  const std::size_t cracked = s.tets_by_case[static_cast<int>(CutCase::kCrackOneEdge)] +
                              s.tets_by_case[static_cast<int>(CutCase::kCrackTwoEdges)] +
                              s.tets_by_case[static_cast<int>(CutCase::kCrackThreeEdges)];
  EXPECT_GT(cracked, 0u);
  // The crack's two faces add about twice its area: 20 mm wide (y) and 9.3 mm deep.
  EXPECT_NEAR(BoundaryArea(m) - area, 2 * 0.02 * 0.0093, 0.1 * 2 * 0.02 * 0.0093);
}

// A blade put into the bar and moved 4 mm sideways: the crack's edges are its tip's path, on
// which the cutter finds face points, and the blade where it started and its heel's path, on
// which it finds none; a tet whose crack meets a face at one cut edge there ends it on that
// face (before, such tets could not be split and their hits were dropped).
TEST(Cutter, ACrackWhoseEdgeNoPathCrossesEndsOnTheFacesItMeets) {
  for (const CutMode mode : {CutMode::kDeferred, CutMode::kProgressive}) {
    SCOPED_TRACE(mode == CutMode::kDeferred ? "deferred" : "progressive");
    TetMesh m = Bar();
    const double volume = RestVolume(m);
    const double area = BoundaryArea(m);
    Cutter cutter = *Cutter::Create(&m, 0.01, {}, mode);
    double time = 0;
    Sweep(cutter, m, {0.0337, 0.0083, 0.0047}, {0.0337, 0.0083, 0.0153}, {0, 0.004, 0}, &time);
    cutter.Finish();
    EXPECT_TRUE(mesh::FindMeshDefects(m).empty()) << mesh::ValidateMesh(m);
    EXPECT_NEAR(RestVolume(m), volume, 1e-12 * volume);
    EXPECT_EQ(mesh::FindConnectedComponents(m).count, 1u);
    const CutStatistics& s = cutter.statistics();
    EXPECT_EQ(s.dropped_hits, 0u);
    EXPECT_GT(s.ended_cracks, 0u);
    EXPECT_GT(s.cut_tets, 0u);
    std::printf("%s: %zu tets cut, %zu crack ends added, crack faces %.1f mm2 (swept 42.4)\n",
                mode == CutMode::kDeferred ? "deferred" : "progressive", s.cut_tets, s.ended_cracks,
                1e6 * (BoundaryArea(m) - area) / 2);
    // The crack's two faces: about the swept 4 mm x 10.6 mm, its ends straight across tets.
    EXPECT_GT(BoundaryArea(m) - area, 2 * 0.5 * 0.004 * 0.0106);
  }
}

// Blades on the lattice's own planes and lines pass exactly through vertices, along edges and
// in the planes of faces; they also reverse and hesitate there. Every pose leaves a valid,
// conforming mesh of the same volume, and crossings too close to a vertex or edge are counted.
TEST(Cutter, DegenerateBladesLeaveAValidMesh) {
  struct Blade {
    const char* what;
    Eigen::Vector3d tip, heel, travel;
  };
  const Blade blades[] = {
      {"through a row of vertices, in the plane x = 30 mm",
       {0.03, -0.005, -0.005},
       {0.03, -0.005, 0.025},
       {0, 0.03, 0}},
      {"its tip along an edge (y = 10 mm, z = 10 mm)",
       {-0.005, 0.01, 0.01},
       {-0.005, 0.01, 0.03},
       {0.07, 0, 0}},
      {"in the plane of faces (z = 10 mm), edge first",
       {0.0237, -0.005, 0.01},
       {0.0237, 0.025, 0.01},
       {0.02, 0, 0}},
      {"through a vertex diagonally",
       {-0.005, -0.005, 0.0},
       {-0.005, -0.005, 0.03},
       {0.04, 0.04, 0}},
  };
  for (const Blade& blade : blades) {
    SCOPED_TRACE(blade.what);
    TetMesh m = Bar();
    const double volume = RestVolume(m);
    Cutter cutter = *Cutter::Create(&m, 0.01, {}, CutMode::kDeferred);
    double time = 0;
    Sweep(cutter, m, blade.tip, blade.heel, blade.travel, &time);
    // Hesitate (the same pose again), then go back half way and forward again.
    Sweep(cutter, m, blade.tip + blade.travel, blade.heel + blade.travel, {0, 0, 0}, &time);
    Sweep(cutter, m, blade.tip + blade.travel, blade.heel + blade.travel, -0.5 * blade.travel,
          &time);
    Sweep(cutter, m, blade.tip + 0.5 * blade.travel, blade.heel + 0.5 * blade.travel,
          0.5 * blade.travel, &time);
    cutter.Finish();
    EXPECT_TRUE(mesh::FindMeshDefects(m).empty()) << mesh::ValidateMesh(m);
    EXPECT_NEAR(RestVolume(m), volume, 1e-12 * volume);
    EXPECT_GT(cutter.statistics().degenerate_hits, 0u);
  }
}

// The bar cut in `mode` with `snap_fraction` by a blade from (x, -5 mm, z_tip) to
// (x, -5 mm, z_heel) swept 30 mm along y; valid and of the same volume after every pose and at
// the end.
struct SnappedBar {
  TetMesh mesh;
  CutStatistics statistics;
};
SnappedBar CutBarAlongY(double snap_fraction, double x, double z_tip, double z_heel,
                        CutMode mode = CutMode::kDeferred) {
  SnappedBar bar{Bar(), {}};
  const double volume = RestVolume(bar.mesh);
  Cutter cutter =
      *Cutter::Create(&bar.mesh, 0.01, {}, mode, kDefaultMinTemporaryHeight, snap_fraction);
  double time = 0;
  Sweep(cutter, bar.mesh, {x, -0.005, z_tip}, {x, -0.005, z_heel}, {0, 0.03, 0}, &time);
  cutter.Finish();
  EXPECT_TRUE(mesh::FindMeshDefects(bar.mesh).empty()) << mesh::ValidateMesh(bar.mesh);
  EXPECT_NEAR(RestVolume(bar.mesh), volume, 1e-12 * volume);
  bar.statistics = cutter.statistics();
  return bar;
}

// Snapping (either mode): a blade 1.2 mm (0.12 of an edge) past the plane of vertices x = 30 mm
// cuts through those vertices instead: each cut tet becomes one tet with copies on the far
// side, so no new shape (and no sliver) appears; without snapping the same blade makes slivers.
TEST(Snapping, ACutNearAPlaneOfVerticesGoesThroughThemAndMakesNoNewShape) {
  const auto smallest_dihedral = [](const TetMesh& m) {
    double smallest = 180;
    for (const mesh::TetId t : m.tets()) {
      const mesh::TetVertices& v = m.tet(t);
      smallest =
          std::min(smallest, geometry::MeasureTet(m.rest_position(v[0]), m.rest_position(v[1]),
                                                  m.rest_position(v[2]), m.rest_position(v[3]))
                                 .min_dihedral_deg);
    }
    return smallest;
  };
  const TetMesh uncut = Bar();
  for (const auto& [snap, mode] :
       {std::pair{0.0, CutMode::kDeferred}, std::pair{0.2, CutMode::kDeferred},
        std::pair{0.0, CutMode::kProgressive}, std::pair{0.2, CutMode::kProgressive}}) {
    SCOPED_TRACE(absl::StrCat(snap, mode == CutMode::kDeferred ? " deferred" : " progressive"));
    const std::uint32_t original_vertices = uncut.vertex_index_bound();
    const SnappedBar bar = CutBarAlongY(snap, 0.0312, -0.005, 0.025, mode);
    const TetMesh& m = bar.mesh;
    EXPECT_EQ(mesh::FindConnectedComponents(m).count, 2u);  // cut through either way
    const CutStatistics& s = bar.statistics;
    EXPECT_EQ(s.dropped_hits, 0u);
    if (snap == 0) {
      EXPECT_EQ(s.snapped_vertices, 0u);
      EXPECT_GT(s.new_tets, s.cut_tets);
      EXPECT_LT(smallest_dihedral(m), 0.5 * smallest_dihedral(uncut));
      continue;
    }
    // The 3 x 3 vertices of the plane x = 30 mm, each copied once: the crack runs along the
    // faces in that plane, no tet is split, and the tets beyond it take the copies.
    EXPECT_EQ(s.snapped_vertices, 9u);
    EXPECT_EQ(s.unsnapped_vertices, 0u);
    EXPECT_EQ(s.parted_vertices, 9u);
    EXPECT_EQ(s.cut_tets, 0u);
    EXPECT_EQ(m.tet_count(), uncut.tet_count());
    EXPECT_EQ(m.vertex_count(), uncut.vertex_count() + 9);
    for (const VertexId v : m.vertices()) {
      if (mesh::Index(v) >= original_vertices) {
        EXPECT_NEAR(m.rest_position(v).x(), 0.03, 1e-15);  // a copy of a vertex on the plane
      }
    }
    EXPECT_DOUBLE_EQ(smallest_dihedral(m), smallest_dihedral(uncut));
  }
}

// A blade exactly through a plane of vertices crosses their edges at their ends: unsnapped
// those crossings are skipped and nothing is cut; snapped, the bar comes apart there.
TEST(Snapping, ABladeExactlyThroughVerticesCutsThroughThem) {
  for (const double snap : {0.0, 0.2}) {
    SCOPED_TRACE(snap);
    const SnappedBar bar = CutBarAlongY(snap, 0.03, -0.005, 0.025);
    const TetMesh& m = bar.mesh;
    const CutStatistics& s = bar.statistics;
    std::printf("exactly through vertices, snap %g: %zu cut, %zu degenerate, %zu snapped\n", snap,
                s.cut_tets, s.degenerate_hits, s.snapped_vertices);
    if (snap == 0) {
      EXPECT_GT(s.degenerate_hits, 0u);
      EXPECT_EQ(mesh::FindConnectedComponents(m).count, 1u);
    } else {
      EXPECT_EQ(s.degenerate_hits, 0u);
      EXPECT_EQ(s.snapped_vertices, 9u);
      EXPECT_EQ(s.parted_vertices, 9u);
      EXPECT_EQ(mesh::FindConnectedComponents(m).count, 2u);
    }
  }
}

// A crack whose front (the tip's path, 9.3 mm deep) runs 1.2 mm past a plane of vertices ends
// at them, in either mode: the tip's crossings of faces beside a snapped vertex make no point
// (the front passes through it), and (progressive) the tets the blade has left are final while
// the front's tets still hold it. The vertices stay one part where the crack ends; nothing is
// dropped, the crack is as deep, and no tet is cut. (Before the face points gave way, deferred
// cutting unsnapped the vertices and cut the same 12 tets as without; progressive cut 6.)
TEST(Snapping, ACrackFrontNearVerticesEndsAtThem) {
  const double area = BoundaryArea(Bar());
  for (const CutMode mode : {CutMode::kDeferred, CutMode::kProgressive}) {
    SCOPED_TRACE(mode == CutMode::kDeferred ? "deferred" : "progressive");
    const SnappedBar plain = CutBarAlongY(0, 0.0312, 0.0107, 0.03, mode);
    const SnappedBar snapped = CutBarAlongY(0.2, 0.0312, 0.0107, 0.03, mode);
    for (const SnappedBar* bar : {&plain, &snapped}) {
      EXPECT_EQ(mesh::FindConnectedComponents(bar->mesh).count, 1u);
      EXPECT_EQ(bar->statistics.dropped_hits, 0u);
      EXPECT_NEAR(BoundaryArea(bar->mesh) - area, 2 * 0.02 * 0.0093, 0.15 * 2 * 0.02 * 0.0093);
    }
    const CutStatistics& s = snapped.statistics;
    EXPECT_GT(plain.statistics.cut_tets, 0u);
    EXPECT_EQ(s.snapped_vertices, 6u);
    EXPECT_EQ(s.unsnapped_vertices, 0u);
    EXPECT_GT(s.parted_vertices, 0u);
    EXPECT_LT(s.parted_vertices, s.snapped_vertices);  // where the crack ends, no copy
    EXPECT_EQ(s.cut_tets, 0u);
    EXPECT_EQ(snapped.mesh.tet_count(), Bar().tet_count());
    EXPECT_EQ(s.held_poses, 0u);
  }
}

// Either mode: a tip path 0.7 mm (0.07 of an edge) above a plane of edges (z = 10 mm), and far
// from their vertices, crosses faces near those edges: snapped, the crack's front is taken to
// cross the edges instead, so the crack ends on them (0.7 mm deeper) and the slivers that face
// points so near an edge make do not appear; nothing is dropped or given back. The tets below
// the edges are split at them too, so more tets are cut.
TEST(Snapping, ATipPathNearEdgesEndsTheCrackOnThem) {
  for (const CutMode mode : {CutMode::kDeferred, CutMode::kProgressive}) {
    const char* name = mode == CutMode::kDeferred ? "deferred" : "progressive";
    SCOPED_TRACE(name);
    const double area = BoundaryArea(Bar());
    const SnappedBar plain = CutBarAlongY(0, 0.035, 0.0107, 0.03, mode);
    const SnappedBar snapped = CutBarAlongY(0.2, 0.035, 0.0107, 0.03, mode);
    const auto slivers = [](const TetMesh& m) { return mesh::MeasureMeshQuality(m).slivers; };
    const CutStatistics& s = snapped.statistics;
    std::printf(
        "tip path near edges, %s: snapped %zu cut, %zu new, %zu slivers, %zu crossings on "
        "edges; unsnapped %zu cut, %zu new, %zu slivers\n",
        name, s.cut_tets, s.new_tets, slivers(snapped.mesh), s.edge_snapped_hits,
        plain.statistics.cut_tets, plain.statistics.new_tets, slivers(plain.mesh));
    for (const SnappedBar* bar : {&plain, &snapped}) {
      EXPECT_EQ(mesh::FindConnectedComponents(bar->mesh).count, 1u);
      EXPECT_EQ(bar->statistics.dropped_hits, 0u);
      EXPECT_EQ(bar->statistics.held_poses, 0u);
    }
    EXPECT_EQ(plain.statistics.edge_snapped_hits, 0u);
    EXPECT_NEAR(BoundaryArea(plain.mesh) - area, 2 * 0.02 * 0.0093, 1e-3 * 2 * 0.02 * 0.0093);
    EXPECT_NEAR(BoundaryArea(snapped.mesh) - area, 2 * 0.02 * 0.01, 1e-2 * 2 * 0.02 * 0.01);
    EXPECT_GT(s.edge_snapped_hits, 0u);
    EXPECT_EQ(s.unsnapped_edges, 0u);
    EXPECT_EQ(s.snapped_vertices, 0u);
    EXPECT_GT(slivers(plain.mesh), 0u);
    EXPECT_EQ(slivers(snapped.mesh), 0u);
    // The tets below the edges are split there too (each in two), not cut.
    EXPECT_GT(s.tets_by_case[static_cast<int>(CutCase::kSplitEdge)], 0u);
  }
}

TEST(Cutter, ABadPoseIsRefusedAndChangesNothing) {
  TetMesh m = Bar();
  Cutter cutter = *Cutter::Create(&m, 0.01, {}, CutMode::kDeferred);
  ASSERT_TRUE(cutter.ApplyPose({0, {0.0337, -0.005, -0.005}, {0.0337, -0.005, 0.025}}).ok());
  const mesh::ChangeMark mark = m.change_log().Mark();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(StatusMessage(cutter.ApplyPose({0.01, {nan, 0, 0}, {0, 0, 0.02}})),
            "the pose has a non-finite time, tip or heel");
  EXPECT_EQ(StatusMessage(cutter.ApplyPose({0.02, {0.0337, 0.03, -0.005}, {0.0337, 0.03, 0.025}})),
            "the blade jumps 0.035 m in one pose; at most 0.02 m is accepted");
  EXPECT_EQ(m.change_log().Mark(), mark);
  // The blade is where it was: a good pose still continues from there.
  EXPECT_TRUE(cutter.ApplyPose({0.03, {0.0337, -0.003, -0.005}, {0.0337, -0.003, 0.025}}).ok());
}

TEST(Cutter, CutsTheDeformedShapeAndPlacesRestPositionsByTheSameCoordinates) {
  TetMesh m = Bar();
  for (const VertexId v : m.vertices()) {
    Eigen::Vector3d p = m.rest_position(v);
    p.x() *= 1.1;  // stretched 10% along x
    m.set_current_position(v, p);
  }
  const std::uint32_t original_vertices = m.vertex_index_bound();
  Cutter cutter = *Cutter::Create(&m, 0.01, {}, CutMode::kDeferred);
  ASSERT_TRUE(cutter.MeshDeformed().ok());
  double time = 0;
  Sweep(cutter, m, {0.0337 * 1.1, -0.005, -0.005}, {0.0337 * 1.1, -0.005, 0.025}, {0, 0.03, 0},
        &time);
  cutter.Finish();
  EXPECT_EQ(mesh::FindConnectedComponents(m).count, 2u);
  for (const VertexId v : m.vertices()) {
    if (mesh::Index(v) < original_vertices) continue;
    EXPECT_NEAR(m.current_position(v).x(), 0.0337 * 1.1, 1e-12);
    EXPECT_NEAR(m.rest_position(v).x(), 0.0337, 1e-12);
  }
}

// Only the motion of blade and tissue relative to each other cuts: a still blade with the bar
// moving across it, in steps of 2 mm, cuts the same tets as the blade moving through the still
// bar (the hits are found where each point met the blade between poses).
TEST(Cutter, TissueMovingAcrossAStillBladeIsCutLikeABladeMovingThroughStillTissue) {
  for (const CutMode mode : {CutMode::kDeferred, CutMode::kProgressive}) {
    SCOPED_TRACE(mode == CutMode::kDeferred ? "deferred" : "progressive");
    TetMesh still = Bar();
    Cutter blade_moves = *Cutter::Create(&still, 0.01, {}, mode);
    double time = 0;
    Sweep(blade_moves, still, {0.0337, -0.005, -0.005}, {0.0337, -0.005, 0.025}, {0, 0.03, 0},
          &time);
    blade_moves.Finish();

    TetMesh moving = Bar();
    const std::uint32_t original_vertices = moving.vertex_index_bound();
    Cutter tissue_moves = *Cutter::Create(&moving, 0.01, {}, mode);
    for (int k = 0; k <= 15; ++k) {
      const Eigen::Vector3d offset(0, -0.002 * k, 0);
      for (const VertexId v : moving.vertices()) {
        moving.set_current_position(v, moving.rest_position(v) + offset);
      }
      ASSERT_TRUE(tissue_moves.MeshDeformed().ok());
      ASSERT_TRUE(
          tissue_moves.ApplyPose({0.01 * k, {0.0337, -0.005, -0.005}, {0.0337, -0.005, 0.025}})
              .ok());
      ASSERT_TRUE(mesh::FindMeshDefects(moving).empty()) << "pose " << k;
    }
    tissue_moves.Finish();
    EXPECT_EQ(tissue_moves.statistics().cut_tets, blade_moves.statistics().cut_tets);
    EXPECT_EQ(tissue_moves.statistics().new_tets, blade_moves.statistics().new_tets);
    EXPECT_EQ(tissue_moves.statistics().dropped_hits, 0u);
    EXPECT_EQ(moving.tet_count(), still.tet_count());
    EXPECT_EQ(mesh::FindConnectedComponents(moving).count, 2u);
    for (const VertexId v : moving.vertices()) {
      if (mesh::Index(v) >= original_vertices) {
        EXPECT_NEAR(moving.rest_position(v).x(), 0.0337, 1e-12);
      }
    }
  }
}

}  // namespace
}  // namespace kerf::cut

namespace kerf::cut {
namespace {

struct RandomCutTotals {
  std::size_t poses = 0, cut_tets = 0, dropped = 0, held = 0, frozen = 0, snapped = 0;
  std::size_t edge_snapped = 0, unsnapped_edges = 0, opened_edges = 0;
};

// How a random path is cut: the mode, and the snap fraction (0: none).
struct RandomCutting {
  CutMode mode;
  double snap_fraction;
  const char* name;
};

// Random blades wandering through `make_mesh()`'s mesh (of about `size` across, starting
// around `low`), cut in `mode`, with reversals and hesitations: the mesh must be valid,
// conforming and keep its volume after every pose.
RandomCutTotals RunRandomPaths(const std::function<TetMesh()>& make_mesh,
                               const Eigen::Vector3d& low, double size, int paths, int poses,
                               std::uint32_t seed, const RandomCutting& cutting) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(0, 1);
  BladeLimits limits;
  limits.max_length = size;
  limits.max_step = 0.1 * size;
  limits.max_speed = 1e9;
  RandomCutTotals totals;
  for (int path = 0; path < paths; ++path) {
    TetMesh m = make_mesh();
    const TetMesh uncut = m;
    const double volume = RestVolume(m);
    Cutter cutter = *Cutter::Create(&m, 0.15 * size, limits, cutting.mode,
                                    kDefaultMinTemporaryHeight, cutting.snap_fraction);
    const auto source = [&](mesh::TetId t) { return cutter.SourceTet(t); };
    // A face the crack runs along, through snapped vertices, is alike from both sides but for
    // the copies the far side took.
    const auto same_as = [&](VertexId v) { return cutter.PartedFrom(v); };
    // A blade a quarter to half the mesh's size, pointing roughly downward.
    Eigen::Vector3d tip = low + size * Eigen::Vector3d(unit(random), unit(random), unit(random));
    Eigen::Vector3d along(unit(random) - 0.5, unit(random) - 0.5, 1.5);
    Eigen::Vector3d heel = tip + size * (0.25 + 0.25 * unit(random)) * along.normalized();
    Eigen::Vector3d velocity(unit(random) - 0.5, unit(random) - 0.5, unit(random) - 0.5);
    double time = 0;
    for (int k = 0; k < poses; ++k, ++totals.poses) {
      EXPECT_TRUE(cutter.ApplyPose({time, tip, heel}).ok());
      const std::vector<mesh::MeshDefect> defects = mesh::FindMeshDefects(m);
      // Conforming, each original face tiled once: properties 2 and 6.
      const absl::Status tiled = mesh::CheckOriginalFacesTiled(uncut, m, source, same_as);
      if (!defects.empty() || std::abs(RestVolume(m) - volume) > 1e-12 * volume || !tiled.ok()) {
        ADD_FAILURE() << "path " << path << " pose " << k << ": " << mesh::ValidateMesh(m)
                      << ", volume " << RestVolume(m) << " of " << volume << ", " << tiled;
        return totals;
      }
      time += 0.01;
      const double what = unit(random);
      if (what < 0.1) continue;              // hesitate
      if (what < 0.2) velocity = -velocity;  // reverse
      if (what < 0.3) velocity += Eigen::Vector3d(unit(random) - 0.5, unit(random) - 0.5, 0);
      const Eigen::Vector3d step = 0.025 * size * velocity.normalized();
      tip += step;
      heel += step + 0.008 * size * Eigen::Vector3d(unit(random) - 0.5, unit(random) - 0.5, 0);
    }
    cutter.Finish();
    EXPECT_TRUE(mesh::FindMeshDefects(m).empty())
        << "path " << path << ": " << mesh::ValidateMesh(m);
    EXPECT_NEAR(RestVolume(m), volume, 1e-12 * volume);
    EXPECT_TRUE(mesh::CheckOriginalFacesTiled(uncut, m, source, same_as).ok())
        << "path " << path << ": " << mesh::CheckOriginalFacesTiled(uncut, m, source, same_as);
    EXPECT_EQ(cutter.waiting_tets(), 0u);
    totals.held += cutter.statistics().held_poses;
    totals.frozen += cutter.statistics().frozen_tets;
    totals.cut_tets += cutter.statistics().cut_tets;
    totals.dropped += cutter.statistics().dropped_hits;
    totals.snapped += cutter.statistics().snapped_vertices;
    totals.edge_snapped += cutter.statistics().edge_snapped_hits;
    totals.unsnapped_edges += cutter.statistics().unsnapped_edges;
    totals.opened_edges += cutter.statistics().opened_edges;
  }
  return totals;
}

// 200 paths of 50 poses each: 10^4 poses per mode.
class RandomPaths : public ::testing::TestWithParam<RandomCutting> {
 protected:
  // Snapping, to vertices and to edges, happens when it is asked for, and only then; some
  // closed cuts open (the blade crossing their edge later), and only deferred cutting gives
  // face points back.
  static void ExpectSnapping(const RandomCutTotals& totals) {
    if (GetParam().snap_fraction > 0) {
      EXPECT_GT(totals.snapped, 0u);
      EXPECT_GT(totals.edge_snapped, 0u);
      EXPECT_GT(totals.opened_edges, 0u);
    } else {
      EXPECT_EQ(totals.snapped, 0u);
      EXPECT_EQ(totals.edge_snapped, 0u);
    }
    if (GetParam().mode == CutMode::kProgressive) {
      EXPECT_EQ(totals.unsnapped_edges, 0u);
    }
  }
};

// Under the sanitizers (10 to 20 times slower) half the paths: 5,000 poses per mode.
#if defined(__SANITIZE_ADDRESS__)
constexpr int kLatticePaths = 100;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr int kLatticePaths = 100;
#else
constexpr int kLatticePaths = 200;
#endif
#else
constexpr int kLatticePaths = 200;
#endif

TEST_P(RandomPaths, ThroughTheLatticeKeepEveryPropertyAfterEveryPose) {
  const RandomCutTotals totals =
      RunRandomPaths(Bar, Eigen::Vector3d(0, -0.005, 0), 0.06, kLatticePaths, 50, 17, GetParam());
  std::printf(
      "random paths, lattice, %s: %zu poses, %zu tets cut, %zu hits dropped, %zu poses "
      "held, %zu tets frozen, %zu vertices snapped, %zu crossings snapped to edges (%zu "
      "unsnapped, %zu opened)\n",
      GetParam().name, totals.poses, totals.cut_tets, totals.dropped, totals.held, totals.frozen,
      totals.snapped, totals.edge_snapped, totals.unsnapped_edges, totals.opened_edges);
  EXPECT_EQ(totals.poses, kLatticePaths * 50u);
  EXPECT_GT(totals.cut_tets, 0u);
  ExpectSnapping(totals);
}

TEST_P(RandomPaths, ThroughTheLiverKeepEveryPropertyAfterEveryPose) {
  const std::string path = kerf::testing::SharedMeshPath("liver.msh");
  if (path.empty()) GTEST_SKIP() << "shared/meshes is not beside the repo";
  const TetMesh liver = *mesh::ReadMeshFile(path);
  const mesh::Bounds bounds = mesh::MeasureBounds(liver);
  const auto copy = [&] { return liver; };
  // 100 paths of 50 poses: 5,000 poses.
  const RandomCutTotals totals = RunRandomPaths(
      copy, bounds.low, (bounds.high - bounds.low).maxCoeff(), 100, 50, 23, GetParam());
  std::printf(
      "random paths, liver, %s: %zu poses, %zu tets cut, %zu hits dropped, %zu poses "
      "held, %zu tets frozen, %zu vertices snapped, %zu crossings snapped to edges (%zu "
      "unsnapped, %zu opened)\n",
      GetParam().name, totals.poses, totals.cut_tets, totals.dropped, totals.held, totals.frozen,
      totals.snapped, totals.edge_snapped, totals.unsnapped_edges, totals.opened_edges);
  EXPECT_EQ(totals.poses, 5000u);
  EXPECT_GT(totals.cut_tets, 0u);
  ExpectSnapping(totals);
}

INSTANTIATE_TEST_SUITE_P(
    BothModes, RandomPaths,
    ::testing::Values(RandomCutting{CutMode::kProgressive, 0, "Progressive"},
                      RandomCutting{CutMode::kProgressive, 0.2, "ProgressiveSnapped"},
                      RandomCutting{CutMode::kDeferred, 0, "Deferred"},
                      RandomCutting{CutMode::kDeferred, 0.2, "DeferredSnapped"}),
    [](const auto& cutting) { return cutting.param.name; });

}  // namespace
}  // namespace kerf::cut
