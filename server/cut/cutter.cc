#include "cut/cutter.h"

#include <algorithm>
#include <cassert>
#include <numeric>
#include <utility>

#include "absl/strings/str_cat.h"
#include "geometry/segment_triangle_intersection.h"
#include "geometry/tet_measures.h"
#include "mesh/mesh_quality.h"

namespace kerf::cut {
namespace {

using mesh::Index;
using mesh::TetId;
using mesh::VertexId;

// Crossings closer than this (as a fraction of the edge, or a barycentric coordinate) to a
// vertex or an edge are degenerate: skipped until snapping handles them.
constexpr double kDegenerate = 1e-6;
constexpr VertexId kNoVertex{0xffffffffu};

std::uint64_t MakeEdgeKey(VertexId a, VertexId b) {
  if (Index(b) < Index(a)) std::swap(a, b);
  return (std::uint64_t{Index(a)} << 32) | Index(b);
}

std::array<VertexId, 3> MakeFaceKey(VertexId a, VertexId b, VertexId c) {
  std::array<VertexId, 3> key = {a, b, c};
  std::sort(key.begin(), key.end());
  return key;
}

}  // namespace

absl::StatusOr<Cutter> Cutter::Create(mesh::TetMesh* mesh, double cell_size,
                                      const BladeLimits& limits) {
  absl::StatusOr<TetGrid> grid = TetGrid::Build(*mesh, cell_size, 0.25 * cell_size);
  if (!grid.ok()) return grid.status();
  return Cutter(mesh, *std::move(grid), limits);
}

absl::Status Cutter::ApplyPose(const BladePose& pose) {
  if (absl::Status s = ValidatePose(pose, previous_ ? &*previous_ : nullptr, limits_); !s.ok()) {
    return s;
  }
  if (absl::Status s = grid_.RefreshTopology(); !s.ok()) return s;
  if (previous_) {
    const std::vector<TetId> near = RecordHits(*previous_, pose);
    SplitReadyGroups(&pose, &near);
  }
  previous_ = pose;
  return absl::OkStatus();
}

void Cutter::Finish() {
  SplitReadyGroups(nullptr, nullptr);
  previous_.reset();
}

std::vector<TetId> Cutter::RecordHits(const BladePose& from, const BladePose& to) {
  const std::array<std::array<Eigen::Vector3d, 3>, 2> swept = {
      {{from.tip, from.heel, to.heel}, {from.tip, to.heel, to.tip}}};
  Eigen::Vector3d low = from.tip.cwiseMin(from.heel).cwiseMin(to.tip).cwiseMin(to.heel);
  Eigen::Vector3d high = from.tip.cwiseMax(from.heel).cwiseMax(to.tip).cwiseMax(to.heel);
  absl::flat_hash_set<EdgeKey> tested_edges;
  absl::flat_hash_set<FaceKey, FaceKeyHash> tested_faces;
  std::vector<EdgeKey> new_edges;
  std::vector<FaceKey> new_faces;
  // The grid lists the tets in the cells the swept surface's box covers; keep those whose own
  // box meets it (the blade can only be inside those, too).
  std::vector<TetId> near = grid_.Candidates(low, high);
  std::erase_if(near, [&](TetId t) {
    const mesh::Bounds box = mesh::MeasureTetBounds(*mesh_, t, /*current=*/true);
    return (box.low.array() > high.array()).any() || (box.high.array() < low.array()).any();
  });
  for (const TetId t : near) {
    const mesh::TetVertices v = mesh_->tet(t);
    for (const auto& [i, j] : mesh::kTetEdges) {
      const EdgeKey key = MakeEdgeKey(v[i], v[j]);
      if (edge_hits_.contains(key) || !tested_edges.insert(key).second) continue;
      const VertexId lo = Index(v[i]) < Index(v[j]) ? v[i] : v[j];
      const VertexId hi = lo == v[i] ? v[j] : v[i];
      for (const auto& tri : swept) {
        const auto crossing = geometry::IntersectSegmentTriangle(
            mesh_->current_position(lo), mesh_->current_position(hi), tri[0], tri[1], tri[2]);
        if (!crossing) continue;
        if (crossing->t < kDegenerate || crossing->t > 1 - kDegenerate) {
          ++statistics_.degenerate_hits;
        } else {
          edge_hits_[key] = {crossing->t};
          new_edges.push_back(key);
        }
        break;
      }
    }
    for (const auto& face : mesh::kTetFaces) {
      const FaceKey key = MakeFaceKey(v[face[0]], v[face[1]], v[face[2]]);
      if (face_hits_.contains(key) || !tested_faces.insert(key).second) continue;
      const auto crossing = geometry::IntersectSegmentTriangle(
          from.tip, to.tip, mesh_->current_position(key[0]), mesh_->current_position(key[1]),
          mesh_->current_position(key[2]));
      if (!crossing) continue;
      if (crossing->barycentric.minCoeff() < kDegenerate) {
        ++statistics_.degenerate_hits;
      } else {
        face_hits_[key] = {crossing->barycentric};
        new_faces.push_back(key);
      }
    }
  }
  for (const EdgeKey key : new_edges) {
    Join(mesh_->TetsAroundEdge(VertexId(static_cast<std::uint32_t>(key >> 32)),
                               VertexId(static_cast<std::uint32_t>(key))));
  }
  for (const FaceKey& key : new_faces) Join(mesh_->TetsAroundFace(key[0], key[1], key[2]));
  return near;
}

TetId Cutter::GroupOf(TetId t) {
  TetId root = t;
  while (group_of_.at(root) != root) root = group_of_.at(root);
  while (t != root) {  // path compression
    TetId& parent = group_of_.at(t);
    t = std::exchange(parent, root);
  }
  return root;
}

void Cutter::Join(std::span<const TetId> tets) {
  for (const TetId t : tets) {
    if (group_of_.try_emplace(t, t).second) members_[t] = {t};
  }
  for (std::size_t i = 1; i < tets.size(); ++i) {
    TetId a = GroupOf(tets[0]), b = GroupOf(tets[i]);
    if (a == b) continue;
    if (members_[a].size() < members_[b].size()) std::swap(a, b);
    std::vector<TetId>& into = members_[a];
    std::vector<TetId>& from = members_[b];
    into.insert(into.end(), from.begin(), from.end());
    members_.erase(b);
    group_of_[b] = a;
  }
}

bool Cutter::BladeInside(TetId t, const BladePose& pose) const {
  const mesh::TetVertices& v = mesh_->tet(t);
  std::array<Eigen::Vector3d, 4> x;
  for (int i = 0; i < 4; ++i) x[i] = mesh_->current_position(v[i]);
  for (const Eigen::Vector3d& end : {pose.tip, pose.heel}) {
    if (geometry::ContainsPoint(x[0], x[1], x[2], x[3], end)) return true;
  }
  for (const auto& face : mesh::kTetFaces) {
    if (geometry::IntersectSegmentTriangle(pose.tip, pose.heel, x[face[0]], x[face[1]],
                                           x[face[2]])) {
      return true;
    }
  }
  return false;
}

std::vector<TetId> Cutter::TetsHoldingBlade(const BladePose& pose) const {
  std::vector<TetId> near =
      grid_.Candidates(pose.tip.cwiseMin(pose.heel), pose.tip.cwiseMax(pose.heel));
  std::erase_if(near, [&](TetId t) { return !mesh_->IsAlive(t) || !BladeInside(t, pose); });
  return near;
}

void Cutter::SplitReadyGroups(const BladePose* pose, const std::vector<TetId>* near) {
  absl::flat_hash_set<TetId> blade_inside;  // roots of groups the blade is still in
  if (near != nullptr) {
    for (const TetId t : *near) {
      if (group_of_.contains(t) && !blade_inside.contains(GroupOf(t)) && BladeInside(t, *pose)) {
        blade_inside.insert(GroupOf(t));
      }
    }
  }
  std::vector<std::vector<TetId>> ready;
  for (const auto& [root, members] : members_) {
    if (!blade_inside.contains(root)) ready.push_back(members);
  }
  for (std::vector<TetId>& group : ready) {
    std::sort(group.begin(), group.end());  // deterministic order
  }
  std::sort(ready.begin(), ready.end());
  for (std::vector<TetId>& group : ready) SplitGroup(std::move(group));
}

VertexId Cutter::MakeVertex(const std::array<VertexId, 3>& from, const Eigen::Vector3d& weights) {
  Eigen::Vector3d rest = Eigen::Vector3d::Zero(), current = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    rest += weights[k] * mesh_->rest_position(from[k]);
    current += weights[k] * mesh_->current_position(from[k]);
  }
  const VertexId v = mesh_->AddVertex(rest, current);
  made_vertices_.push_back({v, from, weights});
  return v;
}

