#include "cut/cutter.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <bit>
#include <cassert>
#include <functional>
#include <numeric>
#include <tuple>
#include <utility>

#include "absl/strings/str_cat.h"
#include "geometry/moving_crossing.h"
#include "geometry/segment_box.h"
#include "geometry/segment_distance.h"
#include "geometry/segment_triangle_intersection.h"
#include "geometry/tet_measures.h"
#include "mesh/face_tiling.h"
#include "mesh/mesh_quality.h"

namespace kerf::cut {
namespace {

using mesh::Index;
using mesh::TetId;
using mesh::VertexId;

// Crossings closer than this (as a fraction of the edge, or a barycentric coordinate) to a
// vertex or an edge are degenerate: skipped until snapping handles them.
constexpr double kDegenerate = 1e-6;
constexpr VertexId kNoVertex{0xffffffffu};

std::uint64_t MakeEdgeKey(VertexId a, VertexId b) {
  if (Index(b) < Index(a)) std::swap(a, b);
  return (std::uint64_t{Index(a)} << 32) | Index(b);
}

// The middle one of three barycentric coordinates: under a snap fraction, with the least, the
// point lies that near a vertex (the largest's).
double MiddleCoefficient(const Eigen::Vector3d& barycentric) {
  return barycentric.sum() - barycentric.minCoeff() - barycentric.maxCoeff();
}

// The two vertices of an edge key, lower id first.
std::array<VertexId, 2> EdgeEnds(std::uint64_t key) {
  return {VertexId(static_cast<std::uint32_t>(key >> 32)),
          VertexId(static_cast<std::uint32_t>(key))};
}

std::array<VertexId, 3> MakeFaceKey(VertexId a, VertexId b, VertexId c) {
  std::array<VertexId, 3> key = {a, b, c};
  std::sort(key.begin(), key.end());
  return key;
}

// The key of face f (local corners) of the tet with corners v.
std::array<VertexId, 3> MakeFaceKey(const mesh::TetVertices& v, const std::array<int, 3>& f) {
  return MakeFaceKey(v[f[0]], v[f[1]], v[f[2]]);
}

// The place of the temporary point inside tet t (the tip, or a point of its crack), beside
// the face keys of temporary face points: no face repeats a vertex.
std::array<VertexId, 3> InsidePlace(TetId t) {
  const VertexId v = static_cast<VertexId>(Index(t));
  return {v, v, v};
}

// Barycentric coordinates of p in the tet (a, b, c, d); NaN for a flat tet.
Eigen::Vector4d TetBarycentric(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                               const Eigen::Vector3d& c, const Eigen::Vector3d& d,
                               const Eigen::Vector3d& p) {
  Eigen::Matrix3d m;
  m.col(0) = b - a;
  m.col(1) = c - a;
  m.col(2) = d - a;
  const Eigen::Vector3d l = m.partialPivLu().solve(p - a);
  return {1 - l.sum(), l[0], l[1], l[2]};
}

// Whether the tet has every one of `vertices` as a corner.
bool HasAll(const mesh::TetVertices& corners, std::span<const VertexId> vertices) {
  return std::all_of(vertices.begin(), vertices.end(),
                     [&](VertexId v) { return mesh::TetHasVertex(corners, v); });
}

// The live tets around an edge (two vertices) or a face (three).
mesh::TetMesh::TetList LiveTetsAround(const mesh::TetMesh& mesh,
                                      std::span<const VertexId> vertices) {
  return vertices.size() == 2 ? mesh.TetsAroundEdge(vertices[0], vertices[1])
                              : mesh.TetsAroundFace(vertices[0], vertices[1], vertices[2]);
}

// A tip closer than this (barycentric) to a face of its tet is taken as on the face: the cone
// from it would make slivers.
constexpr double kTipMargin = 1e-3;

// A tet with a cut this close (fraction of its edge) to a corner is not given points where its
// crack ends (Cutter::EndCracksOnFaces): its pieces at that corner would be slivers, and in a
// live cut such slivers, stretched tenfold as the crack opened, blew backward Euler up with the
// corotational law (the liver; at 0.01 and 0.02 too). Its hits are dropped as before.
constexpr double kCrackEndMargin = 0.05;

// The tet's volume at rest, positive when its corners are in the mesh's order.
double SignedVolume(const mesh::TetMesh& mesh, const mesh::TetVertices& t) {
  return geometry::SignedVolume(mesh.rest_position(t[0]), mesh.rest_position(t[1]),
                                mesh.rest_position(t[2]), mesh.rest_position(t[3]));
}

// The tet's smallest height at rest.
double SmallestHeight(const mesh::TetMesh& mesh, const mesh::TetVertices& t) {
  return geometry::SmallestHeight(mesh.rest_position(t[0]), mesh.rest_position(t[1]),
                                  mesh.rest_position(t[2]), mesh.rest_position(t[3]));
}

// Whether `cut` is pinned at a corner of the tet: a snapped crossing, whose one point is the
// corner itself until the corner's tets part.
bool IsPinned(const mesh::TetVertices& corners, const EdgeCut& cut) {
  return cut.near_a == cut.near_b &&
         (cut.near_a == corners[cut.corner_a] || cut.near_a == corners[cut.corner_b]);
}

// Leaves out the pieces collapsed at cuts pinned at a snapped corner (LeaveOutCollapsedTets),
// and empties the split if the rest does not tile the tet at rest: a flat piece, or volumes that
// do not add up to the tet's (a snapped pattern the case's pieces do not fit).
void KeepIfItTiles(const mesh::TetMesh& mesh, const mesh::TetVertices& corners, TetSplit* split) {
  LeaveOutCollapsedTets(split);
  const double volume = std::abs(SignedVolume(mesh, corners));
  double total = 0;
  for (const mesh::TetVertices& piece : split->tets) {
    const double v = std::abs(SignedVolume(mesh, piece));
    if (v <= 1e-12 * volume) {
      *split = {};
      return;
    }
    total += v;
  }
  if (std::abs(total - volume) > 1e-10 * volume) *split = {};
}

// The first split `make` gives from `cuts` that tiles the tet (KeepIfItTiles): from the cuts as
// they are, else with some of those pinned at a snapped corner left out, the fewest first. A
// pinned cut's point is the corner itself, so leaving one out moves no part of the crack; it
// changes only the minimal case the pattern reads as (a corner cut off whose third cut is
// pinned at the far corner, beside two more cuts pinned there, reads as case i without them).
TetSplit SplitThatTiles(const mesh::TetMesh& mesh, const mesh::TetVertices& corners,
                        const std::vector<EdgeCut>& cuts,
                        const std::function<TetSplit(const std::vector<EdgeCut>&)>& make) {
  std::vector<std::size_t> pinned;
  for (std::size_t k = 0; k < cuts.size(); ++k) {
    if (IsPinned(corners, cuts[k])) pinned.push_back(k);
  }
  std::vector<unsigned> left_out(1u << pinned.size());  // bit b: pinned[b] left out
  std::iota(left_out.begin(), left_out.end(), 0u);
  std::stable_sort(left_out.begin(), left_out.end(),
                   [](unsigned a, unsigned b) { return std::popcount(a) < std::popcount(b); });
  for (const unsigned mask : left_out) {
    std::vector<EdgeCut> kept;
    for (std::size_t k = 0, b = 0; k < cuts.size(); ++k) {
      const bool is_pinned = b < pinned.size() && pinned[b] == k;
      if (!is_pinned || !(mask >> b & 1u)) kept.push_back(cuts[k]);
      b += is_pinned;
    }
    TetSplit split = make(kept);
    KeepIfItTiles(mesh, corners, &split);
    if (!split.tets.empty()) return split;
  }
  return {};
}

// Whether `other` lies beyond the plane through `v` across `far` (by more than `tolerance`
// of the edge between them): on the side a snapped v does not keep.
bool Beyond(const mesh::TetMesh& mesh, VertexId v, VertexId other, const Eigen::Vector3d& far,
            double tolerance = 0) {
  const Eigen::Vector3d edge = mesh.current_position(other) - mesh.current_position(v);
  return edge.dot(far) > tolerance * edge.norm();
}

}  // namespace

int ProgressiveCase(int edges, int faces, int temporary_faces, bool tip_inside,
                    bool edges_share_corner) {
  struct Row {
    int edges, faces, temporary_faces;
    bool tip_inside;
  };
  static constexpr std::array<Row, kProgressiveCases> kTable = {{{0, 1, 1, true},
                                                                 {0, 2, 2, false},
                                                                 {1, 0, 2, false},
                                                                 {1, 1, 1, true},
                                                                 {1, 2, 2, false},
                                                                 {2, 0, 2, false},
                                                                 {2, 1, 1, true},
                                                                 {2, 2, 2, false},
                                                                 {2, 2, 2, false},
                                                                 {3, 0, 2, false},
                                                                 {3, 1, 1, true}}};
  for (int k = 0; k < kProgressiveCases; ++k) {
    const Row& row = kTable[k];
    if (row.edges != edges || row.faces != faces || row.temporary_faces != temporary_faces ||
        row.tip_inside != tip_inside) {
      continue;
    }
    if (k == 7 && !edges_share_corner) continue;  // case 8: the cut edges share a corner
    return k + 1;
  }
  return 0;
}

absl::StatusOr<Cutter> Cutter::Create(mesh::TetMesh* mesh, double cell_size,
                                      const BladeLimits& limits, CutMode mode,
                                      double min_temporary_height, double snap_fraction) {
  if (!(min_temporary_height >= 0 && min_temporary_height < 1)) {
    return absl::InvalidArgumentError(absl::StrCat(
        "the least temporary height must be a fraction in [0, 1), got ", min_temporary_height));
  }
  if (!(snap_fraction >= 0 && snap_fraction < 0.5)) {
    return absl::InvalidArgumentError(
        absl::StrCat("the snap fraction must be in [0, 0.5), got ", snap_fraction));
  }
  absl::StatusOr<TetGrid> grid = TetGrid::Build(*mesh, cell_size, 0.25 * cell_size);
  if (!grid.ok()) return grid.status();
  return Cutter(mesh, *std::move(grid), cell_size, limits, mode, min_temporary_height,
                snap_fraction);
}

absl::Status Cutter::ApplyPose(const BladePose& pose) {
  if (absl::Status s = ValidatePose(pose, previous_ ? &*previous_ : nullptr, limits_); !s.ok()) {
    return s;
  }
  if (absl::Status s = grid_.RefreshTopology(); !s.ok()) return s;
  if (previous_) {
    const std::vector<TetId> near = RecordHits(*previous_, pose);
    if (mode_ == CutMode::kDeferred) SplitReadyGroups(&pose, &near);
  }
  if (mode_ == CutMode::kProgressive) UpdateOpenTets(&pose);
  previous_ = pose;
  return RememberPositionsNear(pose);
}

void Cutter::Finish() {
  if (mode_ == CutMode::kDeferred) {
    SplitReadyGroups(nullptr, nullptr);
  } else {
    // The crack stays where the blade left it: its temporary face points become permanent
    // (the tip's point goes with the temporary tets, and a closed cut's point, on an edge,
    // with the edge's cut, which opens now).
    MakePermanent([](const FaceKey& place, VertexId) {
      return place[0] != place[1] && place[1] != place[2];
    });
    UpdateOpenTets(nullptr);
  }
  previous_.reset();
  positions_at_previous_.clear();
}

double Cutter::StiffnessScale(TetId t) const {
  const auto it = owner_.find(t);
  if (it == owner_.end() || !mesh_->IsAlive(t)) return 1;
  const double guard =
      min_temporary_height_ * SmallestHeight(*mesh_, mesh_->tet_even_if_removed(it->second));
  const double height = SmallestHeight(*mesh_, mesh_->tet(t));
  return height < guard ? height / guard : 1;
}

TetId Cutter::OwnerOf(TetId t) const {
  const auto it = owner_.find(t);
  return it == owner_.end() ? t : it->second;
}

bool Cutter::Realisable(std::span<const VertexId> vertices) const {
  // A face of a tet still open that a final subdivision beside it has split already: the
  // open tet would split it anew with the hit, its neighbour's pieces would not.
  for (const auto& [t, open] : open_) {
    const mesh::TetVertices& corners = mesh_->tet_even_if_removed(t);
    for (const auto& f : mesh::kTetFaces) {
      const FaceKey face = MakeFaceKey(corners, f);
      const bool on_face = std::all_of(vertices.begin(), vertices.end(), [&](VertexId v) {
        return std::find(face.begin(), face.end(), v) != face.end();
      });
      if (on_face && settled_faces_.contains(face)) return false;
    }
  }
  const mesh::TetMesh::TetList live = LiveTetsAround(*mesh_, vertices);
  return std::all_of(live.begin(), live.end(), [&](TetId t) {
    const TetId owner = OwnerOf(t);
    return owner == t || HasAll(mesh_->tet_even_if_removed(owner), vertices);
  });
}

bool Cutter::IsOnBladeNow(VertexId v) const {
  return std::any_of(temporary_points_.begin(), temporary_points_.end(), [&](const auto& entry) {
    return entry.second.vertex == v && entry.second.on_blade;
  });
}

std::vector<TetId> Cutter::TetsWith(std::span<const VertexId> vertices) const {
  std::vector<TetId> tets;
  for (const TetId t : LiveTetsAround(*mesh_, vertices)) tets.push_back(OwnerOf(t));
  // An open tet whose pieces split the edge or face has no piece with all of them.
  for (const auto& [t, open] : open_) {
    if (HasAll(mesh_->tet_even_if_removed(t), vertices)) tets.push_back(t);
  }
  std::sort(tets.begin(), tets.end());
  tets.erase(std::unique(tets.begin(), tets.end()), tets.end());
  return tets;
}

std::vector<TetId> Cutter::OwnersAt(VertexId v) const {
  std::vector<TetId> owners;
  for (const TetId t : mesh_->TetsAround(v)) {
    const TetId owner = OwnerOf(t);
    if (mesh::TetHasVertex(mesh_->tet_even_if_removed(owner), v)) owners.push_back(owner);
  }
  std::sort(owners.begin(), owners.end());
  owners.erase(std::unique(owners.begin(), owners.end()), owners.end());
  return owners;
}

bool Cutter::IsCutEdge(VertexId a, VertexId b, bool pinned) const {
  const auto it = edge_hits_.find(MakeEdgeKey(a, b));
  return it != edge_hits_.end() && !it->second.along && (pinned || it->second.at == kNoVertex);
}

absl::Status Cutter::RememberPositionsNear(const BladePose& pose) {
  positions_at_previous_.clear();
  if (absl::Status s = grid_.RefreshTopology(); !s.ok()) return s;  // the tets this pose made
  for (const TetId t : grid_.Candidates(pose.tip.cwiseMin(pose.heel).array() - memory_margin_,
                                        pose.tip.cwiseMax(pose.heel).array() + memory_margin_)) {
    for (const VertexId v : mesh_->tet_even_if_removed(t)) {
      if (mesh_->IsAlive(v))
        positions_at_previous_.try_emplace(Index(v), mesh_->current_position(v));
    }
  }
  return absl::OkStatus();
}

Eigen::Vector3d Cutter::MovedSincePrevious(VertexId v) const {
  const auto it = positions_at_previous_.find(Index(v));
  if (it == positions_at_previous_.end()) return Eigen::Vector3d::Zero();
  return mesh_->current_position(v) - it->second;
}

std::vector<TetId> Cutter::RecordHits(const BladePose& from, const BladePose& to) {
  // The tissue may have moved since the previous pose: every point is taken to move straight
  // from where it was then to where it is now, like the blade, and a hit is where the two met.
  double farthest = 0;  // squared first
  for (const auto& [v, then] : positions_at_previous_) {
    if (mesh_->IsAlive(VertexId(v))) {
      farthest = std::max(farthest, (mesh_->current_position(VertexId(v)) - then).squaredNorm());
    }
  }
  farthest = std::sqrt(farthest);
  const auto motion = [&](VertexId v) {
    const Eigen::Vector3d& x = mesh_->current_position(v);
    return geometry::Motion{x - MovedSincePrevious(v), x};
  };
  const geometry::Motion tip{from.tip, to.tip}, heel{from.heel, to.heel};
  Eigen::Vector3d low = from.tip.cwiseMin(from.heel).cwiseMin(to.tip).cwiseMin(to.heel);
  Eigen::Vector3d high = from.tip.cwiseMax(from.heel).cwiseMax(to.tip).cwiseMax(to.heel);
  low.array() -= farthest;
  high.array() += farthest;
  absl::flat_hash_set<EdgeKey> tested_edges;
  absl::flat_hash_set<FaceKey, FaceKeyHash> tested_faces;
  std::vector<Crossing> crossings;
  std::vector<EdgeKey> new_edges;
  std::vector<FaceKey> new_faces;
  absl::flat_hash_set<EdgeKey> closed_now;  // closed hits this pose's face crossings snapped to
  // The grid lists the tets in the cells the swept surface's box covers; keep those whose own
  // box meets it (the blade can only be inside those, too).
  std::vector<TetId> near = grid_.Candidates(low, high);
  for (TetId& t : near) t = OwnerOf(t);
  std::sort(near.begin(), near.end());
  near.erase(std::unique(near.begin(), near.end()), near.end());
  std::erase_if(near, [&](TetId t) {
    const mesh::TetVertices& v = mesh_->tet_even_if_removed(t);
    Eigen::Vector3d box_low = mesh_->current_position(v[0]), box_high = box_low;
    for (int k = 1; k < 4; ++k) {
      box_low = box_low.cwiseMin(mesh_->current_position(v[k]));
      box_high = box_high.cwiseMax(mesh_->current_position(v[k]));
    }
    return (box_low.array() > high.array()).any() || (box_high.array() < low.array()).any();
  });
  for (const TetId t : near) {
    const mesh::TetVertices v = mesh_->tet_even_if_removed(t);
    for (const auto& [i, j] : mesh::kTetEdges) {
      const EdgeKey key = MakeEdgeKey(v[i], v[j]);
      const auto hit = edge_hits_.find(key);
      if ((hit != edge_hits_.end() && hit->second.crossed) || !tested_edges.insert(key).second) {
        continue;
      }
      const VertexId lo = Index(v[i]) < Index(v[j]) ? v[i] : v[j];
      const VertexId hi = lo == v[i] ? v[j] : v[i];
      std::optional<double> fraction;
      if (const auto crossing = geometry::FirstEdgeCrossing(motion(lo), motion(hi), tip, heel)) {
        fraction = crossing->fraction;
      } else if (const geometry::ClosestPoints c = geometry::ClosestPointsOfSegments(
                     to.tip, to.heel, mesh_->current_position(lo), mesh_->current_position(hi));
                 c.distance <
                 kDegenerate * (mesh_->current_position(hi) - mesh_->current_position(lo)).norm()) {
        fraction = c.t;  // the blade stops on the edge (short of it by rounding only)
      }
      if (fraction) crossings.push_back({key, lo, hi, *fraction});
    }
    for (const auto& face : mesh::kTetFaces) {
      const FaceKey key = MakeFaceKey(v, face);
      if (face_hits_.contains(key) || !tested_faces.insert(key).second) continue;
      const auto crossing =
          geometry::FirstPointCrossing(tip, motion(key[0]), motion(key[1]), motion(key[2]));
      if (!crossing) continue;
      if (crossing->barycentric.minCoeff() < kDegenerate) {
        ++statistics_.degenerate_hits;
      } else if (!Realisable(key)) {
        ++statistics_.unrealisable_hits;
      } else if (const std::optional<EdgeKey> edge = SnapToEdge(key, crossing->barycentric)) {
        new_edges.push_back(*edge);
        closed_now.insert(*edge);
      } else {
        face_hits_[key] = {crossing->barycentric};
        new_faces.push_back(key);
      }
    }
  }
  // The swept surface's normal (its diagonals' cross product), to tell the sides of a snapped
  // vertex; zero where the blade barely moved (then nothing snaps).
  Eigen::Vector3d normal = (to.heel - from.tip).cross(to.tip - from.heel);
  if (normal.norm() <= 1e-6 * (to.heel - to.tip).squaredNorm()) {
    normal.setZero();
  } else {
    normal.normalize();
  }
  RecordEdgeCrossings(crossings, normal, closed_now, &new_edges);
  for (const EdgeKey key : new_edges) {
    const std::array<VertexId, 2> ends = EdgeEnds(key);
    if (mode_ == CutMode::kDeferred) {
      Join(mesh_->TetsAroundEdge(ends[0], ends[1]));
    } else {
      for (const TetId t : TetsWith(ends)) open_.try_emplace(t);
    }
  }
  for (const FaceKey& key : new_faces) {
    if (mode_ == CutMode::kDeferred) {
      Join(mesh_->TetsAroundFace(key[0], key[1], key[2]));
    } else {
      for (const TetId t : TetsWith(key)) open_.try_emplace(t);
    }
  }
  return near;
}

void Cutter::RecordEdgeCrossings(const std::vector<Crossing>& crossings,
                                 const Eigen::Vector3d& normal,
                                 const absl::flat_hash_set<EdgeKey>& closed_now,
                                 std::vector<EdgeKey>* new_edges) {
  if (snap_fraction_ > 0 && normal != Eigen::Vector3d::Zero()) {
    absl::flat_hash_map<VertexId, Eigen::Vector3d> to_snap;
    for (const Crossing& c : crossings) {
      const Eigen::Vector3d& low = mesh_->current_position(c.low);
      const Eigen::Vector3d& high = mesh_->current_position(c.high);
      const Eigen::Vector3d point = low + c.fraction * (high - low);
      const double length = (high - low).norm();
      // Signed distances of the ends from the swept surface (its plane at the crossing).
      const double low_side = (low - point).dot(normal), high_side = (high - point).dot(normal);
      // An edge along the surface (both ends near it) puts both ends on the crack.
      const bool along =
          std::max(std::abs(low_side), std::abs(high_side)) < snap_fraction_ * length;
      for (const auto& [end, from_end, side] : {std::tuple{c.low, c.fraction, low_side},
                                                std::tuple{c.high, 1 - c.fraction, high_side}}) {
        if (!(along || from_end < snap_fraction_) || snapped_.contains(end) ||
            was_snapped_.contains(end)) {
          continue;
        }
        // The copy takes the side the vertex is not on; a vertex on the surface itself keeps
        // the side the normal points away from (the same for every vertex of the pose).
        to_snap.try_emplace(end, std::abs(side) < kDegenerate * length || side < 0
                                     ? normal
                                     : Eigen::Vector3d(-normal));
      }
    }
    Snap(to_snap);
  }
  for (const Crossing& c : crossings) {
    if (const auto hit = edge_hits_.find(c.key); hit != edge_hits_.end() && hit->second.closed) {
      if (closed_now.contains(c.key)) {
        // The tip passed just beyond the edge: the crack's front still crosses it, where the
        // blade did (unless its vertex is made).
        if (c.fraction > kDegenerate && c.fraction < 1 - kDegenerate &&
            hit->second.near_low == kNoVertex) {
          hit->second.fraction = c.fraction;
        }
        continue;
      }
      // Progressive: a tet split for good at it (frozen) keeps the front there.
      if (ClosedCutSettled(hit->second)) continue;
      // The crack's front was taken to cross the edge; now the blade does, deeper: the
      // crossing is used as found, and the tip's crossings beside the edge are face points.
      UnsnapEdge(c.key);
      ++statistics_.opened_edges;
    }
    if (const auto hit = edge_hits_.find(c.key); hit != edge_hits_.end()) {
      hit->second.fraction = c.fraction;  // cut at its snapped vertex, and now crossed
      hit->second.crossed = true;
      continue;
    }
    const bool low_snapped = snapped_.contains(c.low), high_snapped = snapped_.contains(c.high);
    if (low_snapped && high_snapped) {
      edge_hits_[c.key] = {.fraction = c.fraction, .crossed = true};
      MarkEdgeBetweenSnapped(c.key, c.low, c.high);
      continue;
    }
    if (low_snapped || high_snapped) {
      const VertexId at = low_snapped ? c.low : c.high, other = low_snapped ? c.high : c.low;
      const double from_at = low_snapped ? c.fraction : 1 - c.fraction;
      if (Beyond(*mesh_, at, other, snapped_.at(at).far)) {
        edge_hits_[c.key] = {.fraction = c.fraction, .at = at};
        ++statistics_.snapped_hits;
        new_edges->push_back(c.key);
        continue;
      }
      if (from_at < kDegenerate) continue;  // it touches the crack at the vertex, on its side
      // Crossed on the vertex's own side: the crack bends there. The vertex is taken off the
      // crack, unless a tet split through it for good (progressive): then the crossing is cut
      // as found beside it.
      if (mode_ == CutMode::kDeferred || !committed_.contains(at)) Unsnap(at);
    }
    if (c.fraction < kDegenerate || c.fraction > 1 - kDegenerate) {
      ++statistics_.degenerate_hits;
    } else if (const std::array<VertexId, 2> ends = {c.low, c.high}; !Realisable(ends)) {
      ++statistics_.unrealisable_hits;
    } else {
      edge_hits_[c.key] = {c.fraction};
      CloseAtFacePoints(c.key);
      new_edges->push_back(c.key);
    }
  }
}

void Cutter::CloseAtFacePoints(EdgeKey key) {
  if (snap_fraction_ == 0) return;
  EdgeHit& hit = edge_hits_.at(key);
  const std::array<VertexId, 2> ends = EdgeEnds(key);
  for (const TetId t : TetsWith(ends)) {
    const mesh::TetVertices& corners = mesh_->tet_even_if_removed(t);
    for (const auto& f : mesh::kTetFaces) {
      const FaceKey face = MakeFaceKey(corners, f);
      const auto point = face_hits_.find(face);
      if (point == face_hits_.end() || point->second.vertex != kNoVertex) continue;
      const auto low = std::find(face.begin(), face.end(), ends[0]) - face.begin();
      const auto high = std::find(face.begin(), face.end(), ends[1]) - face.begin();
      if (low == 3 || high == 3) continue;  // not a face at the edge
      const Eigen::Vector3d& b = point->second.barycentric;
      const double along = b[high] / (b[low] + b[high]);
      if (b[3 - low - high] >= snap_fraction_ || std::abs(along - hit.fraction) >= snap_fraction_) {
        continue;
      }
      CloseEdgeAt(key, face, b);
      face_hits_.erase(point);
    }
  }
}

void Cutter::Snap(const absl::flat_hash_map<VertexId, Eigen::Vector3d>& to_snap) {
  const auto on_crack = [&](VertexId v) { return snapped_.contains(v) || to_snap.contains(v); };
  // Every edge from a snapped vertex to the far side is cut at it, and one between two lies
  // along the crack. A hit waiting on an edge to its own side keeps a vertex off the crack;
  // so does a tet at it split for good, or (progressive) a cut at it already made or a face at
  // it split for good (its tets would split differently from their neighbours).
  std::vector<VertexId> snapping;
  for (const auto& [v, far] : to_snap) {
    bool keeps_off = false;
    for (const TetId t : OwnersAt(v)) {
      keeps_off |= MadeByCut(t);
      const mesh::TetVertices& corners = mesh_->tet_even_if_removed(t);
      for (const VertexId other : corners) {
        const auto hit = edge_hits_.find(MakeEdgeKey(v, other));
        if (other == v || hit == edge_hits_.end()) continue;
        keeps_off |= hit->second.near_low != kNoVertex || hit->second.closed;
        if (!on_crack(other)) keeps_off |= !Beyond(*mesh_, v, other, far);
      }
      for (const auto& f : mesh::kTetFaces) {
        const FaceKey face = MakeFaceKey(corners, f);
        if (std::find(face.begin(), face.end(), v) != face.end()) {
          keeps_off |= settled_faces_.contains(face);
        }
      }
    }
    if (!keeps_off) snapping.push_back(v);
  }
  std::sort(snapping.begin(), snapping.end());  // deterministic order
  for (const VertexId v : snapping) {
    snapped_.emplace(v, SnappedVertex{.far = to_snap.at(v)});
  }
  statistics_.snapped_vertices += snapping.size();
  for (const VertexId v : snapping) {
    const std::vector<TetId> around = OwnersAt(v);
    for (const TetId t : around) {
      for (const VertexId other : mesh_->tet_even_if_removed(t)) {
        if (other == v) continue;
        const EdgeKey key = MakeEdgeKey(v, other);
        const auto it = edge_hits_.find(key);
        if (snapped_.contains(other)) {
          if (it == edge_hits_.end()) edge_hits_[key] = {.fraction = 0, .crossed = false};
          MarkEdgeBetweenSnapped(key, v, other);
          continue;
        }
        if (!Beyond(*mesh_, v, other, snapped_.at(v).far, 1e-9)) continue;
        if (it == edge_hits_.end()) {
          edge_hits_[key] = {
              .fraction = Index(v) < Index(other) ? 0.0 : 1.0, .at = v, .crossed = false};
          ++statistics_.snapped_hits;
        } else if (it->second.at == kNoVertex) {
          it->second.at = v;  // a hit waiting at it: now taken at it
          ++statistics_.snapped_hits;
        }
      }
    }
    if (mode_ == CutMode::kDeferred) {
      Join(around);  // they split together, so the copy takes the far side at once
    } else {
      for (const TetId t : around) open_.try_emplace(t);  // parted once all are final
    }
  }
}

void Cutter::MarkEdgeBetweenSnapped(EdgeKey key, VertexId a, VertexId b) {
  EdgeHit& hit = edge_hits_.at(key);
  // Where the two keep the same side the edge lies along the crack and is not cut; where they
  // keep opposite sides its ends part, at the lower id (which either order finds alike).
  hit.along = snapped_.at(a).far.dot(snapped_.at(b).far) > 0;
  hit.at = hit.along ? kNoVertex : (Index(a) < Index(b) ? a : b);
  if (!hit.crossed) hit.fraction = 0;  // at the lower id's end
}

std::optional<Cutter::EdgeKey> Cutter::SnapToEdge(const FaceKey& key,
                                                  const Eigen::Vector3d& barycentric) {
  if (snap_fraction_ == 0) return std::nullopt;
  int far = 0;  // the corner opposite the edge it is near
  if (barycentric.minCoeff(&far) >= snap_fraction_) return std::nullopt;
  const int low = far == 0 ? 1 : 0, high = far == 2 ? 1 : 2;  // the edge's ends in the key
  const EdgeKey edge = MakeEdgeKey(key[low], key[high]);
  const auto hit = edge_hits_.find(edge);
  const std::array<VertexId, 2> ends = {key[low], key[high]};
  const double along = barycentric[high] / (barycentric[low] + barycentric[high]);
  // An edge the blade crossed beside it at an earlier pose, not yet split, the tip passing by
  // now: the crack's front crosses it where the blade did.
  const bool crossed_before = hit != edge_hits_.end() && !hit->second.closed &&
                              hit->second.at == kNoVertex && !hit->second.along &&
                              hit->second.near_low == kNoVertex &&
                              std::abs(along - hit->second.fraction) < snap_fraction_;
  // Else near a vertex it would cut a short piece off the edge: it stays a face point.
  if ((!crossed_before && MiddleCoefficient(barycentric) < snap_fraction_) ||
      (hit != edge_hits_.end() && !hit->second.closed && !crossed_before) ||
      snapped_.contains(key[low]) || snapped_.contains(key[high]) || !Realisable(ends)) {
    return std::nullopt;
  }
  if (hit == edge_hits_.end()) {
    edge_hits_[edge] = {.fraction = along, .crossed = false, .closed = true};
  }
  CloseEdgeAt(edge, key, barycentric);
  return edge;
}

void Cutter::CloseEdgeAt(EdgeKey key, const FaceKey& face, const Eigen::Vector3d& barycentric) {
  EdgeHit& hit = edge_hits_.at(key);
  if (!hit.closed) {  // cut as the blade crossed it: unsnapping cuts it open again
    hit.closed = hit.was_open = true;
    hit.crossed = false;  // a later crossing opens it
  }
  edge_snapped_faces_[key].emplace_back(face, barycentric);
  ++statistics_.edge_snapped_hits;
}

bool Cutter::ClosedCutSettled(const EdgeHit& hit) const {
  if (hit.near_low == kNoVertex) return false;
  const auto& around = mesh_->TetsAround(hit.near_low);
  return std::any_of(around.begin(), around.end(), [&](TetId t) { return !owner_.contains(t); });
}

void Cutter::UnsnapEdge(EdgeKey key) {
  const auto hit = edge_hits_.find(key);
  assert(hit != edge_hits_.end() && hit->second.closed);
  const VertexId made = hit->second.near_low;
  if (made != kNoVertex && !mesh_->RemoveVertex(made).ok()) {
    // Progressive: temporary pieces use it until they are made anew; it goes with them.
    const std::array<VertexId, 2> ends = EdgeEnds(key);
    const double fraction = hit->second.fraction;
    temporary_points_.try_emplace(
        FaceKey{ends[0], ends[1], ends[1]},
        TemporaryPoint{
            .vertex = made, .weights = {1 - fraction, fraction, 0, 0}, .on_blade = false});
  }
  if (hit->second.was_open) {  // cut as the blade crossed it
    hit->second.closed = hit->second.was_open = false;
    hit->second.crossed = true;
    hit->second.near_low = hit->second.near_high = kNoVertex;
  } else {
    edge_hits_.erase(hit);
  }
  for (const auto& [face, barycentric] : edge_snapped_faces_[key]) {
    face_hits_.try_emplace(face, FaceHit{barycentric});
  }
  edge_snapped_faces_.erase(key);
}

TetSplit Cutter::SplitAsCone(const mesh::TetVertices& corners, const std::vector<EdgeCut>& cuts,
                             const std::vector<FacePoint>& faces, const ApexMaker& apex_at) {
  if (cuts.size() == 1 && faces.empty() && cuts[0].near_a == cuts[0].near_b &&
      !IsPinned(corners, cuts[0])) {
    TetSplit split = SplitAtClosedCut(corners, cuts[0]);
    KeepIfItTiles(*mesh_, corners, &split);
    return split;
  }
  // Cut through, the crack's end on a face (between two closed cuts): a complete cut whose
  // closed cuts' copies are one vertex.
  if (faces.empty()) {
    TetSplit split = SplitThatTiles(*mesh_, corners, cuts, [&](const std::vector<EdgeCut>& kept) {
      return SplitCompletelyCutTet(corners, kept);
    });
    if (!split.tets.empty()) return split;
  }
  // The apex's weights on the corners: the mean of the front's points, on the crack.
  Eigen::Vector4d front = Eigen::Vector4d::Zero();
  int points = 0;
  bool cracked = !faces.empty();
  for (const EdgeCut& c : cuts) {
    cracked |= c.near_a != c.near_b;
    if (c.near_a != c.near_b || IsPinned(corners, c)) continue;
    // corner_a is the lower id (EdgeCutsOf), the end the fraction is measured from.
    const double fraction =
        edge_hits_.at(MakeEdgeKey(corners[c.corner_a], corners[c.corner_b])).fraction;
    front[c.corner_a] += 1 - fraction;
    front[c.corner_b] += fraction;
    ++points;
  }
  for (const FacePoint& f : faces) {
    const FaceKey key = MakeFaceKey(corners, mesh::kTetFaces[f.face]);
    const Eigen::Vector3d& barycentric = face_hits_.at(key).barycentric;
    for (int m = 0; m < 4; ++m) {
      const auto at = std::find(key.begin(), key.end(), corners[m]);
      if (at != key.end()) front[m] += barycentric[at - key.begin()];
    }
    ++points;
  }
  // The middle of the tet, strictly inside it, sees every face: the cone from it tiles the tet
  // whenever its faces can be triangulated (the crack then ends there).
  std::vector<Eigen::Vector4d> weights = {Eigen::Vector4d::Constant(0.25)};
  if (cracked && points > 1) weights.insert(weights.begin(), front / points);
  const auto rest = [&](VertexId v) { return mesh_->rest_position(v); };
  for (const Eigen::Vector4d& w : weights) {
    const VertexId apex = apex_at(w);
    TetSplit split = SplitThatTiles(*mesh_, corners, cuts, [&](const std::vector<EdgeCut>& kept) {
      return SplitAsStar(corners, kept, faces, apex, rest);
    });
    if (!split.tets.empty()) return split;
  }
  return {};
}

void Cutter::Commit(const mesh::TetVertices& corners, const std::vector<EdgeCut>& cuts) {
  for (const EdgeCut& cut : cuts) {
    if (IsPinned(corners, cut)) committed_.insert(cut.near_a);
  }
}

void Cutter::Unsnap(VertexId v) {
  assert(!committed_.contains(v));
  snapped_.erase(v);
  was_snapped_.insert(v);
  ++statistics_.unsnapped_vertices;
  // Its edges are cut as found, or at the other end if that is snapped and it lies on the far
  // side there.
  for (const TetId t : OwnersAt(v)) {
    for (const VertexId other : mesh_->tet_even_if_removed(t)) {
      const auto hit = edge_hits_.find(MakeEdgeKey(v, other));
      if (other == v || hit == edge_hits_.end()) continue;
      EdgeHit& h = hit->second;
      h.along = false;
      if (const auto o = snapped_.find(other);
          o != snapped_.end() && Beyond(*mesh_, other, v, o->second.far)) {
        h.at = other;
        continue;
      }
      h.at = kNoVertex;
      if (!h.crossed) {
        edge_hits_.erase(hit);  // never crossed: cut only because of the snapping
      } else if (h.fraction < kDegenerate || h.fraction > 1 - kDegenerate) {
        edge_hits_.erase(hit);  // through a vertex itself: skipped, as unsnapped
        ++statistics_.degenerate_hits;
      } else if (mode_ == CutMode::kProgressive) {
        const std::array<VertexId, 2> ends = {v, other};  // every tet at a hit is open
        for (const TetId owner : TetsWith(ends)) open_.try_emplace(owner);
      }
    }
  }
}

void Cutter::PartSnappedVertices(std::vector<VertexId> vertices) {
  std::sort(vertices.begin(), vertices.end());  // deterministic ids for the copies
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  for (const VertexId v : vertices) {
    const auto it = snapped_.find(v);
    assert(it != snapped_.end());
    parted_.emplace(v, it->second.far);
    snapped_.erase(it);
    was_snapped_.insert(v);
  }
  // A vertex on the crack whose star parted may let a neighbour on the crack part too (or
  // again): its star was joined through a face the parting took apart (progressive cutting
  // parts vertices one by one, as their tets become final).
  std::vector<VertexId> queue = vertices;
  absl::flat_hash_set<VertexId> queued(vertices.begin(), vertices.end());
  for (std::size_t next = 0; next < queue.size(); ++next) {
    const VertexId v = queue[next];
    queued.erase(v);
    const std::vector<VertexId> copies = PartStar(v);
    if (copies.empty()) continue;
    std::vector<VertexId> neighbours;
    for (const VertexId x : copies) {
      for (const TetId t : mesh_->TetsAround(x)) {
        for (const VertexId w : mesh_->tet(t)) {
          if (!snapped_.contains(w) && parted_.contains(PartedFrom(w)) && !Waiting(w)) {
            neighbours.push_back(w);
          }
        }
      }
    }
    std::sort(neighbours.begin(), neighbours.end());
    for (const VertexId w : neighbours) {
      if (queued.insert(w).second) queue.push_back(w);
    }
  }
}

std::vector<VertexId> Cutter::PartStar(VertexId v) {
  // A face between two tets whose corners all are on the crack (snapped, parted, or copies of
  // parted ones) lies on it. The tets at v joined through their faces at v, but for those,
  // form its parts.
  const auto on_crack = [&](VertexId w) {
    return snapped_.contains(w) || parted_.contains(PartedFrom(w));
  };
  const std::vector<TetId> around(mesh_->TetsAround(v).begin(), mesh_->TetsAround(v).end());
  std::vector<std::size_t> part(around.size());
  std::iota(part.begin(), part.end(), 0);
  const auto root = [&](std::size_t k) {
    while (part[k] != k) k = part[k] = part[part[k]];
    return k;
  };
  for (std::size_t a = 0; a < around.size(); ++a) {
    for (std::size_t b = a + 1; b < around.size(); ++b) {
      int shared = 0, shared_on_crack = 0;
      for (const VertexId w : mesh_->tet(around[a])) {
        if (!mesh::TetHasVertex(mesh_->tet(around[b]), w)) continue;
        ++shared;
        shared_on_crack += on_crack(w);
      }
      if (shared == 3 && shared_on_crack < 3) part[root(a)] = root(b);
    }
  }
  // How far each part lies towards the side v gives up (a copy keeps that side): its tets'
  // centroids, summed.
  const Eigen::Vector3d far =
      PartedFrom(v) == v ? parted_.at(v) : Eigen::Vector3d(-parted_.at(PartedFrom(v)));
  absl::flat_hash_map<std::size_t, double> towards_far;
  for (std::size_t k = 0; k < around.size(); ++k) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const VertexId w : mesh_->tet(around[k])) centroid += mesh_->current_position(w) / 4;
    towards_far[root(k)] += (centroid - mesh_->current_position(v)).dot(far);
  }
  if (towards_far.size() < 2) return {};  // the crack ends at v: it stays one
  // The part farthest from the far side keeps v; every other part gets a copy.
  const std::size_t keeps =
      std::min_element(towards_far.begin(), towards_far.end(), [](const auto& x, const auto& y) {
        return x.second < y.second;
      })->first;
  absl::flat_hash_map<std::size_t, VertexId> copy_of;
  std::vector<VertexId> copies;
  for (std::size_t k = 0; k < around.size(); ++k) {
    const std::size_t r = root(k);
    if (r == keeps) continue;
    auto [copy, fresh] = copy_of.try_emplace(r);
    if (fresh) {
      copy->second = MakeVertex({v, v, v, v}, {1, 0, 0, 0});
      parted_from_[copy->second] = PartedFrom(v);
      copies.push_back(copy->second);
    }
    mesh::TetVertices moved = mesh_->tet(around[k]);
    std::replace(moved.begin(), moved.end(), v, copy->second);
    for (const auto& f : mesh::kTetFaces) {  // a face split for good stays so
      FaceKey face = MakeFaceKey(mesh_->tet(around[k]), f);
      if (!settled_faces_.contains(face)) continue;
      std::replace(face.begin(), face.end(), v, copy->second);
      settled_faces_.insert(MakeFaceKey(face[0], face[1], face[2]));
    }
    (void)mesh_->RemoveTet(around[k]);
    const absl::StatusOr<TetId> added = mesh_->AddTet(moved);
    assert(added.ok());
    source_tet_[*added] = SourceTet(around[k]);
  }
  statistics_.parted_vertices += copies.size();
  if (!copies.empty()) copies.push_back(v);  // its own star changed too
  return copies;
}

