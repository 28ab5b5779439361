#include "lab/hand_paths.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "mesh/mesh_quality.h"

namespace kerf::lab {
namespace {

constexpr double kPi = 3.14159265358979323846;

// What every family shares: the tissue's box and scale, the up direction, the random source.
struct Frame {
  mesh::Bounds box;
  double edge;    // mean edge length
  double height;  // of the box along z
  std::mt19937_64 random;

  double Uniform(double low, double high) {
    return std::uniform_real_distribution<double>(low, high)(random);
  }
  // A horizontal unit direction.
  Eigen::Vector3d Direction() {
    const double angle = Uniform(0, 2 * kPi);
    return {std::cos(angle), std::sin(angle), 0};
  }
  // The heel for a tip: straight up, above the tissue.
  Eigen::Vector3d HeelAbove(const Eigen::Vector3d& tip) const {
    return {tip.x(), tip.y(), std::max(box.high.z() + 0.2 * height, tip.z() + edge)};
  }
};

// The half-extent of the box along a horizontal direction, from its centre.
double HalfExtentAlong(const mesh::Bounds& box, const Eigen::Vector3d& d) {
  const Eigen::Vector3d half = 0.5 * (box.high - box.low);
  return std::abs(d.x()) * half.x() + std::abs(d.y()) * half.y();
}

std::vector<cut::BladePose> HandPass(Frame& f, const HandPathOptions& options) {
  const Eigen::Vector3d centre = 0.5 * (f.box.low + f.box.high);
  const Eigen::Vector3d travel = f.Direction();
  const Eigen::Vector3d across(-travel.y(), travel.x(), 0);
  const double reach = HalfExtentAlong(f.box, travel) + 2 * f.edge;
  // One draw per statement: the order of draws within an expression is the compiler's.
  const double aside = f.Uniform(-0.25, 0.25) * HalfExtentAlong(f.box, across);
  const double up = f.Uniform(-0.2, 0.2) * f.height;
  const Eigen::Vector3d start =
      centre - reach * travel + aside * across + Eigen::Vector3d(0, 0, up);
  const double speed = 2 * reach / options.duration;  // along travel
  const double amplitude = f.Uniform(0.02, 0.2) * f.edge;
  const double frequency = f.Uniform(8, 12), phase = f.Uniform(0, 2 * kPi);
  const double along_frequency = f.Uniform(8, 12), along_phase = f.Uniform(0, 2 * kPi);
  const double pause_every = f.Uniform(0.3, 0.5), pause = f.Uniform(0.05, 0.15);
  const double back_off = f.Uniform(0.1, 0.3) * f.edge;
  const double reversal_at = f.Uniform(0.2, 0.7) * options.duration;
  const double reversal_length = f.Uniform(0.6, 1.4) * f.edge;
  const bool withdraw_inside = f.Uniform(0, 1) < 0.5;
  const double end = withdraw_inside ? f.Uniform(0.45, 0.75) * 2 * reach : 2 * reach;
  // The distance travelled as a function of time: forward at `speed`, a pause that backs off
  // and comes again every `pause_every`, one reversal going back and forth.
  std::vector<cut::BladePose> poses;
  const double dt = 1 / options.rate;
  double s = 0, next_pause = pause_every, pause_left = 0, reversal_left = -1;
  for (double t = 0; s < end; t += dt) {
    if (pause_left > 0) {
      pause_left -= dt;
    } else if (t >= next_pause) {
      pause_left = pause;
      next_pause += pause_every;
    } else if (reversal_left < 0 && t >= reversal_at) {
      reversal_left = 2 * reversal_length;
    }
    double ds = speed * dt;
    double offset = 0;
    if (pause_left > 0) {
      const double phase_in_pause = 1 - pause_left / pause;  // 0 -> 1
      offset = -back_off * std::sin(kPi * phase_in_pause);
      ds = 0;
    } else if (reversal_left > 0) {
      ds = reversal_left > reversal_length ? -speed * dt : speed * dt;
      reversal_left -= speed * dt;
      if (reversal_left <= 0) reversal_left = 0;
    }
    s += ds;
    const Eigen::Vector3d shake =
        amplitude * std::sin(2 * kPi * frequency * t + phase) * across +
        0.5 * amplitude * std::sin(2 * kPi * along_frequency * t + along_phase) * travel;
    cut::BladePose pose;
    pose.time = t;
    pose.tip = start + (s + offset) * travel + shake;
    pose.heel = pose.tip + (f.HeelAbove(start).z() - start.z()) * Eigen::Vector3d::UnitZ();
    poses.push_back(pose);
  }
  return poses;
}

// Poses along the polyline `waypoints`, each waypoint the tip of one pose, at most `step` apart.
std::vector<cut::BladePose> AlongWaypoints(const std::vector<Eigen::Vector3d>& waypoints,
                                           const Frame& f, double step, double rate) {
  std::vector<cut::BladePose> poses;
  const double heel_z = f.HeelAbove(waypoints.front()).z();
  auto add = [&](const Eigen::Vector3d& tip) {
    cut::BladePose pose;
    pose.time = static_cast<double>(poses.size()) / rate;
    pose.tip = tip;
    pose.heel = Eigen::Vector3d(tip.x(), tip.y(), std::max(heel_z, tip.z() + f.edge));
    poses.push_back(pose);
  };
  add(waypoints.front());
  for (std::size_t i = 1; i < waypoints.size(); ++i) {
    const Eigen::Vector3d& a = waypoints[i - 1];
    const Eigen::Vector3d& b = waypoints[i];
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step)));
    for (int k = 1; k <= n; ++k) add(a + (b - a) * (static_cast<double>(k) / n));
  }
  return poses;
}

