// A loose uniform grid over the tets' current (deformed) bounding boxes, so that the tets a
// blade first touches are found without scanning the mesh.
//
// Each tet is registered once, in the cell of its box's centre, with its box inflated by twice
// a margin; a query widens its box by the largest registered half-extent, visits those cells
// and keeps the tets whose registered box meets it. Cells are a dense array over the mesh's
// bounds padded by a cell (a point outside them counts in the nearest cell at the edge), so a
// query reads a few contiguous cells and no tet twice.
//
// Each vertex has a reference position. A vertex within the margin of its reference was within
// the margin when its tets were registered, so it is inside their inflated boxes. Refresh()
// moves the reference of a vertex that went farther and re-registers the tets around it;
// RefreshTopology() registers the tets the mesh added or removed (read from its change log). A
// query returns a superset of the live tets whose current bounding box meets the query box.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "absl/container/inlined_vector.h"
#include "absl/functional/function_ref.h"
#include "absl/status/statusor.h"
#include "mesh/tet_mesh.h"

namespace kerf::cut {

class TetGrid {
 public:
  // cell_size (m) must be positive and margin (m) non-negative; INVALID_ARGUMENT otherwise.
  // The cells are made larger when the mesh's bounds would need more than a few cells per
  // tet. The mesh must outlive the grid. O(tets).
  static absl::StatusOr<TetGrid> Build(const mesh::TetMesh& mesh, double cell_size, double margin);

  // Registers the tets the mesh added and forgets those it removed since the last refresh, and
  // those around vertices it moved (TetMesh::MoveVertex) beyond the margin. O(tets changed):
  // cheap enough for every blade pose.
  absl::Status RefreshTopology();

  // Also follows the deformation: re-registers the tets around vertices that moved beyond
  // the margin. O(vertices), as a physics step is: call it after steps, not per pose.
  absl::Status Refresh();
  // The mesh's change log as of the last refresh: none before it is read again.
  mesh::ChangeMark synced() const { return synced_; }

  // Live tets whose current bounding box may meet [low, high]: every such tet is included
  // once, others may be. O(cells covered + tets registered in them).
  std::vector<mesh::TetId> Candidates(const Eigen::Vector3d& low,
                                      const Eigen::Vector3d& high) const;
  // Those of them in cells that may hold a box meeting a region inside [low, high] (a triangle,
  // a segment): `meets(lo, hi)` says whether the box [lo, hi] may meet it, and must not say no
  // where it does. Every live tet whose current box meets the region is included once, so the
  // cost follows the region rather than its bounding box. O(cells covered + tets registered in
  // those met).
  std::vector<mesh::TetId> Candidates(
      const Eigen::Vector3d& low, const Eigen::Vector3d& high,
      absl::FunctionRef<bool(const Eigen::Vector3d&, const Eigen::Vector3d&)> meets) const;

  std::size_t registered_tets() const { return registered_count_; }
  // Tets re-registered by the last Refresh (for tests and benchmarks).
  std::size_t last_refresh_count() const { return last_refresh_count_; }
  double cell_size() const { return cell_size_; }

 private:
  // A registered tet and its box (inflated by twice the margin, rounded outwards to float).
  struct Entry {
    mesh::TetId tet;
    Eigen::Vector3f low, high;
  };
  static constexpr std::uint32_t kUnregistered = 0xffffffffu;

  TetGrid(const mesh::TetMesh& mesh, double margin) : mesh_(&mesh), margin_(margin) {}

  // The cell of `p` along each axis, clamped to the grid.
  std::array<std::int32_t, 3> CellOf(const Eigen::Vector3d& p) const;
  std::uint32_t CellIndex(const std::array<std::int32_t, 3>& c) const {
    return static_cast<std::uint32_t>(c[0] + dims_[0] * (c[1] + dims_[1] * c[2]));
  }
  void Register(mesh::TetId t);
  void Unregister(mesh::TetId t);
  // If `v` is farther than the margin from its reference, makes where it is its reference and
  // adds the tets around it to `stale`.
  void FarFromReference(mesh::VertexId v, std::vector<mesh::TetId>* stale);
  // Registers the tets again (once each).
  void RegisterAgain(std::vector<mesh::TetId> stale);

  const mesh::TetMesh* mesh_;
  double cell_size_ = 0;
  double margin_;
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  std::array<std::int32_t, 3> dims_{1, 1, 1};
  mesh::ChangeMark synced_;
  std::vector<absl::InlinedVector<Entry, 6>> cells_;           // x fastest
  std::vector<std::uint32_t> cell_of_;                         // by tet index, or kUnregistered
  Eigen::Vector3d max_half_extent_ = Eigen::Vector3d::Zero();  // of registered boxes
  std::vector<Eigen::Vector3d> registered_at_;                 // each vertex's reference
  std::size_t registered_count_ = 0;
  std::size_t last_refresh_count_ = 0;
};

}  // namespace kerf::cut