bool Cutter::Waiting(VertexId v) const {
  const std::span<const TetId> around = mesh_->TetsAround(v);
  return std::any_of(around.begin(), around.end(), [&](TetId t) {
    return group_of_.contains(t) || open_.contains(t) || owner_.contains(t);
  });
}

void Cutter::PartFinishedSnappedVertices() {
  std::vector<VertexId> finished;  // every tet at them is final
  for (const auto& [v, snapped] : snapped_) {
    if (!Waiting(v)) finished.push_back(v);
  }
  if (finished.empty()) return;
  PartSnappedVertices(finished);
  // Their hits (kept while they waited, see ForgetHitsOf) served the splits made.
  const absl::flat_hash_set<VertexId> parted(finished.begin(), finished.end());
  absl::erase_if(edge_hits_, [&](const auto& entry) {
    const auto& [key, hit] = entry;
    const std::array<VertexId, 2> ends = EdgeEnds(key);
    const bool at_parted = parted.contains(ends[0]) || parted.contains(ends[1]);
    return at_parted && (hit.along || parted.contains(hit.at));
  });
}

TetId Cutter::GroupOf(TetId t) {
  TetId root = t;
  while (group_of_.at(root) != root) root = group_of_.at(root);
  while (t != root) {  // path compression
    TetId& parent = group_of_.at(t);
    t = std::exchange(parent, root);
  }
  return root;
}

