// One tet and the points a crack may leave on it, with positions, for tests of splits
// (cut/crack_split.h) and of cones' apexes (cut/cone_apex.h).
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <functional>
#include <map>
#include <utility>

#include "cut/crack_split.h"
#include "geometry/tet_measures.h"
#include "mesh/mesh_ids.h"
#include "mesh/tet_mesh.h"

namespace kerf::cut {

// One tet and the points a crack may leave on it, with positions, for checking splits.
class OneTet {
 public:
  OneTet() {
    corners_ = {mesh::VertexId(0), mesh::VertexId(1), mesh::VertexId(2), mesh::VertexId(3)};
    at_ = {{0, {0, 0, 0}}, {1, {1, 0, 0}}, {2, {0.2, 1, 0}}, {3, {0.3, 0.3, 1}}};
  }
  Eigen::Vector3d Rest(mesh::VertexId v) const { return at_.at(static_cast<int>(v)); }
  std::function<Eigen::Vector3d(mesh::VertexId)> RestOf() const {
    return [this](mesh::VertexId v) { return Rest(v); };
  }

  // A point at `t` along the edge between corners i and j (shared by the faces at it).
  void CutEdge(int i, int j, double t) {
    const mesh::VertexId v = Add((1 - t) * Rest(corners_[i]) + t * Rest(corners_[j]));
    edge_points_[{std::min(i, j), std::max(i, j)}] = v;
  }
  // A point inside face k at the given weights on its corners (kTetFaces order).
  void PointInFace(int k, Eigen::Vector3d w) {
    const auto& f = mesh::kTetFaces[k];
    face_points_[k] = Add(w[0] * Rest(corners_[f[0]]) + w[1] * Rest(corners_[f[1]]) +
                          w[2] * Rest(corners_[f[2]]));
  }
  void CornerOnCrack(int i) { on_crack_[i] = true; }

  TetCrack Crack() {
    std::array<FacePoints, 4> points;
    for (int k = 0; k < 4; ++k) {
      const auto& f = mesh::kTetFaces[k];
      FacePoints& p = points[k];
      for (int j = 0; j < 3; ++j) {
        const int a = f[j], b = f[(j + 1) % 3];
        if (const auto it = edge_points_.find({std::min(a, b), std::max(a, b)});
            it != edge_points_.end()) {
          p.on_edge[j] = it->second;
        }
        p.corner_on_crack[j] = on_crack_[f[j]];
      }
      if (face_points_.contains(k)) p.inside = face_points_[k];
      p.corners = {corners_[f[0]], corners_[f[1]], corners_[f[2]]};
      if (NeedsHub(p)) {
        Eigen::Vector3d middle = Eigen::Vector3d::Zero();
        for (int j = 0; j < 3; ++j) middle += Rest(*p.on_edge[j]) / 3;
        p.inside = Add(middle);
      }
    }
    return MakeTetCrack(corners_, points);
  }
  mesh::VertexId Apex(const Eigen::Vector4d& w) {
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k) x += w[k] * Rest(corners_[k]);
    return Add(x);
  }
  // The barycentric weights of `x` on the corners.
  Eigen::Vector4d Weights(const Eigen::Vector3d& x) const {
    Eigen::Matrix3d frame;
    for (int k = 0; k < 3; ++k) frame.col(k) = Rest(corners_[k + 1]) - Rest(corners_[0]);
    const Eigen::Vector3d w = frame.lu().solve(x - Rest(corners_[0]));
    return {1 - w.sum(), w.x(), w.y(), w.z()};
  }
  double Volume(const mesh::TetVertices& t) const {
    return geometry::SignedVolume(Rest(t[0]), Rest(t[1]), Rest(t[2]), Rest(t[3]));
  }
  const mesh::TetVertices& corners() const { return corners_; }

 private:
  mesh::VertexId Add(const Eigen::Vector3d& x) {
    const int id = 100 + static_cast<int>(at_.size());
    at_[id] = x;
    return mesh::VertexId(id);
  }
  mesh::TetVertices corners_;
  std::map<int, Eigen::Vector3d> at_;
  std::map<std::pair<int, int>, mesh::VertexId> edge_points_;
  std::map<int, mesh::VertexId> face_points_;
  std::array<bool, 4> on_crack_ = {false, false, false, false};
};

// Corner 3 cut off by a tilted plane: a crack across the tet.
inline OneTet CornerThreeCutOff() {
  OneTet tet;
  tet.CutEdge(3, 0, 0.7);
  tet.CutEdge(3, 1, 0.5);
  tet.CutEdge(3, 2, 0.6);
  return tet;
}

}  // namespace kerf::cut
