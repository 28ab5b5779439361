// Cuts a tet mesh along a blade's path (the paper's sections 3 and 4).
//
// Per pose, the blade edge moves straight from its previous place to its new one, and so does
// each vertex near it, from its current position at the previous pose to its current position
// now (the tissue may have moved in between). An edge of a tet near (found through a TetGrid
// on the deformed positions) is hit where it met the blade edge in that interval, a face where
// the tip went through it (geometry/moving_crossing.h): only the relative motion cuts. A hit
// is stored once, as a fraction along the edge or barycentric coordinates on the face; the
// first crossing wins. New vertices take their rest and current positions from the same
// coordinates.
//
// Progressive: after every pose, each tet with hits is subdivided at once. While
// the blade is in it, the subdivision is temporary: the points where the blade edge crosses
// its faces (temporary face points) count as face points, and while the tip is inside, the
// crack reaches the tip (a cone from it). Points on a face with no cut edge cannot open and are
// left out, so no face ever carries two points (the overlap of the paper's Figure 5 cannot
// arise). When only the blade moved, the temporary points move (the same vertices and tets,
// recorded as moves for the model to follow); when the case or topology changed, the tet's
// subdivision is rebuilt; when the blade has left, the final minimal subdivision replaces it.
// A cut edge whose point the blade passes through now is closed (one vertex: the crack's front
// runs through the edge) until the blade moves on. Temporary slivers are made and softened
// (StiffnessScale).
// Before anything is applied, each subdivision's triangles on its tet's faces are compared with
// those of the other side (its plan, or the tets there), so the mesh conforms by construction. A
// pose whose subdivisions cannot all be made (a pattern no case covers, or triangles that would
// differ from the other side's) leaves the mesh as it was (held); a tet the blade left in such a
// pattern keeps its last temporary subdivision (frozen), so the crack it made stays. Withdrawing
// the blade makes the temporary face points permanent.
//
// Deferred (for comparison, and for sessions that must cost least; see the README): the tets
// the blade has crossed are subdivided once it has left them. The tets joined through cut edges and
// crossed faces form a group split in one step, when the blade has left all of them (or at Finish).
// A group member whose pattern is none of the five cases has its hits dropped, and the group is
// re-examined.
//
// Either way the mesh stays valid and conforming after every pose: a cut edge becomes two
// vertices in every tet around it at once, and a face is triangulated alike in both its tets.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
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
  std::array<mesh::VertexId, 4> from;  // unused entries have weight 0
  Eigen::Vector4d weights;
};

enum class CutMode { kProgressive, kDeferred };

// Progressive: a temporary tet lower than this fraction of the smallest height of the tet it
// stands in for is softened (StiffnessScale): the elastic model makes it no stiffer than a
// piece of this height, so the slivers a blade near an edge makes do not slow the implicit
// solve, while the opening still follows the blade (README: what it costs and buys).
inline constexpr double kDefaultMinTemporaryHeight = 0.02;

// Snapping (the paper's proposal against slivers): an edge crossed within this fraction of its
// length from a vertex is taken as crossed at the vertex, which then lies on the crack, and
// every edge from it to the side it is not on is cut at it: pinned, the cut's one point the
// corner itself, so cuts through vertices and along edges are the minimal cases with some cut
// points at corners (their collapsed pieces left out). When its tets have split (deferred:
// together, in one group; progressive: each once the blade has left it, the vertex's last
// one ending its wait), the vertex is parted: the part of its tets on its own side keeps it,
// each other part across the crack gets a copy; a neighbour on the crack parted before parts
// again if that separates its tets. A vertex snaps once. Where a tet at it cannot be split
// with it, it is taken off the crack (unsnapped), unless (progressive) a tet has split through
// it for good: it is then committed, and a crossing on its own side is cut as found. While it
// waits, the crack does not open at it: progressive cutting lags the blade by up to a tet
// there. Snapping also takes the crack's front to an edge: where the tip's path crosses a face
// within the fraction (barycentric) of one of its edges, and not of a vertex, the front is taken
// to cross that edge instead (a closed cut: the edge is split at one vertex, not parted; every
// tet at it splits there), and the face point, which would make slivers along the edge, is not
// made. The blade crossing the edge later (the tip deeper) opens it. Deferred, a tet that cannot
// be split with it takes the face points back. Progressive: no tet at a closed cut splits for
// good while the blade is in one of them (they wait in temporary subdivisions, as do the tets at
// closed cuts of waiting tets), so the edge can still open; a tet at it that cannot split is
// frozen (see Cutter) with the cut closed, which then stays closed (ClosedCutSettled). A face
// crossing as near a snapped vertex makes no point (the front passes through the vertex), and a tet
// the blade is not in that no case covers is split as a cone (Cutter::SplitAsCone). 0: no snapping.
inline constexpr double kDefaultSnapFraction = 0;

