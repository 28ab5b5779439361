// The elastic force law the integrators step: the paper's linear model, or the corotational
// linear model, which takes each tet's rotation out of its displacement before its linear
// stiffness acts, so that rotating a body costs no energy.
//
// Linear: f = K u, through the tensor-mass model's vertex and edge tensors.
// Corotational: f = sum_e R_e K_e (R_e^T x_e - X_e), x = X + u, with R_e the rotation of tet
// e's deformation gradient F_e (polar decomposition F = R S), and its stiffness (the matrix an
// implicit step solves with) sum_e R_e K_e R_e^T, the rotations held through a step (Mueller
// and Gross 2004, "Interactive Virtual Materials"). With every R_e = I both are the linear
// model's.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <span>
#include <vector>

#include "fem/tensor_mass_model.h"

namespace kerf::fem {

enum class ElasticLaw {
  kLinear,
  kCorotational,
  // Linear while the largest strain the linear model measures (see largest_strain()) stays
  // under `auto_strain`; corotational from the step it exceeds it until it falls under half.
  kAuto,
};

struct ElasticOptions {
  ElasticLaw law = ElasticLaw::kLinear;
  double auto_strain = 0.1;  // the paper's limit of linear elasticity
};

class ElasticForces {
 public:
  // The model must outlive this object and be synced with its mesh before each Update.
  explicit ElasticForces(const TensorMassModel& model, ElasticOptions options = {});

  // Takes the rotation of every live tet from displacement u (corotational, or auto over its
  // threshold) and measures the largest strain (auto). Call before the forces of a step and
  // after the model synced. O(tets) unless linear.
  void Update(std::span<const Eigen::Vector3d> u);

  // f = the elastic force the body resists displacement w with (so -f acts on its vertices),
  // under the rotations of the last Update: K w, or sum_e R_e K_e (R_e^T (X + w)_e - X_e).
  // Written for active vertices only, as TensorMassModel::MultiplyStiffness. Affine in w, so
  // w = u + beta v adds the Rayleigh damping force beta K_R v.
  void Force(std::span<const Eigen::Vector3d> w, std::span<Eigen::Vector3d> f) const;
  // q = K_R p (K p when not rotating), for active vertices.
  void Multiply(std::span<const Eigen::Vector3d> p, std::span<Eigen::Vector3d> q) const;
  // The 3x3 diagonal blocks of K_R (K when not rotating), for active vertices (by vertex
  // index). O(tets) when rotating.
  void DiagonalBlocks(std::span<Eigen::Matrix3d> blocks) const;
  // The elastic energy of displacement u: sum_e (R_e^T x_e - X_e)^T K_e (R_e^T x_e - X_e) / 2
  // with each R_e taken from u (not stored), or u^T K u / 2 when not rotating. O(tets).
  double Energy(std::span<const Eigen::Vector3d> u) const;

  // Whether the last Update took rotations (corotational, or auto over its threshold).
  bool rotating() const { return rotating_; }
  // The largest principal strain (absolute) of the linear strain sym(grad u) over the tets at
  // the last Update; measured for kAuto only (0 otherwise). A rigid rotation by theta reads
  // 1 - cos theta: the linear model's error.
  double largest_strain() const { return largest_strain_; }

 private:
  // f = sum_e R_e K_e (R_e^T w_e), plus R_e K_e (R_e^T X_e - X_e) if from_rest.
  void MultiplyRotated(std::span<const Eigen::Vector3d> w, bool from_rest,
                       std::span<Eigen::Vector3d> f) const;

  const TensorMassModel* model_;
  ElasticOptions options_;
  bool rotating_ = false;
  double largest_strain_ = 0;
  std::vector<Eigen::Matrix3d> rotations_;  // by tet index
  std::vector<Eigen::Quaterniond> warm_;    // the last rotation, where the next search starts
};

// The rotation R of the polar decomposition F = R S (S symmetric positive definite) for F
// with positive determinant; for inverted or flat F, the rotation nearest it in the sense of
// maximising tr(R^T F). Found by Newton's iteration on the skew part of F R^T from `guess`,
// falling back on the step of Mueller et al. 2016 ("A Robust Method to Extract the Rotational
// Part of Deformations") where Newton's is undefined; stops after a turn under 1e-6 rad: one or
// two iterations from the last step's rotation.
Eigen::Quaterniond ExtractRotation(const Eigen::Matrix3d& f, Eigen::Quaterniond guess,
                                   int max_iterations = 50);

}  // namespace kerf::fem
