// The bars kerf's speed is measured against its accuracy on (kerf experiment tradeoff): the
// cantilever of ../shared/design/accuracy.md, the same bar pulled 10% longer and the same bar
// twisted a quarter turn. Each is a 5 x 1 x 1 bar (unitless, as accuracy.md: E = 5000,
// nu = 0.45, rho = 1) clamped at x = 0 and meshed as 5n x n x n cubes of six tets, and each is
// judged by one vector quantity of its settled state that a converged reference (CalculiX on
// quadratic tets: cli/experiments/calculix_reference.h) also gives.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "fem/elastic_forces.h"
#include "kerf/v1/scene.pb.h"
#include "sim/scene.h"

namespace kerf::lab {

enum class BarLoad {
  // Gravity rho g = 1 in -z. Quantity: the displacement of the tip-face centre (5, 0.5, 0.5).
  kCantilever,
  // The x = 5 face held displaced by (0.5, 0, 0). Quantity: the total force holding that face
  // (the reaction).
  kTension,
  // The x = 5 face held turned a quarter turn about the bar's axis (y = z = 0.5), a large
  // rotation with strains under 16%: the linear model's artefact. Quantity: the displacement of
  // the mid-length corner (2.5, 1, 1).
  kTwist,
};

inline constexpr BarLoad kBarLoads[] = {BarLoad::kCantilever, BarLoad::kTension, BarLoad::kTwist};
inline constexpr double kBarLength = 5;

// "cantilever", "tension", "twist".
std::string BarLoadName(BarLoad load);

// The displacement held at rest position `p` (on the face x = 0 or x = 5: every component
// held), or nullopt where the bar is free.
std::optional<Eigen::Vector3d> HeldDisplacement(BarLoad load, const Eigen::Vector3d& p);

// Where the quantity is read: the vertex at this rest position (kCantilever, kTwist), or the
// face x = 5 whose holding force is summed (kTension: nullopt).
std::optional<Eigen::Vector3d> ProbePoint(BarLoad load);

// OK for a resolution n the bars can be made at: even (so that the probe points are
// vertices) and in [2, 64]; INVALID_ARGUMENT naming n otherwise.
absl::Status CheckBarResolution(int n);

// The bar at resolution n (see CheckBarResolution) as a scene stepped by `method` (its automatic
// step) with `law`, Rayleigh mass damping `mass_damping` (1/s), nothing cut.
absl::StatusOr<sim::Scene> MakeBarScene(BarLoad load, int n, kerf::v1::Integration::Method method,
                                        fem::ElasticLaw law, double mass_damping);

// A displacement near the settled one, to settle from: the held faces' displacement carried
// along the bar in proportion to x (zero for the cantilever). By vertex index.
std::vector<Eigen::Vector3d> StartingDisplacement(BarLoad load, const mesh::TetMesh& mesh);

struct BarSettleResult {
  Eigen::Vector3d quantity;  // see BarLoad
  double simulated_seconds = 0;
  double wall_seconds = 0;  // of the steps alone
  int steps = 0;
  double time_step = 0;
  bool finite = true;  // false if the run blew up (stopped there)
};

// Builds the scene, starts it from StartingDisplacement at rest and steps it for
// `simulated_seconds`, then reads the quantity.
absl::StatusOr<BarSettleResult> SettleBar(BarLoad load, int n, kerf::v1::Integration::Method method,
                                          fem::ElasticLaw law, double mass_damping,
                                          double simulated_seconds);

}  // namespace kerf::lab
