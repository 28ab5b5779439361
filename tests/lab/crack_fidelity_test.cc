#include "lab/crack_fidelity.h"

#include <gtest/gtest.h>

#include <cmath>

#include "absl/container/flat_hash_map.h"
#include "mesh/box_lattice.h"

namespace kerf::lab {
namespace {

using cut::BladePose;
using mesh::TetMesh;
using mesh::VertexId;

// A 4 x 2 x 2 lattice of unit cubes: the tissue.
TetMesh Tissue() { return *mesh::MakeBoxLattice({.cells_x = 4, .cells_y = 2, .cells_z = 2}); }

// The tissue parted along the plane x = `plane` (a lattice plane): the tets beyond it take
// copies of the vertices on it, so the plane's faces become the crack's two lips. Unless
// `whole` the copies stop at y = 1 (a crack through half the depth only).
TetMesh PartedAt(double plane, bool whole = true) {
  TetMesh m = Tissue();
  absl::flat_hash_map<VertexId, VertexId> copy;
  std::vector<mesh::TetId> tets(m.tets().begin(), m.tets().end());
  for (const mesh::TetId t : tets) {
    mesh::TetVertices v = m.tet(t);
    Eigen::Vector3d middle = Eigen::Vector3d::Zero();
    for (const VertexId u : v) middle += m.rest_position(u) / 4;
    if (middle.x() < plane || (!whole && middle.y() > 1)) continue;
    bool changed = false;
    for (VertexId& u : v) {
      const Eigen::Vector3d p = m.rest_position(u);
      if (p.x() != plane || (!whole && p.y() >= 1)) continue;
      if (!copy.contains(u)) copy[u] = m.AddVertex(p);
      u = copy[u];
      changed = true;
    }
    if (!changed) continue;
    EXPECT_TRUE(m.RemoveTet(t).ok());
    EXPECT_TRUE(m.AddTet(v).ok());
  }
  return m;
}

// A blade standing through the whole tissue along z, swept along y at x = `x` over `steps`.
std::vector<BladePose> SweepAt(double x, int steps) {
  std::vector<BladePose> poses;
  for (int i = 0; i <= steps; ++i) {
    const double y = -0.5 + 3.0 * i / steps;
    poses.push_back({.time = 0.01 * i, .tip = {x, y, -0.5}, .heel = {x, y, 2.5}});
  }
  return poses;
}

FidelityMeter MeterFor(const std::vector<BladePose>& poses) {
  FidelityMeter meter(Tissue());
  for (std::size_t i = 1; i < poses.size(); ++i) meter.AddStep(poses[i - 1], poses[i]);
  return meter;
}

TEST(FidelityMeter, SamplesEveryCrossedTetAtLeastTwentyTimes) {
  const FidelityMeter meter = MeterFor(SweepAt(2.3, 12));
  EXPECT_EQ(meter.steps(), 12u);
  EXPECT_GT(meter.crossed_tets(), 8u);
  EXPECT_GE(meter.fewest_samples_per_crossed_tet(), 20u);
  std::size_t outside = meter.StepSamples(0) + meter.StepSamples(11);
  EXPECT_GT(meter.samples(), outside);
  EXPECT_GT(meter.StepSamples(5), 0u);
}

TEST(FidelityMeter, AnUncutMeshCoversNothing) {
  const FidelityMeter meter = MeterFor(SweepAt(2, 12));
  const CrackFaces crack = meter.FindCrack(Tissue());
  EXPECT_EQ(crack.size(), 0u);
  const Fidelity f = meter.Measure(crack);
  EXPECT_EQ(f.covered, 0u);
  EXPECT_EQ(f.coverage, 0);
}

TEST(FidelityMeter, ACrackWhereTheBladeWentCoversItAll) {
  const FidelityMeter meter = MeterFor(SweepAt(2, 12));
  const CrackFaces crack = meter.FindCrack(PartedAt(2));
  EXPECT_EQ(crack.size(), 2u * 2 * 2 * 2);  // 4 squares, 2 triangles each, two lips
  const Fidelity f = meter.Measure(crack);
  EXPECT_EQ(f.coverage, 1);
  EXPECT_EQ(f.unpaired_faces, 0u);
  EXPECT_EQ(f.overcut_faces, 0u);
  EXPECT_LT(f.max_overcut, 1e-12);
  for (std::size_t k = 0; k < meter.steps(); ++k) EXPECT_EQ(meter.StepCoverage(crack, k), 1);
}

TEST(FidelityMeter, ACrackBesideTheBladeIsOvercutAndCoversNothing) {
  const FidelityMeter meter = MeterFor(SweepAt(2.5, 12));  // half a cube from the crack
  const CrackFaces crack = meter.FindCrack(PartedAt(2));
  const Fidelity f = meter.Measure(crack);
  EXPECT_EQ(f.coverage, 0);
  EXPECT_EQ(f.overcut_faces, 16u);
  // Half a cube in local edge lengths (each tet's mean edge is (3 + 2 sqrt 2 + sqrt 3) / 6).
  const double half_cube = 0.5 * 6 / (3 + 2 * std::sqrt(2.0) + std::sqrt(3.0));
  EXPECT_NEAR(f.max_overcut, half_cube, 1e-12);
  const std::vector<FidelityMeter::FaceDistance> overcut = meter.Overcut(crack);
  ASSERT_EQ(overcut.size(), f.overcut_faces);
  for (const FidelityMeter::FaceDistance& face : overcut) {
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(face.triangle[k].x(), 2, 1e-12);
    for (const double d : face.distance) EXPECT_NEAR(d, half_cube, 1e-12);  // the crack is flat
  }
}

TEST(FidelityMeter, ACrackWithinAQuarterEdgeCovers) {
  // The mean edge of a lattice tet is (3 + 2 sqrt 2 + sqrt 3) / 6 = 1.26; 0.2 is within 0.25 of it.
  const FidelityMeter meter = MeterFor(SweepAt(2.2, 12));
  const Fidelity f = meter.Measure(meter.FindCrack(PartedAt(2)));
  EXPECT_EQ(f.coverage, 1);
  EXPECT_EQ(f.overcut_faces, 0u);
}

// The samples within a quarter edge (0.315) of the tissue's boundary are counted apart: across
// the 2 x 2 section that band is 1 - (2 - 0.63)^2 / 4 = 0.53 of the sweep.
TEST(FidelityMeter, SamplesNearTheSurfaceAreCountedApart) {
  const FidelityMeter meter = MeterFor(SweepAt(2, 12));
  const Fidelity uncut = meter.Measure(meter.FindCrack(Tissue()));
  EXPECT_NEAR(static_cast<double>(uncut.surface_samples) / static_cast<double>(uncut.samples), 0.53,
              0.08);
  EXPECT_EQ(uncut.coverage_below_surface, 0);
  const Fidelity cut = meter.Measure(meter.FindCrack(PartedAt(2)));
  EXPECT_EQ(cut.surface_samples, uncut.surface_samples);
  EXPECT_EQ(cut.coverage_below_surface, 1);
}

// A step's lag below the surface judges its samples deeper than a quarter edge only: a blade a
// fifth of an edge inside the tissue's face has none, and its uncut steps lag at the surface.
TEST(FidelityMeter, AStepsLagBelowTheSurfaceLeavesOutItsSamplesAtTheSurface) {
  const CrackFaces uncut = MeterFor(SweepAt(2, 12)).FindCrack(Tissue());
  const FidelityMeter grazing = MeterFor(SweepAt(0.2, 12));
  const FidelityMeter deep = MeterFor(SweepAt(2, 12));
  ASSERT_GT(grazing.StepSamples(5), 0u);
  EXPECT_EQ(grazing.StepCoverage(uncut, 5), 0);
  EXPECT_EQ(grazing.StepCoverageBelowSurface(uncut, 5), 1);
  EXPECT_EQ(deep.StepCoverageBelowSurface(uncut, 5), 0);
  EXPECT_EQ(deep.StepCoverageBelowSurface(deep.FindCrack(PartedAt(2)), 5), 1);
}

TEST(FidelityMeter, AHalfCrackCoversAboutHalf) {
  const FidelityMeter meter = MeterFor(SweepAt(2, 12));
  const Fidelity f = meter.Measure(meter.FindCrack(PartedAt(2, /*whole=*/false)));
  EXPECT_GT(f.coverage, 0.4);
  EXPECT_LT(f.coverage, 0.75);
  EXPECT_EQ(f.overcut_faces, 0u);
}

TEST(FidelityMeter, UnpairedLipsAreCounted) {
  // A lip face whose tet is removed leaves its twin unpaired (the removed tet's other faces
  // become crack faces too, each without a twin).
  TetMesh m = PartedAt(2);
  const FidelityMeter meter = MeterFor(SweepAt(2, 12));
  EXPECT_EQ(meter.Measure(meter.FindCrack(m)).unpaired_faces, 0u);
  for (const mesh::TetId t : m.tets()) {
    int on_plane = 0;
    for (const VertexId u : m.tet(t)) on_plane += m.rest_position(u).x() == 2 ? 1 : 0;
    if (on_plane == 3) {
      ASSERT_TRUE(m.RemoveTet(t).ok());
      break;
    }
  }
  const Fidelity f = meter.Measure(meter.FindCrack(m));
  EXPECT_GE(f.unpaired_faces, 1u);
  EXPECT_EQ(f.crack_faces, 16u - 1 + f.unpaired_faces - 1);  // the lip's twin, and the new ones
}

// The crack near a step is all a step's coverage needs: the same as with the whole crack, for
// whole and half cracks, on the plane swept and beside it.
TEST(FidelityMeter, TheCrackNearAStepCoversItAsTheWholeCrackDoes) {
  for (const double x : {2.0, 1.0, 2.2}) {
    const FidelityMeter meter = MeterFor(SweepAt(x, 12));
    for (const bool whole : {true, false}) {
      const TetMesh cut = PartedAt(2, whole);
      const CrackFaces crack = meter.FindCrack(cut);
      double sum = 0;
      for (std::size_t k = 0; k < meter.steps(); ++k) {
        const CrackFaces near = meter.FindCrackNearStep(cut, k);
        EXPECT_LE(near.size(), crack.size());
        EXPECT_EQ(meter.StepCoverage(near, k), meter.StepCoverage(crack, k)) << x << " " << k;
        EXPECT_EQ(meter.StepCoverageBelowSurface(near, k),
                  meter.StepCoverageBelowSurface(crack, k));
        if (meter.StepSamples(k) > 0) sum += meter.StepCoverage(near, k);
      }
      if (x == 2.0 && whole) {
        EXPECT_GE(sum, 6);  // the steps inside the tissue, all covered
      }
      if (x == 1.0) {
        EXPECT_EQ(sum, 0);  // a crack a whole edge away covers nothing
      }
    }
  }
}

}  // namespace
}  // namespace kerf::lab
