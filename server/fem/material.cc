#include "fem/material.h"

#include <cmath>

#include "absl/strings/str_cat.h"

namespace kerf::fem {
namespace {

absl::Status Invalid(const char* name, double value, const char* requirement) {
  return absl::InvalidArgumentError(absl::StrCat(name, " must be ", requirement, ", got ", value));
}

}  // namespace

absl::Status ValidateMaterial(const Material& m) {
  if (!std::isfinite(m.youngs_modulus) || m.youngs_modulus <= 0) {
    return Invalid("youngs_modulus", m.youngs_modulus, "positive and finite (Pa)");
  }
  if (!std::isfinite(m.poisson_ratio) || m.poisson_ratio <= -1 || m.poisson_ratio >= 0.5) {
    return Invalid("poisson_ratio", m.poisson_ratio, "strictly between -1 and 0.5");
  }
  if (!std::isfinite(m.density) || m.density <= 0) {
    return Invalid("density", m.density, "positive and finite (kg/m^3)");
  }
  if (!std::isfinite(m.mass_damping) || m.mass_damping < 0) {
    return Invalid("mass_damping", m.mass_damping, "non-negative and finite (1/s)");
  }
  if (!std::isfinite(m.stiffness_damping) || m.stiffness_damping < 0) {
    return Invalid("stiffness_damping", m.stiffness_damping, "non-negative and finite (s)");
  }
  return absl::OkStatus();
}

LameParameters CalcLameParameters(double youngs_modulus, double poisson_ratio) {
  const double e = youngs_modulus, nu = poisson_ratio;
  return {e * nu / ((1 + nu) * (1 - 2 * nu)), e / (2 * (1 + nu))};
}

double DilatationalWaveSpeed(const Material& material) {
  const LameParameters lame = CalcLameParameters(material.youngs_modulus, material.poisson_ratio);
  return std::sqrt((lame.lambda + 2 * lame.mu) / material.density);
}

}  // namespace kerf::fem
