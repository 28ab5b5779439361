// CrackCutter: splitting units and parting the crack's vertices (see crack_cutter.h).
#include <algorithm>
#include <limits>
#include <span>

#include "base/check.h"
#include "cut/crack_cutter.h"
#include "geometry/tet_measures.h"

namespace kerf::cut {
namespace {

using mesh::Index;
using mesh::TetId;
using mesh::VertexId;

double SmallestRestVolume(const mesh::TetMesh& mesh, std::span<const TetId> tets) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const TetId t : tets) smallest = std::min(smallest, mesh::RestVolume(mesh, t));
  return smallest;
}

}  // namespace

void CrackCutter::SplitUnits(std::vector<TetId> units,
                             const absl::flat_hash_map<TetId, BladeIn>& blade) {
  std::sort(units.begin(), units.end());
  units.erase(std::unique(units.begin(), units.end()), units.end());
  const auto blade_in = [&](TetId u) {
    const auto in = blade.find(u);
    return in == blade.end() ? nullptr : &in->second;
  };
  stood_.clear();
  std::vector<VertexId> origins, for_good;
  for (const TetId u : units) {
    // A unit named at the last pose may have been renamed by parting since (its tets now are
    // units of their own, found through their points if they have any).
    if (!open_.contains(u) && !mesh_->IsAlive(u)) continue;
    if (const BladeIn* in = blade_in(u)) {
      const int table_case = TableCase(CornersOf(u), *in);
      ++statistics_.poses_by_case[table_case];
      ++last_pose_.tets_by_case[table_case];
    }
    const std::vector<VertexId> used = SplitUnit(u, blade_in(u));
    origins.insert(origins.end(), used.begin(), used.end());
    if (!blade_in(u)) for_good.insert(for_good.end(), used.begin(), used.end());
  }
  Repart(origins);
  // Crack faces parting left shut open at a point of their own, so the crack opens up to the
  // blade and the tip's path however thin it is in a tet.
  // (Only the tets and the blade's units tell which are shut: unchanged, none is again.)
  std::vector<TetId> with_blade;
  for (const auto& [u, in] : blade) with_blade.push_back(u);
  std::sort(with_blade.begin(), with_blade.end());
  absl::flat_hash_map<TetId, std::vector<FaceKey>> shut;
  if (!none_shut_at_ || none_shut_at_->first != edits_ || none_shut_at_->second != with_blade) {
    for (const TetId u : units) {
      if (!open_.contains(u) || !blade_in(u)) continue;
      for (const ShutFace& face : ShutCrackFaces(u, blade)) {
        shut[u].push_back(face.key);
        if (face.beside) shut[*face.beside].push_back(face.key);
      }
    }
  }
  if (shut.empty()) none_shut_at_.emplace(edits_, std::move(with_blade));
  std::vector<TetId> again;
  for (const auto& [u, keys] : shut) again.push_back(u);
  std::sort(again.begin(), again.end());  // the same points whatever the map's order
  origins.clear();
  for (const TetId u : again) {
    std::vector<FaceKey>& keys = shut.at(u);
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    const std::vector<VertexId> used = SplitUnit(u, blade_in(u), keys);
    origins.insert(origins.end(), used.begin(), used.end());
  }
  if (!origins.empty()) Repart(origins);
  // A chip is walled in by crack faces, each of whose corners was to be parted.
  std::vector<TetId> seeds;
  std::sort(for_good.begin(), for_good.end());
  for_good.erase(std::unique(for_good.begin(), for_good.end()), for_good.end());
  for (const VertexId v : for_good) {
    if (!OnTheCrack(v)) continue;
    const std::vector<TetId> around = parting_.TetsAround(*mesh_, v);
    seeds.insert(seeds.end(), around.begin(), around.end());
  }
  HoldChips(std::move(seeds));
  // So do the vertices of edge points the blade's points stand in for (they are made again if
  // the crack's front comes back).
  for (const auto& [u, in] : blade) {
    for (const auto& [key, fraction] : in.edges) {
      const auto point = edge_points_.find(key);
      if (point != edge_points_.end() && point->second.vertex != kNoVertex &&
          RemovePointIfUnused(point->second.vertex)) {
        point->second.vertex = kNoVertex;
      }
    }
  }
  // Temporary points no split uses this pose go.
  for (auto it = temporary_.begin(); it != temporary_.end();) {
    if (!temporary_used_.contains(it->first) && RemovePointIfUnused(it->second)) {
      temporary_.erase(it++);
    } else {
      ++it;
    }
  }
  temporary_used_.clear();
}

