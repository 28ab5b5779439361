#include "cut/cone_apex.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "cut/steps_in_tet.h"
#include "geometry/tet_measures.h"
#include "mesh/tet_mesh.h"

namespace kerf::cut {

Eigen::Vector4d PulledInside(const Eigen::Vector4d& w, const Eigen::Vector4d& towards,
                             double margin) {
  double pull = 0;
  for (int k = 0; k < 4; ++k) {
    if (w[k] < margin) pull = std::max(pull, (margin - w[k]) / (towards[k] - w[k]));
  }
  return w + std::min(pull, 1.0) * (towards - w);
}

namespace {

// The smallest dihedral angle of the cone from `apex` over the crack's face triangles (degrees).
double SmallestConeAngle(const TetCrack& crack,
                         const std::function<Eigen::Vector3d(mesh::VertexId)>& rest,
                         const Eigen::Vector3d& apex) {
  double smallest = 180;
  for (const FaceSplit& f : crack.faces) {
    for (const auto& t : f.triangles) {
      smallest = std::min(smallest,
                          geometry::SmallestDihedralDeg(apex, rest(t[0]), rest(t[1]), rest(t[2])));
    }
  }
  return smallest;
}

// The cone's pieces (from `apex` over the crack's face triangles) under `degrees`.
int ConePiecesUnder(const TetCrack& crack,
                    const std::function<Eigen::Vector3d(mesh::VertexId)>& rest,
                    const Eigen::Vector3d& apex, double degrees) {
  int under = 0;
  for (const FaceSplit& f : crack.faces) {
    for (const auto& t : f.triangles) {
      if (geometry::SmallestDihedralDeg(apex, rest(t[0]), rest(t[1]), rest(t[2])) < degrees) {
        ++under;
      }
    }
  }
  return under;
}

// The point at barycentric `weights` on the tet's corners (rest positions).
Eigen::Vector3d PointAt(const TetCrack& crack,
                        const std::function<Eigen::Vector3d(mesh::VertexId)>& rest,
                        const Eigen::Vector4d& weights) {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  for (int k = 0; k < 4; ++k) point += weights[k] * rest(crack.corners[k]);
  return point;
}

// Where a cone's apex is looked for: from `from` towards `to`, on the crack's plane if it has
// one. Where the crack has no inner part the apex may be anywhere inside: from the tet's middle
// towards the middle of its faces' points. Otherwise from the middle of the trace points towards
// the tet's middle projected on the plane that fits them (its normal: their spread's least
// direction), so the crack's faces stay where the traces are.
struct ApexLine {
  Eigen::Vector3d from, to;
  std::optional<Eigen::Vector3d> normal;
};

ApexLine ApexLineOf(const TetCrack& crack,
                    const std::function<Eigen::Vector3d(mesh::VertexId)>& rest,
                    const Eigen::Vector3d& centre) {
  const auto middle_of = [&](const std::vector<mesh::VertexId>& points) {
    Eigen::Vector3d middle = Eigen::Vector3d::Zero();
    for (const mesh::VertexId v : points) middle += rest(v);
    return Eigen::Vector3d(middle / static_cast<double>(points.size()));
  };
  ApexLine line{centre, centre, std::nullopt};
  if (!HasInnerCrack(crack)) {
    std::vector<mesh::VertexId> on_faces;
    for (const auto& vertices : crack.face_vertices) {
      for (const mesh::VertexId v : vertices) {
        if (!mesh::TetHasVertex(crack.corners, v) &&
            std::find(on_faces.begin(), on_faces.end(), v) == on_faces.end()) {
          on_faces.push_back(v);
        }
      }
    }
    if (!on_faces.empty()) line.to = middle_of(on_faces);
    return line;
  }
  const std::vector<mesh::VertexId> points = TracePoints(crack);
  line.from = line.to = middle_of(points);
  Eigen::Matrix3d spread = Eigen::Matrix3d::Zero();
  for (const mesh::VertexId v : points) {
    spread += (rest(v) - line.from) * (rest(v) - line.from).transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(spread);
  if (points.size() >= 3 && eigen.eigenvalues()[1] > 1e-6 * eigen.eigenvalues()[2]) {
    line.normal = eigen.eigenvectors().col(0);
    line.to = centre - line.normal->dot(centre - line.from) * *line.normal;
  }
  return line;
}

// The search for a cone's apex over one tet's crack (ConeApexWeights).
class ApexSearch {
 public:
  ApexSearch(const TetCrack& crack, const std::function<Eigen::Vector3d(mesh::VertexId)>& rest,
             const ApexNearPath& near_path, const ApexOnPath& on_path)
      : crack_(crack), rest_(rest), near_path_(near_path), on_path_(on_path) {
    for (int k = 0; k < 4; ++k) corner_[k] = rest(crack.corners[k]);
    reach_ = kApexReach * geometry::MeanEdgeLength(corner_[0], corner_[1], corner_[2], corner_[3]);
    line_ = ApexLineOf(crack, rest, At(Eigen::Vector4d::Constant(0.25)));
    if (HasInnerCrack(crack)) traces_ = Traces(crack);
  }

  // Candidates are pulled inside by kApexMargin: towards `to` where that keeps the margin (on the
  // crack's plane), else towards the tet's middle. Of the candidates, the one
  // whose cone's smallest dihedral angle is largest (the first of equals) among those nearest the
  // path (Nearness); and the best among those no farther off the plane than the first.
  struct Best {
    std::optional<Eigen::Vector4d> near;
    Eigen::Vector4d off_plane_no_farther;
  };
  // The best near candidate so far: its nearness first, then its angle.
  struct BestNear {
    int nearness = 0;
    double angle = -1;
    Eigen::Vector4d w;
    void Consider(int n, double a, const Eigen::Vector4d& x) {
      if (n > nearness || (n == nearness && n > 0 && a > angle)) nearness = n, angle = a, w = x;
    }
  };
  Best Run() const {
    const Eigen::Vector4d target = WeightsOf(line_.to);
    const Eigen::Vector4d towards =
        target.minCoeff() < kApexMargin ? Eigen::Vector4d::Constant(0.25) : target;
    const auto pulled = [&](const Eigen::Vector3d& x) {
      return PulledInside(WeightsOf(x), towards);
    };
    Eigen::Vector4d best = pulled(line_.from);
    BestNear best_near;
    const double allowed_off = OffPlane(At(best)) * (1 + 1e-9) + 1e-12;
    double best_angle = -1;
    const auto consider = [&](const Eigen::Vector3d& x) {
      const Eigen::Vector4d w = pulled(x);
      const double off = OffPlane(At(w));
      if (off > std::max(allowed_off, reach_)) return;
      const double angle = SmallestConeAngle(crack_, rest_, At(w));
      best_near.Consider(Nearness(w), angle, w);
      if (off <= allowed_off && angle > best_angle) {
        best_angle = angle;
        best = w;
      }
    };
    for (const double s : {0.0, 0.25, 0.5, 0.75, 1.0}) {
      consider(line_.from + s * (line_.to - line_.from));
    }
    // Then a pattern search around the best, along the crack's plane where there is one.
    const std::vector<Eigen::Vector3d> directions = SearchDirections();
    double step = 0;
    for (int k = 1; k < 4; ++k) step += (corner_[k] - corner_[0]).norm() / 12;
    for (int round = 0; round < 3 && !directions.empty(); ++round, step /= 2) {
      const Eigen::Vector3d around = At(best_near.nearness > 0 ? best_near.w : best);
      for (const Eigen::Vector3d& d : directions) consider(around + step * d);
    }
    // Where none is near, where the blade went inside the tet, pulled inside by less, towards the
    // tet's middle (the plane's is no nearer the path).
    if (best_near.nearness == 0 && on_path_ && near_path_) {
      for (const Eigen::Vector4d& went : SpreadEvenly(on_path_(), kOnPathCandidates)) {
        const Eigen::Vector4d w =
            PulledInside(went, Eigen::Vector4d::Constant(0.25), kOnPathApexMargin);
        const int nearness = Nearness(w);
        if (nearness > 0) best_near.Consider(nearness, SmallestConeAngle(crack_, rest_, At(w)), w);
      }
    }
    return {best_near.nearness > 0 ? std::optional(best_near.w) : std::nullopt, best};
  }

 private:
  Eigen::Vector3d At(const Eigen::Vector4d& w) const {
    Eigen::Vector3d apex = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k) apex += w[k] * corner_[k];
    return apex;
  }
  Eigen::Vector4d WeightsOf(const Eigen::Vector3d& p) const {
    return geometry::BarycentricWeights(corner_[0], corner_[1], corner_[2], corner_[3], p);
  }
  double OffPlane(const Eigen::Vector3d& apex) const {
    return line_.normal ? std::abs(line_.normal->dot(apex - line_.from)) : 0.0;
  }
  // 0 if the apex is not near the blade's path where that is known (else within the reach of the
  // crack's plane), 1 if it is, 2 if the middles of the cone's crack faces are near the path too
  // (where the swept surface bends, a face from an apex near it may still leave it).
  int Nearness(const Eigen::Vector4d& w) const {
    if (!near_path_) return OffPlane(At(w)) <= reach_ ? 1 : 0;
    if (!near_path_(w)) return 0;
    const Eigen::Vector3d apex = At(w);
    const bool faces_near = std::all_of(traces_.begin(), traces_.end(), [&](const auto& s) {
      return near_path_(WeightsOf((apex + rest_(s[0]) + rest_(s[1])) / 3));
    });
    return faces_near ? 2 : 1;
  }
  std::vector<Eigen::Vector3d> SearchDirections() const {
    if (line_.normal) {
      const Eigen::Vector3d u = line_.normal->unitOrthogonal(), v = line_.normal->cross(u);
      return {u, -u, v, -v};
    }
    if (HasInnerCrack(crack_)) return {};
    return {Eigen::Vector3d::UnitX(),  -Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
            -Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ(),  -Eigen::Vector3d::UnitZ()};
  }

  const TetCrack& crack_;
  const std::function<Eigen::Vector3d(mesh::VertexId)>& rest_;
  const ApexNearPath& near_path_;
  const ApexOnPath& on_path_;
  std::array<Eigen::Vector3d, 4> corner_;
  double reach_ = 0;
  ApexLine line_;
  std::vector<std::array<mesh::VertexId, 2>> traces_;  // of the cone's crack faces
};

}  // namespace

Eigen::Vector4d ConeApexWeights(const TetCrack& crack,
                                const std::function<Eigen::Vector3d(mesh::VertexId)>& rest,
                                const ApexNearPath& near_path, const ApexOnPath& on_path) {
  const ApexSearch search(crack, rest, near_path, on_path);
  const ApexSearch::Best best = search.Run();
  return best.near ? *best.near : best.off_plane_no_farther;
}

double SmallestConeAngle(const TetCrack& crack,
                         const std::function<Eigen::Vector3d(mesh::VertexId)>& rest,
                         const Eigen::Vector4d& weights) {
  return SmallestConeAngle(crack, rest, PointAt(crack, rest, weights));
}

std::optional<Eigen::Vector4d> ConeApexWithFewerSlivers(
    const TetCrack& crack, const CrackSplit& split,
    const std::function<Eigen::Vector3d(mesh::VertexId)>& rest, double degrees,
    const ApexNearPath& near_path, const ApexOnPath& on_path) {
  if (split.kind == CrackSplitKind::kWhole) return std::nullopt;
  const int split_slivers = PiecesUnder(split, rest, degrees);
  if (split_slivers == 0) return std::nullopt;
  const Eigen::Vector4d apex = ConeApexWeights(crack, rest, near_path, on_path);
  if (ConePiecesUnder(crack, rest, PointAt(crack, rest, apex), degrees) >= split_slivers) {
    return std::nullopt;
  }
  return apex;
}

}  // namespace kerf::cut
