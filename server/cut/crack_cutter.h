// Cuts a tet mesh along a blade's path with steps that are total: whatever points the blade
// leaves on a tet's edges and faces, the tet is split (cut/crack_split.h), so nothing the blade
// did is dropped, held back or frozen. The crack is a set of points named by origins
// (cut/star_parting.h), so the two lips share them: at most one on each edge and one inside each
// face, and the vertices it passes through (snapped once per crossing); what is cut stays cut.
// Progressive (the default): after every pose each tet with new points, or that the blade is or
// was in, splits at once, the blade's crossings temporary points; deferred: a group of tets that
// share points splits once the blade meets none of them. After every split the crack's vertices
// are parted. docs/cutting-fidelity.md ("The cutter") states each rule, its reason and measures.
#pragma once

#include <algorithm>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/container/flat_hash_set.h"
#include "absl/functional/function_ref.h"
#include "absl/status/statusor.h"
#include "cut/blade.h"
#include "cut/blade_crossings.h"
#include "cut/cone_apex.h"
#include "cut/crack_cutter_state.h"
#include "cut/crack_split.h"
#include "cut/crack_tolerances.h"
#include "cut/cut_statistics.h"
#include "cut/star_parting.h"
#include "cut/swept_path.h"
#include "cut/tissue_surface.h"
#include "geometry/segment_triangle_intersection.h"
#include "mesh/tet_mesh.h"

namespace kerf::cut {

// Where a vertex the cut made comes from: weights on up to four vertices (an edge's two, a
// face's three, a tet's four), the same for its rest and current positions. Data attached to
// vertices (displacement, velocity) follows it by the same weights.
struct MadeVertex {
  mesh::VertexId vertex;
  std::array<mesh::VertexId, 4> from;  // unused entries have weight 0
  Eigen::Vector4d weights;
};

enum class CutMode { kProgressive, kDeferred };

struct CrackCutterOptions {
  CutMode mode = CutMode::kProgressive;
  // In [0, 0.5); below kMinSnapFraction it is that.
  double snap_fraction = kDefaultCrackSnapFraction;
  // In [0, 1): see kDefaultMinTemporaryHeight (0: no piece is soft).
  double min_temporary_height = kDefaultMinTemporaryHeight;
};

class CrackCutter {
 public:
  // The mesh must outlive the cutter and change only through it while it cuts. `cell_size` (m):
  // a mean edge length is a good choice. INVALID_ARGUMENT for a bad size or option.
  static absl::StatusOr<CrackCutter> Create(mesh::TetMesh* mesh, double cell_size,
                                            const BladeLimits& limits = {},
                                            const CrackCutterOptions& options = {});

  // Applies one pose. INVALID_ARGUMENT (and nothing changed) for a bad pose. The first pose only
  // places the blade.
  absl::Status ApplyPose(const BladePose& pose);
  // The blade is withdrawn: the crack ends where it was, and every tet still waiting splits.
  void Finish();
  absl::Status MeshDeformed() { return crossings_.MeshDeformed(); }
  // The oldest point of the mesh's change log the cutter will read again.
  mesh::ChangeMark synced() const { return crossings_.synced(); }

  // The ids the cutter names, live or removed: tets the blade opened, the tissue's tets pieces
  // stand in for, points, their origins and copies. The mesh must not give a removed one of
  // them to a new element (see TetMesh::ReuseIdsRemovedBefore). O(the cutter's state).
  struct HeldIds {
    absl::flat_hash_set<mesh::VertexId> vertices;
    absl::flat_hash_set<mesh::TetId> tets;
  };
  HeldIds Held() const;

  CutMode mode() const { return mode_; }
  const CutStatistics& statistics() const { return statistics_; }
  const PoseSummary& last_pose() const { return last_pose_; }
  // Tets with points not split for good.
  std::size_t waiting_tets() const { return group_of_.size() + open_.size(); }
  mesh::TetId SourceTet(mesh::TetId t) const;
  // Whether `t` is a piece of a tet split in two or more (not one the blade opened and left
  // whole again).
  bool MadeByCut(mesh::TetId t) const {
    const auto it = source_tet_.find(t);
    if (it == source_tet_.end()) return false;
    const auto pieces = pieces_of_source_.find(it->second);  // none: renamed by parting only
    return pieces != pieces_of_source_.end() && pieces->second >= 2;
  }
  // The vertex `v` is a copy of (v itself if it is none).
  mesh::VertexId PartedFrom(mesh::VertexId v) const { return parting_.Origin(v); }
  // The vertices made or moved since the last call that are still alive.
  std::vector<MadeVertex> TakeMadeVertices();

  // The corners of the tets the blade at `pose` meets (current positions): of each piece of a
  // tet the blade is opening, of every other tet itself. O(tets near the blade).
  std::vector<mesh::TetVertices> TetsHoldingBlade(const BladePose& pose) const;
  // The share of its stiffness the elastic model gives `t`: for a piece with a point on the
  // blade (progressive) lower than min_temporary_height times the smallest height of the tet it
  // stands in for, its height over that guard, so it is no stiffer than a piece of the guard's
  // height; 1 for every other tet. Rest positions. O(points on the blade).
  double StiffnessScale(mesh::TetId t) const;