void Cutter::Join(std::span<const TetId> tets) {
  for (const TetId t : tets) {
    if (group_of_.try_emplace(t, t).second) members_[t] = {t};
  }
  for (std::size_t i = 1; i < tets.size(); ++i) {
    TetId a = GroupOf(tets[0]), b = GroupOf(tets[i]);
    if (a == b) continue;
    if (members_[a].size() < members_[b].size()) std::swap(a, b);
    std::vector<TetId>& into = members_[a];
    std::vector<TetId>& from = members_[b];
    into.insert(into.end(), from.begin(), from.end());
    members_.erase(b);
    group_of_[b] = a;
  }
}

bool Cutter::BladeInside(const mesh::TetVertices& v, const BladePose& pose) const {
  std::array<Eigen::Vector3d, 4> x;
  for (int i = 0; i < 4; ++i) x[i] = mesh_->current_position(v[i]);
  const Eigen::Vector3d lo = x[0].cwiseMin(x[1]).cwiseMin(x[2].cwiseMin(x[3]));
  const Eigen::Vector3d hi = x[0].cwiseMax(x[1]).cwiseMax(x[2].cwiseMax(x[3]));
  if (!geometry::SegmentMeetsBox(pose.tip, pose.heel, lo, hi, 1e-6 * (hi - lo).norm())) {
    return false;  // the blade misses the tet's bounding box
  }
  for (const Eigen::Vector3d& end : {pose.tip, pose.heel}) {
    if (geometry::ContainsPoint(x[0], x[1], x[2], x[3], end)) return true;
  }
  for (const auto& face : mesh::kTetFaces) {
    if (geometry::IntersectSegmentTriangle(pose.tip, pose.heel, x[face[0]], x[face[1]],
                                           x[face[2]])) {
      return true;
    }
  }
  return false;
}

