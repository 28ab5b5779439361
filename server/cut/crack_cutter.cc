#include "cut/crack_cutter.h"

#include <Eigen/LU>
#include <algorithm>

#include "absl/strings/str_cat.h"
#include "base/check.h"
#include "geometry/point_triangle_distance.h"
#include "geometry/tet_measures.h"

namespace kerf::cut {
namespace {

using mesh::Index;
using mesh::TetId;
using mesh::VertexId;

constexpr VertexId kNoVertex{0xffffffffu};

// A cone's apex is kept at least this far (barycentric) from the tet's faces.
constexpr double kApexMargin = 0.1;

std::uint64_t MakeEdgeKey(VertexId a, VertexId b) {
  const std::uint64_t lo = std::min(Index(a), Index(b)), hi = std::max(Index(a), Index(b));
  return lo << 32 | hi;
}

}  // namespace

absl::StatusOr<CrackCutter> CrackCutter::Create(mesh::TetMesh* mesh, double cell_size,
                                                const BladeLimits& limits, double snap_fraction) {
  if (!(snap_fraction >= 0 && snap_fraction < 0.5)) {
    return absl::InvalidArgumentError(
        absl::StrCat("the snap fraction must be in [0, 0.5), got ", snap_fraction));
  }
  absl::StatusOr<BladeCrossings> crossings = BladeCrossings::Create(mesh, cell_size);
  if (!crossings.ok()) return crossings.status();
  return CrackCutter(mesh, *std::move(crossings), limits,
                     std::max(snap_fraction, kMinSnapFraction));
}

TetId CrackCutter::SourceTet(TetId t) const {
  const auto it = source_tet_.find(t);
  return it == source_tet_.end() ? t : it->second;
}

std::vector<MadeVertex> CrackCutter::TakeMadeVertices() {
  std::vector<MadeVertex> made;
  for (const MadeVertex& m : made_vertices_) {
    if (mesh_->IsAlive(m.vertex)) made.push_back(m);
  }
  made_vertices_.clear();
  return made;
}

absl::Status CrackCutter::ApplyPose(const BladePose& pose) {
  if (absl::Status valid = ValidatePose(pose, previous_ ? &*previous_ : nullptr, limits_);
      !valid.ok()) {
    return valid;
  }
  if (previous_) {
    const Crossings found = crossings_.Find(
        *previous_, pose,
        [&](VertexId a, VertexId b) { return edge_points_.contains(MakeEdgeKey(a, b)); },
        [&](const std::array<VertexId, 3>& face) { return face_points_.contains(face); });
    std::vector<TetId> touched = RecordCrossings(found);
    SnapVerticesNear(*previous_, pose, found.near, &touched);
    Join(touched);
    SplitReadyGroups(&pose);
  }
  previous_ = pose;
  return crossings_.Remember(pose);
}

void CrackCutter::Finish() {
  if (previous_) {
    // The crack reaches where the blade was: its crossings of faces are where the crack ends.
    Crossings at_blade;
    at_blade.faces = crossings_.FacesCrossedBy(
        *previous_, [&](const std::array<VertexId, 3>& f) { return face_points_.contains(f); });
    Join(RecordCrossings(at_blade));
  }
  SplitReadyGroups(nullptr);
  previous_.reset();
}

std::vector<TetId> CrackCutter::RecordCrossings(const Crossings& found) {
  std::vector<TetId> touched;
  for (const EdgeCrossing& c : found.edges) {
    RecordEdgeCrossing(c.low, c.high, c.fraction, &touched);
  }
  for (const FaceCrossing& c : found.faces) {
    if (face_points_.contains(c.face)) continue;
    const Eigen::Vector3d& b = c.barycentric;
    int largest = 0, smallest = 0;
    b.maxCoeff(&largest);
    b.minCoeff(&smallest);
    if (b[largest] > 1 - snap_fraction_) {
      Snap(c.face[largest], &touched);
    } else if (b[smallest] < snap_fraction_) {
      // Beside the edge opposite the smallest weight: that edge's crossing.
      const int i = (smallest + 1) % 3, j = (smallest + 2) % 3;
      VertexId low = c.face[i], high = c.face[j];
      double fraction = b[j] / (b[i] + b[j]);
      if (Index(high) < Index(low)) std::swap(low, high), fraction = 1 - fraction;
      RecordEdgeCrossing(low, high, fraction, &touched);
    } else {
      face_points_[c.face] = {b};
      for (const TetId t : mesh_->TetsAroundFace(c.face[0], c.face[1], c.face[2])) {
        touched.push_back(t);
      }
    }
  }
  return touched;
}

void CrackCutter::RecordEdgeCrossing(VertexId low, VertexId high, double fraction,
                                     std::vector<TetId>* touched) {
  const EdgeKey key = MakeEdgeKey(low, high);
  if (edge_points_.contains(key)) return;
  if (fraction < snap_fraction_) {
    Snap(low, touched);
  } else if (fraction > 1 - snap_fraction_) {
    Snap(high, touched);
  } else {
    edge_points_[key] = {fraction};
    for (const TetId t : mesh_->TetsAroundEdge(low, high)) touched->push_back(t);
  }
}

void CrackCutter::SnapVerticesNear(const BladePose& from, const BladePose& to,
                                   const std::vector<TetId>& near, std::vector<TetId>* touched) {
  absl::flat_hash_set<VertexId> seen;
  for (const TetId t : near) {
    const mesh::TetVertices& corners = mesh_->tet(t);
    double edges = 0;
    for (const auto& [i, j] : mesh::kTetEdges) {
      edges += (mesh_->current_position(corners[i]) - mesh_->current_position(corners[j])).norm();
    }
    const double within = snap_fraction_ * edges / 6;
    for (const VertexId v : corners) {
      if (on_crack_.contains(v) || !seen.insert(v).second) continue;
      const Eigen::Vector3d& x = mesh_->current_position(v);
      const double distance =
          std::min(geometry::DistanceToTriangle(x, from.tip, from.heel, to.heel),
                   geometry::DistanceToTriangle(x, from.tip, to.heel, to.tip));
      if (distance < within) Snap(v, touched);
    }
  }
}

void CrackCutter::Snap(VertexId v, std::vector<TetId>* touched) {
  if (!on_crack_.insert(v).second) return;
  ++statistics_.snapped_vertices;
  for (const TetId t : mesh_->TetsAround(v)) touched->push_back(t);
}

void CrackCutter::Join(const std::vector<TetId>& tets) {
  for (const TetId t : tets) {
    if (group_of_.try_emplace(t, t).second) members_[t] = {t};
  }
  for (std::size_t i = 1; i < tets.size(); ++i) {
    TetId a = group_of_.at(tets[0]), b = group_of_.at(tets[i]);
    if (a == b) continue;
    if (members_.at(a).size() < members_.at(b).size()) std::swap(a, b);
    std::vector<TetId> moved = std::move(members_.at(b));
    members_.erase(b);
    for (const TetId t : moved) group_of_[t] = a;
    std::vector<TetId>& into = members_.at(a);
    into.insert(into.end(), moved.begin(), moved.end());
  }
}

void CrackCutter::SplitReadyGroups(const BladePose* pose) {
  std::vector<TetId> ready;
  for (const auto& [root, members] : members_) {
    const bool blade_in =
        pose != nullptr && std::any_of(members.begin(), members.end(), [&](TetId t) {
          return crossings_.BladeMeets(mesh_->tet(t), *pose);
        });
    if (!blade_in) ready.push_back(root);
  }
  std::sort(ready.begin(), ready.end());  // the same order whatever the map's
  for (const TetId root : ready) {
    std::vector<TetId> group = std::move(members_.at(root));
    members_.erase(root);
    for (const TetId t : group) group_of_.erase(t);
    std::sort(group.begin(), group.end());
    SplitGroup(group);
  }
}

void CrackCutter::SplitGroup(const std::vector<TetId>& group) {
  std::vector<VertexId> on_new_crack;
  for (const TetId t : group) {
    KERF_CHECK(mesh_->IsAlive(t));
    const mesh::TetVertices corners = mesh_->tet(t);
    const TetCrack crack = MakeTetCrack(corners, PointsOf(corners));
    std::optional<CrackSplit> split = SplitWithoutApex(
        crack, [&](VertexId v) -> Eigen::Vector3d { return mesh_->rest_position(v); });
    if (!split) split = SplitAsCone(crack, MakeApex(crack));
    for (const auto& face : split->crack_faces) {
      crack_.insert(MakeFaceKey(face[0], face[1], face[2]));
      on_new_crack.insert(on_new_crack.end(), face.begin(), face.end());
    }
    if (split->kind == CrackSplitKind::kWhole) continue;
    if (!MadeByCut(t)) ++statistics_.cut_tets;
    ++statistics_.tets_by_case[static_cast<std::size_t>(split->cut_case)];
    Replace(t, split->tets);
  }
  // Points whose edges and faces are split are vertices now.
  absl::erase_if(edge_points_, [&](const auto& e) { return e.second.vertex != kNoVertex; });
  absl::erase_if(face_points_, [&](const auto& f) { return f.second.vertex != kNoVertex; });
  std::sort(on_new_crack.begin(), on_new_crack.end());
  on_new_crack.erase(std::unique(on_new_crack.begin(), on_new_crack.end()), on_new_crack.end());
  const Parting parting = PartVertices(mesh_, on_new_crack, &crack_);
  for (const auto& [old_tet, new_tet] : parting.replaced) {
    source_tet_[new_tet] = SourceTet(old_tet);
    source_tet_.erase(old_tet);
    // A waiting tet keeps its place in its group.
    if (const auto it = group_of_.find(old_tet); it != group_of_.end()) {
      const TetId joined = it->second;
      group_of_.erase(it);
      group_of_[new_tet] = joined;
      std::vector<TetId>& members = members_.at(joined);
      std::replace(members.begin(), members.end(), old_tet, new_tet);
    }
  }
  for (const VertexCopy& c : parting.copies) {
    parted_from_[c.copy] = PartedFrom(c.from);
    if (on_crack_.contains(c.from)) on_crack_.insert(c.copy);
    made_vertices_.push_back({c.copy, {c.from, c.from, c.from, c.from}, {1, 0, 0, 0}});
    ++statistics_.parted_vertices;
  }
}

std::array<FacePoints, 4> CrackCutter::PointsOf(const mesh::TetVertices& corners) {
  std::array<FacePoints, 4> points;
  for (int k = 0; k < 4; ++k) {
    FacePoints& p = points[k];
    for (int j = 0; j < 3; ++j) p.corners[j] = corners[mesh::kTetFaces[k][j]];
    for (int j = 0; j < 3; ++j) {
      const VertexId a = p.corners[j], b = p.corners[(j + 1) % 3];
      if (edge_points_.contains(MakeEdgeKey(a, b))) p.on_edge[j] = EdgePointVertex(a, b);
      p.corner_on_crack[j] = on_crack_.contains(p.corners[j]);
    }
    const FaceKey key = MakeFaceKey(p.corners[0], p.corners[1], p.corners[2]);
    if (!face_points_.contains(key) && NeedsHub(p)) {
      // The hub: the middle of the three edge points, on the face's vertices in key order.
      Eigen::Vector3d weights = Eigen::Vector3d::Zero();
      for (int j = 0; j < 3; ++j) {
        const VertexId a = p.corners[j], b = p.corners[(j + 1) % 3];
        const EdgePoint& e = edge_points_.at(MakeEdgeKey(a, b));
        const VertexId low = Index(a) < Index(b) ? a : b, high = low == a ? b : a;
        for (int i = 0; i < 3; ++i) {
          if (key[i] == low) weights[i] += (1 - e.fraction) / 3;
          if (key[i] == high) weights[i] += e.fraction / 3;
        }
      }
      face_points_[key] = {weights};
    }
    if (face_points_.contains(key)) p.inside = FacePointVertex(key);
  }
  return points;
}

VertexId CrackCutter::EdgePointVertex(VertexId a, VertexId b) {
  EdgePoint& e = edge_points_.at(MakeEdgeKey(a, b));
  if (e.vertex == kNoVertex) {
    const VertexId low = Index(a) < Index(b) ? a : b, high = low == a ? b : a;
    e.vertex = MakeVertex({low, high, low, low}, {1 - e.fraction, e.fraction, 0, 0});
  }
  return e.vertex;
}

VertexId CrackCutter::FacePointVertex(const FaceKey& key) {
  FacePoint& f = face_points_.at(key);
  if (f.vertex == kNoVertex) {
    const Eigen::Vector3d& b = f.barycentric;
    f.vertex = MakeVertex({key[0], key[1], key[2], key[0]}, {b[0], b[1], b[2], 0});
  }
  return f.vertex;
}

VertexId CrackCutter::MakeApex(const TetCrack& crack) {
  const mesh::TetVertices& c = crack.corners;
  Eigen::Vector4d weights = Eigen::Vector4d::Constant(0.25);
  const std::vector<VertexId> points = TracePoints(crack);
  if (HasInnerCrack(crack)) {
    Eigen::Vector3d middle = Eigen::Vector3d::Zero();
    for (const VertexId v : points) middle += mesh_->rest_position(v);
    middle /= static_cast<double>(points.size());
    Eigen::Matrix3d m;
    for (int k = 0; k < 3; ++k)
      m.col(k) = mesh_->rest_position(c[k + 1]) - mesh_->rest_position(c[0]);
    const Eigen::Vector3d w = m.fullPivLu().solve(middle - mesh_->rest_position(c[0]));
    const Eigen::Vector4d at(1 - w.sum(), w.x(), w.y(), w.z());
    // Pulled towards the tet's middle until every weight is at least the margin.
    double pull = 0;
    for (int k = 0; k < 4; ++k) {
      if (at[k] < kApexMargin) pull = std::max(pull, (kApexMargin - at[k]) / (0.25 - at[k]));
    }
    weights = at + std::min(pull, 1.0) * (Eigen::Vector4d::Constant(0.25) - at);
  }
  return MakeVertex(c, weights);
}

VertexId CrackCutter::MakeVertex(const std::array<VertexId, 4>& from,
                                 const Eigen::Vector4d& weights) {
  Eigen::Vector3d rest = Eigen::Vector3d::Zero(), current = Eigen::Vector3d::Zero();
  for (int k = 0; k < 4; ++k) {
    if (weights[k] == 0) continue;
    rest += weights[k] * mesh_->rest_position(from[k]);
    current += weights[k] * mesh_->current_position(from[k]);
  }
  const VertexId v = mesh_->AddVertex(rest, current);
  made_vertices_.push_back({v, from, weights});
  return v;
}

std::vector<TetId> CrackCutter::Replace(TetId t, const std::vector<mesh::TetVertices>& pieces) {
  const TetId source = SourceTet(t);
  if (MadeByCut(t)) --statistics_.new_tets;
  source_tet_.erase(t);
  KERF_CHECK(mesh_->RemoveTet(t).ok());
  std::vector<TetId> made;
  for (mesh::TetVertices piece : pieces) {
    const double volume =
        geometry::SignedVolume(mesh_->rest_position(piece[0]), mesh_->rest_position(piece[1]),
                               mesh_->rest_position(piece[2]), mesh_->rest_position(piece[3]));
    KERF_CHECK(volume != 0);
    if (volume < 0) std::swap(piece[2], piece[3]);
    const absl::StatusOr<TetId> added = mesh_->AddTet(piece);
    KERF_CHECK(added.ok());
    source_tet_[*added] = source;
    ++statistics_.new_tets;
    made.push_back(*added);
  }
  return made;
}

}  // namespace kerf::cut
