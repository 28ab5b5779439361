#include "cut/tet_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "absl/strings/str_cat.h"
#include "base/check.h"
#include "mesh/mesh_quality.h"

namespace kerf::cut {
namespace {

using mesh::Index;
using mesh::TetId;
using mesh::VertexId;

// At most this many cells per tet (and at least kMinCells in all), so that a mesh with a few
// far-flung vertices does not make a huge grid.
constexpr double kMaxCellsPerTet = 1;
constexpr double kMinCells = 4096;

// `value` as a float no larger (or, with `up`, no smaller) than it.
float RoundOutwards(double value, bool up) {
  const float rounded = static_cast<float>(value);
  if (up ? rounded >= value : rounded <= value) return rounded;
  return std::nextafter(rounded, up ? std::numeric_limits<float>::infinity()
                                    : -std::numeric_limits<float>::infinity());
}

}  // namespace

absl::StatusOr<TetGrid> TetGrid::Build(const mesh::TetMesh& mesh, double cell_size, double margin) {
  if (!(cell_size > 0) || !std::isfinite(cell_size)) {
    return absl::InvalidArgumentError(
        absl::StrCat("cell_size must be positive and finite (m), got ", cell_size));
  }
  if (!(margin >= 0) || !std::isfinite(margin)) {
    return absl::InvalidArgumentError(
        absl::StrCat("margin must be non-negative and finite (m), got ", margin));
  }
  TetGrid grid(mesh, margin);
  const mesh::Bounds bounds = mesh::MeasureBounds(mesh, /*current=*/true);
  const Eigen::Vector3d extent = mesh.vertex_count() == 0
                                     ? Eigen::Vector3d::Zero()
                                     : Eigen::Vector3d(bounds.high - bounds.low);
  const double budget =
      std::max(kMinCells, kMaxCellsPerTet * static_cast<double>(mesh.tet_count()));
  auto cells_needed = [&](double size) {
    double cells = 1;
    for (int axis = 0; axis < 3; ++axis) cells *= std::floor(extent[axis] / size) + 3;
    return cells;
  };
  while (cells_needed(cell_size) > budget) cell_size *= 1.25;
  grid.cell_size_ = cell_size;
  grid.origin_ =
      (mesh.vertex_count() == 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(bounds.low)).array() -
      cell_size;
  for (int axis = 0; axis < 3; ++axis) {
    grid.dims_[axis] = static_cast<std::int32_t>(std::floor(extent[axis] / cell_size)) + 3;
  }
  grid.cells_.resize(static_cast<std::size_t>(grid.dims_[0]) * grid.dims_[1] * grid.dims_[2]);
  const auto current = mesh.current_positions();
  grid.registered_at_.assign(current.begin(), current.end());
  for (const TetId t : mesh.tets()) grid.Register(t);
  grid.synced_ = mesh.change_log().Mark();
  return grid;
}

std::array<std::int32_t, 3> TetGrid::CellOf(const Eigen::Vector3d& p) const {
  std::array<std::int32_t, 3> c;
  for (int axis = 0; axis < 3; ++axis) {
    const double cell = std::floor((p[axis] - origin_[axis]) / cell_size_);
    c[axis] =
        static_cast<std::int32_t>(std::clamp(cell, 0.0, static_cast<double>(dims_[axis] - 1)));
  }
  return c;
}

void TetGrid::Register(TetId t) {
  const mesh::Bounds box = mesh::MeasureTetBounds(*mesh_, t, /*current=*/true);
  // A corner is within margin of its reference now and will stay within margin of it until
  // the reference moves, so twice the margin covers it until then.
  const Eigen::Vector3d low = box.low.array() - 2 * margin_;
  const Eigen::Vector3d high = box.high.array() + 2 * margin_;
  Entry entry{t, {}, {}};
  for (int axis = 0; axis < 3; ++axis) {
    entry.low[axis] = RoundOutwards(low[axis], /*up=*/false);
    entry.high[axis] = RoundOutwards(high[axis], /*up=*/true);
  }
  max_half_extent_ = max_half_extent_.cwiseMax(0.5 * (entry.high - entry.low).cast<double>());
  const std::uint32_t cell = CellIndex(CellOf(0.5 * (low + high)));
  if (cell_of_.size() <= Index(t)) cell_of_.resize(Index(t) + 1, kUnregistered);
  cell_of_[Index(t)] = cell;
  cells_[cell].push_back(entry);
  ++registered_count_;
}

void TetGrid::Unregister(TetId t) {
  if (Index(t) >= cell_of_.size() || cell_of_[Index(t)] == kUnregistered) return;
  absl::InlinedVector<Entry, 6>& list = cells_[cell_of_[Index(t)]];
  const auto it =
      std::find_if(list.begin(), list.end(), [&](const Entry& e) { return e.tet == t; });
  KERF_CHECK(it != list.end());
  *it = list.back();
  list.pop_back();
  cell_of_[Index(t)] = kUnregistered;
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
  for (const VertexId v : changes->added_vertices) registered_at_[Index(v)] = current[Index(v)];
  for (const TetId t : changes->added_tets) {
    Register(t);
    ++last_refresh_count_;
  }
  synced_ = mesh_->change_log().Mark();
  // Temporary points of a cut move with the blade (TetMesh::MoveVertex) between physics steps.
  std::vector<TetId> stale;
  for (const VertexId v : changes->moved_vertices) {
    if (mesh_->IsAlive(v)) FarFromReference(v, &stale);
  }
  RegisterAgain(std::move(stale));
  return absl::OkStatus();
}

absl::Status TetGrid::Refresh() {
  if (absl::Status s = RefreshTopology(); !s.ok()) return s;
  std::vector<TetId> stale;
  for (const VertexId v : mesh_->vertices()) FarFromReference(v, &stale);
  RegisterAgain(std::move(stale));
  return absl::OkStatus();
}

void TetGrid::FarFromReference(VertexId v, std::vector<TetId>* stale) {
  const Eigen::Vector3d& now = mesh_->current_position(v);
  if ((now - registered_at_[Index(v)]).norm() <= margin_) return;
  registered_at_[Index(v)] = now;
  const std::span<const TetId> around = mesh_->TetsAround(v);
  stale->insert(stale->end(), around.begin(), around.end());
}

void TetGrid::RegisterAgain(std::vector<TetId> stale) {
  std::sort(stale.begin(), stale.end());
  stale.erase(std::unique(stale.begin(), stale.end()), stale.end());
  for (const TetId t : stale) {
    Unregister(t);
    Register(t);
    ++last_refresh_count_;
  }
}

std::vector<TetId> TetGrid::Candidates(const Eigen::Vector3d& low,
                                       const Eigen::Vector3d& high) const {
  return Candidates(low, high, [](const Eigen::Vector3d&, const Eigen::Vector3d&) { return true; });
}

std::vector<TetId> TetGrid::Candidates(
    const Eigen::Vector3d& low, const Eigen::Vector3d& high,
    absl::FunctionRef<bool(const Eigen::Vector3d&, const Eigen::Vector3d&)> meets) const {
  // A registered box meeting the query has its centre within its half-extent of the query.
  const std::array<std::int32_t, 3> lo = CellOf(low - max_half_extent_);
  const std::array<std::int32_t, 3> hi = CellOf(high + max_half_extent_);
  const Eigen::Vector3f query_low = low.cast<float>(), query_high = high.cast<float>();
  std::vector<TetId> result;
  for (std::int32_t z = lo[2]; z <= hi[2]; ++z) {
    for (std::int32_t y = lo[1]; y <= hi[1]; ++y) {
      for (std::int32_t x = lo[0]; x <= hi[0]; ++x) {
        const absl::InlinedVector<Entry, 6>& cell = cells_[CellIndex({x, y, z})];
        if (cell.empty()) continue;
        // The boxes registered here have their centres in the cell (or beyond it, at the
        // grid's edge: those cells are not narrowed).
        const Eigen::Vector3d cell_low =
            origin_ + cell_size_ * Eigen::Vector3d(x, y, z) - max_half_extent_;
        const Eigen::Vector3d cell_high =
            cell_low + 2 * max_half_extent_ + Eigen::Vector3d::Constant(cell_size_);
        const bool at_edge = x == 0 || y == 0 || z == 0 || x == dims_[0] - 1 || y == dims_[1] - 1 ||
                             z == dims_[2] - 1;
        if (!at_edge && !meets(cell_low, cell_high)) continue;
        for (const Entry& e : cell) {
          // Float comparisons: a query corner rounded either way still meets a box rounded
          // outwards whenever the exact ones meet.
          if ((e.low.array() <= query_high.array()).all() &&
              (e.high.array() >= query_low.array()).all() &&
              meets(e.low.cast<double>(), e.high.cast<double>())) {
            result.push_back(e.tet);
          }
        }
      }
    }
  }
  return result;
}

}  // namespace kerf::cut