std::vector<mesh::TetVertices> Cutter::TetsHoldingBlade(const BladePose& pose) const {
  std::vector<TetId> near =
      grid_.Candidates(pose.tip.cwiseMin(pose.heel), pose.tip.cwiseMax(pose.heel));
  // The grid learns of the tets the last pose made at the next; the open tets stand for theirs.
  std::erase_if(near, [&](TetId t) { return !mesh_->IsAlive(t); });
  for (TetId& t : near) t = OwnerOf(t);
  for (const auto& entry : open_) near.push_back(entry.first);
  std::sort(near.begin(), near.end());
  near.erase(std::unique(near.begin(), near.end()), near.end());
  std::vector<mesh::TetVertices> holding;
  for (const TetId t : near) {
    const mesh::TetVertices& corners = mesh_->tet_even_if_removed(t);
    if (BladeInside(corners, pose)) holding.push_back(corners);
  }
  return holding;
}

void Cutter::SplitReadyGroups(const BladePose* pose, const std::vector<TetId>* near) {
  absl::flat_hash_set<TetId> blade_inside;  // roots of groups the blade is still in
  if (near != nullptr) {
    for (const TetId t : *near) {
      if (group_of_.contains(t) && !blade_inside.contains(GroupOf(t)) && BladeInside(t, *pose)) {
        blade_inside.insert(GroupOf(t));
      }
    }
  }
  std::vector<std::vector<TetId>> ready;
  for (const auto& [root, members] : members_) {
    if (!blade_inside.contains(root)) ready.push_back(members);
  }
  for (std::vector<TetId>& group : ready) {
    std::sort(group.begin(), group.end());  // deterministic order
  }
  std::sort(ready.begin(), ready.end());
  for (std::vector<TetId>& group : ready) SplitGroup(std::move(group));
}