// Interior vertices near the line from `from` along `travel`, in order along it, about
// `spacing` apart; the tip path goes through them (kThroughVertices) or along edges between
// neighbours (kAlongEdges).
std::vector<Eigen::Vector3d> VertexWaypoints(const mesh::TetMesh& tissue, Frame& f,
                                             bool along_edges) {
  const Eigen::Vector3d centre = 0.5 * (f.box.low + f.box.high);
  const Eigen::Vector3d travel = f.Direction();
  const double reach = HalfExtentAlong(f.box, travel) + 2 * f.edge;
  const Eigen::Vector3d start =
      centre - reach * travel + Eigen::Vector3d(0, 0, f.Uniform(-0.2, 0.2) * f.height);
  // The vertex nearest a point (a scan: these paths are made once per test).
  auto nearest = [&](const Eigen::Vector3d& p) {
    mesh::VertexId best{0};
    double distance = HUGE_VAL;
    for (const mesh::VertexId v : tissue.vertices()) {
      const double d = (tissue.rest_position(v) - p).squaredNorm();
      if (d < distance) distance = d, best = v;
    }
    return best;
  };
  std::vector<Eigen::Vector3d> waypoints = {start};
  mesh::VertexId at = nearest(start + 2 * f.edge * travel);
  waypoints.push_back(tissue.rest_position(at));
  const Eigen::Vector3d finish = start + 2 * reach * travel;
  for (int guard = 0; guard < 100000; ++guard) {
    const Eigen::Vector3d here = tissue.rest_position(at);
    if ((finish - here).dot(travel) < 2 * f.edge) break;
    mesh::VertexId next = at;
    if (along_edges) {
      // The neighbour that goes on best towards the line's far end.
      double best = 0;
      for (const mesh::TetId t : tissue.TetsAround(at)) {
        for (const mesh::VertexId v : tissue.tet(t)) {
          const Eigen::Vector3d d = tissue.rest_position(v) - here;
          if (v == at || d.norm() == 0) continue;
          const Eigen::Vector3d to_line = start + (here - start).dot(travel) * travel - here;
          const double score = d.normalized().dot(travel) +
                               0.5 * d.normalized().dot(to_line) / std::max(to_line.norm(), f.edge);
          if (score > best) best = score, next = v;
        }
      }
    } else {
      next = nearest(here + 2 * f.edge * travel + f.Uniform(-0.3, 0.3) * f.edge * travel);
    }
    if (next == at || (tissue.rest_position(next) - here).dot(travel) <= 0) break;
    at = next;
    waypoints.push_back(tissue.rest_position(at));
  }
  waypoints.push_back(waypoints.back() + 2 * f.edge * travel);
  const Eigen::Vector3d out = finish;
  if ((out - waypoints.back()).dot(travel) > 0) waypoints.push_back(out);
  return waypoints;
}

