#include "mesh/cut_surface.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <tuple>

#include "absl/container/flat_hash_map.h"
#include "mesh/boundary_surface.h"

namespace kerf::mesh {

double MeasureCrackArea(const TetMesh& mesh) {
  using Point = std::tuple<double, double, double>;
  using Key = std::array<Point, 3>;
  absl::flat_hash_map<Key, int> count;
  const std::vector<BoundaryTriangle> faces = ExtractBoundarySurface(mesh);
  std::vector<Key> keys;
  keys.reserve(faces.size());
  for (const BoundaryTriangle& face : faces) {
    Key key;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& p = mesh.rest_position(face.vertices[k]);
      key[k] = {p.x(), p.y(), p.z()};
    }
    std::sort(key.begin(), key.end());
    ++count[key];
    keys.push_back(key);
  }
  double crack_area = 0;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    if (count[keys[i]] < 2) continue;
    const std::array<VertexId, 3>& v = faces[i].vertices;
    const Eigen::Vector3d& a = mesh.rest_position(v[0]);
    crack_area += 0.25 * (mesh.rest_position(v[1]) - a).cross(mesh.rest_position(v[2]) - a).norm();
  }
  return crack_area;
}

}  // namespace kerf::mesh
