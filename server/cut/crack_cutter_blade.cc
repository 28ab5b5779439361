// CrackCutter: the blade's points in the units it is in (progressive; see crack_cutter.h).
#include <Eigen/Geometry>
#include <algorithm>
#include <limits>

#include "base/check.h"
#include "cut/crack_cutter.h"
#include "geometry/point_triangle_distance.h"
#include "geometry/segment_box.h"
#include "geometry/segment_distance.h"
#include "geometry/segment_triangle_intersection.h"
#include "geometry/tet_measures.h"

namespace kerf::cut {
namespace {

using mesh::Index;
using mesh::TetId;
using mesh::VertexId;

}  // namespace

absl::flat_hash_map<TetId, CrackCutter::BladeIn> CrackCutter::BladeUnitsAt(
    const BladePose& pose) const {
  absl::flat_hash_map<TetId, BladeIn> blade;
  const std::vector<TetId> units = UnitsAt(pose);
  BladeCrossingsAt at;
  // About half the units meet the blade; those share about half their faces and edges.
  at.faces.reserve(2 * units.size());
  at.edges.reserve(3 * units.size());
  for (const TetId u : units) {
    if (std::optional<BladeIn> in = BladeInUnit(u, pose, &at)) blade[u] = *std::move(in);
  }
  // Every unit at an edge the blade passes through has its point, or meets the blade where the
  // edge is cut already (the edge may lie a rounding error outside the blade's box).
  std::vector<EdgeKey> through;
  const auto add_through = [&](const BladeIn& in) {
    for (const auto& [key, fraction] : in.edges) through.push_back(key);
    through.insert(through.end(), in.cut_edges.begin(), in.cut_edges.end());
  };
  for (const auto& [u, in] : blade) add_through(in);
  while (!through.empty()) {
    const EdgeKey key = through.back();
    through.pop_back();
    const auto [low, high] = EdgeEnds(key);
    for (const TetId u : UnitsAround({low, high})) {
      if (blade.contains(u)) continue;
      std::optional<BladeIn> in = BladeInUnit(u, pose, &at);
      KERF_CHECK(in.has_value());  // it has the edge at least
      add_through(*in);
      blade[u] = *std::move(in);
    }
  }
  return blade;
}

void CrackCutter::KeepEdgePointsLeft(const absl::flat_hash_map<TetId, BladeIn>& blade,
                                     std::vector<TetId>* touched) {
  absl::flat_hash_map<EdgeKey, double> now;
  for (const auto& [u, in] : blade) now.insert(in.edges.begin(), in.edges.end());
  std::vector<std::pair<EdgeKey, double>> left;
  for (const auto& [key, fraction] : blade_edges_) {
    // An edge that got a point for good at this step (the tip's path through it) keeps it.
    if (!now.contains(key) && (advancing_.contains(key) || !edge_points_.contains(key))) {
      left.emplace_back(key, fraction);
    }
  }
  std::sort(left.begin(), left.end());  // the same points whatever the map's order
  for (const auto& [key, fraction] : left) {
    std::vector<TetId> around;
    const auto [low, high] = EdgeEnds(key);
    if (!advancing_.contains(key)) {
      RecordEdgeCrossing(low, high, fraction, EdgeCrossingFrom::kBladeLeaving, &around);
    } else {
      // The crack's front advanced along the edge: its point moves there (its vertex went when
      // the blade's point stood in for it), or, near the far corner, that corner snaps or the
      // point stops short of it.
      KERF_CHECK(edge_points_.at(key).vertex == kNoVertex);
      const std::vector<TetId> units = UnitsAround({low, high});
      around = units;
      if (const std::optional<double> at =
              EdgePointOffCorners(low, high, fraction, EdgeCrossingFrom::kBladeLeaving,
                                  /*may_move=*/true, units, &around)) {
        edge_points_.at(key) = {*at};
      }
    }
    Join(around);
    touched->insert(touched->end(), around.begin(), around.end());
  }
  advancing_.clear();
  for (const auto& [key, fraction] : now) {
    if (edge_points_.contains(key)) advancing_.insert(key);
  }
  blade_edges_ = std::move(now);
}

bool CrackCutter::AdvancesAlongTheCrack(EdgeKey key, double fraction) const {
  const auto [low, high] = EdgeEnds(key);
  const bool from_low = on_crack_.contains(low);
  if (from_low == on_crack_.contains(high)) return false;
  const double at = edge_points_.at(key).fraction;
  return from_low ? fraction > at + kMinTemporaryWeight : fraction < at - kMinTemporaryWeight;
}

namespace {

// Where the blade passes through the edge a-b, as a fraction from a: the blade lying in the
// edge's plane (or its tip on the edge) and not along it, strictly inside the edge.
std::optional<double> BladeThroughEdge(const BladePose& pose, const Eigen::Vector3d& a,
                                       const Eigen::Vector3d& b) {
  const Eigen::Vector3d blade = pose.heel - pose.tip, edge = b - a;
  if (blade.cross(edge).norm() <= 1e-6 * blade.norm() * edge.norm()) return std::nullopt;
  const geometry::ClosestPoints c = geometry::ClosestPointsOfSegments(pose.tip, pose.heel, a, b);
  if (c.distance > kInPlaneTolerance * edge.norm() || c.t < kMinTemporaryWeight ||
      c.t > 1 - kMinTemporaryWeight) {
    return std::nullopt;
  }
  return c.t;
}

}  // namespace

std::optional<CrackCutter::BladeIn> CrackCutter::BladeInUnit(TetId unit, const BladePose& pose,
                                                             BladeCrossingsAt* found) const {
  const mesh::TetVertices corners = CornersOf(unit), placed = PlacedCorners(unit);
  std::array<Eigen::Vector3d, 4> x;
  for (int k = 0; k < 4; ++k) x[k] = mesh_->current_position(placed[k]);
  // Most units near the blade are beside it: their box, grown by more than an edge's in-plane
  // tolerance (BladeThroughEdge), tells. Not for a unit with a parted corner: its faces' crossings
  // may be found on the other side's copies, which lie elsewhere, and it must agree with them.
  const Eigen::Vector3d low = x[0].cwiseMin(x[1]).cwiseMin(x[2].cwiseMin(x[3]));
  const Eigen::Vector3d high = x[0].cwiseMax(x[1]).cwiseMax(x[2].cwiseMax(x[3]));
  if (!geometry::SegmentMeetsBox(pose.tip, pose.heel, low, high,
                                 2 * kInPlaneTolerance * (high - low).norm()) &&
      std::none_of(corners.begin(), corners.end(),
                   [&](VertexId v) { return parting_.HasCopies(v); })) {
    return std::nullopt;
  }
  BladeIn in;
  in.tip_inside = geometry::ContainsPoint(x[0], x[1], x[2], x[3], pose.tip);
  bool meets = in.tip_inside || geometry::ContainsPoint(x[0], x[1], x[2], x[3], pose.heel);
  double first = 1, last = 0;  // the blade's chord through the tet, along it from the tip
  for (const auto& f : mesh::kTetFaces) {
    // Each face's crossing is found once, on its vertices in key order, so the two tets at it
    // agree on it.
    const FaceKey key = MakeFaceKey(corners[f[0]], corners[f[1]], corners[f[2]]);
    auto [at, inserted] = found->faces.try_emplace(key);
    if (inserted) {
      std::array<Eigen::Vector3d, 3> y;  // the face's corners in key order
      for (int j = 0; j < 3; ++j) {
        for (int i = 0; i < 3; ++i) {
          if (corners[f[i]] == key[j]) y[j] = x[f[i]];
        }
      }
      at->second = geometry::IntersectSegmentTriangle(pose.tip, pose.heel, y[0], y[1], y[2]);
    }
    const auto& crossing = at->second;
    if (!crossing) continue;
    meets = true;
    in.crossed.push_back(key);
    first = std::min(first, crossing->t);
    last = std::max(last, crossing->t);
    if (crossing->barycentric.minCoeff() >= kMinTemporaryWeight) {
      (face_points_.contains(key) ? in.beside : in.faces)[key] = crossing->barycentric;
    }
  }
  for (const auto& [i, j] : mesh::kTetEdges) {
    const EdgeKey key = MakeEdgeKey(corners[i], corners[j]);
    // Found once, from the lower id, so the units at the edge agree on it.
    const bool from_i = Index(corners[i]) < Index(corners[j]);
    auto [at, inserted] = found->edges.try_emplace(key);
    if (inserted) {
      at->second = BladeThroughEdge(pose, from_i ? x[i] : x[j], from_i ? x[j] : x[i]);
      // A blade lying in the plane of the tissue's surface there slides along it: it cuts nothing.
      if (at->second &&
          surface_.SegmentOnFaceAtEdge(*mesh_, corners[i], corners[j], pose.tip, pose.heel,
                                       kInPlaneTolerance * (x[i] - x[j]).norm())) {
        at->second.reset();
      }
    }
    if (!at->second) continue;
    // Through an edge cut already the blade meets the unit (it lies in the crack there, which
    // opens where the blade is in the units on both sides) but makes no point.
    meets = true;
    if (!edge_points_.contains(key) || AdvancesAlongTheCrack(key, *at->second)) {
      in.edges[key] = *at->second;
    } else {
      in.cut_edges.push_back(key);
    }
  }
  if (!meets) return std::nullopt;
  Eigen::Vector3d point = 0.25 * (x[0] + x[1] + x[2] + x[3]);
  if (in.tip_inside) {
    point = pose.tip;
  } else if (first <= last) {
    point = pose.tip + 0.5 * (first + last) * (pose.heel - pose.tip);
  }
  in.apex = PulledInside(geometry::BarycentricWeights(x[0], x[1], x[2], x[3], point));
  return in;
}

namespace {

// The distance from `x` to the points, the segments between them and the triangles they span.
double DistanceToSpan(const Eigen::Vector3d& x, const std::vector<Eigen::Vector3d>& on) {
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < on.size(); ++i) {
    d = std::min(d, (x - on[i]).norm());
    for (std::size_t j = i + 1; j < on.size(); ++j) {
      const Eigen::Vector3d s = on[j] - on[i];
      const double t = std::clamp((x - on[i]).dot(s) / std::max(s.squaredNorm(), 1e-300), 0.0, 1.0);
      d = std::min(d, (x - on[i] - t * s).norm());
      for (std::size_t k = j + 1; k < on.size(); ++k) {
        if ((on[j] - on[i]).cross(on[k] - on[i]).squaredNorm() > 0) {
          d = std::min(d, geometry::DistanceToTriangle(x, on[i], on[j], on[k]));
        }
      }
    }
  }
  return d;
}

}  // namespace

