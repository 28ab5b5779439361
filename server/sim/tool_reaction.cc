#include "sim/tool_reaction.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <vector>

#include "geometry/tet_measures.h"

namespace kerf::sim {
namespace {

// Whether p is inside the tet (current positions), faces included.
bool Inside(const mesh::TetMesh& m, const mesh::TetVertices& v, const Eigen::Vector3d& p) {
  return geometry::ContainsPoint(m.current_position(v[0]), m.current_position(v[1]),
                                 m.current_position(v[2]), m.current_position(v[3]), p);
}

}  // namespace

ToolReaction MeasureToolReaction(const Simulation& simulation, const cut::BladePose& pose,
                                 const std::optional<cut::BladePose>& previous) {
  ToolReaction reaction;
  const cut::Cutter* cutter = simulation.cutter();
  if (cutter == nullptr) return reaction;
  const std::vector<mesh::TetVertices> holding = cutter->TetsHoldingBlade(pose);
  if (holding.empty()) return reaction;
  const mesh::TetMesh& m = simulation.mesh();
  std::vector<mesh::VertexId> vertices;
  for (const mesh::TetVertices& corners : holding) {
    for (const mesh::VertexId v : corners) vertices.push_back(v);
  }
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  // (K u)_v = K_vv u_v + sum over v's neighbours w of K_vw u_w: what v's tissue holds.
  const fem::TensorMassModel& model = simulation.model();
  const std::vector<Eigen::Vector3d>& u = simulation.state().displacement;
  for (const mesh::VertexId v : vertices) {
    Eigen::Vector3d f = model.vertex_tensor(v) * u[mesh::Index(v)];
    std::vector<mesh::VertexId> neighbours;
    for (const mesh::TetId t : m.TetsAround(v)) {
      for (const mesh::VertexId w : m.tet(t)) {
        if (w != v) neighbours.push_back(w);
      }
    }
    std::sort(neighbours.begin(), neighbours.end());
    neighbours.erase(std::unique(neighbours.begin(), neighbours.end()), neighbours.end());
    for (const mesh::VertexId w : neighbours) {
      const fem::EdgeTensor* e = model.FindEdge(v, w);
      if (e == nullptr) continue;
      f += (e->a == v ? e->k_ab : Eigen::Matrix3d(e->k_ab.transpose())) * u[mesh::Index(w)];
    }
    reaction.force += f;
    reaction.torque += (m.current_position(v) - pose.tip).cross(f);
  }
  // The cutting resistance, on the length of blade inside the tets that hold it.
  constexpr int kSamples = 32;
  int inside = 0;
  for (int k = 0; k < kSamples; ++k) {
    const Eigen::Vector3d p = pose.tip + (k + 0.5) / kSamples * (pose.heel - pose.tip);
    if (std::any_of(holding.begin(), holding.end(),
                    [&](const mesh::TetVertices& t) { return Inside(m, t, p); })) {
      ++inside;
    }
  }
  reaction.length_inside = (pose.heel - pose.tip).norm() * inside / kSamples;
  if (previous) {
    const Eigen::Vector3d motion = pose.tip - previous->tip;
    if (motion.norm() > 0) {
      const Eigen::Vector3d resistance =
          -kCuttingResistance * reaction.length_inside * motion.normalized();
      reaction.force += resistance;
      const Eigen::Vector3d middle = pose.tip + 0.5 * (pose.heel - pose.tip);
      reaction.torque += (middle - pose.tip).cross(resistance);
    }
  }
  return reaction;
}

}  // namespace kerf::sim