namespace {

// The rest and current positions `weights` give on `from`.
std::pair<Eigen::Vector3d, Eigen::Vector3d> PlaceOf(const mesh::TetMesh& mesh,
                                                    const std::array<VertexId, 4>& from,
                                                    const Eigen::Vector4d& weights) {
  Eigen::Vector3d rest = Eigen::Vector3d::Zero(), current = Eigen::Vector3d::Zero();
  for (int k = 0; k < 4; ++k) {
    if (weights[k] == 0) continue;
    rest += weights[k] * mesh.rest_position(from[k]);
    current += weights[k] * mesh.current_position(from[k]);
  }
  return {rest, current};
}

}  // namespace

VertexId Cutter::MakeVertex(const std::array<VertexId, 4>& from, const Eigen::Vector4d& weights) {
  const auto [rest, current] = PlaceOf(*mesh_, from, weights);
  const VertexId v = mesh_->AddVertex(rest, current);
  made_vertices_.push_back({v, from, weights});
  return v;
}

void Cutter::MoveMadeVertex(VertexId v, const std::array<VertexId, 4>& from,
                            const Eigen::Vector4d& weights) {
  const auto [rest, current] = PlaceOf(*mesh_, from, weights);
  const absl::Status moved = mesh_->MoveVertex(v, rest, current);
  assert(moved.ok());
  (void)moved;
  made_vertices_.push_back({v, from, weights});
}

std::vector<MadeVertex> Cutter::TakeMadeVertices() {
  std::vector<MadeVertex> made;
  for (const MadeVertex& m : made_vertices_) {
    if (mesh_->IsAlive(m.vertex)) made.push_back(m);  // dropped hits removed theirs
  }
  made_vertices_.clear();
  return made;
}

std::vector<EdgeCut> Cutter::EdgeCutsOf(const mesh::TetVertices& corners,
                                        std::vector<EdgeKey>* given, const BladePose* pose,
                                        const ClosedVertexMaker& closed_vertex) {
  std::vector<EdgeCut> cuts;
  for (const auto& [i, j] : mesh::kTetEdges) {
    const auto it = edge_hits_.find(MakeEdgeKey(corners[i], corners[j]));
    if (it == edge_hits_.end()) continue;
    EdgeHit& hit = it->second;
    if (hit.along) continue;  // along the crack between two snapped vertices: not cut
    const bool i_low = Index(corners[i]) < Index(corners[j]);
    const VertexId lo = i_low ? corners[i] : corners[j], hi = i_low ? corners[j] : corners[i];
    if (hit.at != kNoVertex) {  // snapped: pinned at the vertex until its star parts
      cuts.push_back({i_low ? i : j, i_low ? j : i, hit.at, hit.at});
      continue;
    }
    const Eigen::Vector4d weights(1 - hit.fraction, hit.fraction, 0, 0);
    if (hit.closed) {  // the crack's front crosses the edge: one vertex
      if (hit.near_low == kNoVertex) {
        hit.near_low = hit.near_high = MakeVertex({lo, hi, lo, lo}, weights);
        if (given != nullptr) given->push_back(it->first);
      }
      cuts.push_back({i_low ? i : j, i_low ? j : i, hit.near_low, hit.near_low});
      continue;
    }
    if (pose != nullptr && hit.near_low == kNoVertex) {
      const Eigen::Vector3d a = mesh_->current_position(lo), b = mesh_->current_position(hi);
      const Eigen::Vector3d point = a + hit.fraction * (b - a);
      if (geometry::DistanceToSegment(point, pose->tip, pose->heel) <
          kDegenerate * (b - a).norm()) {
        const VertexId v = closed_vertex({lo, hi, hi}, {lo, hi, lo, lo}, weights);
        cuts.push_back({i_low ? i : j, i_low ? j : i, v, v});
        continue;
      }
    }
    if (hit.near_low == kNoVertex) {
      hit.near_low = MakeVertex({lo, hi, lo, lo}, weights);
      hit.near_high = MakeVertex({lo, hi, lo, lo}, weights);
      if (given != nullptr) given->push_back(it->first);
    }
    cuts.push_back({i_low ? i : j, i_low ? j : i, hit.near_low, hit.near_high});
  }
  return cuts;
}

std::vector<FacePoint> Cutter::FacePointsOf(const mesh::TetVertices& corners) const {
  std::vector<FacePoint> points;
  for (int k = 0; k < 4; ++k) {
    const auto& face = mesh::kTetFaces[k];
    const auto it = face_hits_.find(MakeFaceKey(corners, face));
    if (it != face_hits_.end() && !AtSnappedVertex(it->first, it->second.barycentric)) {
      points.push_back({k, it->second.vertex});
    }
  }
  return points;
}

bool Cutter::AtSnappedVertex(const FaceKey& key, const Eigen::Vector3d& barycentric) const {
  int nearest = 0;
  barycentric.maxCoeff(&nearest);
  return MiddleCoefficient(barycentric) < snap_fraction_ && snapped_.contains(key[nearest]);
}

TetId Cutter::SourceTet(TetId t) const {
  const auto it = source_tet_.find(t);
  return it == source_tet_.end() ? t : it->second;
}

void Cutter::SplitGroup(std::vector<TetId> group) {
  const auto rest = [&](VertexId v) { return mesh_->rest_position(v); };
  while (true) {
    // Make the vertices of the group's face hits, then every split.
    for (const TetId t : group) {
      const mesh::TetVertices v = mesh_->tet(t);
      for (const auto& face : mesh::kTetFaces) {
        const auto it = face_hits_.find(MakeFaceKey(v, face));
        if (it != face_hits_.end() && it->second.vertex == kNoVertex &&
            !AtSnappedVertex(it->first, it->second.barycentric)) {
          const FaceKey& k = it->first;
          it->second.vertex = MakeVertex(
              {k[0], k[1], k[2], k[0]},
              {it->second.barycentric[0], it->second.barycentric[1], it->second.barycentric[2], 0});
        }
      }
    }
    std::vector<std::pair<TetId, TetSplit>> splits;
    std::vector<TetId> failed;
    std::vector<VertexId> apexes;  // made for the cones (SplitAsCone)
    for (const TetId t : group) {
      const mesh::TetVertices corners = mesh_->tet(t);
      const std::vector<EdgeCut> cuts = EdgeCutsOf(corners);
      const std::vector<FacePoint> faces = FacePointsOf(corners);
      if (faces.empty() && std::all_of(cuts.begin(), cuts.end(),
                                       [&](const EdgeCut& c) { return IsPinned(corners, c); })) {
        continue;  // its hits were dropped, or its cuts are at a snapped corner: it stays
      }
      const bool closed = std::any_of(cuts.begin(), cuts.end(), [&](const EdgeCut& c) {
        return c.near_a == c.near_b && !IsPinned(corners, c);
      });
      TetSplit split =
          closed ? TetSplit{}
                 : SplitThatTiles(*mesh_, corners, cuts, [&](const std::vector<EdgeCut>& kept) {
                     if (faces.empty()) return SplitCompletelyCutTet(corners, kept);
                     if (faces.size() == 2)
                       return SplitCrackedTet(corners, kept, {faces[0], faces[1]}, rest);
                     return TetSplit{};
                   });
      // Closed cuts (only made when snapping), and patterns no case covers that snapping
      // leaves beside snapped vertices (the crack's front through one): a cone.
      if (split.tets.empty() && snap_fraction_ > 0) {
        split = SplitAsCone(corners, cuts, faces, [&](const Eigen::Vector4d& weights) {
          return apexes.emplace_back(MakeVertex(corners, weights));
        });
      }
      if (split.tets.empty()) {
        failed.push_back(t);
      } else {
        splits.emplace_back(t, std::move(split));
      }
    }
    if (failed.empty()) {
      std::vector<mesh::TetVertices> group_corners;
      for (const TetId t : group) group_corners.push_back(mesh_->tet(t));
      for (auto& [t, split] : splits) {
        (void)mesh_->RemoveTet(t);
        for (mesh::TetVertices piece : split.tets) {
          if (SignedVolume(*mesh_, piece) < 0) std::swap(piece[2], piece[3]);
          const absl::StatusOr<TetId> added = mesh_->AddTet(piece);
          assert(added.ok());
          source_tet_[*added] = SourceTet(t);
        }
        ++statistics_.cut_tets;
        statistics_.new_tets += split.tets.size();
        ++statistics_.tets_by_case[static_cast<int>(split.cut_case)];
      }
      for (const mesh::TetVertices& corners : group_corners) {
        for (const auto& [i, j] : mesh::kTetEdges) {
          edge_hits_.erase(MakeEdgeKey(corners[i], corners[j]));
          edge_snapped_faces_.erase(MakeEdgeKey(corners[i], corners[j]));
        }
        for (const auto& f : mesh::kTetFaces) face_hits_.erase(MakeFaceKey(corners, f));
      }
      std::vector<VertexId> snapped;
      for (const mesh::TetVertices& corners : group_corners) {
        for (const VertexId v : corners) {
          if (snapped_.contains(v)) snapped.push_back(v);
        }
      }
      PartSnappedVertices(std::move(snapped));
      for (const VertexId apex : apexes) {  // a cone's apex tried first, if another was kept
        if (mesh_->TetsAround(apex).empty()) (void)mesh_->RemoveVertex(apex);
      }
      break;
    }
    for (const VertexId apex : apexes) (void)mesh_->RemoveVertex(apex);
    // A tet that cannot be split with snapped points is tried without them: its snapped
    // vertices give their hits back as they were found, its closed cuts their face points.
    bool gave_back = false;
    for (const TetId t : failed) {
      const mesh::TetVertices corners = mesh_->tet(t);
      for (const VertexId v : corners) {
        if (!snapped_.contains(v)) continue;
        Unsnap(v);
        gave_back = true;
      }
      for (const auto& [i, j] : mesh::kTetEdges) {
        const EdgeKey key = MakeEdgeKey(corners[i], corners[j]);
        const auto hit = edge_hits_.find(key);
        if (hit == edge_hits_.end() || !hit->second.closed) continue;
        UnsnapEdge(key);
        ++statistics_.unsnapped_edges;
        gave_back = true;
      }
    }
    if (gave_back) continue;
    if (EndCracksOnFaces(failed)) continue;
    // Drop the hits of the tets that cannot be split, with the vertices made for them (no
    // tet uses those yet), and look at the group again.
    for (const TetId t : failed) {
      const mesh::TetVertices v = mesh_->tet(t);
      for (const auto& [i, j] : mesh::kTetEdges) {
        const auto it = edge_hits_.find(MakeEdgeKey(v[i], v[j]));
        if (it == edge_hits_.end()) continue;
        const EdgeHit& hit = it->second;
        if (hit.near_low != kNoVertex) (void)mesh_->RemoveVertex(hit.near_low);
        if (hit.near_high != kNoVertex && hit.near_high != hit.near_low) {
          (void)mesh_->RemoveVertex(hit.near_high);  // a closed hit has one vertex
        }
        edge_hits_.erase(it);
        ++statistics_.dropped_hits;
      }
      for (const auto& f : mesh::kTetFaces) {
        const auto it = face_hits_.find(MakeFaceKey(v, f));
        if (it == face_hits_.end()) continue;
        if (it->second.vertex != kNoVertex) (void)mesh_->RemoveVertex(it->second.vertex);
        face_hits_.erase(it);
        ++statistics_.dropped_hits;
      }
    }
  }
  for (const TetId t : group) {
    members_.erase(t);
    group_of_.erase(t);
  }
}