 private:
  static constexpr mesh::VertexId kNoVertex = crack_state::kNoVertex;
  using EdgePoint = crack_state::EdgePoint;
  using FacePoint = crack_state::FacePoint;
  using CrackTraces = crack_state::CrackTraces;
  using OpenTet = crack_state::OpenTet;
  using BladeIn = crack_state::BladeIn;
  using CrackFace = crack_state::CrackFace;
  using CrackFaces = absl::flat_hash_map<FaceKey, CrackFace, FaceKeyHash>;

  CrackCutter(mesh::TetMesh* mesh, BladeCrossings crossings, const BladeLimits& limits,
              const CrackCutterOptions& options)
      : mesh_(mesh),
        crossings_(std::move(crossings)),
        surface_(TissueSurface::Of(*mesh)),
        limits_(limits),
        mode_(options.mode),
        snap_fraction_(std::max(options.snap_fraction, kMinSnapFraction)),
        min_temporary_height_(options.min_temporary_height) {}

  // The places of temporary points: a face's (its key's hash, the two high bits clear), an open
  // tet's apex, the point opening one of its crack faces, and an edge's.
  static std::uint64_t FacePlace(const FaceKey& key) {
    return absl::HashOf(mesh::Index(key[0]), mesh::Index(key[1]), mesh::Index(key[2])) >> 2;
  }
  static std::uint64_t ApexPlace(mesh::TetId unit) {
    return (std::uint64_t{1} << 63) | mesh::Index(unit);
  }
  static std::uint64_t OpeningPlace(mesh::TetId unit, const FaceKey& key) {
    return (std::uint64_t{1} << 62) | (absl::HashOf(mesh::Index(unit), FacePlace(key)) >> 2);
  }
  // The point opening a crack face in a face between two units, the same for both.
  static std::uint64_t FaceOpeningPlace(const FaceKey& key) {
    return OpeningPlace(mesh::TetId(0xffffffffu), key);
  }
  static std::uint64_t EdgePlace(EdgeKey key) {
    return (std::uint64_t{3} << 62) | (absl::HashOf(key) >> 2);
  }
  // A tet as the crack sees it: a live tet, or an open tet (by its id before it opened).
  mesh::TetId UnitOf(mesh::TetId t) const;
  mesh::TetVertices CornersOf(mesh::TetId unit) const;  // origins
  // The ids the unit's tets use for its corners, in CornersOf's order: where a corner was parted,
  // the copy on the unit's side, whose positions and state are the unit's (the first found where
  // the unit's own crack parts the corner). Kept in the open unit until the tets change.
  mesh::TetVertices PlacedCorners(mesh::TetId unit) const;
  std::vector<mesh::TetVertices> PlacedCornersOfAll(const std::vector<mesh::TetId>& units) const;
  // Crossings found on placed ids, named by origins.
  Crossings ByOrigins(Crossings found) const;
  // The units of `tets`, each once.
  std::vector<mesh::TetId> UnitsOf(std::vector<mesh::TetId> tets) const;
  // The units with a tet whose box meets the blade's at `pose`: all of them, so that a face the
  // blade crosses only by rounding (lying in its plane beside it) is seen from both sides.
  std::vector<mesh::TetId> UnitsAt(const BladePose& pose) const;
  // The units with a tet whose box meets that of the surface the blade's edge sweeps from `from`
  // to `to`, and lies within kStepMargin grid cells of the surface (BladeCrossings::NearSweep).
  std::vector<mesh::TetId> UnitsNearStep(const BladePose& from, const BladePose& to) const;
  std::vector<mesh::TetId> UnitsAround(const std::vector<mesh::VertexId>& origins) const;
  std::vector<mesh::TetVertices> CornersOfAll(const std::vector<mesh::TetId>& units) const;

