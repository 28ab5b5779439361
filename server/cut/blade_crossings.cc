#include "cut/blade_crossings.h"

#include <algorithm>
#include <cmath>

#include "absl/container/flat_hash_map.h"
#include "absl/container/flat_hash_set.h"
#include "cut/element_keys.h"
#include "geometry/moving_crossing.h"
#include "geometry/segment_box.h"
#include "geometry/segment_distance.h"
#include "geometry/segment_triangle_intersection.h"
#include "geometry/tet_measures.h"
#include "mesh/mesh_quality.h"

namespace kerf::cut {
namespace {

using mesh::Index;
using mesh::TetId;
using mesh::VertexId;

// The tip's path passes through an edge when it comes this near it, in edge lengths.
constexpr double kThroughEdge = 1e-9;
// A sweep's tets are looked for near the blade, not in the sweep's whole box, where the box holds
// more than this many times the cells of the tube around the blade that holds them (a blade
// long and oblique to the axes); else the box's tets are hardly more, and cheaper to find.
constexpr double kNarrowedShare = 3;

}  // namespace

std::optional<double> BladeCrossings::TipPathThroughEdge(const BladePose& from, const BladePose& to,
                                                         VertexId low, VertexId high) const {
  const Eigen::Vector3d& a = mesh_->current_position(low);
  const Eigen::Vector3d& b = mesh_->current_position(high);
  const geometry::ClosestPoints c = geometry::ClosestPointsOfSegments(from.tip, to.tip, a, b);
  if (c.distance > kThroughEdge * (b - a).norm() || c.s == 0) return std::nullopt;
  return c.t;
}

absl::StatusOr<BladeCrossings> BladeCrossings::Create(const mesh::TetMesh* mesh, double cell_size) {
  // A tenth of a cell: a query near the blade reads about twice the tets it keeps (at a quarter,
  // five times), while a vertex the tissue carries a cell re-registers its tets ten times.
  absl::StatusOr<TetGrid> grid = TetGrid::Build(*mesh, cell_size, 0.1 * cell_size);
  if (!grid.ok()) return grid.status();
  return BladeCrossings(mesh, *std::move(grid));
}

Eigen::Vector3d BladeCrossings::MovedSincePrevious(VertexId v) const {
  return Remembers(v) ? Eigen::Vector3d(mesh_->current_position(v) - previous_[Index(v)])
                      : Eigen::Vector3d::Zero();
}

namespace {

// Whether boxes [a_low, a_high] and [b_low, b_high] meet.
bool BoxesMeet(const Eigen::Vector3d& a_low, const Eigen::Vector3d& a_high,
               const Eigen::Vector3d& b_low, const Eigen::Vector3d& b_high) {
  return (a_low.array() <= b_high.array()).all() && (a_high.array() >= b_low.array()).all();
}

}  // namespace

std::vector<TetId> BladeCrossings::Near(const Eigen::Vector3d& low,
                                        const Eigen::Vector3d& high) const {
  std::vector<TetId> near = grid_.Candidates(low, high);
  std::erase_if(near, [&](TetId t) {
    if (!mesh_->IsAlive(t)) return true;
    const mesh::Bounds box = mesh::MeasureTetBounds(*mesh_, t, /*current=*/true);
    return !BoxesMeet(box.low, box.high, low, high);
  });
  return near;
}

std::vector<TetId> BladeCrossings::NearSweep(const BladePose& from, const BladePose& to,
                                             double margin, double box_margin) const {
  // The swept surface lies within the larger of the tip's and the heel's moves of the blade's
  // edge at one pose or the other.
  const double move = std::max((to.tip - from.tip).norm(), (to.heel - from.heel).norm());
  const double within = margin + move;
  const auto meets = [&](const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
    return geometry::SegmentMeetsBox(from.tip, from.heel, lo, hi, within) ||
           geometry::SegmentMeetsBox(to.tip, to.heel, lo, hi, within);
  };
  const Eigen::Vector3d low =
      from.tip.cwiseMin(from.heel).cwiseMin(to.tip).cwiseMin(to.heel).array() - box_margin;
  const Eigen::Vector3d high =
      from.tip.cwiseMax(from.heel).cwiseMax(to.tip).cwiseMax(to.heel).array() + box_margin;
  // The cells of the box and of the tube (each widened by the cell a tet is registered in).
  const double cell = grid_.cell_size();
  const Eigen::Vector3d cells = ((high - low) / cell).array() + 3;
  const double along = ((from.heel - from.tip).norm() + 2 * within) / cell + 3;
  const double across = 2 * within / cell + 3;
  const bool narrow = cells.prod() > kNarrowedShare * along * across * across;
  std::vector<TetId> near =
      narrow ? grid_.Candidates(low, high, meets) : grid_.Candidates(low, high);
  std::erase_if(near, [&](TetId t) {
    if (!mesh_->IsAlive(t)) return true;
    const mesh::Bounds box = mesh::MeasureTetBounds(*mesh_, t, /*current=*/true);
    return !BoxesMeet(box.low, box.high, low, high) || (narrow && !meets(box.low, box.high));
  });
  return near;
}

Crossings BladeCrossings::Find(
    const BladePose& from, const BladePose& to, const std::vector<mesh::TetVertices>& tets,
    const std::function<bool(VertexId, VertexId)>& skip_edge,
    const std::function<bool(const std::array<VertexId, 3>&)>& skip_face) const {
  // Each vertex's motion once (a vertex is a corner of a few of the tets, and of several edges
  // and faces in each).
  absl::flat_hash_map<VertexId, geometry::Motion> motions;
  motions.reserve(tets.size());
  // By value: a later lookup may move the map's entries.
  const auto motion = [&](VertexId v) -> geometry::Motion {
    const auto [it, inserted] = motions.try_emplace(v);
    if (inserted) {
      const Eigen::Vector3d& x = mesh_->current_position(v);
      it->second = {x - MovedSincePrevious(v), x};
    }
    return it->second;
  };
  const geometry::Motion tip{from.tip, to.tip}, heel{from.heel, to.heel};
  // The box of the tip's path: an edge whose box it misses is not passed through.
  const Eigen::Vector3d tip_low = from.tip.cwiseMin(to.tip), tip_high = from.tip.cwiseMax(to.tip);
  Crossings found;
  absl::flat_hash_set<std::uint64_t> tested_edges;
  absl::flat_hash_set<std::array<VertexId, 3>> tested_faces;
  // A tet mesh has about 1.2 edges and 2 faces a tet; those near a blade at the boundary more.
  tested_edges.reserve(2 * tets.size());
  tested_faces.reserve(3 * tets.size());
  for (const mesh::TetVertices& v : tets) {
    for (const auto& [i, j] : mesh::kTetEdges) {
      const VertexId lo = Index(v[i]) < Index(v[j]) ? v[i] : v[j];
      const VertexId hi = lo == v[i] ? v[j] : v[i];
      if (!tested_edges.insert(MakeEdgeKey(lo, hi)).second || skip_edge(lo, hi)) continue;
      const geometry::Motion a = motion(lo), b = motion(hi);
      if (const auto c = geometry::FirstEdgeCrossing(a, b, tip, heel)) {
        found.edges.push_back({lo, hi, c->fraction});
        continue;
      }
      const Eigen::Vector3d slack =
          Eigen::Vector3d::Constant(2 * kThroughEdge * (a.to - b.to).norm());
      const Eigen::Vector3d overlap_low = (a.to.cwiseMin(b.to) - slack).cwiseMax(tip_low);
      const Eigen::Vector3d overlap_high = (a.to.cwiseMax(b.to) + slack).cwiseMin(tip_high);
      if ((overlap_low.array() > overlap_high.array()).any()) continue;
      if (const std::optional<double> at = TipPathThroughEdge(from, to, lo, hi)) {
        found.edges.push_back({lo, hi, *at});
      }
    }
    for (const auto& f : mesh::kTetFaces) {
      std::array<VertexId, 3> face = {v[f[0]], v[f[1]], v[f[2]]};
      std::sort(face.begin(), face.end());
      if (!tested_faces.insert(face).second || skip_face(face)) continue;
      if (const auto c = geometry::FirstPointCrossing(tip, motion(face[0]), motion(face[1]),
                                                      motion(face[2]))) {
        found.faces.push_back({face, c->barycentric});
      }
    }
  }
  return found;
}

std::vector<FaceCrossing> BladeCrossings::FacesCrossedBy(
    const BladePose& pose, const std::vector<mesh::TetVertices>& tets,
    const std::function<bool(const std::array<VertexId, 3>&)>& skip_face) const {
  std::vector<std::array<VertexId, 3>> faces;  // of the tets whose boxes the blade meets
  for (const mesh::TetVertices& v : tets) {
    Eigen::Vector3d low = mesh_->current_position(v[0]), high = low;
    for (int i = 1; i < 4; ++i) {
      low = low.cwiseMin(mesh_->current_position(v[i]));
      high = high.cwiseMax(mesh_->current_position(v[i]));
    }
    if (!geometry::SegmentMeetsBox(pose.tip, pose.heel, low, high, 1e-6 * (high - low).norm())) {
      continue;
    }
    for (const auto& f : mesh::kTetFaces) {
      std::array<VertexId, 3> face = {v[f[0]], v[f[1]], v[f[2]]};
      std::sort(face.begin(), face.end());
      faces.push_back(face);
    }
  }
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  std::vector<FaceCrossing> crossed;
  for (const std::array<VertexId, 3>& face : faces) {
    const auto c = geometry::IntersectSegmentTriangle(
        pose.tip, pose.heel, mesh_->current_position(face[0]), mesh_->current_position(face[1]),
        mesh_->current_position(face[2]));
    if (c && !skip_face(face)) crossed.push_back({face, c->barycentric});
  }
  return crossed;
}

absl::Status BladeCrossings::Remember(const std::vector<VertexId>& vertices) {
  ++remembered_;
  previous_.resize(mesh_->vertex_index_bound());
  remembered_at_.resize(mesh_->vertex_index_bound(), 0);
  for (const VertexId v : vertices) {
    // (A vertex is a corner of several of the tets whose vertices are given.)
    if (!mesh_->IsAlive(v) || remembered_at_[Index(v)] == remembered_) continue;
    previous_[Index(v)] = mesh_->current_position(v);
    remembered_at_[Index(v)] = remembered_;
  }
  return grid_.RefreshTopology();
}

bool BladeCrossings::BladeMeets(const mesh::TetVertices& v, const BladePose& pose) const {
  std::array<Eigen::Vector3d, 4> x;
  for (int i = 0; i < 4; ++i) x[i] = mesh_->current_position(v[i]);
  const Eigen::Vector3d lo = x[0].cwiseMin(x[1]).cwiseMin(x[2].cwiseMin(x[3]));
  const Eigen::Vector3d hi = x[0].cwiseMax(x[1]).cwiseMax(x[2].cwiseMax(x[3]));
  if (!geometry::SegmentMeetsBox(pose.tip, pose.heel, lo, hi, 1e-6 * (hi - lo).norm())) {
    return false;
  }
  for (const Eigen::Vector3d& end : {pose.tip, pose.heel}) {
    if (geometry::ContainsPoint(x[0], x[1], x[2], x[3], end)) return true;
  }
  for (const auto& f : mesh::kTetFaces) {
    if (geometry::IntersectSegmentTriangle(pose.tip, pose.heel, x[f[0]], x[f[1]], x[f[2]])) {
      return true;
    }
  }
  return false;
}

}  // namespace kerf::cut
