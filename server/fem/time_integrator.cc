#include "fem/time_integrator.h"

namespace kerf::fem {

DynamicState DynamicState::AtRest(const TensorMassModel& model, const BoundaryConditions& bc) {
  DynamicState state;
  state.displacement.assign(model.vertex_count(), Eigen::Vector3d::Zero());
  state.velocity.assign(model.vertex_count(), Eigen::Vector3d::Zero());
  for (const PrescribedDisplacement& p : bc.prescribed) {
    state.displacement[mesh::Index(p.vertex)][p.component] = p.value;
  }
  return state;
}

double MechanicalEnergy(const TensorMassModel& model, const DynamicState& state,
                        const ElasticForces* forces) {
  double kinetic = 0;
  for (std::size_t i = 0; i < model.vertex_count(); ++i) {
    kinetic += 0.5 * model.masses()[i] * state.velocity[i].squaredNorm();
  }
  return kinetic + (forces != nullptr ? forces->Energy(state.displacement)
                                      : model.ElasticEnergy(state.displacement));
}

}  // namespace kerf::fem