// The paper's Table 1: the cases of a tet the blade is in, by its cut edges, face points,
// temporary face points and whether the tip is inside. Case 8 and 9 have the same counts; in
// 8 the two cut edges share a corner, in 9 they are opposite. 0: none of the eleven.
int ProgressiveCase(int edges, int faces, int temporary_faces, bool tip_inside,
                    bool edges_share_corner);
inline constexpr int kProgressiveCases = 11;

struct CutStatistics {
  std::size_t cut_tets = 0;                   // original tets replaced
  std::size_t new_tets = 0;                   // tets that replaced them
  std::array<std::size_t, 8> tets_by_case{};  // cut tets by CutCase (index = enum value)
  std::size_t dropped_hits = 0;               // hits that could not be realised
  std::size_t degenerate_hits = 0;            // crossings too close to a vertex or edge, skipped
  std::size_t snapped_vertices = 0;           // vertices put on the crack by snapping
  std::size_t snapped_hits = 0;               // edge crossings taken at a snapped vertex
  // Snapped vertices taken off the crack again: a tet at them could not be split with them.
  std::size_t unsnapped_vertices = 0;
  // Copies made where the crack through a snapped vertex parted its tets.
  std::size_t parted_vertices = 0;
  // Crossings of the tip's path taken on an edge of their face (its crack front closed there),
  // the edges given them back because a tet could not split with them (deferred), and the
  // closed cuts opened because the blade crossed their edge at a later pose.
  std::size_t edge_snapped_hits = 0;
  std::size_t unsnapped_edges = 0;
  std::size_t opened_edges = 0;
  // Faces given a point where the crack ends: it met them at one cut edge, and no path of the
  // blade's crossed them (see Cutter::EndCracksOnFaces).
  std::size_t ended_cracks = 0;
  // Progressive: crossings of an edge or face that a tet the blade is in does not have among its
  // own (made by a final subdivision beside it), skipped: it could not split them alike.
  std::size_t unrealisable_hits = 0;
  // Progressive cutting, summed over poses.
  std::array<std::size_t, kProgressiveCases + 1> poses_by_case{};  // tet-poses by Table 1 case
  std::size_t rebuilt = 0;      // temporary subdivisions made anew (first, or case changed)
  std::size_t moved = 0;        // temporary subdivisions whose points only moved
  std::size_t held_poses = 0;   // poses that left the mesh as it was
  std::size_t frozen_tets = 0;  // tets left in their last temporary subdivision
  // Subdivisions not applied because a face of theirs would differ from the other side's.
  std::size_t nonconforming_plans = 0;
  // Temporary subdivisions made with a soft piece (lower than the guard: see IsSoft).
  std::size_t thin_temporary_plans = 0;
  // Temporary subdivisions no case covers (the blade through an edge or in a face's plane).
  std::size_t uncovered_temporary_plans = 0;
};

