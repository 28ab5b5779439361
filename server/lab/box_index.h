// A uniform grid over items with boxes (triangles, tets), for the lab's measures: which items
// may lie within a distance of a point. Each item is listed in every cell its box covers, so a
// query reads the cells its own box covers; items should be no larger than a few cells.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "absl/container/flat_hash_map.h"

namespace kerf::lab {

class BoxIndex {
 public:
  // `cell_size` (the unit of the boxes) must be positive.
  explicit BoxIndex(double cell_size);

  // Lists item `id` in the cells its box [low, high] covers. O(cells covered).
  void Add(std::uint32_t id, const Eigen::Vector3d& low, const Eigen::Vector3d& high);

  // The ids of the items whose cells meet the box of radius `radius` around `p` (a superset of
  // the items whose box is that near), each once, in no order.
  std::vector<std::uint32_t> Near(const Eigen::Vector3d& p, double radius) const;
  // The same for the box [low, high].
  std::vector<std::uint32_t> InBox(const Eigen::Vector3d& low, const Eigen::Vector3d& high) const;

 private:
  using Cell = std::array<std::int64_t, 3>;
  struct CellHash {
    std::size_t operator()(const Cell& c) const { return absl::HashOf(c[0], c[1], c[2]); }
  };
  Cell CellOf(const Eigen::Vector3d& p) const;

  double cell_size_;
  absl::flat_hash_map<Cell, std::vector<std::uint32_t>, CellHash> cells_;
};

}  // namespace kerf::lab