void Cutter::UpdateOpenTets(const BladePose* pose) {
  const auto rest = [&](VertexId v) { return mesh_->rest_position(v); };
  const auto current = [&](VertexId v) { return mesh_->current_position(v); };
  // Every tet at a hit is open, as for any hit, while its snapped vertex waits (a tet whose cuts
  // are all pinned is closed as soon as the blade is not in it, and the blade may come back).
  for (const auto& [key, hit] : edge_hits_) {
    if (hit.at == kNoVertex && !hit.along && !hit.closed) continue;
    const std::array<VertexId, 2> ends = EdgeEnds(key);
    for (const TetId t : TetsWith(ends)) open_.try_emplace(t);
  }
  while (true) {  // again after a tet the blade left is frozen or has its hits dropped
    last_pose_ = {};
    std::vector<TetId> tets;
    for (const auto& entry : open_) tets.push_back(entry.first);
    std::sort(tets.begin(), tets.end());
    // What this attempt makes, to be taken back if it is not applied.
    std::vector<EdgeKey> edges_given;
    std::vector<FaceKey> faces_given;
    absl::flat_hash_map<FaceKey, TemporaryPoint, FaceKeyHash> points;
    // The previous pose's points this attempt moved, with their positions then.
    struct Before {
      Eigen::Vector3d rest, current;
    };
    absl::flat_hash_map<VertexId, Before> moved_points;
    const std::size_t made_before = made_vertices_.size();
    // A point at a place the previous pose had one moves there (its tets stay the same tets).
    const auto temporary_point = [&](const FaceKey& place, const std::array<VertexId, 4>& from,
                                     const Eigen::Vector4d& weights, bool on_blade = true) {
      // This attempt's point there (asked again for a fallback's apex), else the previous
      // pose's, else a new one; moved where asked (a place's `from` is always the same).
      const auto now = points.find(place);
      if (now != points.end() && now->second.weights == weights) return now->second.vertex;
      const auto old = temporary_points_.find(place);
      VertexId v;
      Eigen::Vector4d at;
      if (now != points.end()) {
        v = now->second.vertex;
        at = now->second.weights;
      } else if (old != temporary_points_.end()) {
        v = old->second.vertex;
        at = old->second.weights;
      } else {
        v = MakeVertex(from, weights);
        at = weights;
      }
      if (at != weights) {
        if (old != temporary_points_.end()) {  // the previous pose's: put back if not applied
          moved_points.try_emplace(v, Before{mesh_->rest_position(v), mesh_->current_position(v)});
        }
        MoveMadeVertex(v, from, weights);
      }
      points[place] = {v, weights, on_blade};
      return v;
    };
    // Puts the points this attempt moved back where they were.
    const auto put_back_moved = [&] {
      for (const auto& [v, before] : moved_points) {
        const absl::Status s = mesh_->MoveVertex(v, before.rest, before.current);
        assert(s.ok());
        (void)s;
      }
      made_vertices_.erase(
          std::remove_if(made_vertices_.begin() + made_before, made_vertices_.end(),
                         [&](const MadeVertex& m) { return moved_points.contains(m.vertex); }),
          made_vertices_.end());
    };
    // Takes back the vertices this attempt made that no tet uses.
    const auto take_back_unused = [&] {
      for (const EdgeKey key : edges_given) {
        EdgeHit& hit = edge_hits_.at(key);
        if (!mesh_->TetsAround(hit.near_low).empty()) continue;
        (void)mesh_->RemoveVertex(hit.near_low);
        (void)mesh_->RemoveVertex(hit.near_high);
        hit.near_low = hit.near_high = kNoVertex;
      }
      for (const FaceKey& key : faces_given) {
        FaceHit& hit = face_hits_.at(key);
        if (!mesh_->TetsAround(hit.vertex).empty()) continue;
        (void)mesh_->RemoveVertex(hit.vertex);
        hit.vertex = kNoVertex;
      }
      absl::erase_if(points, [&](const auto& entry) {
        if (!mesh_->TetsAround(entry.second.vertex).empty()) return false;
        (void)mesh_->RemoveVertex(entry.second.vertex);
        return true;
      });
    };
    std::vector<Plan> plans;
    std::vector<TetId> failed_final;
    bool failed_temporary = false;
    // Where the blade edge crosses each face of each open tet, found once per face so both its
    // tets agree, and whether the blade is in the tet.
    absl::flat_hash_map<FaceKey, std::optional<geometry::SegmentTriangleCrossing>, FaceKeyHash>
        crossing_of;
    struct BladeIn {
      std::array<std::optional<geometry::SegmentTriangleCrossing>, 4> crossings;
      bool inside = false;
    };
    absl::flat_hash_map<TetId, BladeIn> blade_in;
    for (const TetId t : tets) {
      if (pose == nullptr) break;
      const mesh::TetVertices corners = mesh_->tet_even_if_removed(t);
      BladeIn& in = blade_in[t];
      for (int k = 0; k < 4; ++k) {
        const FaceKey key = MakeFaceKey(corners, mesh::kTetFaces[k]);
        auto [it, fresh] = crossing_of.try_emplace(key);
        if (fresh) {
          it->second = geometry::IntersectSegmentTriangle(pose->tip, pose->heel, current(key[0]),
                                                          current(key[1]), current(key[2]));
        }
        in.crossings[k] = it->second;
        in.inside = in.inside || in.crossings[k].has_value();
      }
      std::array<Eigen::Vector3d, 4> x;
      for (int k = 0; k < 4; ++k) x[k] = current(corners[k]);
      in.inside = in.inside || geometry::ContainsPoint(x[0], x[1], x[2], x[3], pose->tip) ||
                  geometry::ContainsPoint(x[0], x[1], x[2], x[3], pose->heel);
    }
    // A snapped closed cut (the crack's front on an edge) opens if the blade crosses the edge
    // later, so no tet at it splits for good while the blade is in one of them: they wait, in
    // temporary subdivisions, and so do the tets at closed cuts of waiting tets.
    absl::flat_hash_set<TetId> waiting;
    for (const auto& [t, in] : blade_in) {
      if (in.inside) waiting.insert(t);
    }
    for (bool grew = !waiting.empty(); grew;) {
      grew = false;
      for (const auto& [key, hit] : edge_hits_) {
        if (!hit.closed) continue;
        const std::vector<TetId> at = TetsWith(EdgeEnds(key));
        if (std::none_of(at.begin(), at.end(), [&](TetId t) { return waiting.contains(t); })) {
          continue;
        }
        for (const TetId t : at) grew |= open_.contains(t) && waiting.insert(t).second;
      }
    }
    for (const TetId t : tets) {
      const mesh::TetVertices corners = mesh_->tet_even_if_removed(t);
      const auto weights_of = [&](const Eigen::Vector3d& p) {  // barycentric, now
        return TetBarycentric(current(corners[0]), current(corners[1]), current(corners[2]),
                              current(corners[3]), p);
      };
      const BladeIn in = pose != nullptr ? blade_in.at(t) : BladeIn{};
      const auto& crossings = in.crossings;
      bool inside = in.inside;
      // A closed cut's one vertex is a temporary point on the blade; the tet holds the blade
      // (but not at a snapped one: the crack's front stays there when the blade has gone).
      const std::vector<EdgeCut> cuts = EdgeCutsOf(corners, &edges_given, pose, temporary_point);
      const bool opens = std::any_of(cuts.begin(), cuts.end(),
                                     [](const EdgeCut& c) { return c.near_a != c.near_b; });
      const auto pinned = [&](const EdgeCut& c) { return IsPinned(corners, c); };
      const bool all_pinned = std::all_of(cuts.begin(), cuts.end(), pinned);
      const auto snapped_closed = [&](const EdgeCut& c) {
        return edge_hits_.at(MakeEdgeKey(corners[c.corner_a], corners[c.corner_b])).closed;
      };
      inside = inside || std::any_of(cuts.begin(), cuts.end(), [&](const EdgeCut& c) {
                 return c.near_a == c.near_b && !pinned(c) && !snapped_closed(c);
               });
      const bool temporary = inside || waiting.contains(t);
      // Face points that can open: on a face with a cut edge (a permanent one first). A
      // temporary one needs an edge that opens: where the face's only cuts are pinned at a
      // snapped corner, the crack passes through the corner and the blade beside it opens
      // nothing until the corner parts.
      std::vector<FacePoint> used;
      Eigen::Vector4d used_sum = Eigen::Vector4d::Zero();  // their corner weights, summed
      int face_hits = 0, temporary_faces = 0;
      for (int k = 0; k < 4; ++k) {
        const auto& f = mesh::kTetFaces[k];
        const FaceKey key = MakeFaceKey(corners, f);
        const auto hit = face_hits_.find(key);
        face_hits += hit != face_hits_.end();
        std::optional<Eigen::Vector3d> crossing;
        if (const auto& c = crossings[k]; c) {
          ++temporary_faces;
          if (c->barycentric.minCoeff() >= kDegenerate) crossing = c->barycentric;
        }
        const auto cut_edge = [&](bool counting_pinned) {
          return IsCutEdge(key[0], key[1], counting_pinned) ||
                 IsCutEdge(key[1], key[2], counting_pinned) ||
                 IsCutEdge(key[0], key[2], counting_pinned);
        };
        Eigen::Vector3d barycentric;
        if (!cut_edge(true)) continue;
        // Beside a snapped vertex the crack's front passes through the vertex: no point (unless
        // one was made, and a tet on the other side uses it).
        if (hit != face_hits_.end() && hit->second.vertex == kNoVertex &&
            AtSnappedVertex(key, hit->second.barycentric)) {
          continue;
        }
        if (hit != face_hits_.end()) {
          if (hit->second.vertex == kNoVertex) {
            const Eigen::Vector3d& b = hit->second.barycentric;
            hit->second.vertex =
                MakeVertex({key[0], key[1], key[2], key[0]}, {b[0], b[1], b[2], 0});
            faces_given.push_back(key);
          }
          used.push_back({k, hit->second.vertex});
          barycentric = hit->second.barycentric;
        } else if (crossing && !settled_faces_.contains(key) && cut_edge(false)) {
          const Eigen::Vector3d& b = *crossing;
          used.push_back(
              {k, temporary_point(key, {key[0], key[1], key[2], key[0]}, {b[0], b[1], b[2], 0})});
          barycentric = b;
        } else {
          continue;
        }
        for (int m = 0; m < 3; ++m) {
          used_sum[std::find(corners.begin(), corners.end(), key[m]) - corners.begin()] +=
              barycentric[m];
        }
      }
      Eigen::Vector4d tip_weights = Eigen::Vector4d::Zero();
      int table_case = 0;
      if (inside) {
        tip_weights = weights_of(pose->tip);
        std::vector<EdgeCut> crossed;  // the cuts but those pinned at a snapped corner
        std::copy_if(cuts.begin(), cuts.end(), std::back_inserter(crossed),
                     [&](const EdgeCut& c) { return !pinned(c); });
        bool share_corner = false;
        if (crossed.size() == 2) {
          share_corner = crossed[0].corner_a == crossed[1].corner_a ||
                         crossed[0].corner_a == crossed[1].corner_b ||
                         crossed[0].corner_b == crossed[1].corner_a ||
                         crossed[0].corner_b == crossed[1].corner_b;
        }
        table_case = ProgressiveCase(static_cast<int>(crossed.size()), face_hits, temporary_faces,
                                     tip_weights.minCoeff() > 0, share_corner);
        ++last_pose_.tets_by_case[table_case];
      }
      const bool tip_inside = inside && tip_weights.minCoeff() >= kTipMargin;
      if (used.empty() && all_pinned) {
        // Nothing can open (no cut, or all at snapped corners): the tet stays, whole again if
        // it stood in pieces.
        Plan stays{.tet = t, .temporary = temporary, .table_case = table_case};
        if (!open_.at(t).pieces.empty()) stays.split.tets = {corners};
        plans.push_back(std::move(stays));
        continue;
      }
      using Apex = SplitInputs::Apex;
      SplitInputs inputs{cuts, used, tip_inside && !cuts.empty() ? Apex::kTip : Apex::kNone};
      if (const OpenTet& open = open_.at(t);
          temporary && !open.pieces.empty() && open.inputs == inputs) {
        // Only the blade moved: the same pieces, their points moved, unless one would now be
        // inverted (then they are chosen anew).
        if (inputs.apex == Apex::kTip) {
          temporary_point(InsidePlace(t), corners, tip_weights);
        } else if (const auto apex = temporary_points_.find(InsidePlace(t));
                   apex != temporary_points_.end()) {
          points.insert(*apex);  // a cone's, where it was
        }
        Plan moved{.tet = t, .temporary = true, .table_case = table_case, .moved = true};
        for (const TetId piece : open.pieces) moved.split.tets.push_back(mesh_->tet(piece));
        if (std::all_of(
                moved.split.tets.begin(), moved.split.tets.end(),
                [&](const mesh::TetVertices& piece) { return SignedVolume(*mesh_, piece) > 0; })) {
          plans.push_back(std::move(moved));
          continue;
        }
      }
      TetSplit split = SplitThatTiles(*mesh_, corners, cuts, [&](const std::vector<EdgeCut>& kept) {
        if (inputs.apex == Apex::kTip) {  // the crack reaches the tip
          return SplitAsStar(corners, kept, used,
                             temporary_point(InsidePlace(t), corners, tip_weights), rest);
        }
        if (used.size() == 2) return SplitCrackedTet(corners, kept, {used[0], used[1]}, rest);
        if (used.empty()) return SplitCompletelyCutTet(corners, kept);
        return TetSplit{};
      });
      // Fallbacks: a cone from a point inside the tet (weights on its corners).
      const auto cone_from = [&](const Eigen::Vector4d& apex) {
        const VertexId point = temporary_point(InsidePlace(t), corners, apex, false);
        split = SplitThatTiles(*mesh_, corners, cuts, [&](const std::vector<EdgeCut>& kept) {
          return SplitAsStar(corners, kept, used, point, rest);
        });
        inputs.apex = Apex::kMiddle;
      };
      if (split.tets.empty() && !used.empty()) {
        // A pattern the minimal cases do not cover (two cracks, say): a cone from the middle
        // of its face points, which lies inside the tet.
        const Eigen::Vector4d middle = used_sum / static_cast<double>(used.size());
        if (middle.minCoeff() >= kTipMargin) cone_from(middle);
      }
      if (split.tets.empty() && inside && !used.empty()) {
        // The blade passes through the tet beside a crack its face points alone do not span
        // (one face point and a crack through a snapped corner, say, the blade skimming an
        // edge): a cone from the middle of the blade's chord through the tet, the crack's front.
        double first = 1, last = 0;  // along the blade, from its tip
        for (const auto& c : crossings) {
          if (!c) continue;
          first = std::min(first, c->t);
          last = std::max(last, c->t);
        }
        if (tip_weights.minCoeff() > 0) first = 0;
        const Eigen::Vector4d chord =
            weights_of(pose->tip + 0.5 * (first + last) * (pose->heel - pose->tip));
        if (first <= last && chord.minCoeff() >= kTipMargin) cone_from(chord);
      }
      if (split.tets.empty() && inside && !opens && !cuts.empty()) {
        // Every cut closed (the blade on the tet's edges): nothing opens here, but the tet
        // must meet its neighbours' faces at those points; a cone from its middle does.
        cone_from(Eigen::Vector4d::Constant(0.25));
      }
      if (split.tets.empty() && !inside && snap_fraction_ > 0) {
        // Snapped, a tet the blade is not in with a closed cut, or that no case covers (the
        // crack's front through a snapped corner, say): see SplitAsCone.
        split = SplitAsCone(corners, cuts, used, [&](const Eigen::Vector4d& apex) {
          inputs.apex = Apex::kMiddle;
          return temporary_point(InsidePlace(t), corners, apex, false);
        });
      }
      if (split.tets.empty()) {
        if (inside) {
          ++statistics_.uncovered_temporary_plans;
          failed_temporary = true;
        } else {
          failed_final.push_back(t);
        }
        continue;
      }
      plans.push_back({.tet = t,
                       .temporary = temporary,
                       .table_case = table_case,
                       .split = std::move(split),
                       .inputs = std::move(inputs)});
    }

    // Plans that change no tet keep the mesh as conforming as it is.
    const bool tets_change = std::any_of(plans.begin(), plans.end(), [&](const Plan& plan) {
      return !plan.moved && !(plan.temporary && plan.split.tets.empty());
    });
    if (!failed_temporary && failed_final.empty() && tets_change) {
      for (const std::size_t k : NonConformingPlans(plans)) {
        ++statistics_.nonconforming_plans;
        if (plans[k].temporary) {
          failed_temporary = true;
        } else {
          failed_final.push_back(plans[k].tet);
        }
      }
    }
    // A temporary subdivision at fault holds the pose, and a held pose drops nothing: the
    // final subdivisions that failed with it may have failed for its sake (a neighbour kept
    // as it was), so they are tried again at the next pose. Final ones alone are frozen.
    if (failed_temporary) failed_final.clear();
    if (failed_temporary || !failed_final.empty()) {
      take_back_unused();  // nothing was applied: the mesh is as it was
      put_back_moved();
      // A snapped vertex no tet has split through for good is taken off the crack where a tet
      // at it cannot be split for good (as deferred cutting does), and the pose is tried again.
      // Not where a temporary subdivision fails (the blade skimming an edge, say): the pose is
      // held and tried again at the next, with the crack as it was (unsnapping drops the cuts
      // pinned at the vertex that the blade never crossed, and the crack about it may no
      // longer close).
      std::vector<VertexId> unsnapping;
      for (const TetId t : failed_final) {
        for (const VertexId v : mesh_->tet_even_if_removed(t)) {
          if (snapped_.contains(v) && !committed_.contains(v)) unsnapping.push_back(v);
        }
      }
      std::sort(unsnapping.begin(), unsnapping.end());
      unsnapping.erase(std::unique(unsnapping.begin(), unsnapping.end()), unsnapping.end());
      for (const VertexId v : unsnapping) Unsnap(v);
      if (!unsnapping.empty()) continue;
      if (failed_final.empty()) {
        ++statistics_.held_poses;
        last_pose_.held = true;
        break;
      }
      // Only once the blade is withdrawn: ended in a live cut, such cracks let the tissue
      // flail against the blade (the liver, corotational: backward Euler blew up).
      if (pose == nullptr && EndCracksOnFaces(failed_final)) continue;
      for (const TetId t : failed_final) {
        OpenTet& open = open_.at(t);
        const mesh::TetVertices corners = mesh_->tet_even_if_removed(t);
        if (!open.pieces.empty()) {
          // Frozen: its temporary points become permanent, so its neighbours keep them.
          MakePermanent([&](const FaceKey&, VertexId v) {
            return std::any_of(open.pieces.begin(), open.pieces.end(), [&](TetId piece) {
              return mesh::TetHasVertex(mesh_->tet(piece), v);
            });
          });
          // Its pieces stay for good: a soft one is made anew, so the model gives it stiffness.
          for (TetId& piece : open.pieces) {
            if (!IsSoft(piece)) continue;
            const mesh::TetVertices piece_corners = mesh_->tet(piece);
            owner_.erase(piece);
            (void)mesh_->RemoveTet(piece);
            const absl::StatusOr<TetId> added = mesh_->AddTet(piece_corners);
            assert(added.ok());
            source_tet_[*added] = SourceTet(t);
            piece = *added;
          }
          Commit(corners, open.inputs.cuts);
          ++statistics_.frozen_tets;
        } else {
          // Never subdivided: its hits were never used; drop them.
          for (const auto& [i, j] : mesh::kTetEdges) {
            const auto it = edge_hits_.find(MakeEdgeKey(corners[i], corners[j]));
            if (it == edge_hits_.end() || it->second.near_low != kNoVertex) continue;
            edge_hits_.erase(it);
            ++statistics_.dropped_hits;
          }
          for (const auto& f : mesh::kTetFaces) {
            const auto it = face_hits_.find(MakeFaceKey(corners, f));
            if (it == face_hits_.end() || it->second.vertex != kNoVertex) continue;
            face_hits_.erase(it);
            ++statistics_.dropped_hits;
          }
        }
        CloseOpenTet(t);
        ForgetHitsOf(corners);
      }
      continue;
    }

    // Apply: temporary points by place, for the signatures.
    absl::flat_hash_map<VertexId, std::uint64_t> place_code;
    for (const auto& [place, point] : points) {
      place_code[point.vertex] =
          (std::uint64_t{1} << 63) |
          (absl::HashOf(Index(place[0]), Index(place[1]), Index(place[2])) >> 1);
    }
    const auto code = [&](VertexId v) {
      const auto it = place_code.find(v);
      return it == place_code.end() ? std::uint64_t{Index(v)} : it->second;
    };
    std::vector<mesh::TetVertices> closed;
    for (Plan& plan : plans) {
      if (plan.moved) {
        ++statistics_.moved;  // only its points moved, in place: its pieces stay
        continue;
      }
      OpenTet& open = open_.at(plan.tet);
      const mesh::TetVertices corners = mesh_->tet_even_if_removed(plan.tet);
      if (plan.split.tets.empty()) {
        assert(open.pieces.empty());
        if (!plan.temporary) {
          closed.push_back(corners);
          CloseOpenTet(plan.tet);
        }
        continue;
      }
      std::vector<std::array<std::uint64_t, 4>> signature;
      for (const mesh::TetVertices& piece : plan.split.tets) {
        std::array<std::uint64_t, 4> c = {code(piece[0]), code(piece[1]), code(piece[2]),
                                          code(piece[3])};
        std::sort(c.begin(), c.end());
        signature.push_back(c);
      }
      std::sort(signature.begin(), signature.end());
      const auto positive = [&](const mesh::TetVertices& v) { return SignedVolume(*mesh_, v) > 0; };
      if (plan.temporary && signature == open.signature &&
          std::all_of(open.pieces.begin(), open.pieces.end(),
                      [&](TetId piece) { return positive(mesh_->tet(piece)); })) {
        ++statistics_.moved;  // only its points moved, in place: its pieces stay
        continue;
      }
      // Take out what stands for the tet now.
      if (open.pieces.empty()) {
        if (mesh_->IsAlive(plan.tet)) (void)mesh_->RemoveTet(plan.tet);
      }
      for (const TetId piece : open.pieces) {
        owner_.erase(piece);
        (void)mesh_->RemoveTet(piece);
      }
      std::vector<TetId> kept;
      for (mesh::TetVertices piece : plan.split.tets) {
        if (!positive(piece)) std::swap(piece[2], piece[3]);
        const absl::StatusOr<TetId> added = mesh_->AddTet(piece);
        assert(added.ok());
        source_tet_[*added] = SourceTet(plan.tet);
        kept.push_back(*added);
        if (plan.temporary) owner_[*added] = plan.tet;
      }
      if (plan.temporary) {
        ++statistics_.rebuilt;
        if (std::any_of(kept.begin(), kept.end(), [&](TetId piece) { return IsSoft(piece); })) {
          ++statistics_.thin_temporary_plans;
        }
        open.pieces = std::move(kept);
        open.signature = std::move(signature);
        open.inputs = std::move(plan.inputs);
      } else {
        // A point made inside it for good (the middle of its face points) stays.
        for (auto it = points.begin(); it != points.end();) {
          const VertexId v = it->second.vertex;
          const bool used = std::any_of(
              plan.split.tets.begin(), plan.split.tets.end(),
              [&](const mesh::TetVertices& piece) { return mesh::TetHasVertex(piece, v); });
          if (used) {
            points.erase(it++);
          } else {
            ++it;
          }
        }
        if (plan.split.cut_case != CutCase::kNone) {  // not whole again (see `stays`)
          ++statistics_.cut_tets;
          statistics_.new_tets += plan.split.tets.size();
          ++statistics_.tets_by_case[static_cast<int>(plan.split.cut_case)];
        }
        Commit(corners, plan.inputs.cuts);
        open.pieces.clear();
        closed.push_back(corners);
        CloseOpenTet(plan.tet);
      }
    }
    // The previous pose's temporary points no tet uses any more.
    for (const auto& [place, point] : temporary_points_) {
      if (!place_code.contains(point.vertex)) (void)mesh_->RemoveVertex(point.vertex);
    }
    take_back_unused();  // made for subdivisions that were kept instead
    temporary_points_ = std::move(points);
    for (const mesh::TetVertices& corners : closed) ForgetHitsOf(corners);
    break;
  }
  if (!last_pose_.held) PartFinishedSnappedVertices();
  for (int k = 0; k <= kProgressiveCases; ++k) {
    statistics_.poses_by_case[k] += last_pose_.tets_by_case[k];
  }
  last_pose_.open_tets = open_.size();
  for (const auto& [t, open] : open_) last_pose_.temporary_tets += open.pieces.size();
}

