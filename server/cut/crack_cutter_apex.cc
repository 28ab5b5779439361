// CrackCutter: where a tet split for good as a cone has its apex (see crack_cutter.h).
#include <algorithm>

#include "cut/crack_cutter.h"
#include "cut/steps_in_tet.h"
#include "geometry/tet_measures.h"

namespace kerf::cut {

using mesh::TetId;
using mesh::VertexId;

std::optional<Eigen::Vector4d> CrackCutter::WithdrawnApex(TetId unit, const TetCrack& crack,
                                                          bool fits_without) const {
  const auto at = withdrawn_at_.find(unit);
  if (at == withdrawn_at_.end() || at->second.apex.minCoeff() <= 0 ||
      (fits_without && !at->second.tip_inside)) {
    return std::nullopt;
  }
  const auto rest = [&](VertexId v) -> Eigen::Vector3d { return mesh_->rest_position(v); };
  if (SmallestConeAngle(crack, rest, at->second.apex) < kSliverAngleDeg) return std::nullopt;
  return at->second.apex;
}

std::optional<std::size_t> CrackCutter::FirstPoseIn(TetId unit) const {
  const auto met = met_at_.find(unit);
  if (met == met_at_.end()) return std::nullopt;
  return met->second > 0 ? met->second - 1 : 0;
}

ApexNearPath CrackCutter::NearPath(TetId unit, const mesh::TetVertices& corners) const {
  const std::optional<std::size_t> met = FirstPoseIn(unit);
  if (!met) return nullptr;
  const std::size_t first = *met;
  const auto at = [&](int k) { return mesh_->current_position(corners[k]); };
  const double reach = kApexReach * geometry::MeanEdgeLength(at(0), at(1), at(2), at(3));
  return [this, corners, first, reach](const Eigen::Vector4d& w) {
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k) x += w[k] * mesh_->current_position(corners[k]);
    return SweptNear(x, first, poses_, reach);
  };
}

bool CrackCutter::TraceInTheTissueSurface(const TetCrack& crack) const {
  const std::vector<int> holding = FacesHoldingTheTrace(crack);
  return std::any_of(holding.begin(), holding.end(), [&](int k) {
    const auto& f = mesh::kTetFaces[k];
    return surface_.HasFace(
        MakeFaceKey(crack.corners[f[0]], crack.corners[f[1]], crack.corners[f[2]]));
  });
}

std::vector<Eigen::Vector4d> CrackCutter::StepsInUnit(TetId unit, bool* tip_inside) const {
  const std::optional<std::size_t> met = FirstPoseIn(unit);
  if (!met) return {};
  const std::size_t first = std::max(*met, swept_.first());
  if (first >= poses_) return {};
  const mesh::TetVertices placed = PlacedCorners(unit);
  std::array<Eigen::Vector3d, 4> now;
  for (int k = 0; k < 4; ++k) now[k] = mesh_->current_position(placed[k]);
  return StepSamplesIn(now, swept_, first, poses_, tip_inside);
}

std::optional<CrackCutter::CoveringApex> CrackCutter::ApexCoveringTheSteps(
    TetId unit, const TetCrack& crack, const CrackSplit* split,
    const std::optional<Eigen::Vector4d>& apex, bool apex_on_crack) const {
  bool tip_inside = false;
  const std::vector<Eigen::Vector4d> samples = StepsInUnit(unit, &tip_inside);
  if (samples.empty()) return std::nullopt;
  std::array<Eigen::Vector3d, 4> rest;
  for (int k = 0; k < 4; ++k) rest[k] = mesh_->rest_position(crack.corners[k]);
  // The crack faces of a split, a cone's apex (kNoVertex) at `at`.
  const auto faces_of = [&](const CrackSplit& s, const Eigen::Vector4d& at) {
    const Eigen::Vector3d apex_at = PointAtWeights(rest, at);
    std::vector<std::array<Eigen::Vector3d, 3>> faces;
    for (const auto& f : s.crack_faces) {
      std::array<Eigen::Vector3d, 3> t;
      for (int k = 0; k < 3; ++k) t[k] = f[k] == kNoVertex ? apex_at : mesh_->rest_position(f[k]);
      faces.push_back(t);
    }
    return faces;
  };
  const double reach = kStepCoverReach * LengthsOf(crack.corners).tissue_edge();
  const std::vector<std::array<Eigen::Vector3d, 3>> now_faces =
      split != nullptr ? faces_of(*split, Eigen::Vector4d::Zero())
                       : faces_of(SplitAsCone(crack, kNoVertex, apex_on_crack), *apex);
  // Where the split cuts nothing but in the tissue's surface and the tip went through the unit,
  // the blade grazed the surface: the cone's crack runs from the traces there to the apex.
  const bool on_crack = now_faces.empty() && tip_inside && TraceInTheTissueSurface(crack);
  const SamplesFrom now_from = Measure(samples, rest, now_faces, reach);
  if (now_from.beyond == 0) return std::nullopt;
  const auto rest_of = [&](VertexId v) -> Eigen::Vector3d { return mesh_->rest_position(v); };
  // Of the farthest sample and a few spread over them, the one whose cone leaves fewest beyond.
  const ApexNearPath near_path = NearPath(unit, crack.corners);
  std::vector<Eigen::Vector4d> candidates = {now_from.farthest};
  for (const Eigen::Vector4d& w : SpreadEvenly(samples, kCoveringApexCandidates)) {
    candidates.push_back(w);
  }
  std::optional<Eigen::Vector4d> best;
  int best_beyond = now_from.beyond;
  for (const Eigen::Vector4d& candidate : candidates) {
    const Eigen::Vector4d w = PulledInside(candidate);
    if (SmallestConeAngle(crack, rest_of, w) < kCoveringConeAngleDeg || !near_path(w)) continue;
    const SamplesFrom cone_from =
        Measure(samples, rest, faces_of(SplitAsCone(crack, kNoVertex, on_crack), w), reach);
    if (cone_from.beyond < best_beyond) best_beyond = cone_from.beyond, best = w;
    if (best_beyond == 0) break;  // none does better
  }
  if (!best) return std::nullopt;
  return CoveringApex{*best, on_crack};
}

}  // namespace kerf::cut
