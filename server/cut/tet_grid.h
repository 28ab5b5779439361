// A uniform grid over the tets' current (deformed) bounding boxes, so that the tets a blade
// first touches are found without scanning the mesh.
//
// Each vertex has a reference position, and each tet is registered in the cells its bounding
// box covers, inflated by twice a margin. A vertex within the margin of its reference was
// within the margin when its tets were registered, so it is inside their boxes. Refresh()
// moves the reference of a vertex that went farther and re-registers the tets around it;
// RefreshTopology() registers the tets the mesh added or removed (read from its change log). A
// query returns a superset of the live tets whose current bounding box meets the query box.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/status/statusor.h"
#include "mesh/tet_mesh.h"

namespace kerf::cut {

class TetGrid {
 public:
  // cell_size (m) must be positive and margin (m) non-negative; INVALID_ARGUMENT otherwise.
  // The mesh must outlive the grid. O(tets).
  static absl::StatusOr<TetGrid> Build(const mesh::TetMesh& mesh, double cell_size, double margin);

  // Registers the tets the mesh added and forgets those it removed since the last refresh.
  // O(tets changed): cheap enough for every blade pose.
  absl::Status RefreshTopology();

  // Also follows the deformation: re-registers the tets around vertices that moved beyond
  // the margin. O(vertices), as a physics step is: call it after steps, not per pose.
  absl::Status Refresh();

  // Live tets whose current bounding box may meet [low, high]: every such tet is included,
  // others may be. O(cells covered + tets listed in them).
  std::vector<mesh::TetId> Candidates(const Eigen::Vector3d& low,
                                      const Eigen::Vector3d& high) const;

  std::size_t registered_tets() const { return registered_count_; }
  // Tets re-registered by the last Refresh (for tests and benchmarks).
  std::size_t last_refresh_count() const { return last_refresh_count_; }

 private:
  using Cell = std::array<std::int32_t, 3>;
  struct CellRange {
    Cell low;
    Cell high;
    bool registered = false;
  };
  struct CellHash {
    std::size_t operator()(const Cell& c) const { return absl::HashOf(c[0], c[1], c[2]); }
  };

  TetGrid(const mesh::TetMesh& mesh, double cell_size, double margin)
      : mesh_(&mesh), cell_size_(cell_size), margin_(margin) {}

  Cell CellOf(const Eigen::Vector3d& p) const;
  void Register(mesh::TetId t);
  void Unregister(mesh::TetId t);

  const mesh::TetMesh* mesh_;
  double cell_size_;
  double margin_;
  mesh::ChangeMark synced_;
  absl::flat_hash_map<Cell, std::vector<mesh::TetId>, CellHash> cells_;
  std::vector<CellRange> ranges_;               // by tet index
  std::vector<Eigen::Vector3d> registered_at_;  // each vertex's reference position
  std::size_t registered_count_ = 0;
  std::size_t last_refresh_count_ = 0;
  mutable std::vector<std::uint32_t> seen_;  // per tet: the query that listed it last
  mutable std::uint32_t query_ = 0;
};

}  // namespace kerf::cut