bool CrackCutter::SamePieces(const std::vector<TetId>& pieces,
                             const std::vector<mesh::TetVertices>& split) const {
  if (pieces.size() != split.size()) return false;
  const auto sorted = [](mesh::TetVertices t) {
    std::sort(t.begin(), t.end());
    return t;
  };
  std::vector<mesh::TetVertices> now, then;
  for (const TetId p : pieces) {
    mesh::TetVertices t = mesh_->tet(p);
    for (VertexId& v : t) v = parting_.Origin(v);
    now.push_back(sorted(t));
  }
  for (const mesh::TetVertices& t : split) then.push_back(sorted(t));
  std::sort(now.begin(), now.end());
  std::sort(then.begin(), then.end());
  return now == then;
}

std::vector<VertexId> CrackCutter::SplitUnit(TetId unit, const BladeIn* blade,
                                             std::span<const FaceKey> to_open) {
  const mesh::TetVertices corners = CornersOf(unit);
  std::array<FacePoints, 4> points = PointsOf(corners, blade);
  if (blade != nullptr && to_open.empty() && PiecesStand(unit, points, *blade)) {
    stood_.insert(unit);
    return {};
  }
  const TetCrack crack = MakeTetCrack(corners, points);
  const CrackTraces traces = TracesOf(crack);
  const auto rest = [&](VertexId v) -> Eigen::Vector3d { return mesh_->rest_position(v); };
  // Pieces that stood this pose are opened as they are (made anew, the split could differ
  // where it is chosen by shape, and lack the faces to open). While the blade is in the unit the
  // crack reaches it: where a split without the blade's point would miss the blade, the unit
  // splits as the cone from that point.
  const bool stood = stood_.contains(unit);
  std::optional<CrackSplit> split;
  if (stood) {
    split = PiecesAsSplit(unit);
  } else if (blade == nullptr || !SplitsAsTheBladesCone(points, traces, *blade)) {
    split = SplitWithoutApex(crack, rest);
  }
  // For good, a minimal split with slivers gives way to a cone that has fewer; a unit the blade
  // is withdrawn from splits as the cone from where it was, the crack reaching that point.
  // Either gives way to the cone that covers the blade's steps inside the unit better.
  std::optional<Eigen::Vector4d> cone_apex;
  bool apex_on_crack = blade != nullptr;
  if (blade == nullptr && !stood) {
    const ApexOnPath on_path = [&] { return StepsInUnit(unit); };
    if (const auto withdrawn = WithdrawnApex(unit, crack, /*fits_without=*/split.has_value())) {
      cone_apex = withdrawn, apex_on_crack = true;
    } else if (split) {
      cone_apex = ConeApexWithFewerSlivers(crack, *split, rest, kSliverAngleDeg,
                                           NearPath(unit, crack.corners), on_path);
    } else {
      cone_apex = ConeApexWeights(crack, rest, NearPath(unit, crack.corners), on_path);
    }
    if (const auto closer = ApexCoveringTheSteps(unit, crack, cone_apex ? nullptr : &*split,
                                                 cone_apex, apex_on_crack)) {
      cone_apex = closer->weights, apex_on_crack = closer->on_crack;
    }
    if (cone_apex) split.reset();
  }
  const bool was_open = open_.contains(unit);
  if (split && split->kind == CrackSplitKind::kWhole && !was_open) {
    std::vector<VertexId> to_part;
    for (const auto& f : split->crack_faces) {
      AddCrack(MakeFaceKey(f[0], f[1], f[2]));
      to_part.insert(to_part.end(), f.begin(), f.end());
    }
    return to_part;
  }
  if (!split) {
    const Eigen::Vector4d apex = blade != nullptr ? blade->apex : *cone_apex;
    split = SplitAsCone(crack, TemporaryVertex(ApexPlace(unit), corners, apex), apex_on_crack);
  }
  // For good, no piece is cut free but by the blade; while the blade is in the tet, pieces
  // between its points and the crack stay open until it moves on.
  // (Chips walled in by the faces of tets beside hold once parted: HoldChips.)
  if (blade == nullptr) ReleaseWalledInPieces(crack, &*split);
  // While the blade is in the unit, crack faces parting leaves shut are opened at their middle
  // (SplitUnits) and stay so as the blade moves. A split for good opens none: the crack's edge has
  // moved on, and the faces it leaves shut open by parting, or at the end (OpenShutCrackFaces).
  // Faces inside the unit stay opened; one in a face of the unit opens only while both units at
  // it have the blade in them and find it shut (SplitUnits), so the two always agree.
  std::vector<FaceKey> openings;
  if (was_open && blade != nullptr) {
    for (const FaceKey& key : open_.at(unit).openings) {
      // Pieces that stood have them open already.
      if (stood || OpenAtItsMiddle(unit, crack, key, &*split) == 2) openings.push_back(key);
    }
  }
  bool opened_in_face = false;
  for (const FaceKey& key : to_open) {
    // The split is the one that left it shut, made again: it has the face (the unit beside
    // opens it too).
    const int sides = OpenAtItsMiddle(unit, crack, key, &*split);
    KERF_CHECK(sides > 0);
    if (sides == 2) openings.push_back(key);
    opened_in_face = opened_in_face || sides == 1;
  }
  return LayOut(unit, crack, points, traces, *split, std::move(openings), opened_in_face,
                /*blade_in=*/blade != nullptr);
}

