// CrackCutter: chips the crack walls in without the blade having cut around them (see
// crack_cutter.h, HoldChips).
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <optional>
#include <utility>
#include <vector>

#include "cut/crack_cutter.h"

namespace kerf::cut {
namespace {

using mesh::TetId;
using mesh::VertexId;

// The largest chip looked for, in tets: the chips the crack walls in are a few pieces of one or
// two of the tissue's tets (3-22 tets where traced); a piece of tissue the blade cuts off has
// corners off the crack anyway.
constexpr std::size_t kMostChipTets = 48;
// Holding a chip can join it to another (two chips side by side); each round holds those.
constexpr int kChipRounds = 4;

}  // namespace

bool CrackCutter::OnTheCrack(VertexId v) const {
  const VertexId origin = parting_.Origin(v);
  return on_crack_.contains(origin) || recipe_.contains(origin);
}

bool CrackCutter::AllCornersOnTheCrack(const mesh::TetVertices& corners) const {
  return std::all_of(corners.begin(), corners.end(), [&](VertexId v) { return OnTheCrack(v); });
}

std::optional<std::vector<TetId>> CrackCutter::ChipAt(TetId seed,
                                                      absl::flat_hash_set<TetId>* seen) const {
  std::vector<TetId> chip = {seed};
  absl::flat_hash_set<TetId> in_chip = {seed};
  seen->insert(seed);
  for (std::size_t next = 0; next < chip.size(); ++next) {
    // Pieces of a unit the blade is in are looked at once it has left.
    if (const auto owner = owner_.find(chip[next]);
        owner != owner_.end() &&
        std::find(blade_units_.begin(), blade_units_.end(), owner->second) != blade_units_.end()) {
      return std::nullopt;
    }
    const mesh::TetVertices& c = mesh_->tet(chip[next]);
    if (!AllCornersOnTheCrack(c)) {
      return std::nullopt;
    }
    for (const auto& f : mesh::kTetFaces) {
      for (const TetId beside : mesh_->TetsAroundFace(c[f[0]], c[f[1]], c[f[2]])) {
        if (in_chip.contains(beside)) continue;
        // Joined to tets looked at before: to no chip (a chip's tets are all found from any).
        if (!seen->insert(beside).second) return std::nullopt;
        in_chip.insert(beside);
        chip.push_back(beside);
        if (chip.size() > kMostChipTets) return std::nullopt;
      }
    }
  }
  if (chip.size() == mesh_->tet_count()) return std::nullopt;  // the whole tissue
  return chip;
}

std::optional<FaceKey> CrackCutter::FaceToHoldChipBy(const std::vector<TetId>& chip) const {
  // The largest of its crack faces with a tet on the other side, rather one beside a tet with a
  // corner off the crack (that side is no chip) than one beside another chip.
  const absl::flat_hash_set<TetId> chip_tets(chip.begin(), chip.end());
  std::optional<FaceKey> best;
  std::pair<int, double> best_rank = {0, 0};
  for (const TetId t : chip) {
    const mesh::TetVertices& c = mesh_->tet(t);
    for (const auto& f : mesh::kTetFaces) {
      const FaceKey key = parting_.OriginKey(c[f[0]], c[f[1]], c[f[2]]);
      if (!crack_.contains(key)) continue;
      int beside = 0;  // 2: a tet with a corner off the crack, 1: another chip, 0: none
      for (const TetId other : parting_.TetsAround(*mesh_, key[0])) {
        const mesh::TetVertices& o = mesh_->tet(other);
        const auto in = [&](VertexId v) {
          return std::any_of(o.begin(), o.end(),
                             [&](VertexId w) { return parting_.Origin(w) == v; });
        };
        if (chip_tets.contains(other) || !in(key[1]) || !in(key[2])) continue;
        beside = std::max(beside, AllCornersOnTheCrack(o) ? 1 : 2);
      }
      if (beside == 0) continue;
      const Eigen::Vector3d a = mesh_->rest_position(key[0]);
      const std::pair<int, double> rank = {
          beside,
          (mesh_->rest_position(key[1]) - a).cross(mesh_->rest_position(key[2]) - a).norm()};
      if (rank > best_rank) best = key, best_rank = rank;
    }
  }
  return best;
}

std::vector<FaceKey> CrackCutter::UnitFacesWith(const FaceKey& triangle) const {
  const auto has = [&](const std::array<VertexId, 3>& points, VertexId v) {
    return std::find(points.begin(), points.end(), v) != points.end();
  };
  std::vector<FaceKey> faces;
  for (const TetId t : parting_.TetsAround(*mesh_, triangle[0])) {
    const auto owner = owner_.find(t);
    if (owner == owner_.end()) {
      faces.push_back(triangle);  // a unit of its own: its face is the triangle
      continue;
    }
    for (const FacePoints& p : open_.at(owner->second).points) {
      std::array<VertexId, 3> on = p.corners;
      const auto on_face = [&](VertexId v) {
        return has(on, v) || v == p.inside ||
               std::any_of(p.on_edge.begin(), p.on_edge.end(),
                           [&](const std::optional<VertexId>& e) { return e == v; });
      };
      if (std::all_of(triangle.begin(), triangle.end(), on_face)) {
        faces.push_back(MakeFaceKey(on[0], on[1], on[2]));
      }
    }
  }
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  return faces;
}

void CrackCutter::HoldChips(std::vector<TetId> seeds) {
  for (int round = 0; round < kChipRounds && !seeds.empty(); ++round) {
    // A chip's tets have every corner on the crack: others are no seeds.
    std::erase_if(seeds, [&](TetId t) {
      if (!mesh_->IsAlive(t)) return true;
      const mesh::TetVertices& c = mesh_->tet(t);
      return !AllCornersOnTheCrack(c);
    });
    std::sort(seeds.begin(), seeds.end());  // the same holds whatever the callers' order
    absl::flat_hash_set<TetId> seen;
    std::vector<VertexId> held;
    for (const TetId s : seeds) {
      if (seen.contains(s)) continue;
      const std::optional<std::vector<TetId>> chip = ChipAt(s, &seen);
      if (!chip) continue;
      const std::optional<FaceKey> key = FaceToHoldChipBy(*chip);
      if (!key) continue;
      kept_off_.insert(*key);
      // The face rule of every unit with the triangle in a face keeps it off (a unit split
      // anew puts it on the crack otherwise).
      for (const FaceKey& face : UnitFacesWith(*key)) kept_off_in_face_[face].push_back(*key);
      EraseCrack(crack_.find(*key));
      held.insert(held.end(), key->begin(), key->end());
    }
    if (held.empty()) return;
    Repart(held);
    seeds.clear();
    for (const VertexId v : held) {
      const std::vector<TetId> around = parting_.TetsAround(*mesh_, v);
      seeds.insert(seeds.end(), around.begin(), around.end());
    }
  }
}

}  // namespace kerf::cut