// What the last pose did (progressive cutting).
struct PoseSummary {
  std::array<std::size_t, kProgressiveCases + 1> tets_by_case{};  // tets the blade is in
  std::size_t open_tets = 0;       // tets with hits not yet finally subdivided
  std::size_t temporary_tets = 0;  // tets standing in for them now
  bool held = false;               // the mesh was left as it was
};

class Cutter {
 public:
  // The mesh must outlive the cutter and change only through it while it cuts. `cell_size`
  // (m) sets the grid; a mean edge length is a good choice. INVALID_ARGUMENT for a bad size.
  // `min_temporary_height`: see kDefaultMinTemporaryHeight (0: no piece is soft).
  // `snap_fraction`: see kDefaultSnapFraction; in [0, 0.5).
  static absl::StatusOr<Cutter> Create(mesh::TetMesh* mesh, double cell_size,
                                       const BladeLimits& limits = {},
                                       CutMode mode = CutMode::kProgressive,
                                       double min_temporary_height = kDefaultMinTemporaryHeight,
                                       double snap_fraction = kDefaultSnapFraction);

  // Applies one pose. INVALID_ARGUMENT (and nothing changed) for a bad pose. The first pose
  // only places the blade. Cost: the tets near the swept surface and the groups split.
  absl::Status ApplyPose(const BladePose& pose);

  // The blade is withdrawn: every tet still waiting is split (progressive: the temporary face
  // points become permanent, so the crack stays).
  void Finish();

  // Call after the mesh deformed (a physics step): the spatial index follows the current
  // positions. O(vertices).
  absl::Status MeshDeformed() { return grid_.Refresh(); }

  CutMode mode() const { return mode_; }
  const CutStatistics& statistics() const { return statistics_; }
  const PoseSummary& last_pose() const { return last_pose_; }
  // Tets with hits not yet finally subdivided.
  std::size_t waiting_tets() const { return group_of_.size() + open_.size(); }
  // Whether `v` is a temporary point of the current pose on the blade: a temporary face point,
  // or the tip inside a tet.
  bool IsOnBladeNow(mesh::VertexId v) const;

  // The tet of the mesh as it was when the cutter was created that `t` came from (t itself
  // if it was never cut).
  mesh::TetId SourceTet(mesh::TetId t) const;
  // The vertices made since the last call that are still used (in creation order).
  std::vector<MadeVertex> TakeMadeVertices();

  // The corners of the tets the blade at `pose` is inside or crosses (on current positions). A
  // tet the blade is subdividing progressively counts whole: the blade lies on the faces of its
  // temporary pieces. O(tets near).
  std::vector<mesh::TetVertices> TetsHoldingBlade(const BladePose& pose) const;

  // The vertex `v` is a copy of, made where a crack through a snapped vertex parted it; v
  // itself for any other vertex. O(1).
  mesh::VertexId PartedFrom(mesh::VertexId v) const {
    const auto it = parted_from_.find(v);
    return it == parted_from_.end() ? v : it->second;
  }

  // Whether the cutter made `t` (it replaced a cut tet).
  bool MadeByCut(mesh::TetId t) const { return source_tet_.contains(t); }
  // The share of its stiffness the elastic model gives `t`: for a temporary piece lower than
  // the guard (see kDefaultMinTemporaryHeight) of the tet it stands in for, its height over the
  // guard's, so that it is no stiffer than a piece of the guard's height; 1 for every other
  // tet. O(1).
  double StiffnessScale(mesh::TetId t) const;
  bool IsSoft(mesh::TetId t) const { return StiffnessScale(t) < 1; }

 private:
  struct EdgeHit {
    double fraction;  // from the lower-id vertex to the higher
    mesh::VertexId near_low{0xffffffffu}, near_high{0xffffffffu};  // made when split
    mesh::VertexId at{0xffffffffu};  // snapped: the end it is taken to be crossed at
    // False for an edge cut at a snapped vertex before the blade crossed it (`fraction` is
    // then that vertex's end), until it does.
    bool crossed = true;
    // Both ends snapped on the same side: the edge lies along the crack and is not cut (kept
    // so that the crossing comes back if either end is unsnapped).
    bool along = false;
    // The crack's front crosses the edge here (a face crossing snapped to it): one
    // vertex (near_low == near_high) that every tet at the edge splits at, not parted.
    bool closed = false;
    // Closed from an ordinary cut (the tip passing beside the blade's crossing): unsnapping it
    // cuts it open again.
    bool was_open = false;
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

