// Cuts a tet mesh along a blade's path with steps that are total: whatever points the blade
// leaves on a tet's edges and faces, the tet is split (cut/crack_split.h), so nothing the blade
// did is dropped, held back or frozen.
//
// The crack's state is a set of points on the mesh: at most one on each edge (the first
// crossing of the blade's edge; later ones are the same cut), at most one inside each face (the
// first crossing of the tip's path: where the crack ends), and the vertices the crack passes
// through. Snapping is decided once per crossing: one within `snap_fraction` of an edge's length
// from a corner (of a face's, barycentric, from a corner, or from an edge, where it becomes that
// edge's point) is taken at the corner, which is then on the crack. Points are kept as weights
// on their edge or face until their tets split, so a crossing never makes a dangling vertex.
//
// The tets that share points form groups; a group splits once the blade meets none of its tets
// (deferred cutting), or when the blade is withdrawn. After a group splits, the vertices of its
// crack faces are parted where the crack separates their tets (cut/star_parting.h).
#pragma once

#include <optional>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/container/flat_hash_set.h"
#include "absl/status/statusor.h"
#include "cut/blade.h"
#include "cut/blade_crossings.h"
#include "cut/crack_split.h"
#include "cut/cutter.h"
#include "cut/star_parting.h"
#include "mesh/tet_mesh.h"

namespace kerf::cut {

// Crossings closer than this to a corner are always taken at it, whatever the snap fraction.
inline constexpr double kMinSnapFraction = 0.01;

class CrackCutter {
 public:
  // The mesh must outlive the cutter and change only through it while it cuts. `cell_size` (m):
  // a mean edge length is a good choice. `snap_fraction` in [0, 0.5) (below kMinSnapFraction it
  // is that). INVALID_ARGUMENT for a bad size or fraction.
  static absl::StatusOr<CrackCutter> Create(mesh::TetMesh* mesh, double cell_size,
                                            const BladeLimits& limits = {},
                                            double snap_fraction = 0.2);

  // Applies one pose. INVALID_ARGUMENT (and nothing changed) for a bad pose. The first pose only
  // places the blade.
  absl::Status ApplyPose(const BladePose& pose);
  // The blade is withdrawn: every group still waiting splits.
  void Finish();
  absl::Status MeshDeformed() { return crossings_.MeshDeformed(); }

  const CutStatistics& statistics() const { return statistics_; }
  const PoseSummary& last_pose() const { return last_pose_; }
  std::size_t waiting_tets() const { return group_of_.size(); }
  mesh::TetId SourceTet(mesh::TetId t) const;
  bool MadeByCut(mesh::TetId t) const { return source_tet_.contains(t); }
  mesh::VertexId PartedFrom(mesh::VertexId v) const {
    const auto it = parted_from_.find(v);
    return it == parted_from_.end() ? v : it->second;
  }
  std::vector<MadeVertex> TakeMadeVertices();

 private:
  struct EdgePoint {
    double fraction;  // from the lower id
    mesh::VertexId vertex{0xffffffffu};
  };
  struct FacePoint {
    Eigen::Vector3d barycentric;  // on the face key's vertices
    mesh::VertexId vertex{0xffffffffu};
  };
  using EdgeKey = std::uint64_t;

  CrackCutter(mesh::TetMesh* mesh, BladeCrossings crossings, const BladeLimits& limits,
              double snap_fraction)
      : mesh_(mesh),
        crossings_(std::move(crossings)),
        limits_(limits),
        snap_fraction_(snap_fraction) {}

  // Records this pose's crossings as points (snapping them), returns the tets they touch.
  std::vector<mesh::TetId> RecordCrossings(const Crossings& found);
  // An edge crossing at `fraction` from `low`: a point, or its corner snapped. Adds the tets it
  // touches.
  void RecordEdgeCrossing(mesh::VertexId low, mesh::VertexId high, double fraction,
                          std::vector<mesh::TetId>* touched);
  // Snaps the vertices of the `near` tets within the snap fraction of their tet's mean edge of
  // the surface swept from `from` to `to`: the crack passes through them (this catches the
  // blade through a vertex, along an edge or in a face's plane, where no edge is crossed inside).
  void SnapVerticesNear(const BladePose& from, const BladePose& to,
                        const std::vector<mesh::TetId>& near, std::vector<mesh::TetId>* touched);
  void Snap(mesh::VertexId v, std::vector<mesh::TetId>* touched);
  void Join(const std::vector<mesh::TetId>& tets);
  // Splits the groups the blade at `pose` meets none of (every group if null).
  void SplitReadyGroups(const BladePose* pose);
  void SplitGroup(const std::vector<mesh::TetId>& group);
  // The points of the tet's faces, their vertices made as needed.
  std::array<FacePoints, 4> PointsOf(const mesh::TetVertices& corners);
  mesh::VertexId EdgePointVertex(mesh::VertexId a, mesh::VertexId b);
  mesh::VertexId FacePointVertex(const FaceKey& key);
  // The point strictly inside the tet a cone splits it from: the middle of the crack's trace
  // points pulled inside, or the tet's middle.
  mesh::VertexId MakeApex(const TetCrack& crack);
  mesh::VertexId MakeVertex(const std::array<mesh::VertexId, 4>& from,
                            const Eigen::Vector4d& weights);
  // Replaces t by the pieces (oriented on rest positions); returns them.
  std::vector<mesh::TetId> Replace(mesh::TetId t, const std::vector<mesh::TetVertices>& pieces);

  mesh::TetMesh* mesh_;
  BladeCrossings crossings_;
  BladeLimits limits_;
  double snap_fraction_;
  std::optional<BladePose> previous_;
  absl::flat_hash_map<EdgeKey, EdgePoint> edge_points_;
  absl::flat_hash_map<FaceKey, FacePoint, FaceKeyHash> face_points_;
  absl::flat_hash_set<mesh::VertexId> on_crack_;  // snapped corners, and their copies
  CrackFaceSet crack_;
  // Groups of tets with points, joined through shared points: each waiting tet's group (named
  // by one of its tets) and each group's tets.
  absl::flat_hash_map<mesh::TetId, mesh::TetId> group_of_;
  absl::flat_hash_map<mesh::TetId, std::vector<mesh::TetId>> members_;
  absl::flat_hash_map<mesh::TetId, mesh::TetId> source_tet_;
  absl::flat_hash_map<mesh::VertexId, mesh::VertexId> parted_from_;
  std::vector<MadeVertex> made_vertices_;
  CutStatistics statistics_;
  PoseSummary last_pose_;
};

}  // namespace kerf::cut