  // Whether the point `x` (rest positions) on the element of `origins` lies within Reach of the
  // tets at it of a crack face made before, in a tet at one of `origins`: before the
  // oldest group there is now began (the blade's visit), open (its two sides have vertices of
  // their own: a face parting left shut has cut nothing yet), and not one of an open unit's own
  // crack faces. The crack is there already.
  bool OnTheCrackAlready(const Eigen::Vector3d& x, std::span<const mesh::VertexId> origins) const;
  // Whether `x` (rest positions) lies within `reach` (m) of a crack face of a tet `t` at one of
  // `origins` that `counts(t, ids, key, face)` accepts, `ids` the face's vertices as t names them.
  bool CrackFaceWithin(const Eigen::Vector3d& x, std::span<const mesh::VertexId> origins,
                       double reach,
                       absl::FunctionRef<bool(mesh::TetId, const std::array<mesh::VertexId, 3>&,
                                              const FaceKey&, const CrackFace&)>
                           counts) const;
  // Where a face's crossing comes from: a step's sweep; the blade leaving the face (its farthest
  // crossing, kept a point of the face: see StaysInTheFace); or the blade withdrawn there.
  enum class FaceCrossingsFrom { kSweep, kBladeLeft, kWithdrawal };
  // Records crossings as points (snapping them); adds the units they touch.
  void RecordCrossings(const Crossings& found, std::vector<mesh::TetId>* touched,
                       FaceCrossingsFrom from = FaceCrossingsFrom::kSweep);
  // Whether a face's crossing near the edge low-high (its smallest weight's opposite) stays a
  // point of the face rather than being taken as the edge's crossing. One the blade left does
  // (it came near an edge without crossing it: taken at the edge, the crack would reach every tet
  // around it).
  bool StaysInTheFace(const FaceCrossing& c, double share, mesh::VertexId low, mesh::VertexId high,
                      FaceCrossingsFrom from) const;
  // The rest position of barycentric weights on a face's vertices (key order).
  Eigen::Vector3d RestAt(const FaceKey& face, const Eigen::Vector3d& barycentric) const;
  // The rest positions of a face's points for good on its corners and edges: its corners on the
  // crack and its edges' points.
  std::vector<Eigen::Vector3d> OwnPointsOf(const FaceKey& key) const;
  // The rest position of the edge a-b's point for good, if it has one.
  std::optional<Eigen::Vector3d> EdgePointAt(mesh::VertexId a, mesh::VertexId b) const;
  // Where an edge's crossing comes from: the blade's edge swept across the edge in a step, or the
  // blade, having lain across the edge (a temporary point the pieces around stood on), left it.
  enum class EdgeCrossingFrom { kSweep, kBladeLeaving };
  void RecordEdgeCrossing(mesh::VertexId low, mesh::VertexId high, double fraction,
                          EdgeCrossingFrom from, std::vector<mesh::TetId>* touched);
  // Where a point of the edge low-high at `fraction` goes: within the snap share of a corner (or
  // within the sliver share, where a piece under kSliverAngleDeg or a thin corner would come of
  // it), that corner snaps onto the crack if it may (MaySnap; none is returned), else the point
  // moves away from it, out of those shares as far as it may without leaving the reach of where
  // the blade was (where `may_move`; else it stays). `units`: those at the edge. Adds the units a
  // snap touches.
  std::optional<double> EdgePointOffCorners(mesh::VertexId low, mesh::VertexId high,
                                            double fraction, EdgeCrossingFrom from, bool may_move,
                                            const std::vector<mesh::TetId>& units,
                                            std::vector<mesh::TetId>* touched);
  // Snaps the corners of `units` within the snap fraction of their unit's mean edge of the
  // step's swept surface (the blade through a vertex, along an edge or in a face's plane crosses
  // no edge inside).
  void SnapVerticesNear(const std::vector<mesh::TetId>& units, std::vector<mesh::TetId>* touched);
  // Puts `v` on the crack, and decides, for each edge from it to a vertex on the crack already,
  // whether the crack runs along that edge: where the edge's middle lies within kJoinReach of the
  // tissue's edge there of the surface the blade swept between the poses its two ends came onto
  // the crack (the last kJoinSteps steps at the most). Two vertices the blade passed at two
  // places, such as the corner it comes out by and one it runs along a side to, do not join.
  void Snap(mesh::VertexId v, std::vector<mesh::TetId>* touched);
  // Whether the crack runs along the edge (origins) where both its ends are on it (Snap).
  bool EdgeOnCrack(mesh::VertexId a, mesh::VertexId b) const;
  // Whether `x` (current positions) lies within `reach` (m) of the surface the blade swept from
  // pose `first` to pose `last`; true where `first` is older than the poses kept (swept_).
  bool SweptNear(const Eigen::Vector3d& x, std::size_t first, std::size_t last, double reach) const;
  // The point of the step's swept surface (its two triangles) nearest `x`, current positions;
  // only within a step.
  Eigen::Vector3d NearestOnStep(const Eigen::Vector3d& x) const;
  // The distance from `x` (current positions) to the step's swept surface (0 outside a step).
  double DistanceToStep(const Eigen::Vector3d& x) const;
  // kSnapReach of the smallest mean edge of `units` (the tissue's, for pieces).
  double Reach(const std::vector<mesh::TetId>& units) const;
  // Whether `v` may snap onto the crack: it lies within Reach of its units of the step's swept
  // surface and, for a crossing the blade swept (`from`), snapping it would not lay the crack on
  // the tissue's surface (the blade passing through it to the least snapping, it may).
  // How far a vertex is from where the step's swept surface crosses the tissue's surface
  // triangles at it (current positions); none where it crosses none (or off the surface).
  std::optional<double> DistanceToTheEntry(mesh::VertexId v) const;
  bool MaySnap(mesh::VertexId v, EdgeCrossingFrom from = EdgeCrossingFrom::kSweep) const;
  // Whether snapping `v`, a vertex of the tissue's surface, would lay the crack on the surface
  // and lose what the blade cut under it: the tip's path passes within `reach` (m) of the point
  // of the step's swept surface nearest v, under the surface there, and v lies on the heel's side
  // of it (the blade came in through the surface near v and went no deeper: it grazed the
  // surface, or its tip ran just under it), or the blade swept along the surface there
  // (kAlongSurfaceCosine). False for a vertex not on the surface, or outside a step.
  bool SnapWouldLayCrackOnSurface(mesh::VertexId v, double reach) const;
  // Whether bisecting one of `units` (those at the edge) at the point `fraction` from `low` to
  // `high` leaves a half under kSliverAngleDeg (rest positions).
  bool BisectionLeavesSliver(mesh::VertexId low, mesh::VertexId high, double fraction,
                             const std::vector<mesh::TetId>& units) const;
  // Whether the edge from `corner` to `other` meets another edge of one of `units` at `corner`
  // under kThinCornerDeg (rest positions): a point on it near that corner makes a thin triangle
  // with that edge, in whatever split.
  bool IsThinCorner(mesh::VertexId corner, mesh::VertexId other,
                    const std::vector<mesh::TetId>& units) const;
  // The share of a crossing's edge (or face) within which it snaps to a corner: the snap
  // fraction of the tissue's edge length there, so a piece's edges snap as far as the edges of
  // the tet it is part of (cuts through pieces make no smaller pieces than cuts through tets).
  double SnapShare(std::span<const mesh::VertexId> corners) const;
  // Whether `origin` is a point the cut made inside a tet (a cone's apex, the blade's, the middle
  // of a crack face it opened). Such a point is never snapped onto the crack: snapped, the pieces
  // around it would split as cones with apexes of their own near the blade, snapped in turn at
  // the next pose (a blade sweeping again beside the crack multiplied its pieces without end).
  bool IsInnerPoint(mesh::VertexId origin) const {
    const auto it = recipe_.find(origin);
    return it != recipe_.end() && (it->second.weights.array() != 0).count() == 4;
  }
  // A made point's PointRecipe::scale (0 for the tissue's own vertices).
  double TissueScale(mesh::VertexId origin) const {
    const auto it = recipe_.find(origin);
    return it == recipe_.end() ? 0 : it->second.scale;
  }
  double ScaleOf(const std::array<mesh::VertexId, 4>& origins,
                 const Eigen::Vector4d& weights) const;
  // The mean rest length of the edges between `vertices` (0 for fewer than two) and the largest
  // TissueScale among them.
  struct Lengths {
    double mean_edge = 0, scale = 0;
    // The tissue's edge length there: the mean edge, or a made point's scale if larger (a
    // piece's edges are shorter than its tissue's).
    double tissue_edge() const { return std::max(mean_edge, scale); }
  };
  Lengths LengthsOf(std::span<const mesh::VertexId> vertices) const;
  // The blade's crossings of faces and edges at a pose, by face and edge (origins).
  struct BladeCrossingsAt {
    absl::flat_hash_map<FaceKey, std::optional<geometry::SegmentTriangleCrossing>, FaceKeyHash>
        faces;
    absl::flat_hash_map<EdgeKey, std::optional<double>> edges;
  };
  // The blade's points in the unit, if the blade at `pose` meets it (crosses a face, passes
  // through an edge, or has an end inside); `found` keeps the crossings, for the units sharing
  // each face and edge, so they agree on them.
  std::optional<BladeIn> BladeInUnit(mesh::TetId unit, const BladePose& pose,
                                     BladeCrossingsAt* found) const;
  // The units the blade at `pose` meets, with its points in each.
  absl::flat_hash_map<mesh::TetId, BladeIn> BladeUnitsAt(const BladePose& pose) const;
  // Whether the blade passing through the edge at `fraction` (from its lower id) is farther from
  // its end on the crack than its point: the crack's front, lying along the edge, advances. The
  // blade's point then stands in for the edge's while the blade is there (a blade trembling
  // across the plane of faces crossed their edges, and the crack's front stayed where it
  // crossed them first).
  bool AdvancesAlongTheCrack(EdgeKey key, double fraction) const;
  // Progressive: a temporary edge point the blade at the new pose no longer makes (it left the
  // edge's plane, or the edge behind) becomes a point for good where it was last, snapped as
  // any crossing: what was cut stays cut.
  void KeepEdgePointsLeft(const absl::flat_hash_map<mesh::TetId, BladeIn>& blade,
                          std::vector<mesh::TetId>* touched);
  // Progressive: a face of the units in groups (those with points) the blade's edge crossed and
  // at this pose (`blade`, BladeUnitsAt's crossings) no longer does: where its crossing reached
  // farther than kSnapReach of the tissue's edge there from the crack the points for good of the
  // tets at the face span, and from every crack face at the face's corners (the blade went into a
  // tet and came back the way it went: a reversal, a hairpin), the farthest such crossing becomes
  // the face's point, snapped as any crossing, so the crack reaches where the blade did.
  // Crossings on an edge of the face are the edge's (KeepEdgePointsLeft). `blade` null: every
  // face it crossed (it is withdrawn).
  void KeepFarthestFaceCrossings(const absl::flat_hash_map<mesh::TetId, BladeIn>* blade,
                                 std::vector<mesh::TetId>* touched);
  // Of `crossings` (barycentric on the face key's vertices), the one farthest from the crack the
  // points for good of the tets at the face span (each tet's corners on the crack, edge and face
  // points, and the segments and triangles between them) of those farther than kSnapReach of the
  // tissue's edge there and from every crack face at the face's corners (an open unit's too:
  // while the blade is in it, its crack reaches the blade), and not beside the tissue's
  // surface (within kSnapReach, as a share of the face, of a corner or an edge of it on the
  // surface); none where the face has no such point of its own.
  std::optional<Eigen::Vector3d> FarthestFromTheFacesCrack(
      const FaceKey& key, const std::vector<Eigen::Vector3d>& crossings) const;