std::vector<std::size_t> Cutter::NonConformingPlans(const std::vector<Plan>& plans) const {
  using Triangle = std::array<VertexId, 3>;
  // Each plan's triangles on each face of its tet, and the (plan, face) pairs on each face.
  std::vector<std::array<std::vector<Triangle>, 4>> on_face(plans.size());
  absl::flat_hash_map<FaceKey, std::vector<std::pair<std::size_t, int>>, FaceKeyHash> sides;
  for (std::size_t p = 0; p < plans.size(); ++p) {
    const mesh::TetVertices& corners = mesh_->tet_even_if_removed(plans[p].tet);
    const std::vector<mesh::TetVertices> whole = {corners};
    const std::vector<mesh::TetVertices>& placed =
        plans[p].split.tets.empty() ? whole : plans[p].split.tets;
    for (int k = 0; k < 4; ++k) {
      on_face[p][k] = mesh::TrianglesOnFace(*mesh_, corners, k, placed);
      sides[MakeFaceKey(corners, mesh::kTetFaces[k])].push_back({p, k});
    }
  }
  // Whether a live tet not standing for `t` has the triangle.
  const auto attached = [&](TetId t, const Triangle& tri) {
    for (const TetId other : mesh_->TetsAroundFace(tri[0], tri[1], tri[2])) {
      if (OwnerOf(other) != t) return true;
    }
    return false;
  };
  // Whether plan p's triangles on face k are those of the other side.
  const auto conforms = [&](std::size_t p, int k) {
    const TetId t = plans[p].tet;
    const mesh::TetVertices& corners = mesh_->tet_even_if_removed(t);
    const std::vector<Triangle>& mine = on_face[p][k];
    const auto& sharing = sides.at(MakeFaceKey(corners, mesh::kTetFaces[k]));
    if (sharing.size() > 1) {  // the other side is planned too
      const auto [q, j] = sharing[0].first == p ? sharing[1] : sharing[0];
      return on_face[q][j] == mine;
    }
    // The other side stays as it is: every triangle has a tet there, or none has (the surface,
    // or a crack); what stands for t now tells which.
    const std::size_t with_tet = static_cast<std::size_t>(std::count_if(
        mine.begin(), mine.end(), [&](const Triangle& tri) { return attached(t, tri); }));
    if (with_tet == mine.size()) return true;
    if (with_tet > 0) return false;
    std::vector<mesh::TetVertices> now;
    const auto open = open_.find(t);
    if (open == open_.end() || open->second.pieces.empty()) {
      now.push_back(corners);
    } else {
      for (const TetId piece : open->second.pieces) now.push_back(mesh_->tet(piece));
    }
    const std::vector<Triangle> before = mesh::TrianglesOnFace(*mesh_, corners, k, now);
    return std::none_of(before.begin(), before.end(),
                        [&](const Triangle& tri) { return attached(t, tri); });
  };
  std::vector<std::size_t> faulty;
  for (std::size_t p = 0; p < plans.size(); ++p) {
    if (!conforms(p, 0) || !conforms(p, 1) || !conforms(p, 2) || !conforms(p, 3)) {
      faulty.push_back(p);
    }
  }
  return faulty;
}

