// What the subscribers of a session at one level have been sent, and the frames that move
// them on: each frame carries the net topology change since the previous one (O(changes) for
// tets and boundary triangles, read from the mesh's change log) and the positions or forces of
// the whole view.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "cut/blade.h"
#include "kerf/v1/frame.pb.h"
#include "mesh/tet_mesh.h"
#include "sim/simulation.h"

namespace kerf::service {

// The blade's reaction and the step statistics that every frame of one tick carries.
struct TickReport {
  double simulation_time = 0;  // s
  double blade_time = 0;       // s, on the cutter's clock (see Frame.blade_time)
  Eigen::Vector3d tool_force = Eigen::Vector3d::Zero();   // N
  Eigen::Vector3d tool_torque = Eigen::Vector3d::Zero();  // N m
  std::optional<cut::BladePose> blade;                    // the blade's last applied pose
  kerf::v1::StepStatistics statistics;
  // The elastic force -K u on every vertex slot (N), computed once per tick by the session
  // when a FORCES frame is due; empty otherwise. Valid during the tick only.
  std::span<const Eigen::Vector3d> nodal_forces;
};

// -K u on every vertex slot of the simulation. O(vertices + edges).
std::vector<Eigen::Vector3d> ComputeElasticForces(const sim::Simulation& simulation);

class LevelView {
 public:
  // An empty view: the first Advance lists everything as added. `simulation` must outlive it.
  LevelView(kerf::v1::Level level, const sim::Simulation& simulation);

  // The next frame, numbered `sequence` (more than the last; numbers may be skipped while
  // nobody watches): what changed since the previous frame, and the view's positions or forces
  // now. O(changes + vertices in the view).
  kerf::v1::Frame Advance(const TickReport& report, std::uint64_t sequence);

  // The whole view as of the last frame, with its sequence number (for a subscriber that joins
  // or falls behind). O(view).
  kerf::v1::Frame Keyframe() const;

  kerf::v1::Level level() const { return level_; }
  std::uint64_t sequence() const { return sequence_; }
  // The mesh's change log as of the last frame. A view may lose the history after it (it then
  // compares with the mesh, O(mesh), once).
  mesh::ChangeMark synced() const { return synced_; }

 private:
  struct Element {
    std::array<std::uint32_t, 4> vertices;  // 3 used for a triangle
    bool on_cut = false;
  };
  using FaceKey = std::array<std::uint32_t, 3>;
  struct FaceKeyHash {
    std::size_t operator()(const FaceKey& k) const { return absl::HashOf(k[0], k[1], k[2]); }
  };

  // Brings the element and vertex sets up to date, recording the net change in `frame`.
  void UpdateTets(kerf::v1::Frame* frame);
  void UpdateSurface(kerf::v1::Frame* frame);
  void UpdateAllVertices(kerf::v1::Frame* frame);
  void AddTriangle(const FaceKey& key, const std::array<std::uint32_t, 3>& vertices,
                   kerf::v1::Frame* frame);
  void RemoveTriangle(const FaceKey& key, kerf::v1::Frame* frame);
  void FillArrays(const TickReport& report, kerf::v1::Frame* frame) const;

  kerf::v1::Level level_;
  const sim::Simulation* simulation_;
  std::uint32_t original_vertex_bound_;  // vertices at or past it were made by cuts
  mesh::ChangeMark synced_;
  std::uint64_t sequence_ = 0;
  std::uint64_t topology_version_ = 0;
  absl::flat_hash_map<std::uint32_t, Element> elements_;
  // SURFACE: the boundary triangle on each boundary face, and how many use each vertex.
  absl::flat_hash_map<FaceKey, std::uint32_t, FaceKeyHash> triangle_of_face_;
  absl::flat_hash_map<std::uint32_t, std::uint32_t> triangles_using_vertex_;
  std::uint32_t next_triangle_id_ = 0;
  std::vector<std::uint32_t> vertices_;  // the view's vertices, increasing
  TickReport last_report_;               // without its nodal forces (they do not outlive the tick)
  std::string last_positions_, last_forces_;
};

// A keyframe made afresh from the model, independently of any view (for snapshots, and to
// check what subscribers reconstruct): triangles are numbered 0.. in ExtractBoundarySurface's
// order; FORCES takes the report's nodal forces. O(mesh).
kerf::v1::Frame MakeSnapshot(kerf::v1::Level level, const sim::Simulation& simulation,
                             std::uint32_t original_vertex_bound, std::uint64_t sequence,
                             const TickReport& report);

// SHA-256 of the model's whole state in float64 (see Frame.model_sha256). O(mesh).
std::string ModelSha256(const sim::Simulation& simulation);

// Appends x, y, z as little-endian float32.
void AppendFloat32(const Eigen::Vector3d& v, std::string* out);

}  // namespace kerf::service
