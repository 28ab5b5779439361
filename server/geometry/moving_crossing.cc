#include "geometry/moving_crossing.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace kerf::geometry {
namespace {

double Det(const Eigen::Vector3d& u, const Eigen::Vector3d& v, const Eigen::Vector3d& w) {
  return u.dot(v.cross(w));
}

// At most four times, with no allocation (this runs for every edge near the blade).
class Times {
 public:
  void Add(double t) { at_[count_++] = t; }
  double* begin() { return at_.data(); }
  double* end() { return at_.data() + count_; }
  std::size_t size() const { return count_; }
  double operator[](std::size_t k) const { return at_[k]; }

 private:
  std::array<double, 4> at_;
  std::size_t count_ = 0;
};

// The times in (0, 1], ascending, at which det(u(t), v(t), w(t)) changes sign (or reaches 0
// from one side), each vector moving linearly. The determinant is a cubic in t; between the
// roots of its derivative it is monotone, and each sign change there is found by bisection.
Times CoplanarTimes(const Motion& u, const Motion& v, const Motion& w) {
  const Eigen::Vector3d du = u.to - u.from, dv = v.to - v.from, dw = w.to - w.from;
  const std::array<double, 4> c = {
      Det(u.from, v.from, w.from),
      Det(du, v.from, w.from) + Det(u.from, dv, w.from) + Det(u.from, v.from, dw),
      Det(u.from, dv, dw) + Det(du, v.from, dw) + Det(du, dv, w.from), Det(du, dv, dw)};
  // In one plane throughout (up to rounding): no crossing, a degenerate blade.
  const double scale =
      (u.from.norm() + du.norm()) * (v.from.norm() + dv.norm()) * (w.from.norm() + dw.norm());
  if (std::all_of(c.begin(), c.end(), [&](double x) { return std::abs(x) <= 1e-14 * scale; })) {
    return {};
  }
  // Evaluated on the points themselves, so that at the ends it is exactly the determinant of
  // the positions given (a blade reaching an edge's plane exactly at a pose meets it then).
  const auto f = [&](double t) { return Det(u.At(t), v.At(t), w.At(t)); };
  // Roots of f' = 3 c3 t^2 + 2 c2 t + c1 inside (0, 1), ascending, between 0 and 1.
  Times extrema;
  const double qa = 3 * c[3], qb = 2 * c[2], qc = c[1];
  if (qa != 0) {
    const double disc = qb * qb - 4 * qa * qc;
    if (disc > 0) {
      const double root = std::sqrt(disc);
      // The numerically stable pair of roots.
      const double qq = -0.5 * (qb + std::copysign(root, qb));
      const double r1 = qq / qa, r2 = qq != 0 ? qc / qq : 0.0;
      for (const double t : {std::min(r1, r2), std::max(r1, r2)}) {
        if (t > 0 && t < 1) extrema.Add(t);
      }
    }
  } else if (qb != 0) {
    const double t = -qc / qb;
    if (t > 0 && t < 1) extrema.Add(t);
  }
  Times ends;
  ends.Add(0);
  for (const double t : extrema) ends.Add(t);
  ends.Add(1);
  Times times;
  for (std::size_t k = 0; k + 1 < ends.size(); ++k) {
    double low = ends[k], high = ends[k + 1];
    const double f_low = f(low), f_high = f(high);
    if (f_high == 0) {
      times.Add(high);
      continue;
    }
    if (f_low == 0 || (f_low > 0) == (f_high > 0)) continue;
    for (int i = 0; i < 100 && high - low > 1e-15; ++i) {
      const double mid = 0.5 * (low + high);
      ((f(mid) > 0) == (f_low > 0) ? low : high) = mid;
    }
    times.Add(high);
  }
  return times;
}

// The box a group of points sweeps over the interval.
struct Box {
  Eigen::Vector3d low, high;
};
template <std::size_t N>
Box SweptBox(const std::array<const Motion*, N>& motions) {
  Box box{motions[0]->from.cwiseMin(motions[0]->to), motions[0]->from.cwiseMax(motions[0]->to)};
  for (std::size_t k = 1; k < N; ++k) {
    box.low = box.low.cwiseMin(motions[k]->from).cwiseMin(motions[k]->to);
    box.high = box.high.cwiseMax(motions[k]->from).cwiseMax(motions[k]->to);
  }
  return box;
}

// Whether the boxes the two groups of points sweep over the interval are apart: then they
// never meet.
template <std::size_t N, std::size_t M>
bool SweptBoxesApart(const std::array<const Motion*, N>& one,
                     const std::array<const Motion*, M>& other) {
  const Box a = SweptBox(one), b = SweptBox(other);
  return (a.low.array() > b.high.array()).any() || (b.low.array() > a.high.array()).any();
}

}  // namespace

std::optional<MovingEdgeCrossing> FirstEdgeCrossing(const Motion& a, const Motion& b,
                                                    const Motion& p, const Motion& q) {
  if (SweptBoxesApart<2, 2>({&a, &b}, {&p, &q})) return std::nullopt;
  const auto from_a = [&](const Motion& m) { return Motion{m.from - a.from, m.to - a.to}; };
  for (const double t : CoplanarTimes(from_a(b), from_a(p), from_a(q))) {
    // Closest points of the two lines at time t (they are in one plane).
    const Eigen::Vector3d at_a = a.At(t), at_p = p.At(t);
    const Eigen::Vector3d d1 = b.At(t) - at_a, d2 = q.At(t) - at_p, r = at_a - at_p;
    const double aa = d1.dot(d1), ab = d1.dot(d2), bb = d2.dot(d2);
    const double ar = d1.dot(r), br = d2.dot(r);
    const double denominator = aa * bb - ab * ab;
    if (!(denominator > 1e-12 * aa * bb)) continue;  // parallel, or a point
    const double s = (ab * br - bb * ar) / denominator;
    const double u = (aa * br - ab * ar) / denominator;
    if (s >= 0 && s <= 1 && u >= 0 && u <= 1) return MovingEdgeCrossing{t, s, u};
  }
  return std::nullopt;
}

std::optional<MovingPointCrossing> FirstPointCrossing(const Motion& p, const Motion& a,
                                                      const Motion& b, const Motion& c) {
  if (SweptBoxesApart<1, 3>({&p}, {&a, &b, &c})) return std::nullopt;
  const auto from_a = [&](const Motion& m) { return Motion{m.from - a.from, m.to - a.to}; };
  for (const double t : CoplanarTimes(from_a(b), from_a(c), from_a(p))) {
    const Eigen::Vector3d at_a = a.At(t), at_b = b.At(t), at_c = c.At(t), at_p = p.At(t);
    const Eigen::Vector3d normal = (at_b - at_a).cross(at_c - at_a);
    if (normal.squaredNorm() == 0) continue;
    const Eigen::Vector3d weights((at_c - at_b).cross(at_p - at_b).dot(normal),
                                  (at_a - at_c).cross(at_p - at_c).dot(normal),
                                  (at_b - at_a).cross(at_p - at_a).dot(normal));
    if (weights.minCoeff() >= 0 && weights.sum() > 0) {
      return MovingPointCrossing{t, weights / weights.sum()};
    }
  }
  return std::nullopt;
}

}  // namespace kerf::geometry
