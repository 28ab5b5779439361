// A scene for simulation tests: a 6 x 2 x 2 cm bar of soft tissue (100 kPa: it sags about
// 5 mm) held at x = 0, under gravity, lightly damped.
#pragma once

namespace kerf::testing {

inline constexpr char kHeldBarScene[] = R"(
name: "held-bar"
mesh { lattice { cells_x: 6 cells_y: 2 cells_z: 2 size { x: 0.06 y: 0.02 z: 0.02 } } }
material { youngs_modulus: 100000 poisson_ratio: 0.45 density: 1000 mass_damping: 5 }
displacements { vertices { half_space { point { x: 0 } normal { x: -1 } } } }
gravity { z: -9.81 }
)";

}  // namespace kerf::testing