std::vector<VertexId> CrackCutter::LayOut(TetId unit, const TetCrack& crack,
                                          const std::array<FacePoints, 4>& points,
                                          const CrackTraces& traces, const CrackSplit& split,
                                          std::vector<FaceKey> openings, bool opened_in_face,
                                          bool blade_in) {
  const bool was_open = open_.contains(unit);
  std::vector<FaceKey> crack_faces;
  for (const auto& f : split.crack_faces) crack_faces.push_back(MakeFaceKey(f[0], f[1], f[2]));
  std::sort(crack_faces.begin(), crack_faces.end());
  if (was_open && open_.at(unit).crack == crack_faces &&
      SamePieces(open_.at(unit).pieces, split.tets)) {
    // Only the temporary points moved (TemporaryVertex moved them): the pieces stand, laid out
    // for the points as they are now.
    OpenTet& open = open_.at(unit);
    open.points = points;
    open.traces = traces;
    open.smallest_volume = SmallestRestVolume(*mesh_, open.pieces);
    return {};
  }
  // Parting can change only at vertices of the crack faces going or coming, and at those with
  // copies (the pieces name origins; the tets around them may use copies).
  std::vector<VertexId> to_part;
  if (was_open) {
    for (const FaceKey& key : open_.at(unit).crack) {
      RemoveCrack(key);
      to_part.insert(to_part.end(), key.begin(), key.end());
    }
  }
  for (const FaceKey& key : crack_faces) to_part.insert(to_part.end(), key.begin(), key.end());
  for (const mesh::TetVertices& t : split.tets) {
    for (const VertexId v : t) {
      if (parting_.HasCopies(v)) to_part.push_back(v);
    }
  }
  for (const FaceKey& key : crack_faces) AddCrack(key);
  if (blade_in) {
    ++statistics_.rebuilt;
  } else {
    ++statistics_.tets_by_case[static_cast<std::size_t>(split.cut_case)];
  }
  const TetId source = was_open ? open_.at(unit).source : SourceTet(unit);
  std::vector<TetId> pieces = Replace(unit, split.tets);
  for (const TetId p : pieces) owner_[p] = unit;
  const double smallest_volume = SmallestRestVolume(*mesh_, pieces);
  const bool cone = split.kind == CrackSplitKind::kCone;
  open_[unit] = {.corners = crack.corners,
                 .source = source,
                 .pieces = std::move(pieces),
                 .crack = std::move(crack_faces),
                 .openings = std::move(openings),
                 .points = points,
                 .cone = cone,
                 .opened_in_face = opened_in_face,
                 .smallest_volume = smallest_volume,
                 .traces = traces,
                 .placed = std::nullopt};
  return to_part;
}

CrackCutter::CrackTraces CrackCutter::TracesOf(const TetCrack& crack) {
  CrackTraces traces;
  traces.any = !TracePoints(crack).empty();
  if (!traces.any) return traces;
  for (const int k : FacesHoldingTheTrace(crack)) {
    const auto& f = mesh::kTetFaces[k];
    traces.holding.push_back(
        MakeFaceKey(crack.corners[f[0]], crack.corners[f[1]], crack.corners[f[2]]));
  }
  return traces;
}