std::vector<cut::BladePose> InFacePlane(const mesh::TetMesh& tissue, Frame& f,
                                        const HandPathOptions& options) {
  std::vector<mesh::TetId> tets(tissue.tets().begin(), tissue.tets().end());
  const mesh::TetVertices& v =
      tissue.tet(tets[static_cast<std::size_t>(f.Uniform(0, 1) * static_cast<double>(tets.size())) %
                      tets.size()]);
  const int skip = static_cast<int>(f.Uniform(0, 4)) % 4;
  std::array<Eigen::Vector3d, 3> face;
  for (int k = 0, j = 0; k < 4; ++k) {
    if (k != skip) face[j++] = tissue.rest_position(v[k]);
  }
  const Eigen::Vector3d normal = (face[1] - face[0]).cross(face[2] - face[0]).normalized();
  // The blade along the plane's direction nearest to up; the tip travels across it.
  Eigen::Vector3d blade = Eigen::Vector3d::UnitZ() - normal.z() * normal;
  if (blade.norm() < 0.2) blade = face[1] - face[0];
  blade.normalize();
  const Eigen::Vector3d travel = normal.cross(blade).normalized();
  const Eigen::Vector3d middle = (face[0] + face[1] + face[2]) / 3;
  const double reach = f.box.diagonal() * 0.5 + 2 * f.edge;
  const double length = f.box.diagonal() + f.edge;
  const Eigen::Vector3d tip0 = middle - f.Uniform(0.5, 1.5) * f.edge * blade - reach * travel;
  const int n =
      std::max(2, static_cast<int>(std::ceil(2 * reach / (options.degenerate_step * f.edge))));
  std::vector<cut::BladePose> poses;
  for (int i = 0; i <= n; ++i) {
    cut::BladePose pose;
    pose.time = static_cast<double>(i) / options.rate;
    pose.tip = tip0 + (2 * reach * i / n) * travel;
    pose.heel = pose.tip + length * blade;
    poses.push_back(pose);
  }
  return poses;
}

}  // namespace

absl::StatusOr<PathFamily> ParsePathFamily(absl::string_view name) {
  for (const PathFamily family : {PathFamily::kHand, PathFamily::kThroughVertices,
                                  PathFamily::kAlongEdges, PathFamily::kInFacePlane}) {
    if (PathFamilyName(family) == name) return family;
  }
  return absl::InvalidArgumentError(absl::StrCat("unknown path family \"", name,
                                                 "\" (known: hand, vertices, edges, face-plane)"));
}

absl::string_view PathFamilyName(PathFamily family) {
  switch (family) {
    case PathFamily::kHand:
      return "hand";
    case PathFamily::kThroughVertices:
      return "vertices";
    case PathFamily::kAlongEdges:
      return "edges";
    case PathFamily::kInFacePlane:
      return "face-plane";
  }
  return "";
}

std::vector<cut::BladePose> MakeHandPath(const mesh::TetMesh& tissue, PathFamily family,
                                         std::uint64_t seed, const HandPathOptions& options) {
  Frame f{mesh::MeasureBounds(tissue), mesh::MeanEdgeLength(tissue), 0, std::mt19937_64(seed)};
  f.height = f.box.high.z() - f.box.low.z();
  switch (family) {
    case PathFamily::kHand:
      return HandPass(f, options);
    case PathFamily::kThroughVertices:
    case PathFamily::kAlongEdges:
      return AlongWaypoints(VertexWaypoints(tissue, f, family == PathFamily::kAlongEdges), f,
                            options.degenerate_step * f.edge, options.rate);
    case PathFamily::kInFacePlane:
      return InFacePlane(tissue, f, options);
  }
  return {};
}

std::string FormatBladePathJson(const std::vector<cut::BladePose>& poses) {
  // Every digit, so that the path read back is the path made.
  const auto exact = [](double x) { return absl::StrFormat("%.17g", x); };
  std::string json = "{\"poses\": [\n";
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const cut::BladePose& p = poses[i];
    absl::StrAppend(&json, "  {\"time\": ", exact(p.time), ", \"tip\": [", exact(p.tip.x()), ", ",
                    exact(p.tip.y()), ", ", exact(p.tip.z()), "], \"heel\": [", exact(p.heel.x()),
                    ", ", exact(p.heel.y()), ", ", exact(p.heel.z()), "]}",
                    i + 1 < poses.size() ? ",\n" : "\n");
  }
  return json + "]}\n";
}

}  // namespace kerf::lab
