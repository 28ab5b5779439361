#include "cut/tissue_surface.h"

#include <Eigen/Geometry>
#include <cmath>

#include "mesh/boundary_surface.h"

namespace kerf::cut {

TissueSurface TissueSurface::Of(const mesh::TetMesh& mesh) {
  TissueSurface surface;
  for (const mesh::BoundaryTriangle& triangle : mesh::ExtractBoundarySurface(mesh)) {
    const auto& v = triangle.vertices;
    surface.faces_.insert(MakeFaceKey(v[0], v[1], v[2]));
    for (int i = 0; i < 3; ++i) {
      surface.vertices_.insert(v[i]);
      surface.triangles_[v[i]].push_back(v);
      surface.edges_.insert(MakeEdgeKey(v[i], v[(i + 1) % 3]));
    }
  }
  return surface;
}

Eigen::Vector3d TissueSurface::Normal(const mesh::TetMesh& mesh, mesh::VertexId v) const {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  const auto it = triangles_.find(v);
  if (it == triangles_.end()) return normal;
  for (const auto& t : it->second) {
    const Eigen::Vector3d& a = mesh.current_position(t[0]);
    normal += (mesh.current_position(t[1]) - a).cross(mesh.current_position(t[2]) - a);
  }
  return normal.normalized();
}

bool TissueSurface::SegmentOnFaceAtEdge(const mesh::TetMesh& mesh, mesh::VertexId a,
                                        mesh::VertexId b, const Eigen::Vector3d& p,
                                        const Eigen::Vector3d& q, double tolerance) const {
  const auto it = triangles_.find(a);
  if (it == triangles_.end()) return false;
  for (const auto& t : it->second) {
    if (t[0] != b && t[1] != b && t[2] != b) continue;
    const Eigen::Vector3d& o = mesh.current_position(t[0]);
    const Eigen::Vector3d n =
        (mesh.current_position(t[1]) - o).cross(mesh.current_position(t[2]) - o);
    if (n.squaredNorm() == 0) continue;
    const Eigen::Vector3d unit = n.normalized();
    if (std::abs(unit.dot(p - o)) <= tolerance && std::abs(unit.dot(q - o)) <= tolerance) {
      return true;
    }
  }
  return false;
}

}  // namespace kerf::cut
