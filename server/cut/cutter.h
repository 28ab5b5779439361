// Cuts a tet mesh along a blade's path (the paper's section 3), deferred: the tets the blade
// has crossed are subdivided once it has left them.
//
// Per pose, the swept surface between the previous and the new blade edge is tested against
// the edges of the tets near it (found through a TetGrid on the deformed positions), and the
// tip's path against their faces, on current positions. A hit is stored once, as a fraction
// along the edge or barycentric coordinates on the face; the first crossing wins. New
// vertices take their rest and current positions from the same coordinates.
//
// Conformity: a cut edge becomes two vertices in every tet around it at once, and a crossed
// face is split in both its tets at once, so the tets joined through cut edges and crossed
// faces form a group that is split in one step, when the blade has left all of them (or at
// Finish). A group member whose pattern is none of the five cases (a blade that turned back,
// or hits too close to a vertex or edge, which snapping will handle) has its hits dropped,
// and the group is re-examined: the mesh always stays valid, at worst less cut.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/container/flat_hash_set.h"
#include "absl/status/statusor.h"
#include "cut/blade.h"
#include "cut/tet_grid.h"
#include "cut/tet_split.h"
#include "mesh/tet_mesh.h"

namespace kerf::cut {

// Where a vertex the cut made comes from: weights on up to three vertices (an edge's two, or
// a face's three), the same for its rest and current positions. Data attached to vertices
// (displacement, velocity) follows it by the same weights.
struct MadeVertex {
  mesh::VertexId vertex;
  std::array<mesh::VertexId, 3> from;
  Eigen::Vector3d weights;
};

struct CutStatistics {
  std::size_t cut_tets = 0;                   // original tets replaced
  std::size_t new_tets = 0;                   // tets that replaced them
  std::array<std::size_t, 6> tets_by_case{};  // cut tets by CutCase (index = enum value)
  std::size_t dropped_hits = 0;               // hits that could not be realised
  std::size_t degenerate_hits = 0;            // crossings too close to a vertex or edge, skipped
};

class Cutter {
 public:
  // The mesh must outlive the cutter and change only through it while it cuts. `cell_size`
  // (m) sets the grid; a mean edge length is a good choice. INVALID_ARGUMENT for a bad size.
  static absl::StatusOr<Cutter> Create(mesh::TetMesh* mesh, double cell_size,
                                       const BladeLimits& limits = {});

  // Applies one pose. INVALID_ARGUMENT (and nothing changed) for a bad pose. The first pose
  // only places the blade. Cost: the tets near the swept surface and the groups split.
  absl::Status ApplyPose(const BladePose& pose);

  // The blade is withdrawn: every group still waiting is split.
  void Finish();

  // Call after the mesh deformed (a physics step): the spatial index follows the current
  // positions. O(vertices).
  absl::Status MeshDeformed() { return grid_.Refresh(); }

  const CutStatistics& statistics() const { return statistics_; }
  // Tets with hits that wait for the blade to leave their group.
  std::size_t waiting_tets() const { return group_of_.size(); }

  // The tet of the mesh as it was when the cutter was created that `t` came from (t itself
  // if it was never cut).
  mesh::TetId SourceTet(mesh::TetId t) const;
  // The vertices made since the last call that are still used (in creation order).
  std::vector<MadeVertex> TakeMadeVertices();

  // The live tets the blade at `pose` is inside or crosses (on current positions). O(tets near).
  std::vector<mesh::TetId> TetsHoldingBlade(const BladePose& pose) const;

  // Whether the cutter made `t` (it replaced a cut tet).
  bool MadeByCut(mesh::TetId t) const { return source_tet_.contains(t); }

 private:
  struct EdgeHit {
    double fraction;  // from the lower-id vertex to the higher
    mesh::VertexId near_low{0xffffffffu}, near_high{0xffffffffu};  // made when split
  };
  struct FaceHit {
    Eigen::Vector3d barycentric;  // on the face's vertices in increasing id order
    mesh::VertexId vertex{0xffffffffu};
  };
  using EdgeKey = std::uint64_t;
  using FaceKey = std::array<mesh::VertexId, 3>;
  struct FaceKeyHash {
    std::size_t operator()(const FaceKey& k) const {
      return absl::HashOf(mesh::Index(k[0]), mesh::Index(k[1]), mesh::Index(k[2]));
    }
  };

  Cutter(mesh::TetMesh* mesh, TetGrid grid, const BladeLimits& limits)
      : mesh_(mesh), grid_(std::move(grid)), limits_(limits) {}

  // Records the hits of the swept surface from `from` to `to`, and returns the tets near it.
  std::vector<mesh::TetId> RecordHits(const BladePose& from, const BladePose& to);
  bool BladeInside(mesh::TetId t, const BladePose& pose) const;
  // Joins the groups of tets that share a new hit (each made a group if it was not in one).
  void Join(std::span<const mesh::TetId> tets);
  mesh::TetId GroupOf(mesh::TetId t);
  // Splits the groups none of whose members the blade is inside: it can only be inside the
  // tets near it, `near` (every group if `near` is null). O(near + groups).
  void SplitReadyGroups(const BladePose* pose, const std::vector<mesh::TetId>* near);
  void SplitGroup(std::vector<mesh::TetId> group);
  std::vector<EdgeCut> EdgeCutsOf(const mesh::TetVertices& corners);
  std::vector<FacePoint> FacePointsOf(const mesh::TetVertices& corners) const;
  mesh::VertexId MakeVertex(const std::array<mesh::VertexId, 3>& from,
                            const Eigen::Vector3d& weights);

  mesh::TetMesh* mesh_;
  TetGrid grid_;
  BladeLimits limits_;
  std::optional<BladePose> previous_;
  absl::flat_hash_map<EdgeKey, EdgeHit> edge_hits_;
  absl::flat_hash_map<FaceKey, FaceHit, FaceKeyHash> face_hits_;
  // Groups of unsplit tets with hits, joined through shared hits: a union-find forest over the
  // tets (parent links) and the members of each root.
  absl::flat_hash_map<mesh::TetId, mesh::TetId> group_of_;
  absl::flat_hash_map<mesh::TetId, std::vector<mesh::TetId>> members_;
  absl::flat_hash_map<mesh::TetId, mesh::TetId> source_tet_;  // tets the cut made, by source
  std::vector<MadeVertex> made_vertices_;
  CutStatistics statistics_;
};

}  // namespace kerf::cut