void CrackCutter::KeepFarthestFaceCrossings(const absl::flat_hash_map<TetId, BladeIn>* blade,
                                            std::vector<TetId>* touched) {
  absl::flat_hash_set<FaceKey, FaceKeyHash> now;
  if (blade != nullptr) {
    for (const auto& [u, in] : *blade) {
      if (!group_of_.contains(u)) continue;
      for (const auto& crossing : in.faces) {
        const FaceKey& face = crossing.first;
        const Eigen::Vector3d& barycentric = crossing.second;
        // On an edge of the face (in its plane), the blade's crossing is the edge's
        // (KeepEdgePointsLeft). A face with every corner on the crack lies on it (the blade
        // sweeping in its plane).
        if (barycentric.minCoeff() <= kMinTemporaryWeight ||
            std::all_of(face.begin(), face.end(), [&](VertexId v) { return OnTheCrack(v); })) {
          continue;
        }
        if (!now.insert(face).second) continue;
        std::vector<Eigen::Vector3d>& kept = crossed_faces_[face];
        if (std::none_of(kept.begin(), kept.end(), [&](const Eigen::Vector3d& b) {
              return (b - barycentric).lpNorm<Eigen::Infinity>() <= kMinTemporaryWeight;
            })) {
          kept.push_back(barycentric);
        }
      }
    }
  }
  Crossings left;
  for (auto it = crossed_faces_.begin(); it != crossed_faces_.end();) {
    if (now.contains(it->first)) {
      ++it;
      continue;
    }
    if (!face_points_.contains(it->first)) {
      if (const std::optional<Eigen::Vector3d> b =
              FarthestFromTheFacesCrack(it->first, it->second)) {
        left.faces.push_back({it->first, *b});
      }
    }
    crossed_faces_.erase(it++);
  }
  if (left.faces.empty()) return;
  std::sort(left.faces.begin(), left.faces.end(),
            [](const FaceCrossing& a, const FaceCrossing& b) { return a.face < b.face; });
  std::vector<TetId> around;
  RecordCrossings(left, &around, FaceCrossingsFrom::kBladeLeft);
  Join(around);
  touched->insert(touched->end(), around.begin(), around.end());
}