std::vector<MadeVertex> Cutter::TakeMadeVertices() {
  std::vector<MadeVertex> made;
  for (const MadeVertex& m : made_vertices_) {
    if (mesh_->IsAlive(m.vertex)) made.push_back(m);  // dropped hits removed theirs
  }
  made_vertices_.clear();
  return made;
}

std::vector<EdgeCut> Cutter::EdgeCutsOf(const mesh::TetVertices& corners) {
  std::vector<EdgeCut> cuts;
  for (const auto& [i, j] : mesh::kTetEdges) {
    const auto it = edge_hits_.find(MakeEdgeKey(corners[i], corners[j]));
    if (it == edge_hits_.end()) continue;
    EdgeHit& hit = it->second;
    const bool i_low = Index(corners[i]) < Index(corners[j]);
    const VertexId lo = i_low ? corners[i] : corners[j], hi = i_low ? corners[j] : corners[i];
    if (hit.near_low == kNoVertex) {
      const Eigen::Vector3d weights(1 - hit.fraction, hit.fraction, 0);
      hit.near_low = MakeVertex({lo, hi, lo}, weights);
      hit.near_high = MakeVertex({lo, hi, lo}, weights);
    }
    cuts.push_back({i_low ? i : j, i_low ? j : i, hit.near_low, hit.near_high});
  }
  return cuts;
}