void Cutter::MakePermanent(const std::function<bool(const FaceKey&, VertexId)>& which) {
  for (auto it = temporary_points_.begin(); it != temporary_points_.end();) {
    const auto& [place, point] = *it;
    if (!which(place, point.vertex)) {
      ++it;
      continue;
    }
    if (place[0] != place[1]) face_hits_[place] = {point.weights.head<3>(), point.vertex};
    temporary_points_.erase(it++);
  }
}

bool Cutter::EndCracksOnFaces(const std::vector<TetId>& tets) {
  bool added = false;
  for (const TetId t : tets) {
    const mesh::TetVertices corners = mesh_->tet_even_if_removed(t);
    bool near_corner = false;
    for (const auto& [i, j] : mesh::kTetEdges) {
      const auto hit = edge_hits_.find(MakeEdgeKey(corners[i], corners[j]));
      if (hit == edge_hits_.end() || hit->second.at != kNoVertex || hit->second.along) continue;
      near_corner |= std::min(hit->second.fraction, 1 - hit->second.fraction) < kCrackEndMargin;
    }
    if (near_corner) continue;
    for (const auto& f : mesh::kTetFaces) {
      const FaceKey key = MakeFaceKey(corners, f);
      // Not a face the blade crossed at the last pose: its point is the blade's.
      if (face_hits_.contains(key) || temporary_points_.contains(key)) continue;
      int cut = -1, cuts = 0;  // the cut edge: key[cut] to key[(cut + 1) % 3]
      bool closed = false;     // the crack's front crosses an edge of it: it ends there
      for (int m = 0; m < 3; ++m) {
        if (IsCutEdge(key[m], key[(m + 1) % 3], false)) {
          cut = m;
          ++cuts;
        }
        const auto hit = edge_hits_.find(MakeEdgeKey(key[m], key[(m + 1) % 3]));
        closed |= hit != edge_hits_.end() && hit->second.closed;
      }
      // Not beside a snapped vertex (its pinned cuts and the edges along the crack make
      // other patterns).
      const bool snapped =
          std::any_of(key.begin(), key.end(), [&](VertexId v) { return snapped_.contains(v); });
      if (cuts != 1 || closed || snapped || !Realisable(key)) continue;
      // The key is in increasing id order but for the edge from its last vertex to its first.
      const VertexId a = key[cut], b = key[(cut + 1) % 3];
      const double from_low = edge_hits_.at(MakeEdgeKey(a, b)).fraction;
      Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();
      barycentric[cut] = Index(a) < Index(b) ? 1 - from_low : from_low;
      barycentric[(cut + 1) % 3] = 1 - barycentric[cut];
      face_hits_[key] = {0.5 * barycentric + Eigen::Vector3d::Constant(1.0 / 6)};
      ++statistics_.ended_cracks;
      added = true;
    }
  }
  return added;
}

void Cutter::CloseOpenTet(TetId t) {
  const auto it = open_.find(t);
  if (it == open_.end()) return;
  // Its faces with points are split for good.
  const mesh::TetVertices& corners = mesh_->tet_even_if_removed(t);
  // (A cut pinned at a snapped corner, or along the crack, leaves a face whole on its own.)
  for (const auto& f : mesh::kTetFaces) {
    const FaceKey key = MakeFaceKey(corners, f);
    if (face_hits_.contains(key) || IsCutEdge(key[0], key[1], false) ||
        IsCutEdge(key[1], key[2], false) || IsCutEdge(key[0], key[2], false)) {
      settled_faces_.insert(key);
    }
  }
  for (const TetId piece : it->second.pieces) owner_.erase(piece);
  open_.erase(it);
}

void Cutter::ForgetHitsOf(const mesh::TetVertices& corners) {
  const auto open_has = [&](std::initializer_list<VertexId> vertices) {
    return std::any_of(open_.begin(), open_.end(), [&](const auto& entry) {
      return HasAll(mesh_->tet_even_if_removed(entry.first),
                    std::span<const VertexId>(vertices.begin(), vertices.size()));
    });
  };
  for (const auto& [i, j] : mesh::kTetEdges) {
    const auto hit = edge_hits_.find(MakeEdgeKey(corners[i], corners[j]));
    if (hit == edge_hits_.end() || open_has({corners[i], corners[j]})) continue;
    // A hit at a snapped vertex, or along the crack, stays until the vertex parts: a tet
    // opened again before then must split with it, as its neighbours did.
    const bool at_snapped =
        hit->second.at != kNoVertex
            ? snapped_.contains(hit->second.at)
            : hit->second.along && (snapped_.contains(corners[i]) || snapped_.contains(corners[j]));
    if (at_snapped) continue;
    // A copy of its point no tet took (the pieces on a side collapsed at a snapped corner).
    for (const VertexId made : {hit->second.near_low, hit->second.near_high}) {
      if (made != kNoVertex && mesh_->TetsAround(made).empty()) (void)mesh_->RemoveVertex(made);
    }
    edge_snapped_faces_.erase(hit->first);
    edge_hits_.erase(hit);
  }
  for (const auto& f : mesh::kTetFaces) {
    const auto hit = face_hits_.find(MakeFaceKey(corners, f));
    if (hit == face_hits_.end() || open_has({corners[f[0]], corners[f[1]], corners[f[2]]})) {
      continue;
    }
    const VertexId made = hit->second.vertex;
    if (made != kNoVertex && mesh_->TetsAround(made).empty()) (void)mesh_->RemoveVertex(made);
    face_hits_.erase(hit);
  }
}

}  // namespace kerf::cut