  // What a temporary subdivision is made from. The pieces follow from these ids but for
  // diagonals chosen on geometry, so while a pose finds the same ones only the points moved.
  struct SplitInputs {
    std::vector<EdgeCut> cuts;
    std::vector<FacePoint> face_points;
    enum class Apex { kNone, kTip, kMiddle } apex = Apex::kNone;  // the cone's, if a star
    bool operator==(const SplitInputs&) const = default;
  };
  // A tet with hits, progressive: what stands for it in the mesh now.
  struct OpenTet {
    std::vector<mesh::TetId> pieces;  // live tets replacing it; empty: it is itself in the mesh
    // The pieces' corners with temporary points named by place (see Signature).
    std::vector<std::array<std::uint64_t, 4>> signature;
    SplitInputs inputs;  // of the pieces
  };
  // A temporary point of the applied subdivisions.
  struct TemporaryPoint {
    mesh::VertexId vertex;
    Eigen::Vector4d weights;  // on the face's vertices (key order) or the tet's corners
    bool on_blade = true;     // false for the middle of a crack's face points
  };

  Cutter(mesh::TetMesh* mesh, TetGrid grid, double cell_size, const BladeLimits& limits,
         CutMode mode, double min_temporary_height, double snap_fraction)
      : mesh_(mesh),
        grid_(std::move(grid)),
        memory_margin_(0.25 * cell_size),
        limits_(limits),
        mode_(mode),
        min_temporary_height_(min_temporary_height),
        snap_fraction_(snap_fraction) {}

