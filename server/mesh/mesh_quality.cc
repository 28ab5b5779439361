#include "mesh/mesh_quality.h"

#include <algorithm>
#include <limits>

#include "geometry/tet_measures.h"

namespace kerf::mesh {

Bounds MeasureBounds(const TetMesh& mesh, bool current) {
  Bounds bounds;
  bool first = true;
  for (const VertexId v : mesh.vertices()) {
    const Eigen::Vector3d& p = current ? mesh.current_position(v) : mesh.rest_position(v);
    bounds.low = first ? p : Eigen::Vector3d(bounds.low.cwiseMin(p));
    bounds.high = first ? p : Eigen::Vector3d(bounds.high.cwiseMax(p));
    first = false;
  }
  return bounds;
}

double MeanEdgeLength(const TetMesh& mesh) {
  double sum = 0;
  std::size_t count = 0;
  for (const TetId t : mesh.tets()) {
    const TetVertices& v = mesh.tet(t);
    for (const auto& [i, j] : kTetEdges) {
      sum += (mesh.current_position(v[i]) - mesh.current_position(v[j])).norm();
      ++count;
    }
  }
  return count ? sum / static_cast<double>(count) : 0;
}

MeshQuality MeasureMeshQuality(const TetMesh& mesh, double sliver_angle_deg) {
  MeshQuality q;
  if (mesh.tet_count() == 0) return q;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  q.min_volume = q.min_edge_length = q.min_dihedral_deg = q.min_radius_ratio = kInf;
  q.max_volume = q.max_edge_length = q.max_dihedral_deg = -kInf;
  double radius_ratio_sum = 0;
  for (const TetId t : mesh.tets()) {
    const TetVertices& v = mesh.tet(t);
    const geometry::TetMeasures m =
        geometry::MeasureTet(mesh.rest_position(v[0]), mesh.rest_position(v[1]),
                             mesh.rest_position(v[2]), mesh.rest_position(v[3]));
    ++q.tets;
    q.total_volume += m.signed_volume;
    q.min_volume = std::min(q.min_volume, m.signed_volume);
    q.max_volume = std::max(q.max_volume, m.signed_volume);
    q.min_edge_length = std::min(q.min_edge_length, m.min_edge_length);
    q.max_edge_length = std::max(q.max_edge_length, m.max_edge_length);
    q.min_dihedral_deg = std::min(q.min_dihedral_deg, m.min_dihedral_deg);
    q.max_dihedral_deg = std::max(q.max_dihedral_deg, m.max_dihedral_deg);
    q.min_radius_ratio = std::min(q.min_radius_ratio, m.radius_ratio);
    radius_ratio_sum += m.radius_ratio;
    if (m.min_dihedral_deg < sliver_angle_deg) ++q.slivers;
    const auto bin = static_cast<std::size_t>(std::clamp(m.min_dihedral_deg / 10.0, 0.0, 7.0));
    ++q.min_dihedral_histogram[bin];
  }
  q.mean_radius_ratio = radius_ratio_sum / static_cast<double>(q.tets);
  return q;
}

}  // namespace kerf::mesh
