// CrackCutter: the blade's crossings recorded as the crack's points, and snapping (see
// crack_cutter.h).
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "cut/crack_cutter.h"
#include "cut/face_point_weights.h"
#include "geometry/point_triangle_distance.h"
#include "geometry/segment_distance.h"
#include "geometry/tet_measures.h"
#include "geometry/triangle_crossing.h"

namespace kerf::cut {
namespace {

using mesh::Index;
using mesh::TetId;
using mesh::VertexId;

}  // namespace

void CrackCutter::RecordCrossings(const Crossings& found, std::vector<TetId>* touched,
                                  FaceCrossingsFrom from) {
  for (const EdgeCrossing& c : found.edges) {
    RecordEdgeCrossing(c.low, c.high, c.fraction, EdgeCrossingFrom::kSweep, touched);
  }
  for (const FaceCrossing& c : found.faces) {
    if (face_points_.contains(c.face)) continue;
    const Eigen::Vector3d& b = c.barycentric;
    if (OnTheCrackAlready(RestAt(c.face, b), c.face)) continue;
    int largest = 0, smallest = 0;
    b.maxCoeff(&largest);
    b.minCoeff(&smallest);
    const double share = SnapShare(c.face);
    VertexId low = c.face[(smallest + 1) % 3], high = c.face[(smallest + 2) % 3];
    double fraction = b[(smallest + 2) % 3] / (b[(smallest + 1) % 3] + b[(smallest + 2) % 3]);
    if (Index(high) < Index(low)) std::swap(low, high), fraction = 1 - fraction;
    const bool stays = StaysInTheFace(c, share, low, high, from);
    // The corner's, where it may snap: within the share of the corner, or, for a crossing that
    // stays a point of the face, within the share of its two edges (a point beside both fans
    // flat pieces).
    const bool near_corner = b[largest] > 1 - share || (stays && (b.array() < share).count() == 2);
    if (near_corner && MaySnap(c.face[largest])) {
      Snap(c.face[largest], touched);
      continue;
    }
    if (b[smallest] < share && !stays) {
      // Beside the edge opposite the smallest weight: that edge's crossing.
      RecordEdgeCrossing(low, high, fraction, EdgeCrossingFrom::kSweep, touched);
    } else {
      face_points_[c.face] = {FacePointOffEdges(b, share)};
      const std::vector<TetId> units = UnitsAround({c.face[0], c.face[1], c.face[2]});
      touched->insert(touched->end(), units.begin(), units.end());
    }
  }
}

bool CrackCutter::StaysInTheFace(const FaceCrossing& c, double share, VertexId low, VertexId high,
                                 FaceCrossingsFrom from) const {
  if (from == FaceCrossingsFrom::kBladeLeft) return true;
  const Eigen::Vector3d& b = c.barycentric;
  // Beside the tissue's surface, off an edge of it (not on it, to rounding), the crossing stays
  // a point of the face, moved off its edges (face_point_weights.h): taken at the edge, the crack
  // would end on the surface, and the blade's cut under it would be lost.
  if (b.minCoeff() > kMinSnapFraction && !surface_.HasFace(c.face) && surface_.HasEdge(low, high)) {
    return true;
  }
  // Where the blade is withdrawn, a crossing beside an edge the crack crossed already stays a
  // point of the face if that edge's point is the face's only one: taken at the edge, it would be
  // dropped (the edge keeps its point), and with it the crack the face had up to the blade (one
  // point traces nothing). Not where moving it off the edges would take it farther than
  // kWithdrawnPointShift from the blade.
  if (from != FaceCrossingsFrom::kWithdrawal || !edge_points_.contains(MakeEdgeKey(low, high))) {
    return false;
  }
  return OwnPointsOf(c.face).size() == 1 &&
         (RestAt(c.face, FacePointOffEdges(b, share)) - RestAt(c.face, b)).norm() <=
             kWithdrawnPointShift * LengthsOf(c.face).tissue_edge();
}

Eigen::Vector3d CrackCutter::RestAt(const FaceKey& face, const Eigen::Vector3d& barycentric) const {
  return barycentric[0] * mesh_->rest_position(face[0]) +
         barycentric[1] * mesh_->rest_position(face[1]) +
         barycentric[2] * mesh_->rest_position(face[2]);
}

bool CrackCutter::CrackFaceWithin(
    const Eigen::Vector3d& x, std::span<const VertexId> origins, double reach,
    absl::FunctionRef<bool(TetId, const std::array<VertexId, 3>&, const FaceKey&, const CrackFace&)>
        counts) const {
  for (const VertexId o : origins) {
    for (const TetId t : parting_.TetsAround(*mesh_, o)) {
      const mesh::TetVertices& c = mesh_->tet(t);
      for (const auto& f : mesh::kTetFaces) {
        const std::array<VertexId, 3> ids = {c[f[0]], c[f[1]], c[f[2]]};
        const FaceKey key = parting_.OriginKey(ids[0], ids[1], ids[2]);
        const auto face = crack_.find(key);
        if (face != crack_.end() &&
            geometry::DistanceToTriangle(x, mesh_->rest_position(key[0]),
                                         mesh_->rest_position(key[1]),
                                         mesh_->rest_position(key[2])) < reach &&
            counts(t, ids, key, face->second)) {
          return true;
        }
      }
    }
  }
  return false;
}

bool CrackCutter::OnTheCrackAlready(const Eigen::Vector3d& x,
                                    std::span<const VertexId> origins) const {
  std::size_t visit = poses_;
  for (const auto& [root, since] : group_since_) visit = std::min(visit, since);
  // None made before the visit: nothing to look for.
  if (crack_faces_since_.empty() || crack_faces_since_.begin()->first >= visit) return false;
  // The reach is that of the tets there (the coverage of a cut is judged by its tet's mean edge):
  // an element's own length is longer for a tet's long edge, and a crack farther than a tet's
  // tolerance from the blade does not cover what it cuts.
  return CrackFaceWithin(
      x, origins, Reach(UnitsAround({origins.begin(), origins.end()})),
      [&](TetId t, const std::array<VertexId, 3>& ids, const FaceKey& key, const CrackFace& face) {
        if (face.since >= visit) return false;
        // Shut, the face has a tet on either side.
        if (mesh_->TetsAroundFace(ids[0], ids[1], ids[2]).size() > 1) return false;
        // An open unit's own crack faces are the crack being made, up to the blade.
        const auto owner = open_.find(UnitOf(t));
        return owner == open_.end() ||
               !std::binary_search(owner->second.crack.begin(), owner->second.crack.end(), key);
      });
}

void CrackCutter::RecordEdgeCrossing(VertexId low, VertexId high, double fraction,
                                     EdgeCrossingFrom from, std::vector<TetId>* touched) {
  const EdgeKey key = MakeEdgeKey(low, high);
  if (edge_points_.contains(key)) return;
  // What is cut stays cut: a crossing the crack made before already covers adds nothing.
  if (OnTheCrackAlready(
          (1 - fraction) * mesh_->rest_position(low) + fraction * mesh_->rest_position(high),
          std::array<VertexId, 2>{low, high})) {
    return;
  }
  const std::vector<TetId> units = UnitsAround({low, high});
  // A swept crossing that may not snap moves off the corner. One the blade leaves stays where the
  // pieces around stood on it: moved, the crack would jump as the blade goes (in a live cut, the
  // liver's progressive rows of the stability matrix blew up).
  const std::optional<double> at = EdgePointOffCorners(
      low, high, fraction, from, from == EdgeCrossingFrom::kSweep, units, touched);
  if (!at) return;
  edge_points_[key] = {*at};
  touched->insert(touched->end(), units.begin(), units.end());
}

std::optional<double> CrackCutter::EdgePointOffCorners(VertexId low, VertexId high, double fraction,
                                                       EdgeCrossingFrom from, bool may_move,
                                                       const std::vector<TetId>& units,
                                                       std::vector<TetId>* touched) {
  const double share = SnapShare(std::array<VertexId, 2>{low, high});
  // The least snapping (the fraction at its minimum) moves no crossing for quality either.
  const double sliver_share = snap_fraction_ > kMinSnapFraction ? kSliverSnapScale * share : 0;
  const double from_corner = std::min(fraction, 1 - fraction);
  if (from_corner >= std::max(share, sliver_share)) return fraction;
  const VertexId nearer = fraction <= 0.5 ? low : high;
  if (from_corner >= share && !BisectionLeavesSliver(low, high, fraction, units) &&
      !IsThinCorner(nearer, nearer == low ? high : low, units)) {
    return fraction;
  }
  if (MaySnap(nearer, from)) {
    Snap(nearer, touched);
    return std::nullopt;
  }
  if (!may_move) return fraction;
  const double length = (mesh_->rest_position(low) - mesh_->rest_position(high)).norm();
  const double moved =
      std::min({std::max(share, sliver_share), from_corner + Reach(units) / length, 0.5});
  return nearer == low ? moved : 1 - moved;
}

bool CrackCutter::BisectionLeavesSliver(VertexId low, VertexId high, double fraction,
                                        const std::vector<TetId>& units) const {
  const Eigen::Vector3d point =
      (1 - fraction) * mesh_->rest_position(low) + fraction * mesh_->rest_position(high);
  for (const TetId u : units) {
    const mesh::TetVertices corners = CornersOf(u);
    std::array<Eigen::Vector3d, 4> x;
    for (int k = 0; k < 4; ++k) x[k] = mesh_->rest_position(corners[k]);
    for (int k = 0; k < 4; ++k) {
      if (corners[k] != low && corners[k] != high) continue;
      std::array<Eigen::Vector3d, 4> half = x;  // the half without corners[k]
      half[k] = point;
      if (geometry::SmallestDihedralDeg(half[0], half[1], half[2], half[3]) < kSliverAngleDeg) {
        return true;
      }
    }
  }
  return false;
}

bool CrackCutter::IsThinCorner(VertexId corner, VertexId other,
                               const std::vector<TetId>& units) const {
  const Eigen::Vector3d at = mesh_->rest_position(corner);
  const Eigen::Vector3d along = (mesh_->rest_position(other) - at).normalized();
  const double cosine = std::cos(kThinCornerDeg * M_PI / 180);
  for (const TetId u : units) {
    for (const VertexId w : CornersOf(u)) {
      if (w == corner || w == other) continue;
      if (along.dot((mesh_->rest_position(w) - at).normalized()) > cosine) return true;
    }
  }
  return false;
}

void CrackCutter::SnapVerticesNear(const std::vector<TetId>& units, std::vector<TetId>* touched) {
  absl::flat_hash_set<VertexId> seen;
  for (const TetId u : units) {
    const mesh::TetVertices corners = CornersOf(u), placed = PlacedCorners(u);
    double edges = 0;
    for (const auto& [i, j] : mesh::kTetEdges) {
      edges += (mesh_->current_position(placed[i]) - mesh_->current_position(placed[j])).norm();
    }
    const double within = snap_fraction_ * edges / 6;
    for (int k = 0; k < 4; ++k) {
      const VertexId v = corners[k];
      if (on_crack_.contains(v) || IsInnerPoint(v) || !seen.insert(v).second) continue;
      if (DistanceToStep(mesh_->current_position(placed[k])) < within && MaySnap(v)) {
        Snap(v, touched);
      }
    }
  }
}

bool CrackCutter::SnapWouldLayCrackOnSurface(VertexId v, double reach) const {
  if (!surface_.HasVertex(v) || !step_) return false;
  const auto& [from, to] = *step_;
  const Eigen::Vector3d& x = mesh_->current_position(v);
  // The crack's front: the tip's path near the point of the swept surface nearest the vertex,
  // under the surface there, the vertex on the heel's side of it (the blade came in through the
  // surface there and went no deeper; a vertex beyond the tip snaps: the crack then reaches it).
  const Eigen::Vector3d nearest = NearestOnStep(x);
  const geometry::ClosestPoints front =
      geometry::ClosestPointsOfSegments(from.tip, to.tip, nearest, nearest);
  const Eigen::Vector3d tip = from.tip + front.s * (to.tip - from.tip);
  const Eigen::Vector3d normal = surface_.Normal(*mesh_, v);
  const Eigen::Vector3d blade = from.heel - from.tip + to.heel - to.tip;
  if (front.distance < reach && (tip - x).dot(normal) < 0 && (x - tip).dot(blade) > 0) {
    return true;
  }
  // The blade sweeping along the surface there.
  Eigen::Vector3d swept = (from.heel - from.tip).cross(to.heel - from.tip);
  if (swept.squaredNorm() == 0) swept = (to.heel - from.tip).cross(to.tip - from.tip);
  if (swept.squaredNorm() == 0) return true;  // the blade did not move: where it lies is all
  return std::abs(swept.normalized().dot(normal)) > kAlongSurfaceCosine;
}

Eigen::Vector3d CrackCutter::NearestOnStep(const Eigen::Vector3d& x) const {
  const auto& [from, to] = *step_;
  const Eigen::Vector3d p = geometry::ClosestPointOnTriangle(x, from.tip, from.heel, to.heel);
  const Eigen::Vector3d q = geometry::ClosestPointOnTriangle(x, from.tip, to.heel, to.tip);
  return (p - x).squaredNorm() < (q - x).squaredNorm() ? p : q;
}

double CrackCutter::DistanceToStep(const Eigen::Vector3d& x) const {
  return step_ ? (NearestOnStep(x) - x).norm() : 0;
}

bool CrackCutter::MaySnap(VertexId v, EdgeCrossingFrom from) const {
  const std::vector<TetId> units = UnitsAround({v});
  const double distance = DistanceToStep(mesh_->current_position(v));
  const double reach = Reach(units);
  if (distance > reach) return false;
  // Where the blade lay across an edge and left it, the pieces around stood on its point: that
  // snaps as anywhere, so the crack does not jump as the blade goes.
  if (from != EdgeCrossingFrom::kSweep) return true;
  // The blade through the vertex (to the least snapping) takes it.
  if (distance <= kMinSnapFraction / kSnapReach * reach) return true;
  // Where the blade came in through the tissue's surface beside a vertex of it, snapping moves
  // the crack's rim there: farther than the reach, the cut along the rim would be lost (an
  // oblique blade passes nearer the vertex than its way in does).
  const std::optional<double> entry = DistanceToTheEntry(v);
  if (entry && *entry > reach) return false;
  // A vertex of the tissue's surface the blade swept past stays off the crack where the crack
  // would then lie on the surface, and what the blade cut under it be lost.
  return !SnapWouldLayCrackOnSurface(v, reach);
}

std::optional<double> CrackCutter::DistanceToTheEntry(VertexId v) const {
  if (!step_) return std::nullopt;
  const auto swept = SweptTriangles(step_->first, step_->second);
  const Eigen::Vector3d& x = mesh_->current_position(v);
  std::optional<double> nearest;
  for (const auto& triangle : surface_.TrianglesAt(v)) {
    const auto at = [&](int k) { return mesh_->current_position(triangle[k]); };
    for (const auto& s : swept) {
      const auto crossing = geometry::TrianglesCross(at(0), at(1), at(2), s[0], s[1], s[2]);
      if (!crossing) continue;
      const double d = geometry::DistanceToSegment(x, (*crossing)[0], (*crossing)[1]);
      nearest = nearest ? std::min(*nearest, d) : d;
    }
  }
  return nearest;
}

double CrackCutter::Reach(const std::vector<TetId>& units) const {
  double edge = std::numeric_limits<double>::infinity();
  for (const TetId u : units) {
    edge = std::min(edge, LengthsOf(CornersOf(u)).tissue_edge());
  }
  return kSnapReach * edge;
}

double CrackCutter::SnapShare(std::span<const VertexId> corners) const {
  const Lengths lengths = LengthsOf(corners);
  const double own = lengths.mean_edge;
  return own > 0 ? snap_fraction_ * lengths.tissue_edge() / own : snap_fraction_;
}

void CrackCutter::Snap(VertexId v, std::vector<TetId>* touched) {
  if (!on_crack_.insert(v).second) return;
  ++statistics_.snapped_vertices;
  snapped_at_[v] = poses_;
  const std::vector<TetId> units = UnitsAround({v});
  touched->insert(touched->end(), units.begin(), units.end());
  absl::flat_hash_set<VertexId> beside;
  for (const TetId u : units) {
    for (const VertexId w : CornersOf(u)) {
      if (w != v && on_crack_.contains(w)) beside.insert(w);
    }
  }
  for (const VertexId w : beside) {
    const auto at = snapped_at_.find(w);
    if (at == snapped_at_.end()) continue;  // on the crack from the start: EdgeOnCrack
    // From the pose before the earlier snap's step to this one.
    const Eigen::Vector3d middle = 0.5 * (mesh_->current_position(v) + mesh_->current_position(w));
    if (SweptNear(middle, std::min(at->second, poses_) - 1, poses_,
                  kJoinReach / kSnapReach * Reach(UnitsAround({v, w})))) {
      joined_.insert(MakeEdgeKey(v, w));
    }
  }
}

bool CrackCutter::SweptNear(const Eigen::Vector3d& x, std::size_t first, std::size_t last,
                            double reach) const {
  if (first < swept_.first()) return true;  // too long ago to tell
  bool near = false;
  swept_.ForEachStepNear(first, last, x, x, reach, [&](std::size_t i) {
    near = DistanceToSweep(x, swept_.at(i), swept_.at(i + 1)) <= reach;
    return !near;
  });
  return near;
}

bool CrackCutter::EdgeOnCrack(VertexId a, VertexId b) const {
  return !snapped_at_.contains(a) || !snapped_at_.contains(b) ||
         joined_.contains(MakeEdgeKey(a, b));
}

}  // namespace kerf::cut