bool CrackCutter::SplitsAsTheBladesCone(const std::array<FacePoints, 4>& points,
                                        const CrackTraces& traces, const BladeIn& blade) {
  return std::any_of(points.begin(), points.end(),
                     [](const FacePoints& p) { return p.beside.has_value(); }) ||
         MissesTheBlade(traces, blade);
}

bool CrackCutter::MissesTheBlade(const CrackTraces& traces, const BladeIn& blade) {
  if (!traces.any) return false;
  if (blade.tip_inside) return true;
  return std::any_of(traces.holding.begin(), traces.holding.end(), [&](const FaceKey& key) {
    return std::find(blade.crossed.begin(), blade.crossed.end(), key) != blade.crossed.end();
  });
}

CrackSplit CrackCutter::PiecesAsSplit(TetId unit) const {
  const OpenTet& open = open_.at(unit);
  CrackSplit split;
  split.kind = open.cone ? CrackSplitKind::kCone : CrackSplitKind::kMinimal;
  for (const TetId p : open.pieces) {
    mesh::TetVertices t = mesh_->tet(p);
    for (VertexId& v : t) v = parting_.Origin(v);
    split.tets.push_back(t);
  }
  split.crack_faces.assign(open.crack.begin(), open.crack.end());
  return split;
}

bool CrackCutter::PiecesStand(TetId unit, const std::array<FacePoints, 4>& points,
                              const BladeIn& blade) {
  const auto it = open_.find(unit);
  if (it == open_.end() || it->second.opened_in_face || it->second.points != points) {
    return false;
  }
  const OpenTet& open = it->second;
  // Pieces with crack faces opened inside stand only as the cone a split made anew would be
  // again (the blade may have left that cone's reasons with its points unchanged: its tip come
  // out, or gone from the face it came in by).
  if (!open.openings.empty() && !(open.cone && SplitsAsTheBladesCone(points, open.traces, blade))) {
    return false;
  }
  // The apex first, then the points opening faces through it: the pieces' volumes are checked
  // where they now are. (If they fail, the split made anew uses them again or leaves them to go
  // with the unused temporary points.)
  if (open.cone) TemporaryVertex(ApexPlace(unit), open.corners, blade.apex);
  for (const FaceKey& key : open.openings) {
    TemporaryVertex(OpeningPlace(unit, key), open.corners, MiddleOf(open.corners, key));
  }
  const double floor = 0.5 * open.smallest_volume;
  if (std::all_of(open.pieces.begin(), open.pieces.end(),
                  [&](TetId p) { return mesh::RestVolume(*mesh_, p) > floor; })) {
    return true;
  }
  temporary_used_.erase(ApexPlace(unit));
  for (const FaceKey& key : open.openings) temporary_used_.erase(OpeningPlace(unit, key));
  return false;
}

Eigen::Vector4d CrackCutter::MiddleOf(const mesh::TetVertices& corners, const FaceKey& key) const {
  const auto rest = [&](VertexId v) -> const Eigen::Vector3d& { return mesh_->rest_position(v); };
  const Eigen::Vector3d middle = (rest(key[0]) + rest(key[1]) + rest(key[2])) / 3;
  return geometry::BarycentricWeights(rest(corners[0]), rest(corners[1]), rest(corners[2]),
                                      rest(corners[3]), middle);
}

namespace {

// The barycentric weights of `x`, a point in the triangle's plane, on its corners.
Eigen::Vector3d TriangleWeights(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                const Eigen::Vector3d& c, const Eigen::Vector3d& x) {
  const Eigen::Vector3d u = b - a, v = c - a, r = x - a;
  const double uu = u.dot(u), uv = u.dot(v), vv = v.dot(v), ru = r.dot(u), rv = r.dot(v);
  const double det = uu * vv - uv * uv;
  const double s = (ru * vv - rv * uv) / det, t = (rv * uu - ru * uv) / det;
  return {1 - s - t, s, t};
}

}  // namespace

