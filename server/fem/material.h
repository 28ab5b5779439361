// An isotropic linear elastic material with Rayleigh damping.
//
// Units: any consistent system; with SI, Pa, kg/m^3, metres and seconds. The scenes and
// tests use SI unless they say otherwise.
#pragma once

#include "absl/status/status.h"

namespace kerf::fem {

struct Material {
  double youngs_modulus = 5000;  // E, in Pa. Must be positive and finite.
  double poisson_ratio = 0.45;   // nu. Must be strictly between -1 and 0.5.
  double density = 1000;         // rho, in kg/m^3. Must be positive and finite.
  // Rayleigh damping C = alpha M + beta K: alpha in 1/s, beta in s. Both must be >= 0.
  double mass_damping = 0;
  double stiffness_damping = 0;
};

// OK, or INVALID_ARGUMENT naming the parameter and its value.
absl::Status ValidateMaterial(const Material& material);

struct LameParameters {
  double lambda;  // first Lame parameter, in Pa
  double mu;      // shear modulus, in Pa
};

// lambda = E nu / ((1 + nu)(1 - 2 nu)), mu = E / (2 (1 + nu)). E = 280, nu = 0.4 gives
// lambda = 400, mu = 100. Requires a valid material.
LameParameters CalcLameParameters(double youngs_modulus, double poisson_ratio);

// The dilatational (P) wave speed sqrt((lambda + 2 mu) / rho), in m/s: the speed that sets
// the explicit critical time step h / c.
double DilatationalWaveSpeed(const Material& material);

}  // namespace kerf::fem
