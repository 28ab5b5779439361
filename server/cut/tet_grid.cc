#include "cut/tet_grid.h"

#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "mesh/mesh_quality.h"

namespace kerf::cut {

using mesh::Index;
using mesh::TetId;
using mesh::VertexId;

absl::StatusOr<TetGrid> TetGrid::Build(const mesh::TetMesh& mesh, double cell_size, double margin) {
  if (!(cell_size > 0) || !std::isfinite(cell_size)) {
    return absl::InvalidArgumentError(
        absl::StrCat("cell_size must be positive and finite (m), got ", cell_size));
  }
  if (!(margin >= 0) || !std::isfinite(margin)) {
    return absl::InvalidArgumentError(
        absl::StrCat("margin must be non-negative and finite (m), got ", margin));
  }
  TetGrid grid(mesh, cell_size, margin);
  const auto current = mesh.current_positions();
  grid.registered_at_.assign(current.begin(), current.end());
  for (const TetId t : mesh.tets()) grid.Register(t);
  grid.synced_ = mesh.change_log().Mark();
  return grid;
}

TetGrid::Cell TetGrid::CellOf(const Eigen::Vector3d& p) const {
  Cell c;
  for (int axis = 0; axis < 3; ++axis) {
    c[axis] = static_cast<std::int32_t>(std::floor(p[axis] / cell_size_));
  }
  return c;
}

void TetGrid::Register(TetId t) {
  const mesh::Bounds box = mesh::MeasureTetBounds(*mesh_, t, /*current=*/true);
  if (ranges_.size() <= Index(t)) ranges_.resize(Index(t) + 1);
  CellRange& range = ranges_[Index(t)];
  // A corner is within margin of its reference now and will stay within margin of it until
  // the reference moves, so twice the margin covers it until then.
  range = {CellOf(box.low.array() - 2 * margin_), CellOf(box.high.array() + 2 * margin_), true};
  for (std::int32_t x = range.low[0]; x <= range.high[0]; ++x) {
    for (std::int32_t y = range.low[1]; y <= range.high[1]; ++y) {
      for (std::int32_t z = range.low[2]; z <= range.high[2]; ++z) cells_[{x, y, z}].push_back(t);
    }
  }
  ++registered_count_;
}

void TetGrid::Unregister(TetId t) {
  CellRange& range = ranges_[Index(t)];
  if (!range.registered) return;
  for (std::int32_t x = range.low[0]; x <= range.high[0]; ++x) {
    for (std::int32_t y = range.low[1]; y <= range.high[1]; ++y) {
      for (std::int32_t z = range.low[2]; z <= range.high[2]; ++z) {
        const auto cell = cells_.find(Cell{x, y, z});
        std::vector<TetId>& list = cell->second;
        const auto it = std::find(list.begin(), list.end(), t);
        *it = list.back();
        list.pop_back();
        if (list.empty()) cells_.erase(cell);
      }
    }
  }
  range.registered = false;
  --registered_count_;
}

absl::Status TetGrid::RefreshTopology() {
  absl::StatusOr<mesh::MeshChanges> changes = mesh_->change_log().ChangesSince(synced_);
  if (!changes.ok()) return changes.status();
  last_refresh_count_ = 0;
  for (const TetId t : changes->removed_tets) Unregister(t);
  const auto current = mesh_->current_positions();
  for (std::size_t i = registered_at_.size(); i < current.size(); ++i) {
    registered_at_.push_back(current[i]);  // new vertices start at their current position
  }
  for (const TetId t : changes->added_tets) {
    Register(t);
    ++last_refresh_count_;
  }
  synced_ = mesh_->change_log().Mark();
  return absl::OkStatus();
}

absl::Status TetGrid::Refresh() {
  if (absl::Status s = RefreshTopology(); !s.ok()) return s;
  // A vertex that moved farther than the margin from its reference gets a new reference, and
  // every tet around it is registered again.
  const auto current = mesh_->current_positions();
  std::vector<TetId> stale;
  for (const VertexId v : mesh_->vertices()) {
    if ((current[Index(v)] - registered_at_[Index(v)]).norm() <= margin_) continue;
    registered_at_[Index(v)] = current[Index(v)];
    for (const TetId t : mesh_->TetsAround(v)) stale.push_back(t);
  }
  std::sort(stale.begin(), stale.end());
  stale.erase(std::unique(stale.begin(), stale.end()), stale.end());
  for (const TetId t : stale) {
    Unregister(t);
    Register(t);
    ++last_refresh_count_;
  }
  return absl::OkStatus();
}

std::vector<TetId> TetGrid::Candidates(const Eigen::Vector3d& low,
                                       const Eigen::Vector3d& high) const {
  const Cell lo = CellOf(low), hi = CellOf(high);
  seen_.resize(ranges_.size(), 0);
  ++query_;
  std::vector<TetId> result;
  for (std::int32_t x = lo[0]; x <= hi[0]; ++x) {
    for (std::int32_t y = lo[1]; y <= hi[1]; ++y) {
      for (std::int32_t z = lo[2]; z <= hi[2]; ++z) {
        const auto cell = cells_.find(Cell{x, y, z});
        if (cell == cells_.end()) continue;
        for (const TetId t : cell->second) {
          if (seen_[Index(t)] == query_) continue;
          seen_[Index(t)] = query_;
          result.push_back(t);
        }
      }
    }
  }
  return result;
}

}  // namespace kerf::cut
