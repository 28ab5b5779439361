// Whether a cut is where the blade went, judged from the cut mesh and the blade's path alone
// (none of the cutter's own bookkeeping): shared/design/cutting.md, property 8.
//
// The swept surface is the two triangles of each step between poses (T_i, H_i, H_i+1) and
// (T_i, H_i+1, T_i+1), taken at the tissue's rest positions (the path is given in the frame of
// the tissue at rest, as `kerf cut` cuts it) and clipped to each tet of the tissue. Each piece
// is sampled with seeded points (a piece lying in the tissue's boundary is not: the blade ran
// along the surface there and cut nothing) (at least 20 per piece, more for a large one: options).
// The crack of a cut mesh is its faces of one tet that do not lie on the tissue's boundary. With l
// the mean edge length of the tissue's tet that holds a point:
//   coverage: the share of samples with a crack face within `tolerance` l;
//   overcut: the crack faces with a point (a corner or the middle) farther than that from the
//            swept surface;
//   unpaired: the crack faces with no face of the other lip at the same rest positions (the two
//             lips triangulated differently, or a gap);
//   step coverage (point-wise lag): the share of one step's own samples covered now;
//   coverage below the surface: coverage of the samples farther than `tolerance` l from the
//            tissue's boundary. Nearer, the blade grazed the surface: a cut there would shave
//            a skin thinner than the tolerance, which snapping puts on the surface (a mesh of
//            edge l holds no thinner skin without slivers), and the meter could not tell it
//            from the surface itself at its tolerance. Both are reported.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "cut/blade.h"
#include "lab/box_index.h"
#include "mesh/tet_mesh.h"

namespace kerf::lab {

struct FidelityOptions {
  double tolerance = 0.25;  // of the local edge length
  // Samples of a crossed tet: this many per l^2 of the area swept in it, and at least
  // min_samples_per_tet.
  double samples_per_square_edge = 80;
  int min_samples_per_tet = 20;
  // Samples of one step's piece in a tet, for the step's lag: per l^2, and at least one.
  double step_samples_per_square_edge = 20;
  std::uint64_t seed = 1;
};

// The crack faces of a cut mesh, with distance queries. O(tets * star size) to build.
class CrackFaces {
 public:
  std::size_t size() const { return triangles_.size(); }
  // Crack faces with no face at the same three rest positions.
  std::size_t unpaired() const { return unpaired_; }
  // Whether a crack face lies within `radius` of `p` (rest positions).
  bool Within(const Eigen::Vector3d& p, double radius) const;
  const std::vector<std::array<Eigen::Vector3d, 3>>& triangles() const { return triangles_; }

 private:
  friend class FidelityMeter;
  explicit CrackFaces(double cell_size) : index_(cell_size) {}
  void Add(const std::array<Eigen::Vector3d, 3>& t);

  std::vector<std::array<Eigen::Vector3d, 3>> triangles_;
  BoxIndex index_;
  std::size_t unpaired_ = 0;
};

struct Fidelity {
  std::size_t samples = 0;
  std::size_t covered = 0;
  double coverage = 1;  // covered / samples (1 when nothing was swept inside)
  // Samples within `tolerance` l of the tissue's boundary, and the coverage of the others.
  std::size_t surface_samples = 0;
  double coverage_below_surface = 1;
  std::size_t crack_faces = 0;
  std::size_t unpaired_faces = 0;
  std::size_t overcut_faces = 0;
  // The largest distance of a crack face's point from the swept surface, in local edge
  // lengths, capped at twice the tolerance.
  double max_overcut = 0;
};

class FidelityMeter {
 public:
  // The tissue before the cut; it is copied. O(tets).
  explicit FidelityMeter(const mesh::TetMesh& tissue, const FidelityOptions& options = {});

  // Adds and samples the surface swept between two poses; returns the step's index (steps are
  // numbered from 0 in the order added). O(tets near the step).
  std::size_t AddStep(const cut::BladePose& from, const cut::BladePose& to);

  // The crack of `cut`, a mesh cut from the tissue (its vertices at their rest positions).
  // O(tets * star size).
  CrackFaces FindCrack(const mesh::TetMesh& cut) const;
  // The crack faces of `cut` that may cover step k's samples: those with a corner within the
  // tolerance at the samples plus the tissue's longest edge of them (no others can), unpaired
  // faces not counted. O(vertices + the crack there): what a check after every pose needs.
  CrackFaces FindCrackNearStep(const mesh::TetMesh& cut, std::size_t k) const;