  // Splits the units (for good, or temporarily where `blade` has them), then parts the crack's
  // vertices and forgets temporary points no split uses.
  void SplitUnits(std::vector<mesh::TetId> units,
                  const absl::flat_hash_map<mesh::TetId, BladeIn>& blade);
  // Splits one unit, opening its crack faces in `to_open` and those it opened before (where the
  // split still has them); returns the origins whose parting may have changed.
  std::vector<mesh::VertexId> SplitUnit(mesh::TetId unit, const BladeIn* blade,
                                        std::span<const FaceKey> to_open = {});
  // Replaces the unit's tets by `split`'s pieces, `openings` open in them (and one in a face of
  // it if `opened_in_face`), unless they are its pieces now; returns as SplitUnit does.
  std::vector<mesh::VertexId> LayOut(mesh::TetId unit, const TetCrack& crack,
                                     const std::array<FacePoints, 4>& points,
                                     const CrackTraces& traces, const CrackSplit& split,
                                     std::vector<FaceKey> openings, bool opened_in_face,
                                     bool blade_in);
  // Whether the open unit's pieces stand as they are with the blade in it at `points`: the
  // same points as when they were made (only temporary ones moved), no crack face in a face of it
  // opened, crack faces opened inside only in the cone from the blade's point that a split made
  // anew would be again (SplitsAsTheBladesCone), and every piece still holding over half of
  // OpenTet::smallest_volume (a piece thinned further
  // by the moving points, the layout is chosen again: a sliver the tissue inverts makes the
  // corotational law pump energy into it). A cone's apex then moves with the blade, and the
  // points opening crack faces inside it with the middles of those faces.
  bool PiecesStand(mesh::TetId unit, const std::array<FacePoints, 4>& points, const BladeIn& blade);
  // The open unit's pieces and crack faces, by origins, as a split.
  CrackSplit PiecesAsSplit(mesh::TetId unit) const;
  // A crack face of an open unit that parting left shut (its sides use the same vertices: every
  // corner lies on the crack's edge, the blade or the tip's path), and for one in a face of the
  // unit the open unit beside it that must open it alike (none if it is inside the unit).
  struct ShutFace {
    FaceKey key;
    std::optional<mesh::TetId> beside;
  };
  // Those of `unit` that can open: inside it, or in a face shared with a unit the blade is in
  // (`blade`), which is split again with it.
  std::vector<ShutFace> ShutCrackFaces(
      mesh::TetId unit, const absl::flat_hash_map<mesh::TetId, BladeIn>& blade) const;
  // Opens the crack face `key` of `split` (if it has it) at a point in its middle: for a face
  // inside the unit, on the unit's corners; for one in a face of the unit, on that face's
  // corners, the same point for the unit beside it. Returns CrackFaceSides (0: not opened).
  int OpenAtItsMiddle(mesh::TetId unit, const TetCrack& crack, const FaceKey& key,
                      CrackSplit* split);
  // The middle of the face `key` (rest positions), barycentric on `corners`.
  Eigen::Vector4d MiddleOf(const mesh::TetVertices& corners, const FaceKey& key) const;
  static CrackTraces TracesOf(const TetCrack& crack);
  // Whether a split of the unit by the crack's points alone (no point of the blade's inside)
  // would leave the blade off the crack: where the crack has traces and the tip is inside (no
  // such split has the tip on its crack; the paper's Table 1 splits a tet at the tip), or where
  // every trace lies in one face the blade crosses (it came in by that face: the crack would lie
  // in it; a blade lying in the face's plane crosses it not, and its crack does lie there).
  static bool MissesTheBlade(const CrackTraces& traces, const BladeIn& blade);
  // Whether the unit, with the blade in it at `points`, splits as the cone from the blade's point:
  // a face has the blade's point beside its own (no minimal case fits), or a split of the points
  // alone would miss the blade.
  static bool SplitsAsTheBladesCone(const std::array<FacePoints, 4>& points,
                                    const CrackTraces& traces, const BladeIn& blade);
  // The unit's case of the paper's Table 1 with the blade in it (0: none of the eleven).
  int TableCase(const mesh::TetVertices& corners, const BladeIn& blade) const;
  // Whether the pieces (live tets) are the split's tets, up to copies and orientation.
  bool SamePieces(const std::vector<mesh::TetId>& pieces,
                  const std::vector<mesh::TetVertices>& split) const;
  std::array<FacePoints, 4> PointsOf(const mesh::TetVertices& corners, const BladeIn* blade);
  // The hub of face `key` (its three edge points, weights on key's vertices), for good: their
  // middle, or where that is over kStepCoverReach l off the blade's path since a unit at the face
  // met it, of it and the points 0.25 and 0.55 of the way to each edge point, the nearest the path.
  Eigen::Vector3d HubNearThePath(const FaceKey& key,
                                 const std::array<Eigen::Vector3d, 3>& edge_points) const;
  // Where the blade crosses the face `key` (barycentric on its vertices), which has a point for
  // good, well inside a triangle of that point's fan: a temporary point beside it (p->beside), so
  // the crack runs from where the tip's path crossed the face to the blade. Else nothing.
  void PlaceBesidePoint(const FaceKey& key, const Eigen::Vector3d& crossing, FacePoints* p);
  // The weights on `key`'s vertices of `v`: one of them, or a point the cut made on the face.
  Eigen::Vector3d WeightsOnFace(const FaceKey& key, mesh::VertexId v) const;
  mesh::VertexId EdgePointVertex(mesh::VertexId a, mesh::VertexId b);
  mesh::VertexId FacePointVertex(const FaceKey& key);
  // New points (and temporary ones moved) take their positions, and the state the simulation
  // gives them, from `weights` on `origins` as their own side's tets name them (PlaceOnItsSide;
  // a new point once parting is done). The point at `place`, made or moved; asked again in one
  // split of units with the same recipe and no tets changed (each unit at it asks), left as it is.
  mesh::VertexId TemporaryVertex(std::uint64_t place, const std::array<mesh::VertexId, 4>& origins,
                                 const Eigen::Vector4d& weights);
  mesh::VertexId MakeVertex(const std::array<mesh::VertexId, 4>& origins,
                            const Eigen::Vector4d& weights);
  // Removes a point the cut made, with its copies and its recipe, if no tet uses them.
  bool RemovePointIfUnused(mesh::VertexId point);
  // Moves `v` (a point the cut made, or a copy of one) to `weights` on `origins` as the tets
  // around it name them, so it takes its own side's place and state; a copy whose tets lack
  // them (a chip the crack cut off) keeps its displacement.
  void PlaceOnItsSide(mesh::VertexId v, const std::array<mesh::VertexId, 4>& origins,
                      const Eigen::Vector4d& weights);
  // `origins` as the tets around `v` name them; none if they lack one `weights` uses.
  std::optional<std::array<mesh::VertexId, 4>> PlacedAround(
      mesh::VertexId v, const std::array<mesh::VertexId, 4>& origins,
      const Eigen::Vector4d& weights) const;
  // `origins` with each not yet `found` replaced by the first id `tets` use for it (a copy or
  // the origin itself), marking it found.
  std::array<mesh::VertexId, 4> NamedIn(std::span<const mesh::TetId> tets,
                                        std::array<mesh::VertexId, 4> origins,
                                        std::array<bool, 4>* found) const;
  // Where the blade is withdrawn from the unit with its tip inside, or no split without a point
  // inside fits the unit's points: its point there (withdrawn_at_, barycentric), if inside and
  // the cone from it has no piece under kSliverAngleDeg. The unit splits for good as that cone,
  // its crack reaching the point, as while the blade was there.
  std::optional<Eigen::Vector4d> WithdrawnApex(mesh::TetId unit, const TetCrack& crack,
                                               bool fits_without) const;
  // The pose the step in which the blade first met the unit starts at (met_at_); none for a unit
  // the blade never met.
  std::optional<std::size_t> FirstPoseIn(mesh::TetId unit) const;
  // Samples of the blade's steps inside the unit since it first met it (StepSamplesIn, its
  // `tip_inside` too), weights on its corners; none for a unit the blade never met.
  std::vector<Eigen::Vector4d> StepsInUnit(mesh::TetId unit, bool* tip_inside = nullptr) const;
  // Whether a point (barycentric on `corners`, the unit's origins) lies within kApexReach of the
  // unit's mean edge of the surface the blade swept since it first met the unit (met_at_); null
  // for a unit the blade never met.
  ApexNearPath NearPath(mesh::TetId unit, const mesh::TetVertices& corners) const;
  // For good: the apex of a cone that covers the blade's steps inside the unit (StepSamplesIn,
  // since the blade first met it) better than the split to make (`split`, or if null the cone
  // from `apex`, on its crack if `apex_on_crack`): where samples lie farther than
  // kStepCoverReach of the tissue's edge from that split's crack, of the farthest and
  // kCoveringApexCandidates more spread over the samples, each pulled inside (PulledInside), the
  // one whose cone leaves fewest samples that far (fewer than the split), among those near the
  // path (NearPath) whose cone has no piece under kCoveringConeAngleDeg. Where the split's crack
  // has no face, its traces lie in the tissue's surface (TraceInTheTissueSurface) and the blade's
  // tip went through the unit, the blade grazed the surface and cut under it: the apex is on the
  // cone's crack, which runs from the traces to it.
  struct CoveringApex {
    Eigen::Vector4d weights;
    bool on_crack = false;
  };
  // Whether a face of the tissue's boundary holds all the crack's traces.
  bool TraceInTheTissueSurface(const TetCrack& crack) const;
  std::optional<CoveringApex> ApexCoveringTheSteps(mesh::TetId unit, const TetCrack& crack,
                                                   const CrackSplit* split,
                                                   const std::optional<Eigen::Vector4d>& apex,
                                                   bool apex_on_crack) const;
  // Puts `pieces` (oriented on rest positions) in place of the unit's tets.
  // Keeps cut_tets and new_tets: the tissue's tets standing in two pieces or more, and those.
  void CountPieces(mesh::TetId source, std::size_t removed, std::size_t added);
  std::vector<mesh::TetId> Replace(mesh::TetId unit, const std::vector<mesh::TetVertices>& pieces);
  void Repart(const std::vector<mesh::VertexId>& origins);
  void AddCrack(const FaceKey& key) {
    if (kept_off_.contains(key)) return;
    CrackFace& face = crack_[key];
    if (face.marks++ == 0) {
      face.since = poses_;
      ++crack_faces_since_[poses_];
    }
  }
  void RemoveCrack(const FaceKey& key);
  // Takes the face off the crack whatever marks it, with its count in crack_faces_since_.
  void EraseCrack(CrackFaces::iterator face);

