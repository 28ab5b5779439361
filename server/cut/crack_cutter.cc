#include "cut/crack_cutter.h"

#include <Eigen/Geometry>
#include <algorithm>

#include "absl/strings/str_cat.h"
#include "base/check.h"
#include "cut/opening_point.h"
#include "geometry/point_triangle_distance.h"
#include "geometry/tet_measures.h"

namespace kerf::cut {
namespace {

using mesh::Index;
using mesh::TetId;
using mesh::VertexId;

void SortUnique(std::vector<TetId>* v) {
  std::sort(v->begin(), v->end());
  v->erase(std::unique(v->begin(), v->end()), v->end());
}

}  // namespace

absl::StatusOr<CrackCutter> CrackCutter::Create(mesh::TetMesh* mesh, double cell_size,
                                                const BladeLimits& limits,
                                                const CrackCutterOptions& options) {
  if (!(options.snap_fraction >= 0 && options.snap_fraction < 0.5)) {
    return absl::InvalidArgumentError(
        absl::StrCat("the snap fraction must be in [0, 0.5), got ", options.snap_fraction));
  }
  if (!(options.min_temporary_height >= 0 && options.min_temporary_height < 1)) {
    return absl::InvalidArgumentError(
        absl::StrCat("the least temporary height must be a fraction in [0, 1), got ",
                     options.min_temporary_height));
  }
  absl::StatusOr<BladeCrossings> crossings = BladeCrossings::Create(mesh, cell_size);
  if (!crossings.ok()) return crossings.status();
  return CrackCutter(mesh, *std::move(crossings), limits, options);
}

TetId CrackCutter::SourceTet(TetId t) const {
  const auto it = source_tet_.find(t);
  return it == source_tet_.end() ? t : it->second;
}

std::vector<MadeVertex> CrackCutter::TakeMadeVertices() {
  std::vector<MadeVertex> made;
  for (const MadeVertex& m : made_vertices_) {
    if (mesh_->IsAlive(m.vertex)) made.push_back(m);
  }
  made_vertices_.clear();
  return made;
}

std::vector<mesh::TetVertices> CrackCutter::TetsHoldingBlade(const BladePose& pose) const {
  std::vector<mesh::TetVertices> holding;
  for (const TetId u : UnitsAt(pose)) {
    if (!crossings_.BladeMeets(CornersOf(u), pose)) continue;
    if (const auto it = open_.find(u); it != open_.end()) {
      for (const TetId p : it->second.pieces) holding.push_back(mesh_->tet(p));
    } else {
      holding.push_back(mesh_->tet(u));
    }
  }
  return holding;
}

double CrackCutter::StiffnessScale(TetId t) const {
  const auto owner = owner_.find(t);
  if (owner == owner_.end() || !mesh_->IsAlive(t)) return 1;
  const mesh::TetVertices& piece = mesh_->tet(t);
  const bool on_blade = std::any_of(piece.begin(), piece.end(), [&](VertexId v) {
    const VertexId origin = parting_.Origin(v);
    return std::any_of(temporary_.begin(), temporary_.end(),
                       [&](const auto& entry) { return entry.second == origin; });
  });
  if (!on_blade) return 1;
  const auto rest = [&](const mesh::TetVertices& c) {
    return geometry::SmallestHeight(mesh_->rest_position(c[0]), mesh_->rest_position(c[1]),
                                    mesh_->rest_position(c[2]), mesh_->rest_position(c[3]));
  };
  const double guard = min_temporary_height_ * rest(open_.at(owner->second).corners);
  const double height = rest(piece);
  return height < guard ? height / guard : 1;
}

TetId CrackCutter::UnitOf(TetId t) const {
  const auto it = owner_.find(t);
  return it == owner_.end() ? t : it->second;
}

mesh::TetVertices CrackCutter::CornersOf(TetId unit) const {
  if (const auto it = open_.find(unit); it != open_.end()) return it->second.corners;
  mesh::TetVertices corners = mesh_->tet(unit);
  for (VertexId& v : corners) v = parting_.Origin(v);
  return corners;
}

mesh::TetVertices CrackCutter::PlacedCorners(TetId unit) const {
  const auto open = open_.find(unit);
  if (open == open_.end()) return mesh_->tet(unit);
  auto& placed = open->second.placed;
  if (!placed || placed->first != edits_) {
    std::array<bool, 4> found{};
    placed.emplace(edits_, NamedIn(open->second.pieces, open->second.corners, &found));
  }
  return placed->second;
}

std::array<VertexId, 4> CrackCutter::NamedIn(std::span<const TetId> tets,
                                             std::array<VertexId, 4> origins,
                                             std::array<bool, 4>* found) const {
  for (const TetId t : tets) {
    for (const VertexId v : mesh_->tet(t)) {
      const VertexId origin = parting_.Origin(v);
      for (int k = 0; k < 4; ++k) {
        if (!(*found)[k] && origins[k] == origin) origins[k] = v, (*found)[k] = true;
      }
    }
    if ((*found)[0] && (*found)[1] && (*found)[2] && (*found)[3]) break;
  }
  return origins;
}

std::vector<mesh::TetVertices> CrackCutter::PlacedCornersOfAll(
    const std::vector<TetId>& units) const {
  std::vector<mesh::TetVertices> placed;
  for (const TetId u : units) placed.push_back(PlacedCorners(u));
  return placed;
}

Crossings CrackCutter::ByOrigins(Crossings found) const {
  for (EdgeCrossing& c : found.edges) {
    c.low = parting_.Origin(c.low);
    c.high = parting_.Origin(c.high);
    if (Index(c.high) < Index(c.low)) std::swap(c.low, c.high), c.fraction = 1 - c.fraction;
  }
  for (FaceCrossing& c : found.faces) {
    std::array<std::pair<VertexId, double>, 3> corners;
    for (int k = 0; k < 3; ++k) corners[k] = {parting_.Origin(c.face[k]), c.barycentric[k]};
    std::sort(corners.begin(), corners.end(),
              [](const auto& a, const auto& b) { return Index(a.first) < Index(b.first); });
    for (int k = 0; k < 3; ++k) c.face[k] = corners[k].first, c.barycentric[k] = corners[k].second;
  }
  return found;
}

std::vector<TetId> CrackCutter::UnitsOf(std::vector<TetId> tets) const {
  for (TetId& t : tets) t = UnitOf(t);
  SortUnique(&tets);
  return tets;
}

std::vector<TetId> CrackCutter::UnitsAt(const BladePose& pose) const {
  return UnitsOf(crossings_.Near(pose.tip.cwiseMin(pose.heel), pose.tip.cwiseMax(pose.heel)));
}

std::vector<TetId> CrackCutter::UnitsNearStep(const BladePose& from, const BladePose& to) const {
  return UnitsOf(crossings_.NearSweep(from, to, kStepMargin * crossings_.cell_size()));
}

std::vector<TetId> CrackCutter::UnitsAround(const std::vector<VertexId>& origins) const {
  std::vector<TetId> units;
  for (const TetId t : parting_.TetsAround(*mesh_, origins.front())) {
    const TetId unit = UnitOf(t);
    const mesh::TetVertices corners = CornersOf(unit);
    if (std::all_of(origins.begin(), origins.end(),
                    [&](VertexId o) { return mesh::TetHasVertex(corners, o); })) {
      units.push_back(unit);
    }
  }
  SortUnique(&units);
  return units;
}

std::vector<mesh::TetVertices> CrackCutter::CornersOfAll(const std::vector<TetId>& units) const {
  std::vector<mesh::TetVertices> corners;
  for (const TetId u : units) corners.push_back(CornersOf(u));
  return corners;
}

absl::Status CrackCutter::ApplyPose(const BladePose& pose) {
  if (absl::Status valid = ValidatePose(pose, previous_ ? &*previous_ : nullptr, limits_);
      !valid.ok()) {
    return valid;
  }
  last_pose_ = {};
  ++poses_;
  swept_.Add(pose);
  if (previous_) {
    const BladePose& from = *previous_;
    step_ = {from, pose};
    const std::vector<TetId> near = UnitsNearStep(from, pose);
    const Crossings found = ByOrigins(crossings_.Find(
        from, pose, PlacedCornersOfAll(near),
        [&](VertexId a, VertexId b) {
          return edge_points_.contains(MakeEdgeKey(parting_.Origin(a), parting_.Origin(b)));
        },
        [&](const std::array<VertexId, 3>& f) {
          return face_points_.contains(parting_.OriginKey(f[0], f[1], f[2]));
        }));
    std::vector<TetId> touched;
    RecordCrossings(found, &touched);
    SnapVerticesNear(near, &touched);
    Join(touched);
    if (mode_ == CutMode::kDeferred) {
      SplitReadyGroups(&pose);
    } else {
      const absl::flat_hash_map<TetId, BladeIn> blade = BladeUnitsAt(pose);
      KeepEdgePointsLeft(blade, &touched);
      KeepFarthestFaceCrossings(&blade, &touched);
      // Split: the units with new points, those the blade is in, and those it was in.
      touched.insert(touched.end(), blade_units_.begin(), blade_units_.end());
      blade_units_.clear();
      for (const auto& [u, in] : blade) {
        touched.push_back(u);
        blade_units_.push_back(u);
      }
      SplitUnits(std::move(touched), blade);
      CloseUnitsTheBladeLeft();
    }
    step_.reset();
  }
  previous_ = pose;
  std::vector<VertexId> near_blade;
  const double around = 0.1 * (pose.heel - pose.tip).norm();
  const std::vector<TetId> near_tets = crossings_.NearSweep(pose, pose, around, around);
  near_blade.reserve(4 * near_tets.size());
  for (const TetId t : near_tets) {
    for (const VertexId v : mesh_->tet(t)) {
      near_blade.push_back(v);
      if (const VertexId origin = parting_.Origin(v); origin != v) near_blade.push_back(origin);
    }
  }
  last_pose_.open_tets = open_.size();
  for (const auto& [u, open] : open_) last_pose_.temporary_tets += open.pieces.size();
  return crossings_.Remember(near_blade);
}

void CrackCutter::Finish() {
  std::vector<TetId> touched;
  if (previous_) {
    // The crack reaches where the blade was: its crossings of faces are where the crack ends,
    // and a tet it is in splits for good from its point there (withdrawn_at_).
    const BladePose& at = *previous_;
    for (const auto& [u, in] : BladeUnitsAt(at)) withdrawn_at_[u] = {in.apex, in.tip_inside};
    step_ = {at, at};  // what snaps now snaps within reach of the blade where it was
    Crossings crossed;
    crossed.faces = crossings_.FacesCrossedBy(
        at, PlacedCornersOfAll(UnitsAt(at)), [&](const std::array<VertexId, 3>& f) {
          return face_points_.contains(parting_.OriginKey(f[0], f[1], f[2]));
        });
    RecordCrossings(ByOrigins(std::move(crossed)), &touched, FaceCrossingsFrom::kWithdrawal);
  }
  Join(touched);
  if (mode_ == CutMode::kProgressive) {
    KeepEdgePointsLeft({}, &touched);
    KeepFarthestFaceCrossings(nullptr, &touched);
    touched.insert(touched.end(), blade_units_.begin(), blade_units_.end());
    blade_units_.clear();
    SplitUnits(std::move(touched), {});
  }
  step_.reset();
  SplitReadyGroups(nullptr);  // progressive: every group closes
  withdrawn_at_.clear();
  OpenShutCrackFaces();
  previous_.reset();
}

void CrackCutter::OpenShutCrackFaces() {
  std::vector<FaceKey> shut;
  for (const auto& [key, marks] : crack_) {
    if (!face_points_.contains(key) &&
        std::none_of(key.begin(), key.end(), [&](VertexId v) { return parting_.HasCopies(v); })) {
      shut.push_back(key);
    }
  }
  std::sort(shut.begin(), shut.end());  // the same points whatever the map's order
  std::vector<TetId> touched;
  for (const FaceKey& key : shut) {
    const std::vector<TetId> units = UnitsAround({key[0], key[1], key[2]});
    if (units.size() < 2) continue;  // on the tissue's boundary
    face_points_[key] = {OpeningPointAt(key, units)};
    // Its corners are on the crack (points the cut made among them too), so the face rule puts
    // the three triangles through the new point on it.
    on_crack_.insert(key.begin(), key.end());
    touched.insert(touched.end(), units.begin(), units.end());
  }
  if (touched.empty()) return;
  Join(touched);
  if (mode_ == CutMode::kProgressive) SplitUnits(touched, {});
  SplitReadyGroups(nullptr);
}

Eigen::Vector3d CrackCutter::OpeningPointAt(const FaceKey& key,
                                            const std::vector<TetId>& units) const {
  const std::array<Eigen::Vector3d, 3> face = {
      mesh_->rest_position(key[0]), mesh_->rest_position(key[1]), mesh_->rest_position(key[2])};
  std::vector<Eigen::Vector3d> apexes;
  for (const TetId u : units) {
    for (const VertexId v : CornersOf(u)) {
      if (std::find(key.begin(), key.end(), v) == key.end())
        apexes.push_back(mesh_->rest_position(v));
    }
  }
  return OpeningPointWeights(face, apexes);
}

// Deferred groups.

void CrackCutter::Join(const std::vector<TetId>& units) {
  for (const TetId t : units) {
    if (group_of_.try_emplace(t, t).second) {
      met_at_[t] = poses_;
      members_[t] = {t};
      group_since_[t] = poses_;
    }
  }
  for (std::size_t i = 1; i < units.size(); ++i) {
    TetId a = group_of_.at(units[0]), b = group_of_.at(units[i]);
    if (a == b) continue;
    if (members_.at(a).size() < members_.at(b).size()) std::swap(a, b);
    std::vector<TetId> moved = std::move(members_.at(b));
    members_.erase(b);
    group_since_[a] = std::min(group_since_.at(a), group_since_.at(b));
    group_since_.erase(b);
    for (const TetId t : moved) group_of_[t] = a;
    std::vector<TetId>& into = members_.at(a);
    into.insert(into.end(), moved.begin(), moved.end());
  }
}

void CrackCutter::SplitReadyGroups(const BladePose* pose) {
  std::vector<TetId> ready;
  for (const auto& [root, members] : members_) {
    // Newest members first: the blade is where the cut grew last.
    const bool blade_in =
        pose != nullptr && std::any_of(members.rbegin(), members.rend(), [&](TetId t) {
          return crossings_.BladeMeets(CornersOf(t), *pose);
        });
    if (!blade_in) ready.push_back(root);
  }
  std::sort(ready.begin(), ready.end());  // the same order whatever the map's
  for (const TetId root : ready) {
    const std::vector<TetId> group = TakeGroup(root);
    if (mode_ == CutMode::kDeferred) SplitUnits(group, {});
    CloseUnits(group);
  }
}

std::vector<TetId> CrackCutter::TakeGroup(TetId root) {
  std::vector<TetId> group = std::move(members_.at(root));
  members_.erase(root);
  group_since_.erase(root);
  for (const TetId t : group) group_of_.erase(t);
  return group;
}

void CrackCutter::CloseUnitsTheBladeLeft() {
  absl::flat_hash_set<TetId> with_blade;
  for (const TetId u : blade_units_) {
    if (const auto it = group_of_.find(u); it != group_of_.end()) with_blade.insert(it->second);
  }
  std::vector<TetId> closing;
  for (const auto& [root, members] : members_) {
    if (!with_blade.contains(root)) closing.push_back(root);
  }
  for (const TetId root : closing) {
    const std::vector<TetId> group = TakeGroup(root);
    CloseUnits(group);
  }
  // Units the blade passed with no point of their own.
  std::vector<TetId> passed;
  for (const auto& [u, open] : open_) {
    if (!group_of_.contains(u) &&
        std::find(blade_units_.begin(), blade_units_.end(), u) == blade_units_.end()) {
      passed.push_back(u);
    }
  }
  CloseUnits(passed);
}

void CrackCutter::CloseUnits(const std::vector<TetId>& units) {
  std::vector<TetId> pieces;
  for (const TetId u : units) {
    met_at_.erase(u);
    const auto it = open_.find(u);
    if (it == open_.end()) continue;
    for (const TetId p : it->second.pieces) owner_.erase(p);
    pieces.insert(pieces.end(), it->second.pieces.begin(), it->second.pieces.end());
    // Its apex and opening points, if it has them, are ordinary vertices now.
    temporary_.erase(ApexPlace(u));
    for (const FaceKey& key : it->second.openings) temporary_.erase(OpeningPlace(u, key));
    open_.erase(it);
  }
  HoldChips(std::move(pieces));
}

}  // namespace kerf::cut
