#include "fem/material.h"

#include <gtest/gtest.h>

#include "support/status_message.h"

namespace kerf::fem {
namespace {

using kerf::testing::StatusMessage;

TEST(CalcLameParameters, PenAndPaper) {
  const LameParameters lame = CalcLameParameters(280, 0.4);
  EXPECT_NEAR(lame.lambda, 400, 1e-12);
  EXPECT_NEAR(lame.mu, 100, 1e-12);
}

TEST(DilatationalWaveSpeed, PenAndPaper) {
  Material m;
  m.youngs_modulus = 280;
  m.poisson_ratio = 0.4;
  m.density = 6;
  EXPECT_NEAR(DilatationalWaveSpeed(m), 10.0, 1e-12);  // sqrt((400 + 200) / 6)
}

TEST(ValidateMaterial, NamesTheParameterAndValue) {
  EXPECT_TRUE(ValidateMaterial(Material()).ok());
  Material m;
  m.poisson_ratio = 0.5;
  EXPECT_EQ(StatusMessage(ValidateMaterial(m)),
            "poisson_ratio must be strictly between -1 and 0.5, got 0.5");
  m = Material();
  m.youngs_modulus = -3;
  EXPECT_EQ(StatusMessage(ValidateMaterial(m)),
            "youngs_modulus must be positive and finite (Pa), got -3");
  m = Material();
  m.density = 0;
  EXPECT_EQ(StatusMessage(ValidateMaterial(m)),
            "density must be positive and finite (kg/m^3), got 0");
  m = Material();
  m.mass_damping = -1;
  EXPECT_EQ(StatusMessage(ValidateMaterial(m)),
            "mass_damping must be non-negative and finite (1/s), got -1");
  m = Material();
  m.stiffness_damping = std::numeric_limits<double>::infinity();
  EXPECT_EQ(StatusMessage(ValidateMaterial(m)),
            "stiffness_damping must be non-negative and finite (s), got inf");
}

}  // namespace
}  // namespace kerf::fem