  // Records the hits of the blade moving from `from` to `to`, and returns the tets near it
  // (progressive: the open tets for their pieces).
  std::vector<mesh::TetId> RecordHits(const BladePose& from, const BladePose& to);
  // Keeps the current positions of the vertices within `memory_margin_` of the blade.
  absl::Status RememberPositionsNear(const BladePose& pose);
  // How far `v` moved since the previous pose, m: zero for a vertex made since or farther
  // than `memory_margin_` from the blade then (tissue is taken to move less than that between
  // poses).
  Eigen::Vector3d MovedSincePrevious(mesh::VertexId v) const;
  bool BladeInside(const mesh::TetVertices& corners, const BladePose& pose) const;
  bool BladeInside(mesh::TetId t, const BladePose& pose) const {
    return BladeInside(mesh_->tet(t), pose);
  }
  // The tet a live tet stands for: its open tet if it is a temporary piece, else itself.
  mesh::TetId OwnerOf(mesh::TetId t) const;
  // Whether a hit on the edge (two vertices) or face (three) could be realised: every tet
  // around it has it among its corners, or is a temporary piece whose open tet does.
  bool Realisable(std::span<const mesh::VertexId> vertices) const;
  // The tets (as OwnerOf) with both vertices, or all three.
  std::vector<mesh::TetId> TetsWith(std::span<const mesh::VertexId> vertices) const;
  // Progressive: subdivides every open tet for the blade at `pose` (null: withdrawn).
  void UpdateOpenTets(const BladePose* pose);
  // What an open tet becomes in this pose: `split.tets` empty means it stays as it is.
  struct Plan {
    mesh::TetId tet;
    bool temporary;
    int table_case;
    TetSplit split = {};
    bool moved = false;       // temporary, made from the same inputs: `split.tets` are its pieces
    SplitInputs inputs = {};  // temporary: what `split` was made from
  };
  // The plans (by index) whose triangles on a face of their tet differ from those of the other
  // side: the plan there, or the live tets there if its tet is not open. Applying them all
  // keeps the mesh conforming exactly when this is empty. O(plans * pieces).
  std::vector<std::size_t> NonConformingPlans(const std::vector<Plan>& plans) const;
  // Each face of the `tets` (deferred: a group the blade has left; progressive: once the blade
  // is withdrawn; they could not be split) with one cut edge and no point gets a point halfway from
  // the cut to the face's middle, where the crack ends (the tet across the face shares it). Where
  // the blade crossed an edge beside a vertex, or the tissue's motion carried an edge across the
  // blade, neither the tip's path nor another cut may close the crack on such a face, and no case
  // covers it. Returns whether any point was added. Not a face a final subdivision has split
  // already, nor a tet with a cut near a corner (see kCrackEndMargin), nor a face the blade crossed
  // at the last pose (progressive: its point is the blade's).
  bool EndCracksOnFaces(const std::vector<mesh::TetId>& tets);
  // Makes the temporary points `which` picks (by place and vertex) permanent: a face point
  // becomes that face's hit, a point inside a tet an ordinary vertex.
  void MakePermanent(const std::function<bool(const FaceKey&, mesh::VertexId)>& which);
  // Ends an open tet's life as such, keeping what stands for it now.
  void CloseOpenTet(mesh::TetId t);
  // Forgets the hits of `corners` that no open tet has any more (removing the vertices made for
  // them that no tet took).
  void ForgetHitsOf(const mesh::TetVertices& corners);
  // An edge crossing found this pose: fraction from the lower-id vertex.
  struct Crossing {
    EdgeKey key;
    mesh::VertexId low, high;
    double fraction;
  };
  // Records this pose's edge crossings, snapping them where snap_fraction_ says (see
  // kDefaultSnapFraction), and adds the keys of the new hits to `new_edges`.
  // `normal`: the swept surface's, unit (zero: nothing snaps). `closed_now`: the closed hits
  // this pose's face crossings were snapped to; the blade crossing one of them in the same
  // pose passed it by less than the fraction, and it stays closed (else it opens).
  void RecordEdgeCrossings(const std::vector<Crossing>& crossings, const Eigen::Vector3d& normal,
                           const absl::flat_hash_set<EdgeKey>& closed_now,
                           std::vector<EdgeKey>* new_edges);
  // With snapping, the new ordinary hit `key` is closed where the tip's path crossed a face at
  // the edge within snap_fraction_ of its point (of the edge, barycentric; and along it): the
  // crack's front passes through it. Those face points (not made yet) are not made.
  void CloseAtFacePoints(EdgeKey key);
  // Puts each vertex on the crack, to be parted from the side its direction points to: the hits
  // waiting at it are taken at it and its tets join one group. Not a vertex with a hit waiting
  // on an edge to its own side, nor one at a tet split for good.
  void Snap(const absl::flat_hash_map<mesh::VertexId, Eigen::Vector3d>& to_snap);
  // The hit `key` of an edge between the snapped vertices `a` and `b`, made along the crack or
  // cut at one of them.
  void MarkEdgeBetweenSnapped(EdgeKey key, mesh::VertexId a, mesh::VertexId b);
  // Takes `v` off the crack: its hits are as they were found (those through it skipped), and
  // it does not snap again. Not once committed.
  void Unsnap(mesh::VertexId v);
  // The face crossing `key` (barycentric on its vertices in key order) taken on the edge it
  // lies within snap_fraction_ of, if it lies so near one edge (whose only hit, if any, is
  // closed, whose ends are not snapped, and which can be cut: Realisable) and not near a
  // vertex. Returns the edge's key if so.
  std::optional<EdgeKey> SnapToEdge(const FaceKey& key, const Eigen::Vector3d& barycentric);
  // The hit `key` (closed, or cut open by the blade, which closes it) takes the face crossing
  // `face` at `barycentric` (on its vertices in key order): the crack's front crosses the edge
  // there instead, and the crossing comes back if the edge is unsnapped.
  void CloseEdgeAt(EdgeKey key, const FaceKey& face, const Eigen::Vector3d& barycentric);
  // Whether a tet split for good (progressive: frozen) uses the closed hit's vertex: the
  // crack's front stays there.
  bool ClosedCutSettled(const EdgeHit& hit) const;
  // The closed hit `key` is dropped (with its vertex, if made: progressive, once no temporary
  // piece uses it), its face crossings given back as face hits: the edge opens (the blade
  // crossed it), or (deferred) a tet could not split with it.
  void UnsnapEdge(EdgeKey key);
  // Makes a point inside a tet from weights on its corners (a cone's apex).
  using ApexMaker = std::function<mesh::VertexId(const Eigen::Vector4d&)>;
  // The split of a tet the blade is not in with closed cuts, or with snapping one no case
  // covers: two tets at one closed cut alone, a complete cut if it is cut through, else a cone
  // from a point `apex_at` makes on its crack (the middle of its front: closed cuts and face
  // points, which must be hits) or else from its middle. Empty if none tiles (the points made
  // are the caller's to take back).
  TetSplit SplitAsCone(const mesh::TetVertices& corners, const std::vector<EdgeCut>& cuts,
                       const std::vector<FacePoint>& faces, const ApexMaker& apex_at);
  // Progressive: the snapped corners that `cuts` (of the tet `corners`, split for good) are
  // pinned at are committed: they stay on the crack.
  void Commit(const mesh::TetVertices& corners, const std::vector<EdgeCut>& cuts);
  // After the tets at them split: each of the snapped `vertices` is parted, its tets joined
  // through faces at it forming parts (the crack separates them; one part if the crack ends
  // there). The part on its own side keeps it, each other part gets a copy.
  // A vertex on the crack parted before may part again once a neighbour's parting separates
  // its star.
  void PartSnappedVertices(std::vector<mesh::VertexId> vertices);
  // Parts the star of `v` (snapped and parted, or a copy): returns the copies made, with v
  // itself if any was (their stars changed); none if the crack does not separate it.
  std::vector<mesh::VertexId> PartStar(mesh::VertexId v);
  // Progressive: parts the snapped vertices no open tet has (every tet at them is final), and
  // forgets their hits.
  void PartFinishedSnappedVertices();
  // Whether a tet at `v` waits to split: in a group (deferred), open or a temporary piece
  // (progressive). O(tets at v).
  bool Waiting(mesh::VertexId v) const;
  // The tets (as OwnerOf) with `v` among their corners.
  std::vector<mesh::TetId> OwnersAt(mesh::VertexId v) const;
  // Whether the edge has a hit that cuts it (not one along the crack), counting one pinned at a
  // snapped corner if `pinned`.
  bool IsCutEdge(mesh::VertexId a, mesh::VertexId b, bool pinned) const;
  // Joins the groups of tets that share a new hit (each made a group if it was not in one).
  void Join(std::span<const mesh::TetId> tets);
  mesh::TetId GroupOf(mesh::TetId t);
  // Splits the groups none of whose members the blade is inside: it can only be inside the
  // tets near it, `near` (every group if `near` is null). O(near + groups).
  void SplitReadyGroups(const BladePose* pose, const std::vector<mesh::TetId>* near);
  void SplitGroup(std::vector<mesh::TetId> group);
  // Makes (or finds) a temporary point at a place from weights on up to four vertices.
  using ClosedVertexMaker = std::function<mesh::VertexId(
      const FaceKey& place, const std::array<mesh::VertexId, 4>& from, const Eigen::Vector4d&)>;
  // The tet's cut edges, their vertices made if needed (and their keys added to `given`). A
  // cut whose point the blade at `pose` passes through is closed: the crack's front runs
  // through it, so it does not open yet; its one vertex (near_a == near_b) comes from
  // `closed_vertex`, needed with `pose`.
  std::vector<EdgeCut> EdgeCutsOf(const mesh::TetVertices& corners,
                                  std::vector<EdgeKey>* given = nullptr,
                                  const BladePose* pose = nullptr,
                                  const ClosedVertexMaker& closed_vertex = {});
  std::vector<FacePoint> FacePointsOf(const mesh::TetVertices& corners) const;
  // Whether a face crossing of `key` at `barycentric` (on its vertices in key order) lies within
  // snap_fraction_ (its other two barycentrics) of a snapped vertex: the crack's front passes
  // through the vertex, and the point is not made (it is again if the vertex is unsnapped).
  bool AtSnappedVertex(const FaceKey& key, const Eigen::Vector3d& barycentric) const;
  mesh::VertexId MakeVertex(const std::array<mesh::VertexId, 4>& from,
                            const Eigen::Vector4d& weights);
  // Moves a vertex the cut made to the place `weights` give on `from` (rest and current).
  void MoveMadeVertex(mesh::VertexId v, const std::array<mesh::VertexId, 4>& from,
                      const Eigen::Vector4d& weights);

