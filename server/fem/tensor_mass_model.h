// The paper's tensor-mass form of linear FEM (section 5): the global stiffness split into a
// 3x3 tensor per vertex (K_ii) and per edge (K_ij), with mass lumped at the vertices, kept in
// step with a mesh as its tets change.
//
// Incremental by construction: the model follows the mesh through the mesh's change log.
// SyncWithMesh() subtracts the contributions of tets removed since the last sync and adds
// those of tets added, at a cost proportional to the tets changed; the result equals a model
// built from scratch to rounding. Per-vertex and per-edge data grow with the mesh there and
// nowhere else.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/status/statusor.h"
#include "fem/material.h"
#include "mesh/tet_mesh.h"

namespace kerf::fem {

// The stiffness between two vertices, a < b by index: the force on a due to b's displacement
// is k_ab u_b, and on b due to a's is k_ab^T u_a.
struct EdgeTensor {
  mesh::VertexId a;
  mesh::VertexId b;
  Eigen::Matrix3d k_ab;
  std::uint32_t tets;  // live tets sharing this edge
};

// A live tet as the model added it: what an element-by-element force law (fem::ElasticForces)
// needs to rebuild its stiffness K_ab = weight (lambda g_a g_b^T + mu g_b g_a^T +
// mu (g_a . g_b) I) without the corners.
struct TetElement {
  std::array<Eigen::Vector3d, 4> gradients;  // of the shape functions on the rest shape, 1/m
  double weight;                             // rest volume (m^3) times the stiffness scale
};

class TensorMassModel {
 public:
  // Builds from every live tet of `mesh`, which must outlive the model and only change
  // through its own API. INVALID_ARGUMENT for an invalid material or a tet with zero rest
  // volume. `stiffness_scale`: see SetStiffnessScale.
  static absl::StatusOr<TensorMassModel> Create(
      const mesh::TetMesh& mesh, const Material& material,
      std::function<double(mesh::TetId)> stiffness_scale = nullptr);

  // Applies the mesh's tet additions and removals, and vertex moves (the tets around a moved
  // vertex are taken away as they were added and added anew), since the last sync.
  // INVALID_ARGUMENT (and nothing applied) if an added or moved tet has zero rest volume.
  // O(tets changed).
  absl::Status SyncWithMesh();
  // Whether the mesh has changed since the last sync (or creation).
  bool InSyncWithMesh() const { return synced_ == mesh_->change_log().Mark(); }
  // The mesh's change log as of the last sync: the model reads none before it.
  mesh::ChangeMark synced() const { return synced_; }
  // A tet carries its stiffness times `scale(t)` (in [0, 1], taken when it is added) and all
  // its mass: a progressive cut's thin pieces on the blade are softened
  // (cut::CrackCutter::StiffnessScale). For tets added (or reshaped) from the next sync on;
  // null: every scale is 1. A tet is taken away as it was added.
  void SetStiffnessScale(std::function<double(mesh::TetId)> scale) {
    stiffness_scale_ = std::move(scale);
  }

  // f = K u: the paper's Eq. 2, f_i = K_ii u_i + sum_j K_ij u_j. u and f are indexed by vertex
  // index and must hold mesh.vertex_index_bound() entries. Only the entries of active vertices
  // are written (K has nothing elsewhere); the others are left as they were. The elastic force
  // the body exerts on its vertices is -f. O(active vertices + edges).
  void MultiplyStiffness(std::span<const Eigen::Vector3d> u, std::span<Eigen::Vector3d> f) const;
  // The same product for the rows of `rows` (vertex indices) only: f_i for i in rows, from u
  // at i and its neighbours; nothing else read or written. O(rows x their edges).
  void MultiplyStiffnessRows(std::span<const std::uint32_t> rows,
                             std::span<const Eigen::Vector3d> u,
                             std::span<Eigen::Vector3d> f) const;
  // The same rows edge by edge, as MultiplyStiffness (faster for many rows): `edges` (indices
  // into edges()) must hold every edge at a row once. The other end of a listed edge that is
  // not a row also receives its share (scratch). O(rows + edges listed).
  void MultiplyStiffnessOver(std::span<const std::uint32_t> rows,
                             std::span<const std::uint32_t> edges,
                             std::span<const Eigen::Vector3d> u,
                             std::span<Eigen::Vector3d> f) const;

  // The global 3n x 3n stiffness assembled from the tensors, n = vertex_index_bound().
  Eigen::SparseMatrix<double> AssembleStiffness() const;

  // Elastic energy u^T K u / 2.
  double ElasticEnergy(std::span<const Eigen::Vector3d> u) const;

  const Material& material() const { return material_; }
  const LameParameters& lame() const { return lame_; }
  // Tet t as it was added; t must be live and synced.
  const TetElement& element(mesh::TetId t) const { return elements_[mesh::Index(t)]; }
  const mesh::TetMesh& mesh() const { return *mesh_; }
  std::size_t vertex_count() const { return vertex_tensors_.size(); }
  const Eigen::Matrix3d& vertex_tensor(mesh::VertexId v) const {
    return vertex_tensors_[mesh::Index(v)];
  }
  // Lumped mass: rho V / 4 from each tet at the vertex.
  double mass(mesh::VertexId v) const { return masses_[mesh::Index(v)]; }
  std::span<const double> masses() const { return masses_; }
  std::span<const EdgeTensor> edges() const { return edges_; }
  // The indices of the vertices some tet uses (with mass and stiffness), ascending: fewer than
  // the mesh's vertex slots, which include removed vertices whose ids wait for reuse.
  std::span<const std::uint32_t> active_vertices() const { return active_; }
  // The tensor of the edge between a and b, or nullptr if no tet has that edge.
  const EdgeTensor* FindEdge(mesh::VertexId a, mesh::VertexId b) const;
  // The edges at vertex index i, as indices into edges().
  std::span<const std::uint32_t> edges_at(std::uint32_t i) const { return edges_at_[i]; }

 private:
  TensorMassModel(const mesh::TetMesh& mesh, const Material& material);

  void GrowToMesh();
  // Updates active_ after tets were added (their vertices become active) and vertices lost
  // their last tet (`emptied`). O(active + changed).
  void UpdateActive(std::span<const mesh::TetId> added, std::span<const mesh::VertexId> emptied);
  // Adds (sign +1, at its rest corners now) or subtracts (sign -1, at the rest positions it was
  // added with) the contributions of tet t on corners v (those it had when added).
  void Accumulate(mesh::TetId t, const mesh::TetVertices& v, double sign);

  const mesh::TetMesh* mesh_;
  Material material_;
  LameParameters lame_;
  mesh::ChangeMark synced_;
  std::vector<Eigen::Matrix3d> vertex_tensors_;
  std::vector<double> masses_;
  std::vector<EdgeTensor> edges_;
  std::vector<std::uint32_t> active_;
  std::vector<bool> is_active_;                                  // by vertex index
  absl::flat_hash_map<std::uint64_t, std::uint32_t> edge_slot_;  // edge key -> index in edges_
  std::vector<std::vector<std::uint32_t>> edges_at_;             // by vertex index
  // The rest corners each live tet was added with (by tet index), to take it away exactly
  // after its vertices moved.
  std::vector<std::array<Eigen::Vector3d, 4>> added_with_;
  std::vector<double> added_scale_;   // the stiffness scale each live tet was added with
  std::vector<TetElement> elements_;  // by tet index, of live tets
  std::function<double(mesh::TetId)> stiffness_scale_;
};

}  // namespace kerf::fem
