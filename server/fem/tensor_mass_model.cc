#include "fem/tensor_mass_model.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <utility>

#include "absl/strings/str_cat.h"
#include "base/check.h"
#include "fem/linear_tet_element.h"

namespace kerf::fem {
namespace {

using mesh::Index;
using mesh::TetId;
using mesh::VertexId;

std::uint64_t EdgeKey(VertexId a, VertexId b) { return (std::uint64_t{Index(a)} << 32) | Index(b); }

std::array<Eigen::Vector3d, 4> RestCorners(const mesh::TetMesh& mesh, TetId t) {
  const mesh::TetVertices& v = mesh.tet(t);
  return {mesh.rest_position(v[0]), mesh.rest_position(v[1]), mesh.rest_position(v[2]),
          mesh.rest_position(v[3])};
}

absl::Status CheckRestVolumeNonZero(const mesh::TetMesh& mesh, TetId t) {
  const std::array<Eigen::Vector3d, 4> x = RestCorners(mesh, t);
  if ((x[1] - x[0]).cross(x[2] - x[0]).dot(x[3] - x[0]) == 0) {
    return absl::InvalidArgumentError(
        absl::StrCat("tet ", Index(t), " has zero rest volume: its stiffness is undefined"));
  }
  return absl::OkStatus();
}

}  // namespace

TensorMassModel::TensorMassModel(const mesh::TetMesh& mesh, const Material& material)
    : mesh_(&mesh),
      material_(material),
      lame_(CalcLameParameters(material.youngs_modulus, material.poisson_ratio)) {}

absl::StatusOr<TensorMassModel> TensorMassModel::Create(
    const mesh::TetMesh& mesh, const Material& material,
    std::function<double(mesh::TetId)> stiffness_scale) {
  if (absl::Status s = ValidateMaterial(material); !s.ok()) return s;
  for (const TetId t : mesh.tets()) {
    if (absl::Status s = CheckRestVolumeNonZero(mesh, t); !s.ok()) return s;
  }
  TensorMassModel model(mesh, material);
  model.stiffness_scale_ = std::move(stiffness_scale);
  model.GrowToMesh();
  std::vector<TetId> tets;
  for (const TetId t : mesh.tets()) {
    model.Accumulate(t, mesh.tet(t), +1);
    tets.push_back(t);
  }
  model.UpdateActive(tets, {});
  model.synced_ = mesh.change_log().Mark();
  return model;
}

absl::Status TensorMassModel::SyncWithMesh() {
  absl::StatusOr<mesh::MeshChanges> changes = mesh_->change_log().ChangesSince(synced_);
  if (!changes.ok()) return changes.status();
  // Tets that were in the model and are still in the mesh, around a moved vertex.
  std::vector<TetId> reshaped;
  for (const VertexId v : changes->moved_vertices) {
    for (const TetId t : mesh_->TetsAround(v)) {
      if (!std::binary_search(changes->added_tets.begin(), changes->added_tets.end(), t)) {
        reshaped.push_back(t);
      }
    }
  }
  std::sort(reshaped.begin(), reshaped.end());
  reshaped.erase(std::unique(reshaped.begin(), reshaped.end()), reshaped.end());
  for (const std::vector<TetId>* list : {&changes->added_tets, &reshaped}) {
    for (const TetId t : *list) {
      if (absl::Status s = CheckRestVolumeNonZero(*mesh_, t); !s.ok()) return s;
    }
  }
  GrowToMesh();
  for (std::size_t i = 0; i < changes->removed_tets.size(); ++i) {
    Accumulate(changes->removed_tets[i], changes->removed_tet_corners[i], -1);
  }
  for (const TetId t : reshaped) Accumulate(t, mesh_->tet(t), -1);
  for (const TetId t : reshaped) Accumulate(t, mesh_->tet(t), +1);
  // A vertex no tet uses any more (a temporary point of a progressive cut), or removed and its
  // id reused, has no mass or stiffness: exactly, not the rounding left by adding and taking
  // away.
  std::vector<VertexId> emptied = changes->removed_vertices;
  for (const mesh::TetVertices& corners : changes->removed_tet_corners) {
    for (const VertexId v : corners) {
      if (mesh_->IsAlive(v) && !mesh_->TetsAround(v).empty()) continue;
      emptied.push_back(v);
    }
  }
  for (const VertexId v : emptied) {
    masses_[Index(v)] = 0;
    vertex_tensors_[Index(v)].setZero();
  }
  for (const TetId t : changes->added_tets) Accumulate(t, mesh_->tet(t), +1);
  UpdateActive(changes->added_tets, emptied);
  synced_ = mesh_->change_log().Mark();
  return absl::OkStatus();
}

void TensorMassModel::GrowToMesh() {
  const std::size_t n = mesh_->vertex_index_bound();
  vertex_tensors_.resize(n, Eigen::Matrix3d::Zero());
  masses_.resize(n, 0.0);
  is_active_.resize(n, false);
  edges_at_.resize(n);
}

void TensorMassModel::UpdateActive(std::span<const TetId> added,
                                   std::span<const VertexId> emptied) {
  bool removed = false;
  for (const VertexId v : emptied) {
    removed = removed || is_active_[Index(v)];
    is_active_[Index(v)] = false;
  }
  if (removed) {
    std::erase_if(active_, [&](std::uint32_t i) { return !is_active_[i]; });
  }
  const std::size_t old_end = active_.size();
  for (const TetId t : added) {
    for (const VertexId v : mesh_->tet(t)) {
      if (is_active_[Index(v)] || masses_[Index(v)] <= 0) continue;
      is_active_[Index(v)] = true;
      active_.push_back(Index(v));
    }
  }
  std::sort(active_.begin() + static_cast<std::ptrdiff_t>(old_end), active_.end());
  std::inplace_merge(active_.begin(), active_.begin() + static_cast<std::ptrdiff_t>(old_end),
                     active_.end());
}

void TensorMassModel::Accumulate(TetId t, const mesh::TetVertices& v, double sign) {
  if (added_with_.size() <= Index(t)) {
    added_with_.resize(Index(t) + 1);
    added_scale_.resize(Index(t) + 1);
    elements_.resize(Index(t) + 1);
  }
  if (sign > 0) {
    added_with_[Index(t)] = RestCorners(*mesh_, t);
    added_scale_[Index(t)] = stiffness_scale_ ? stiffness_scale_(t) : 1.0;
  }
  const LinearTetStiffness k = ComputeLinearTetStiffness(added_with_[Index(t)], lame_);
  if (sign > 0) {
    elements_[Index(t)] = {k.gradients, k.volume * added_scale_[Index(t)]};
  }
  const double corner_mass = material_.density * k.volume / 4;
  const double stiffness_sign = sign * added_scale_[Index(t)];
  for (int a = 0; a < 4; ++a) {
    vertex_tensors_[Index(v[a])] += stiffness_sign * k.blocks[a][a];
    masses_[Index(v[a])] += sign * corner_mass;
  }
  for (const auto& [i, j] : mesh::kTetEdges) {
    // Store each edge once, from its lower vertex index.
    const bool ordered = Index(v[i]) < Index(v[j]);
    const int a = ordered ? i : j, b = ordered ? j : i;
    const std::uint64_t key = EdgeKey(v[a], v[b]);
    auto [it, inserted] = edge_slot_.try_emplace(key, static_cast<std::uint32_t>(edges_.size()));
    if (inserted) {
      edges_.push_back({v[a], v[b], Eigen::Matrix3d::Zero(), 0});
      edges_at_[Index(v[a])].push_back(it->second);
      edges_at_[Index(v[b])].push_back(it->second);
    }
    EdgeTensor& edge = edges_[it->second];
    edge.k_ab += stiffness_sign * k.blocks[a][b];
    edge.tets = sign > 0 ? edge.tets + 1 : edge.tets - 1;
    if (edge.tets == 0) {
      // No tet has this edge any more: move the last edge into its slot.
      const std::uint32_t slot = it->second;
      const auto last = static_cast<std::uint32_t>(edges_.size() - 1);
      edge_slot_.erase(it);
      for (const VertexId end : {v[a], v[b]}) std::erase(edges_at_[Index(end)], slot);
      if (slot != last) {
        edges_[slot] = edges_.back();
        edge_slot_[EdgeKey(edges_[slot].a, edges_[slot].b)] = slot;
        for (const VertexId end : {edges_[slot].a, edges_[slot].b}) {
          std::replace(edges_at_[Index(end)].begin(), edges_at_[Index(end)].end(), last, slot);
        }
      }
      edges_.pop_back();
    }
  }
}

const EdgeTensor* TensorMassModel::FindEdge(VertexId a, VertexId b) const {
  if (Index(b) < Index(a)) std::swap(a, b);
  const auto it = edge_slot_.find(EdgeKey(a, b));
  return it == edge_slot_.end() ? nullptr : &edges_[it->second];
}

void TensorMassModel::MultiplyStiffness(std::span<const Eigen::Vector3d> u,
                                        std::span<Eigen::Vector3d> f) const {
  KERF_CHECK(u.size() >= vertex_tensors_.size() && f.size() >= vertex_tensors_.size());
  for (const std::uint32_t i : active_) f[i] = vertex_tensors_[i] * u[i];
  for (const EdgeTensor& e : edges_) {
    const std::uint32_t a = Index(e.a), b = Index(e.b);
    const Eigen::Vector3d u_a = u[a], u_b = u[b];
    f[a] += e.k_ab * u_b;
    f[b] += e.k_ab.transpose() * u_a;
  }
}

void TensorMassModel::MultiplyStiffnessRows(std::span<const std::uint32_t> rows,
                                            std::span<const Eigen::Vector3d> u,
                                            std::span<Eigen::Vector3d> f) const {
  for (const std::uint32_t i : rows) {
    Eigen::Vector3d sum = vertex_tensors_[i] * u[i];
    for (const std::uint32_t slot : edges_at_[i]) {
      const EdgeTensor& e = edges_[slot];
      sum += Index(e.a) == i ? Eigen::Vector3d(e.k_ab * u[Index(e.b)])
                             : Eigen::Vector3d(e.k_ab.transpose() * u[Index(e.a)]);
    }
    f[i] = sum;
  }
}

void TensorMassModel::MultiplyStiffnessOver(std::span<const std::uint32_t> rows,
                                            std::span<const std::uint32_t> edges,
                                            std::span<const Eigen::Vector3d> u,
                                            std::span<Eigen::Vector3d> f) const {
  for (const std::uint32_t i : rows) f[i] = vertex_tensors_[i] * u[i];
  for (const std::uint32_t slot : edges) {
    const EdgeTensor& e = edges_[slot];
    const std::uint32_t a = Index(e.a), b = Index(e.b);
    const Eigen::Vector3d u_a = u[a], u_b = u[b];
    f[a] += e.k_ab * u_b;
    f[b] += e.k_ab.transpose() * u_a;
  }
}

Eigen::SparseMatrix<double> TensorMassModel::AssembleStiffness() const {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(9 * (vertex_tensors_.size() + 2 * edges_.size()));
  auto add_block = [&](std::uint32_t row, std::uint32_t col, const Eigen::Matrix3d& block) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) {
        if (block(r, c) != 0) entries.emplace_back(3 * row + r, 3 * col + c, block(r, c));
      }
    }
  };
  for (std::uint32_t i = 0; i < vertex_tensors_.size(); ++i) add_block(i, i, vertex_tensors_[i]);
  for (const EdgeTensor& e : edges_) {
    add_block(Index(e.a), Index(e.b), e.k_ab);
    add_block(Index(e.b), Index(e.a), e.k_ab.transpose());
  }
  const auto n = static_cast<Eigen::Index>(3 * vertex_tensors_.size());
  Eigen::SparseMatrix<double> k(n, n);
  k.setFromTriplets(entries.begin(), entries.end());
  return k;
}

double TensorMassModel::ElasticEnergy(std::span<const Eigen::Vector3d> u) const {
  std::vector<Eigen::Vector3d> f(vertex_tensors_.size());
  MultiplyStiffness(u, f);
  double energy = 0;
  for (const std::uint32_t i : active_) energy += 0.5 * u[i].dot(f[i]);
  return energy;
}

}  // namespace kerf::fem
