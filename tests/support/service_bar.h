// What the service tests cut: a 4 x 2 x 2 cm bar held at x = 0, offering every level (no
// gravity: it would sag the free end onto the blade's tip), and the blade across it.
#pragma once

#include "kerf/v1/blade.pb.h"

namespace kerf::testing {

inline constexpr char kServiceBarScene[] = R"pb(
  name: "test-bar"
  mesh {
    lattice {
      cells_x: 4
      cells_y: 2
      cells_z: 2
      size { x: 0.04 y: 0.02 z: 0.02 }
    }
  }
  material { youngs_modulus: 5000 poisson_ratio: 0.45 density: 1000 mass_damping: 20 }
  displacements {
    vertices {
      half_space {
        point { x: 0 }
        normal { x: -1 }
      }
    }
  }
)pb";

// The blade across the bar at x = 23.7 mm, its edge at y, from below the bar to above it.
inline kerf::v1::BladePose BarBladePose(double time, double y, double x = 0.0237) {
  kerf::v1::BladePose pose;
  pose.set_time(time);
  for (const double c : {x, y, -0.005}) pose.add_tip(c);
  for (const double c : {x, y, 0.025}) pose.add_heel(c);
  return pose;
}

}  // namespace kerf::testing