  // The groups of units sharing points: they split together (deferred) and stay open together
  // (progressive), so a unit split from its own faces never meets one split finer.
  void Join(const std::vector<mesh::TetId>& units);
  // Removes the group named `root`, returning its units.
  std::vector<mesh::TetId> TakeGroup(mesh::TetId root);
  // Closes the groups the blade at `pose` meets none of (every group if null), splitting them
  // first (deferred).
  void SplitReadyGroups(const BladePose* pose);
  // Progressive: closes the groups none of blade_units_ is in, and the open units in no group the
  // blade is not in.
  void CloseUnitsTheBladeLeft();
  // Their pieces become units of their own.
  void CloseUnits(const std::vector<mesh::TetId>& units);
  // Whether `v` lies on the crack: snapped onto it, or a point the cut made.
  bool OnTheCrack(mesh::VertexId v) const;
  bool AllCornersOnTheCrack(const mesh::TetVertices& corners) const;
  // The chip `seed` is in: the tets joined to it through faces not on the crack, if they are
  // at most a few, all their corners lie on the crack, none is a piece of a unit the blade is
  // in, and they are not the whole tissue. Marks the tets it looks at in `seen`.
  std::optional<std::vector<mesh::TetId>> ChipAt(mesh::TetId seed,
                                                 absl::flat_hash_set<mesh::TetId>* seen) const;
  // The crack face (origins) a chip holds by: its largest, rather one beside a tet with a
  // corner off the crack.
  std::optional<FaceKey> FaceToHoldChipBy(const std::vector<mesh::TetId>& chip) const;
  // The faces (origins) of the units with `triangle` in one of their faces: a unit of its own
  // whose face it is, and an open unit's face whose points it is on.
  std::vector<FaceKey> UnitFacesWith(const FaceKey& triangle) const;
  // Each chip the tets `seeds` are in holds by a face kept off the crack for both sides: the
  // crack walled it in (its corners snapped onto the crack) where the blade did not cut around
  // it, so the cut frees nothing the blade did not cut off.
  void HoldChips(std::vector<mesh::TetId> seeds);
  // Once the blade is withdrawn: a crack face inside the tissue none of whose corners the crack
  // parts (its corners all lie on the crack's front, where the front turns) cannot open; a point
  // in its middle, on the crack and parted, opens it.
  void OpenShutCrackFaces();
  // The weights on `key`'s corners of the point it opens at, `units` the tets beside it (see
  // cut/opening_point.h).
  Eigen::Vector3d OpeningPointAt(const FaceKey& key, const std::vector<mesh::TetId>& units) const;

