// Where the blade, moving from one pose to the next, crossed the mesh: the tet edges its edge
// swept over and the faces its tip went through, found on the deformed (current) positions.
// The tissue may move between poses too: each vertex near the blade is taken to move straight
// from where it was at the previous pose to where it is now, like the blade, and a crossing is
// where the two met (geometry/moving_crossing.h), so only the relative motion cuts.
#pragma once

#include <Eigen/Core>
#include <array>
#include <functional>
#include <optional>
#include <vector>

#include "absl/status/statusor.h"
#include "cut/blade.h"
#include "cut/tet_grid.h"
#include "mesh/tet_mesh.h"

namespace kerf::cut {

struct EdgeCrossing {
  mesh::VertexId low, high;  // low has the smaller id
  double fraction;           // from low to high, in [0, 1]
};

struct FaceCrossing {
  std::array<mesh::VertexId, 3> face;  // smallest id first
  Eigen::Vector3d barycentric;         // on face's vertices in that order
};

struct Crossings {
  std::vector<EdgeCrossing> edges;
  std::vector<FaceCrossing> faces;
};

class BladeCrossings {
 public:
  // `cell_size` (m): the grid's, a mean edge length is a good choice. The mesh must outlive it.
  static absl::StatusOr<BladeCrossings> Create(const mesh::TetMesh* mesh, double cell_size);

  // The crossings of the blade moving from `from` to `to` with the edges and faces of `tets`
  // (corners of live vertices), each edge and face once; those `skip` names are not tested
  // (they are cut already). O(tets).
  Crossings Find(const BladePose& from, const BladePose& to,
                 const std::vector<mesh::TetVertices>& tets,
                 const std::function<bool(mesh::VertexId, mesh::VertexId)>& skip_edge,
                 const std::function<bool(const std::array<mesh::VertexId, 3>&)>& skip_face) const;

  // The faces of `tets` the blade at `pose` crosses (its edge, tip to heel), but those `skip`
  // names.
  std::vector<FaceCrossing> FacesCrossedBy(
      const BladePose& pose, const std::vector<mesh::TetVertices>& tets,
      const std::function<bool(const std::array<mesh::VertexId, 3>&)>& skip_face) const;

  // Keeps the current positions of `vertices` (those near the blade), for the next Find, and
  // lets the grid learn the tets the mesh added and removed. Call after a pose was applied.
  absl::Status Remember(const std::vector<mesh::VertexId>& vertices);
  // Whether the remembered positions include `v`'s.
  bool Remembers(mesh::VertexId v) const {
    const std::size_t i = mesh::Index(v);
    return i < remembered_at_.size() && remembered_at_[i] == remembered_;
  }

  // Whether the blade at `pose` meets the tet (its inside or boundary), on current positions.
  bool BladeMeets(const mesh::TetVertices& tet, const BladePose& pose) const;

  // Live tets whose box meets the box [low, high] (on current positions).
  std::vector<mesh::TetId> Near(const Eigen::Vector3d& low, const Eigen::Vector3d& high) const;
  // Live tets whose box meets the box of the surface the blade's edge sweeps from `from` to `to`
  // (its two triangles; the blade's edge where they are one pose), grown by `box_margin` (m), on
  // current positions; where the blade is long and oblique, only those within `margin` (m) of
  // the surface besides (within that and the blade's move of its edge at either pose): a small
  // share of the box's.
  std::vector<mesh::TetId> NearSweep(const BladePose& from, const BladePose& to, double margin,
                                     double box_margin = 0) const;

  double cell_size() const { return grid_.cell_size(); }  // m

  // After the mesh deformed (a physics step). O(vertices).
  absl::Status MeshDeformed() { return grid_.Refresh(); }
  // The mesh's change log as of the grid's last refresh: none before it is read again.
  mesh::ChangeMark synced() const { return grid_.synced(); }

 private:
  BladeCrossings(const mesh::TetMesh* mesh, TetGrid grid) : mesh_(mesh), grid_(std::move(grid)) {}

  // Where the tip's path from `from` to `to` passes through the edge, as a fraction from `low`,
  // when the blade's edge does not cross it (the blade sweeping in the edge's plane, or its tip
  // along it): there the crack's front crosses the edge.
  std::optional<double> TipPathThroughEdge(const BladePose& from, const BladePose& to,
                                           mesh::VertexId low, mesh::VertexId high) const;

  // How far `v` moved since the previous pose (zero if it was not near the blade then).
  Eigen::Vector3d MovedSincePrevious(mesh::VertexId v) const;

  const mesh::TetMesh* mesh_;
  TetGrid grid_;
  // The positions Remember kept, by vertex index: valid where remembered_at_ holds remembered_,
  // the count of Remember calls (so a call forgets the last one's without touching them).
  std::vector<Eigen::Vector3d> previous_;
  std::vector<std::uint64_t> remembered_at_;
  std::uint64_t remembered_ = 0;
};

}  // namespace kerf::cut
