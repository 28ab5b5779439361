#include "fem/static_solver.h"

#include <Eigen/SparseCholesky>

namespace kerf::fem {

absl::StatusOr<std::vector<Eigen::Vector3d>> SolveStaticEquilibrium(const TensorMassModel& model,
                                                                    const BoundaryConditions& bc) {
  if (absl::Status s = ValidateBoundaryConditions(model.mesh(), bc); !s.ok()) return s;
  const std::size_t n = model.vertex_count();
  // Each component is free, prescribed, or absent (a vertex no tet uses).
  constexpr std::int64_t kAbsent = -1, kPrescribed = -2;
  std::vector<std::int64_t> free_index(3 * n, kAbsent);
  std::vector<double> prescribed_value(3 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    if (model.masses()[i] > 0) {
      for (int c = 0; c < 3; ++c) free_index[3 * i + c] = 0;
    }
  }
  for (const PrescribedDisplacement& p : bc.prescribed) {
    const std::size_t dof =
        3 * static_cast<std::size_t>(mesh::Index(p.vertex)) + static_cast<std::size_t>(p.component);
    free_index[dof] = kPrescribed;
    prescribed_value[dof] = p.value;
  }
  std::int64_t free_count = 0;
  for (std::int64_t& index : free_index) {
    if (index == 0) index = free_count++;
  }

  const std::vector<Eigen::Vector3d> external = ExternalForces(bc, model.masses());
  Eigen::VectorXd rhs(free_count);
  for (std::size_t dof = 0; dof < 3 * n; ++dof) {
    if (free_index[dof] >= 0) rhs[free_index[dof]] = external[dof / 3][static_cast<int>(dof % 3)];
  }
  const Eigen::SparseMatrix<double> k = model.AssembleStiffness();
  std::vector<Eigen::Triplet<double>> reduced;
  reduced.reserve(static_cast<std::size_t>(k.nonZeros()));
  for (Eigen::Index col = 0; col < k.outerSize(); ++col) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(k, col); it; ++it) {
      const std::int64_t r = free_index[static_cast<std::size_t>(it.row())];
      const std::int64_t c = free_index[static_cast<std::size_t>(col)];
      if (r < 0) continue;
      if (c >= 0) {
        reduced.emplace_back(r, c, it.value());
      } else if (c == kPrescribed) {
        rhs[r] -= it.value() * prescribed_value[static_cast<std::size_t>(col)];
      }
    }
  }
  Eigen::SparseMatrix<double> k_free(free_count, free_count);
  k_free.setFromTriplets(reduced.begin(), reduced.end());

  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(k_free);
  const Eigen::VectorXd pivots =
      solver.info() == Eigen::Success ? solver.vectorD() : Eigen::VectorXd();
  if (solver.info() != Eigen::Success ||
      (free_count > 0 && pivots.minCoeff() <= 1e-12 * pivots.cwiseAbs().maxCoeff())) {
    return absl::FailedPreconditionError(
        "the stiffness is singular: the body can move rigidly; hold it with prescribed "
        "displacements");
  }
  const Eigen::VectorXd u_free = solver.solve(rhs);

  std::vector<Eigen::Vector3d> u(n, Eigen::Vector3d::Zero());
  for (std::size_t dof = 0; dof < 3 * n; ++dof) {
    const auto c = static_cast<int>(dof % 3);
    if (free_index[dof] >= 0) u[dof / 3][c] = u_free[free_index[dof]];
    if (free_index[dof] == kPrescribed) u[dof / 3][c] = prescribed_value[dof];
  }
  return u;
}

}  // namespace kerf::fem