  mesh::TetMesh* mesh_;
  BladeCrossings crossings_;
  TissueSurface surface_;
  BladeLimits limits_;
  CutMode mode_;
  double snap_fraction_;
  double min_temporary_height_;
  std::optional<BladePose> previous_;
  // The step being cut (from the previous pose to this one) while ApplyPose runs; the last pose
  // twice while Finish records where the blade was.
  std::optional<std::pair<BladePose, BladePose>> step_;
  VertexParting parting_;
  absl::flat_hash_map<EdgeKey, EdgePoint> edge_points_;               // by origins
  absl::flat_hash_map<FaceKey, FacePoint, FaceKeyHash> face_points_;  // by origins
  absl::flat_hash_set<mesh::VertexId> on_crack_;                      // origins
  // The pose each vertex snapped at (the crack's other vertices are on it from the start), the
  // edges between snapped vertices the crack runs along, and the poses of the last kJoinSteps
  // steps.
  absl::flat_hash_map<mesh::VertexId, std::size_t> snapped_at_;
  absl::flat_hash_set<EdgeKey> joined_;
  // While the blade is withdrawn, its point (BladeIn::apex) in each unit it is in and whether
  // that is its tip: a cone split for good there takes it for its apex (WithdrawnApex), so the
  // crack ends where the blade did.
  struct Withdrawn {
    Eigen::Vector4d apex;
    bool tip_inside = false;
  };
  absl::flat_hash_map<mesh::TetId, Withdrawn> withdrawn_at_;
  SweptPath swept_{kJoinSteps + 1};
  CrackFaces crack_;  // by origins
  // Triangles kept off the crack though the face rule puts them on it (HoldChips), and by the
  // faces of the units they lie in (origins).
  absl::flat_hash_set<FaceKey, FaceKeyHash> kept_off_;
  absl::flat_hash_map<FaceKey, std::vector<std::array<mesh::VertexId, 3>>, FaceKeyHash>
      kept_off_in_face_;
  // The poses applied, how many crack faces were made at each, and when each group (by its root)
  // began: a crack face made before every group there is now is the crack made before
  // (OnTheCrackAlready).
  std::size_t poses_ = 0;
  std::map<std::size_t, std::size_t> crack_faces_since_;
  absl::flat_hash_map<mesh::TetId, std::size_t> group_since_;
  // The pose at which the blade first met each unit of a group (when it joined one), until the
  // unit closes (after its group is taken, so its split for good can read it).
  absl::flat_hash_map<mesh::TetId, std::size_t> met_at_;
  absl::flat_hash_set<mesh::TetId> fresh_;  // tets made from origins since the last parting
  absl::flat_hash_map<mesh::TetId, OpenTet> open_;
  absl::flat_hash_set<mesh::TetId> stood_;  // open units whose pieces stood this pose
  // Edits of the tets (Replace, Repart), and their count and the blade's units when no crack face
  // was found shut: with both the same, none is (SplitUnits).
  std::uint64_t edits_ = 0;
  std::optional<std::pair<std::uint64_t, std::vector<mesh::TetId>>> none_shut_at_;
  std::vector<mesh::TetId> blade_units_;              // the units the blade was in at the last pose
  absl::flat_hash_map<EdgeKey, double> blade_edges_;  // its temporary edge points then
  absl::flat_hash_set<EdgeKey> advancing_;            // those standing in for edges' points
  // The blade's crossings of each face it crosses (faces with no point for good), barycentric,
  // since it began to cross it; a crossing within kMinTemporaryWeight of one kept is not kept
  // again, so a blade held still in a face keeps a few, not one a pose.
  absl::flat_hash_map<FaceKey, std::vector<Eigen::Vector3d>, FaceKeyHash> crossed_faces_;
  absl::flat_hash_map<mesh::TetId, mesh::TetId> owner_;  // temporary piece -> its open tet
  // Temporary points by place (a face's key hash, or an open tet's id), and those used this pose.
  absl::flat_hash_map<std::uint64_t, mesh::VertexId> temporary_;
  absl::flat_hash_map<std::uint64_t, std::uint64_t> temporary_used_;  // -> edits_ when placed
  absl::flat_hash_map<mesh::TetId, mesh::TetId> group_of_;
  absl::flat_hash_map<mesh::TetId, std::vector<mesh::TetId>> members_;
  absl::flat_hash_map<mesh::TetId, mesh::TetId> source_tet_;
  // How many pieces a tissue's tet stands in now, for those ever replaced.
  absl::flat_hash_map<mesh::TetId, std::size_t> pieces_of_source_;
  std::vector<MadeVertex> made_vertices_;
  // Where each point the cut made lies: weights on origins, and the tissue's edge length there
  // (the mean edge between its origins, or an origin's own if larger: a piece's edges are shorter
  // than its tissue's).
  struct PointRecipe {
    std::array<mesh::VertexId, 4> origins;
    Eigen::Vector4d weights;
    double scale = 0;
  };
  absl::flat_hash_map<mesh::VertexId, PointRecipe> recipe_;
  std::vector<mesh::VertexId> new_points_;  // made since the last parting
  CutStatistics statistics_;
  PoseSummary last_pose_;
};

}  // namespace kerf::cut