std::optional<Eigen::Vector3d> CrackCutter::FarthestFromTheFacesCrack(
    const FaceKey& key, const std::vector<Eigen::Vector3d>& crossings) const {
  const double reach = kSnapReach * LengthsOf(key).tissue_edge();
  // The face's own points for good first: a crack the blade left as it went covers its crossings.
  const std::vector<Eigen::Vector3d> own = OwnPointsOf(key);
  if (own.empty()) return std::nullopt;
  if (std::all_of(crossings.begin(), crossings.end(), [&](const Eigen::Vector3d& b) {
        return DistanceToSpan(RestAt(key, b), own) <= reach;
      })) {
    return std::nullopt;
  }
  // Each tet's at the face points for good on the crack (rest positions): its corners on the
  // crack, its edge points and its face points; the crack it will split by spans them.
  std::vector<std::vector<Eigen::Vector3d>> tets;
  for (const TetId unit : UnitsAround({key[0], key[1], key[2]})) {
    const mesh::TetVertices c = CornersOf(unit);
    std::vector<Eigen::Vector3d> on;
    for (const VertexId v : c) {
      if (on_crack_.contains(v)) on.push_back(mesh_->rest_position(v));
    }
    for (const auto& [i, j] : mesh::kTetEdges) {
      if (const std::optional<Eigen::Vector3d> p = EdgePointAt(c[i], c[j])) on.push_back(*p);
    }
    for (const auto& f : mesh::kTetFaces) {
      const FaceKey face = MakeFaceKey(c[f[0]], c[f[1]], c[f[2]]);
      if (const auto p = face_points_.find(face); p != face_points_.end()) {
        on.push_back(RestAt(face, p->second.barycentric));
      }
    }
    if (!on.empty()) tets.push_back(std::move(on));
  }
  if (tets.empty()) return std::nullopt;
  const auto distance = [&](const Eigen::Vector3d& x) {
    double d = std::numeric_limits<double>::infinity();
    for (const std::vector<Eigen::Vector3d>& on : tets) d = std::min(d, DistanceToSpan(x, on));
    return d;
  };
  // Farthest first; one a crack face at the face's corners lies beside is cut already.
  std::vector<std::pair<double, int>> beyond;
  for (int i = 0; i < static_cast<int>(crossings.size()); ++i) {
    const double d = distance(RestAt(key, crossings[i]));
    if (d > reach) beyond.emplace_back(-d, i);
  }
  std::sort(beyond.begin(), beyond.end());
  for (const auto& [d, i] : beyond) {
    const Eigen::Vector3d& b = crossings[i];
    // Beside the tissue's surface (within the snap reach, as a share of the face, of a corner or
    // an edge of it) the crack stays off the surface (SnapWouldLayCrackOnSurface, the face points
    // moved off its edges): a point there would cut the layer between them into slivers.
    bool beside_surface = false;
    for (int k = 0; k < 3; ++k) {
      beside_surface = beside_surface || (surface_.HasVertex(key[k]) && b[k] > 1 - kSnapReach) ||
                       (surface_.HasEdge(key[(k + 1) % 3], key[(k + 2) % 3]) && b[k] < kSnapReach);
    }
    if (beside_surface) continue;
    if (!CrackFaceWithin(RestAt(key, b), key, reach,
                         [](TetId, const std::array<VertexId, 3>&, const FaceKey&,
                            const CrackFace&) { return true; })) {
      return b;
    }
  }
  return std::nullopt;
}

std::vector<Eigen::Vector3d> CrackCutter::OwnPointsOf(const FaceKey& key) const {
  std::vector<Eigen::Vector3d> own;
  for (int k = 0; k < 3; ++k) {
    const VertexId a = key[k], b = key[(k + 1) % 3];
    if (on_crack_.contains(a)) own.push_back(mesh_->rest_position(a));
    if (const std::optional<Eigen::Vector3d> p = EdgePointAt(a, b)) own.push_back(*p);
  }
  return own;
}

std::optional<Eigen::Vector3d> CrackCutter::EdgePointAt(VertexId a, VertexId b) const {
  const auto e = edge_points_.find(MakeEdgeKey(a, b));
  if (e == edge_points_.end()) return std::nullopt;
  const auto [low, high] = EdgeEnds(e->first);
  return (1 - e->second.fraction) * mesh_->rest_position(low) +
         e->second.fraction * mesh_->rest_position(high);
}

}  // namespace kerf::cut
