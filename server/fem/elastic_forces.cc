#include "fem/elastic_forces.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "base/check.h"

namespace kerf::fem {
namespace {

using mesh::Index;

constexpr double kRotationTolerance = 1e-6;  // rad

// grad w = sum_a w_a g_a^T over tet t's corners.
Eigen::Matrix3d Gradient(const mesh::TetVertices& v, const TetElement& e,
                         std::span<const Eigen::Vector3d> w) {
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  for (int a = 0; a < 4; ++a) h.noalias() += w[Index(v[a])] * e.gradients[a].transpose();
  return h;
}

Eigen::Matrix3d Stress(const Eigen::Matrix3d& strain, const LameParameters& lame) {
  return lame.lambda * strain.trace() * Eigen::Matrix3d::Identity() + 2 * lame.mu * strain;
}

}  // namespace

Eigen::Quaterniond ExtractRotation(const Eigen::Matrix3d& f, Eigen::Quaterniond guess,
                                   int max_iterations) {
  Eigen::Quaterniond q = guess.normalized();
  for (int i = 0; i < max_iterations; ++i) {
    const Eigen::Matrix3d r = q.toRotationMatrix();
    // R is F's rotation when B = F R^T is symmetric. Turning R by a small omega (world frame)
    // changes the axial vector of B's skew part by -(tr(B) I - B) omega / 2, and that axial
    // vector is half the torque sum_i r_i x f_i of F's columns on R's: Newton's step solves
    // (tr(B) I - sym(B)) omega = torque. Where that matrix is not positive definite (far
    // from the answer, or F inverted) the step divides by tr(B) alone (Mueller et al.).
    const Eigen::Vector3d torque =
        r.col(0).cross(f.col(0)) + r.col(1).cross(f.col(1)) + r.col(2).cross(f.col(2));
    const Eigen::Matrix3d b = f * r.transpose();
    const Eigen::Matrix3d newton =
        b.trace() * Eigen::Matrix3d::Identity() - 0.5 * (b + b.transpose());
    // Positive definite: its leading minors are positive (Sylvester); then solved by its
    // adjugate over its determinant.
    const double minor2 = newton(0, 0) * newton(1, 1) - newton(0, 1) * newton(0, 1);
    const double det = newton.determinant();
    const Eigen::Vector3d omega = newton(0, 0) > 0 && minor2 > 0 && det > 0
                                      ? Eigen::Vector3d(newton.inverse() * torque)
                                      : Eigen::Vector3d(torque / (std::abs(b.trace()) + 1e-9));
    const double angle = omega.norm();
    // Under 1e-3 rad the quaternion (1, omega / 2), whose error after normalising is
    // O(angle^3), saves the sine and cosine.
    const Eigen::Quaterniond turn =
        angle < 1e-3 ? Eigen::Quaterniond(1, omega.x() / 2, omega.y() / 2, omega.z() / 2)
                     : Eigen::Quaterniond(Eigen::AngleAxisd(angle, omega / angle));
    q = (turn * q).normalized();
    // Newton's steps converge quadratically: after a turn this small, the rest is rounding.
    if (angle < kRotationTolerance) break;
  }
  return q;
}

ElasticForces::ElasticForces(const TensorMassModel& model, ElasticOptions options)
    : model_(&model), options_(options), rotating_(options.law == ElasticLaw::kCorotational) {
  KERF_CHECK(options.auto_strain > 0);
}

void ElasticForces::Update(std::span<const Eigen::Vector3d> u) {
  if (options_.law == ElasticLaw::kLinear) return;
  const mesh::TetMesh& mesh = model_->mesh();
  if (options_.law == ElasticLaw::kAuto) {
    largest_strain_ = 0;
    for (const mesh::TetId t : mesh.tets()) {
      const Eigen::Matrix3d h = Gradient(mesh.tet(t), model_->element(t), u);
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> principal;
      principal.computeDirect(0.5 * (h + h.transpose()), Eigen::EigenvaluesOnly);
      largest_strain_ = std::max(largest_strain_, principal.eigenvalues().cwiseAbs().maxCoeff());
    }
    if (!rotating_ && largest_strain_ > options_.auto_strain) rotating_ = true;
    if (rotating_ && largest_strain_ < options_.auto_strain / 2) rotating_ = false;
  }
  if (!rotating_) return;
  const std::size_t tet_bound = mesh.tet_index_bound();
  rotations_.resize(tet_bound, Eigen::Matrix3d::Identity());
  warm_.resize(tet_bound, Eigen::Quaterniond::Identity());
  for (const mesh::TetId t : mesh.tets()) {
    const Eigen::Matrix3d f =
        Eigen::Matrix3d::Identity() + Gradient(mesh.tet(t), model_->element(t), u);
    warm_[Index(t)] = ExtractRotation(f, warm_[Index(t)]);
    rotations_[Index(t)] = warm_[Index(t)].toRotationMatrix();
  }
}

void ElasticForces::DiagonalBlocks(std::span<Eigen::Matrix3d> blocks) const {
  for (const std::uint32_t i : model_->active_vertices()) {
    blocks[i] =
        rotating_ ? Eigen::Matrix3d::Zero() : model_->vertex_tensor(static_cast<mesh::VertexId>(i));
  }
  if (!rotating_) return;
  const mesh::TetMesh& mesh = model_->mesh();
  const LameParameters& lame = model_->lame();
  for (const mesh::TetId t : mesh.tets()) {
    const mesh::TetVertices& v = mesh.tet(t);
    const TetElement& e = model_->element(t);
    for (int a = 0; a < 4; ++a) {
      // R K_aa R^T, K_aa = w ((lambda + mu) g g^T + mu |g|^2 I).
      const Eigen::Vector3d rg = rotations_[Index(t)] * e.gradients[a];
      blocks[Index(v[a])] +=
          e.weight * ((lame.lambda + lame.mu) * rg * rg.transpose() +
                      lame.mu * e.gradients[a].squaredNorm() * Eigen::Matrix3d::Identity());
    }
  }
}

void ElasticForces::Force(std::span<const Eigen::Vector3d> w, std::span<Eigen::Vector3d> f) const {
  if (!rotating_) {
    model_->MultiplyStiffness(w, f);
    return;
  }
  MultiplyRotated(w, /*from_rest=*/true, f);
}

void ElasticForces::Multiply(std::span<const Eigen::Vector3d> p,
                             std::span<Eigen::Vector3d> q) const {
  if (!rotating_) {
    model_->MultiplyStiffness(p, q);
    return;
  }
  MultiplyRotated(p, /*from_rest=*/false, q);
}

void ElasticForces::MultiplyRotated(std::span<const Eigen::Vector3d> w, bool from_rest,
                                    std::span<Eigen::Vector3d> f) const {
  for (const std::uint32_t i : model_->active_vertices()) f[i].setZero();
  const mesh::TetMesh& mesh = model_->mesh();
  for (const mesh::TetId t : mesh.tets()) {
    const mesh::TetVertices& v = mesh.tet(t);
    const TetElement& e = model_->element(t);
    const Eigen::Matrix3d& r = rotations_[Index(t)];
    // The unrotated gradient: R^T grad w, plus R^T - I for the rest shape's turn.
    Eigen::Matrix3d g = r.transpose() * Gradient(v, e, w);
    if (from_rest) g += r.transpose() - Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d p = e.weight * r * Stress(0.5 * (g + g.transpose()), model_->lame());
    for (int a = 0; a < 4; ++a) f[Index(v[a])] += p * e.gradients[a];
  }
}

double ElasticForces::Energy(std::span<const Eigen::Vector3d> u) const {
  if (!rotating_) return model_->ElasticEnergy(u);
  const mesh::TetMesh& mesh = model_->mesh();
  const LameParameters& lame = model_->lame();
  double energy = 0;
  for (const mesh::TetId t : mesh.tets()) {
    const TetElement& e = model_->element(t);
    const Eigen::Matrix3d f = Eigen::Matrix3d::Identity() + Gradient(mesh.tet(t), e, u);
    const Eigen::Quaterniond guess =
        Index(t) < warm_.size() ? warm_[Index(t)] : Eigen::Quaterniond::Identity();
    const Eigen::Matrix3d g =
        ExtractRotation(f, guess).toRotationMatrix().transpose() * f - Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d strain = 0.5 * (g + g.transpose());
    energy += e.weight * (lame.mu * strain.squaredNorm() +
                          0.5 * lame.lambda * strain.trace() * strain.trace());
  }
  return energy;
}

}  // namespace kerf::fem