int CrackCutter::OpenAtItsMiddle(TetId unit, const TetCrack& crack, const FaceKey& key,
                                 CrackSplit* split) {
  const int sides = CrackFaceSides(*split, key);
  if (sides == 0) return 0;
  const auto rest = [&](VertexId v) -> const Eigen::Vector3d& { return mesh_->rest_position(v); };
  const Eigen::Vector3d middle = (rest(key[0]) + rest(key[1]) + rest(key[2])) / 3;
  VertexId point;
  if (sides == 2) {
    point = TemporaryVertex(OpeningPlace(unit, key), crack.corners, MiddleOf(crack.corners, key));
  } else {
    const auto in_face = [&](int k) {
      const std::vector<VertexId>& on = crack.face_vertices[k];
      return std::all_of(key.begin(), key.end(), [&](VertexId v) {
        return std::find(on.begin(), on.end(), v) != on.end();
      });
    };
    int k = 0;
    while (!in_face(k)) ++k;
    const FaceKey face = MakeFaceKey(crack.points[k].corners[0], crack.points[k].corners[1],
                                     crack.points[k].corners[2]);
    const Eigen::Vector3d w = TriangleWeights(rest(face[0]), rest(face[1]), rest(face[2]), middle);
    point = TemporaryVertex(FaceOpeningPlace(key), {face[0], face[1], face[2], face[0]},
                            {w[0], w[1], w[2], 0});
  }
  KERF_CHECK(OpenCrackFace(split, key, point));
  return sides;
}

std::vector<CrackCutter::ShutFace> CrackCutter::ShutCrackFaces(
    TetId unit, const absl::flat_hash_map<TetId, BladeIn>& blade) const {
  const OpenTet& open = open_.at(unit);
  std::vector<mesh::TetVertices> origins_of_pieces;  // by the pieces' order
  for (const TetId p : open.pieces) {
    mesh::TetVertices origins = mesh_->tet(p);
    for (VertexId& v : origins) v = parting_.Origin(v);
    origins_of_pieces.push_back(origins);
  }
  std::vector<ShutFace> shut;
  for (const FaceKey& key : open.crack) {
    std::vector<std::array<VertexId, 3>> sides;  // each piece's ids for the key's origins
    for (std::size_t i = 0; i < open.pieces.size(); ++i) {
      const mesh::TetVertices& ids = mesh_->tet(open.pieces[i]);
      std::array<VertexId, 3> side;
      int found = 0;
      for (int k = 0; k < 3; ++k) {
        for (int j = 0; j < 4; ++j) {
          if (origins_of_pieces[i][j] == key[k]) {
            side[k] = ids[j];
            ++found;
            break;
          }
        }
      }
      if (found == 3) sides.push_back(side);
    }
    if (sides.size() == 2 && sides[0] == sides[1]) shut.push_back({key, std::nullopt});
    if (sides.size() != 1) continue;
    // In a face of the unit: shut if a tet beside uses the same vertices.
    const auto [a, b, c] = sides[0];
    for (const TetId t : mesh_->TetsAroundFace(a, b, c)) {
      const TetId beside = UnitOf(t);
      if (beside == unit) continue;
      const auto other = open_.find(beside);
      if (blade.contains(beside) && other != open_.end() &&
          std::binary_search(other->second.crack.begin(), other->second.crack.end(), key)) {
        shut.push_back({key, beside});
      }
    }
  }
  return shut;
}

int CrackCutter::TableCase(const mesh::TetVertices& corners, const BladeIn& blade) const {
  std::vector<std::pair<VertexId, VertexId>> cut;
  for (const auto& [i, j] : mesh::kTetEdges) {
    if (edge_points_.contains(MakeEdgeKey(corners[i], corners[j]))) {
      cut.emplace_back(corners[i], corners[j]);
    }
  }
  // Table 1 counts the points for good on faces (where the tip's path went through) and the
  // blade's crossings of faces (its temporary points), on a face with a point for good or not.
  int faces = 0;
  for (const auto& f : mesh::kTetFaces) {
    faces += face_points_.contains(MakeFaceKey(corners[f[0]], corners[f[1]], corners[f[2]]));
  }
  const int temporary = static_cast<int>(blade.crossed.size());
  const bool share_corner =
      cut.size() == 2 && (cut[0].first == cut[1].first || cut[0].first == cut[1].second ||
                          cut[0].second == cut[1].first || cut[0].second == cut[1].second);
  return ProgressiveCase(static_cast<int>(cut.size()), faces, temporary, blade.tip_inside,
                         share_corner);
}