  mesh::TetMesh* mesh_;
  TetGrid grid_;
  double memory_margin_;  // m
  BladeLimits limits_;
  CutMode mode_;
  double min_temporary_height_;  // a fraction of the smallest height
  double snap_fraction_;         // of an edge's length
  // Snapped vertices whose tets wait to split, with the direction of the side they do not keep,
  // and the vertices that snapped once (they do not again).
  struct SnappedVertex {
    Eigen::Vector3d far;  // towards the side it does not keep
  };
  absl::flat_hash_map<mesh::VertexId, SnappedVertex> snapped_;
  absl::flat_hash_set<mesh::VertexId> was_snapped_;
  absl::flat_hash_set<mesh::VertexId> committed_;  // see Commit
  // Snapped vertices parted (copies made or not), with the side each gave up.
  absl::flat_hash_map<mesh::VertexId, Eigen::Vector3d> parted_;
  absl::flat_hash_map<mesh::VertexId, mesh::VertexId> parted_from_;  // copy -> vertex
  std::optional<BladePose> previous_;
  // The current positions, when the previous pose was applied, of the vertices then near the
  // blade (by index).
  absl::flat_hash_map<std::uint32_t, Eigen::Vector3d> positions_at_previous_;
  absl::flat_hash_map<EdgeKey, EdgeHit> edge_hits_;
  absl::flat_hash_map<FaceKey, FaceHit, FaceKeyHash> face_hits_;
  // The face crossings each closed hit stands for (see SnapToEdge).
  absl::flat_hash_map<EdgeKey, std::vector<std::pair<FaceKey, Eigen::Vector3d>>>
      edge_snapped_faces_;
  // Groups of unsplit tets with hits, joined through shared hits: a union-find forest over the
  // tets (parent links) and the members of each root.
  absl::flat_hash_map<mesh::TetId, mesh::TetId> group_of_;
  absl::flat_hash_map<mesh::TetId, std::vector<mesh::TetId>> members_;
  absl::flat_hash_map<mesh::TetId, mesh::TetId> source_tet_;  // tets the cut made, by source
  // Progressive state: the open tets, their pieces' owners, and the temporary points in the
  // mesh by place (a face key, or the tip's tet as {t, t, t}).
  absl::flat_hash_map<mesh::TetId, OpenTet> open_;
  absl::flat_hash_map<mesh::TetId, mesh::TetId> owner_;
  absl::flat_hash_map<FaceKey, TemporaryPoint, FaceKeyHash> temporary_points_;
  // Faces of tets whose subdivision is final: a point added to one later (the blade coming
  // back) would split it differently on its two sides, so none is.
  absl::flat_hash_set<FaceKey, FaceKeyHash> settled_faces_;
  std::vector<MadeVertex> made_vertices_;
  CutStatistics statistics_;
  PoseSummary last_pose_;
};

}  // namespace kerf::cut
