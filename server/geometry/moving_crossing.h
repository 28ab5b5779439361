// Where a moving edge crosses a moving segment, or a moving point a moving triangle, in one
// interval over which every point moves linearly in time (continuous collision detection). The
// tests behind cutting tissue that moves while the blade does: a tet edge against the blade's
// edge, the blade's tip against a tet face, each point going from its position at the previous
// pose to its position now.
#pragma once

#include <Eigen/Core>
#include <optional>

namespace kerf::geometry {

// A point's straight path over the interval: at time t in [0, 1] it is at from + t (to - from).
struct Motion {
  Eigen::Vector3d from, to;
  // Exactly `from` at 0 and `to` at 1.
  Eigen::Vector3d At(double t) const { return t == 1 ? to : from + t * (to - from); }
};

struct MovingEdgeCrossing {
  double time;      // in (0, 1]
  double fraction;  // along the edge: a + fraction (b - a), in [0, 1]
  double along;     // along the other segment: p + along (q - p), in [0, 1]
};

// The first time in (0, 1] at which edge ab meets segment pq, ends included. nullopt if they
// never meet, touch without crossing (a double root), or stay in one plane over an interval
// (a degenerate blade, handled apart). A meeting at time 0 is the previous interval's.
std::optional<MovingEdgeCrossing> FirstEdgeCrossing(const Motion& a, const Motion& b,
                                                    const Motion& p, const Motion& q);

struct MovingPointCrossing {
  double time;                  // in (0, 1]
  Eigen::Vector3d barycentric;  // on (a, b, c) at that time: non-negative, sum 1
};

// The first time in (0, 1] at which point p is on triangle abc, boundary included; nullopt as
// for FirstEdgeCrossing.
std::optional<MovingPointCrossing> FirstPointCrossing(const Motion& p, const Motion& a,
                                                      const Motion& b, const Motion& c);

}  // namespace kerf::geometry