std::vector<TetId> CrackCutter::Replace(TetId unit, const std::vector<mesh::TetVertices>& pieces) {
  TetId source = SourceTet(unit);
  std::vector<TetId> old = {unit};
  if (const auto it = open_.find(unit); it != open_.end()) {
    source = it->second.source;
    old = it->second.pieces;
  }
  CountPieces(source, old.size(), pieces.size());
  ++edits_;
  for (const TetId t : old) {
    source_tet_.erase(t);
    owner_.erase(t);
    KERF_CHECK(mesh_->RemoveTet(t).ok());
  }
  std::vector<TetId> made;
  for (mesh::TetVertices piece : pieces) {
    const double volume =
        geometry::SignedVolume(mesh_->rest_position(piece[0]), mesh_->rest_position(piece[1]),
                               mesh_->rest_position(piece[2]), mesh_->rest_position(piece[3]));
    KERF_CHECK(volume != 0);
    if (volume < 0) std::swap(piece[2], piece[3]);
    const absl::StatusOr<TetId> added = mesh_->AddTet(piece);
    KERF_CHECK(added.ok());
    source_tet_[*added] = source;
    made.push_back(*added);
    fresh_.insert(*added);
  }
  return made;
}

void CrackCutter::CountPieces(TetId source, std::size_t removed, std::size_t added) {
  std::size_t& pieces = pieces_of_source_.try_emplace(source, 1).first->second;  // once whole
  KERF_CHECK(pieces >= removed);
  const std::size_t before = pieces;
  pieces = before - removed + added;
  const auto split = [](std::size_t n) { return n >= 2; };
  statistics_.cut_tets = statistics_.cut_tets + split(pieces) - split(before);
  statistics_.new_tets =
      statistics_.new_tets + (split(pieces) ? pieces : 0) - (split(before) ? before : 0);
}

void CrackCutter::RemoveCrack(const FaceKey& key) {
  const auto it = crack_.find(key);
  if (it == crack_.end() && kept_off_.contains(key)) return;  // taken off for both units
  KERF_CHECK(it != crack_.end());
  if (--it->second.marks == 0) EraseCrack(it);
}

void CrackCutter::EraseCrack(CrackFaces::iterator face) {
  const auto made = crack_faces_since_.find(face->second.since);
  if (--made->second == 0) crack_faces_since_.erase(made);
  crack_.erase(face);
}

void CrackCutter::Repart(const std::vector<VertexId>& origins) {
  const PartingChanges changes = parting_.Repart(
      mesh_, origins, [&](const FaceKey& key) { return crack_.contains(key); },
      [&](TetId t) { return fresh_.contains(t); });
  fresh_.clear();
  for (const auto& [old_tet, new_tet] : changes.replaced) {
    source_tet_[new_tet] = SourceTet(old_tet);  // a tet renamed by parting keeps its source
    source_tet_.erase(old_tet);
    if (const auto it = owner_.find(old_tet); it != owner_.end()) {
      const TetId unit = it->second;
      owner_.erase(it);
      owner_[new_tet] = unit;
      std::vector<TetId>& pieces = open_.at(unit).pieces;
      std::replace(pieces.begin(), pieces.end(), old_tet, new_tet);
    }
    if (const auto it = group_of_.find(old_tet); it != group_of_.end()) {
      const TetId group = it->second;
      group_of_.erase(it);
      group_of_[new_tet] = group;
      std::vector<TetId>& members = members_.at(group);
      std::replace(members.begin(), members.end(), old_tet, new_tet);
    }
  }
  if (!changes.made.empty() || !changes.removed.empty() || !changes.replaced.empty()) ++edits_;
  // A copy takes the place and state of the vertex its tets used; a copy of a point the cut
  // made then moves to where its own side has the point (the sides of an opened crack are apart:
  // a point on an edge lying in the crack, cut again, say), after the copies it is placed on:
  // points in the order they were made, each placed on vertices older than itself.
  // So does every point made by this split: parting may have renamed the corners it was placed on
  // (a corner's part taking the origin, or a copy).
  std::vector<VertexId> points;
  for (const VertexCopy& c : changes.made) {
    if (parting_.Origin(c.copy) != c.copy) ++statistics_.parted_vertices;
    made_vertices_.push_back({c.copy, {c.from, c.from, c.from, c.from}, {1, 0, 0, 0}});
    if (recipe_.contains(parting_.Origin(c.copy))) points.push_back(c.copy);
  }
  for (const VertexId p : new_points_) {
    if (mesh_->IsAlive(p)) points.push_back(p);
  }
  new_points_.clear();
  std::sort(points.begin(), points.end(), [&](VertexId a, VertexId b) {
    return Index(parting_.Origin(a)) < Index(parting_.Origin(b));
  });
  for (const VertexId v : points) {
    const PointRecipe& recipe = recipe_.at(parting_.Origin(v));
    PlaceOnItsSide(v, recipe.origins, recipe.weights);
  }
}

}  // namespace kerf::cut
