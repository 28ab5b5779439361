#include "sim/tool_reaction.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <vector>

#include "base/check.h"
#include "geometry/tet_measures.h"

namespace kerf::sim {
namespace {

// Whether p is inside the tet (current positions), faces included.
bool Inside(const mesh::TetMesh& m, const mesh::TetVertices& v, const Eigen::Vector3d& p) {
  return geometry::ContainsPoint(m.current_position(v[0]), m.current_position(v[1]),
                                 m.current_position(v[2]), m.current_position(v[3]), p);
}

}  // namespace

ToolReaction MeasureToolReaction(const Simulation& simulation,
                                 std::span<const Eigen::Vector3d> elastic_forces,
                                 const cut::BladePose& pose,
                                 const std::optional<cut::BladePose>& previous) {
  ToolReaction reaction;
  const cut::CrackCutter* cutter = simulation.cutter();
  if (cutter == nullptr) return reaction;
  const std::vector<mesh::TetVertices> holding = cutter->TetsHoldingBlade(pose);
  if (holding.empty()) return reaction;
  const mesh::TetMesh& m = simulation.mesh();
  KERF_CHECK(elastic_forces.size() >= m.vertex_index_bound());
  std::vector<mesh::VertexId> vertices;
  for (const mesh::TetVertices& corners : holding) {
    for (const mesh::VertexId v : corners) vertices.push_back(v);
  }
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  for (const mesh::VertexId v : vertices) {
    const Eigen::Vector3d f = -elastic_forces[mesh::Index(v)];  // what v's tissue holds
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