std::vector<FacePoint> Cutter::FacePointsOf(const mesh::TetVertices& corners) const {
  std::vector<FacePoint> points;
  for (int k = 0; k < 4; ++k) {
    const auto& face = mesh::kTetFaces[k];
    const auto it =
        face_hits_.find(MakeFaceKey(corners[face[0]], corners[face[1]], corners[face[2]]));
    if (it != face_hits_.end()) points.push_back({k, it->second.vertex});
  }
  return points;
}

TetId Cutter::SourceTet(TetId t) const {
  const auto it = source_tet_.find(t);
  return it == source_tet_.end() ? t : it->second;
}

void Cutter::SplitGroup(std::vector<TetId> group) {
  const auto rest = [&](VertexId v) { return mesh_->rest_position(v); };
  while (true) {
    // Make the vertices of the group's face hits, then every split.
    for (const TetId t : group) {
      const mesh::TetVertices v = mesh_->tet(t);
      for (const auto& face : mesh::kTetFaces) {
        const auto it = face_hits_.find(MakeFaceKey(v[face[0]], v[face[1]], v[face[2]]));
        if (it != face_hits_.end() && it->second.vertex == kNoVertex) {
          it->second.vertex = MakeVertex(it->first, it->second.barycentric);
        }
      }
    }
    std::vector<std::pair<TetId, TetSplit>> splits;
    std::vector<TetId> failed;
    for (const TetId t : group) {
      const mesh::TetVertices corners = mesh_->tet(t);
      const std::vector<EdgeCut> cuts = EdgeCutsOf(corners);
      const std::vector<FacePoint> faces = FacePointsOf(corners);
      if (cuts.empty() && faces.empty()) continue;  // its hits were dropped
      TetSplit split;
      if (faces.empty()) split = SplitCompletelyCutTet(corners, cuts);
      if (faces.size() == 2) split = SplitCrackedTet(corners, cuts, {faces[0], faces[1]}, rest);
      if (split.tets.empty()) {
        failed.push_back(t);
      } else {
        splits.emplace_back(t, std::move(split));
      }
    }
    if (failed.empty()) {
      for (auto& [t, split] : splits) {
        const mesh::TetVertices corners = mesh_->tet(t);
        (void)mesh_->RemoveTet(t);
        for (mesh::TetVertices piece : split.tets) {
          if (geometry::SignedVolume(rest(piece[0]), rest(piece[1]), rest(piece[2]),
                                     rest(piece[3])) < 0) {
            std::swap(piece[2], piece[3]);
          }
          const absl::StatusOr<TetId> added = mesh_->AddTet(piece);
          assert(added.ok());
          source_tet_[*added] = SourceTet(t);
        }
        ++statistics_.cut_tets;
        statistics_.new_tets += split.tets.size();
        ++statistics_.tets_by_case[static_cast<int>(split.cut_case)];
        for (const auto& [i, j] : mesh::kTetEdges)
          edge_hits_.erase(MakeEdgeKey(corners[i], corners[j]));
        for (const auto& f : mesh::kTetFaces) {
          face_hits_.erase(MakeFaceKey(corners[f[0]], corners[f[1]], corners[f[2]]));
        }
      }
      break;
    }
    // Drop the hits of the tets that cannot be split, with the vertices made for them (no
    // tet uses those yet), and look at the group again.
    for (const TetId t : failed) {
      const mesh::TetVertices v = mesh_->tet(t);
      for (const auto& [i, j] : mesh::kTetEdges) {
        const auto it = edge_hits_.find(MakeEdgeKey(v[i], v[j]));
        if (it == edge_hits_.end()) continue;
        for (const VertexId made : {it->second.near_low, it->second.near_high}) {
          if (made != kNoVertex) (void)mesh_->RemoveVertex(made);
        }
        edge_hits_.erase(it);
        ++statistics_.dropped_hits;
      }
      for (const auto& f : mesh::kTetFaces) {
        const auto it = face_hits_.find(MakeFaceKey(v[f[0]], v[f[1]], v[f[2]]));
        if (it == face_hits_.end()) continue;
        if (it->second.vertex != kNoVertex) (void)mesh_->RemoveVertex(it->second.vertex);
        face_hits_.erase(it);
        ++statistics_.dropped_hits;
      }
    }
  }
  for (const TetId t : group) {
    members_.erase(t);
    group_of_.erase(t);
  }
}

}  // namespace kerf::cut