  // Coverage over every step so far, overcut and unpaired faces. O(samples + crack faces).
  Fidelity Measure(const CrackFaces& crack) const;
  // The samples no crack face covers, and the local edge length at each (m).
  std::vector<std::pair<Eigen::Vector3d, double>> Uncovered(const CrackFaces& crack) const;
  // A crack face's distance from the swept surface: at its corners and its middle, in local edge
  // lengths (that of the tissue's tet holding the middle), each capped at twice the tolerance.
  struct FaceDistance {
    std::array<Eigen::Vector3d, 3> triangle;
    std::array<double, 4> distance;  // corners 0-2, then the middle
    double edge = 0;                 // the local edge length (m)
    double farthest() const { return *std::max_element(distance.begin(), distance.end()); }
  };
  // The crack faces farther than the tolerance from the swept surface (Measure's overcut).
  std::vector<FaceDistance> Overcut(const CrackFaces& crack) const;
  // The share of step k's samples that the crack covers (1 for a step that swept nothing
  // inside the tissue).
  double StepCoverage(const CrackFaces& crack, std::size_t k) const;
  // The same for step k's samples below the surface (farther than the tolerance from the
  // tissue's boundary; 1 if it has none).
  double StepCoverageBelowSurface(const CrackFaces& crack, std::size_t k) const;
  // Step k's samples the crack does not cover: where, the local edge length (m), the tissue's tet
  // holding it, and whether it lies within the tolerance of the tissue's boundary.
  struct UncoveredSample {
    Eigen::Vector3d point;
    double edge;
    std::uint32_t tet;
    bool at_surface;
  };
  std::vector<UncoveredSample> StepUncovered(const CrackFaces& crack, std::size_t k) const;
  std::size_t StepSamples(std::size_t k) const { return step_end_[k] - StepBegin(k); }

  std::size_t steps() const { return step_end_.size(); }
  // The samples Measure judges. O(pieces) the first time after a step was added.
  std::size_t samples() const { return Samples().size(); }
  // Tets of the tissue the swept surface crossed, and the fewest samples any of them holds.
  std::size_t crossed_tets() const;
  std::size_t fewest_samples_per_crossed_tet() const;

 private:
  struct Sample {
    Eigen::Vector3d point;
    double edge;  // the local edge length, m
    std::uint32_t tet;
    bool at_surface;  // within the tolerance of the tissue's boundary
  };
  // A step's triangle clipped to one tet of the tissue: a convex polygon.
  struct Piece {
    std::uint32_t tet;
    std::vector<Eigen::Vector3d> polygon;
    double area;
  };
  std::size_t StepBegin(std::size_t k) const { return k == 0 ? 0 : step_end_[k - 1]; }
  // The tissue's tet holding `p` (or the nearest to holding it) and its mean edge length.
  double LocalEdgeLength(const Eigen::Vector3d& p) const;
  FaceDistance DistanceFromSweep(const std::array<Eigen::Vector3d, 3>& t) const;
  bool IsOvercut(const FaceDistance& d) const {
    return d.farthest() > options_.tolerance * (1 + 1e-9);
  }
  // Clips the triangle to the tissue's tets, keeps the pieces and samples them for the step.
  void AddTriangle(const std::array<Eigen::Vector3d, 3>& triangle, std::uint64_t seed);
  const std::vector<Sample>& Samples() const;
  // Whether a piece in `tet` lies in one of its faces on the tissue's boundary.
  bool OnBoundary(const std::vector<Eigen::Vector3d>& piece, std::uint32_t tet) const;
  Sample MakeSample(const Eigen::Vector3d& p, std::uint32_t tet) const;
  bool Covered(const CrackFaces& crack, const Sample& s) const;
  // Whether a triangle (rest positions) lies in the tissue's boundary.
  bool InTissueBoundary(const std::array<Eigen::Vector3d, 3>& t) const;

  FidelityOptions options_;
  double mean_edge_;
  double longest_edge_ = 0;
  std::vector<std::array<Eigen::Vector3d, 4>> tets_;  // rest corners
  std::vector<double> tet_edge_;                      // mean edge length per tet
  std::vector<std::array<bool, 4>> boundary_face_;    // per tet: is face k (opposite k) outside
  BoxIndex tet_index_;
  std::vector<std::array<Eigen::Vector3d, 3>> boundary_;  // the tissue's boundary triangles
  BoxIndex boundary_index_;
  std::vector<std::array<Eigen::Vector3d, 3>> swept_;
  BoxIndex swept_index_;
  std::vector<Piece> pieces_;
  std::vector<Sample> step_samples_;
  std::vector<std::size_t> step_end_;    // step_samples_[StepBegin(k), step_end_[k]) are step k's
  mutable std::vector<Sample> samples_;  // by tet; made again once pieces were added
  mutable std::size_t sampled_pieces_ = 0;
};

}  // namespace kerf::lab
