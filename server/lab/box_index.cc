#include "lab/box_index.h"

#include <algorithm>
#include <cmath>

namespace kerf::lab {

BoxIndex::BoxIndex(double cell_size) : cell_size_(cell_size) {}

BoxIndex::Cell BoxIndex::CellOf(const Eigen::Vector3d& p) const {
  return {static_cast<std::int64_t>(std::floor(p.x() / cell_size_)),
          static_cast<std::int64_t>(std::floor(p.y() / cell_size_)),
          static_cast<std::int64_t>(std::floor(p.z() / cell_size_))};
}

void BoxIndex::Add(std::uint32_t id, const Eigen::Vector3d& low, const Eigen::Vector3d& high) {
  const Cell a = CellOf(low), b = CellOf(high);
  for (std::int64_t x = a[0]; x <= b[0]; ++x) {
    for (std::int64_t y = a[1]; y <= b[1]; ++y) {
      for (std::int64_t z = a[2]; z <= b[2]; ++z) cells_[Cell{x, y, z}].push_back(id);
    }
  }
}

std::vector<std::uint32_t> BoxIndex::Near(const Eigen::Vector3d& p, double radius) const {
  const Eigen::Vector3d r = Eigen::Vector3d::Constant(radius);
  return InBox(p - r, p + r);
}

std::vector<std::uint32_t> BoxIndex::InBox(const Eigen::Vector3d& low,
                                           const Eigen::Vector3d& high) const {
  const Cell a = CellOf(low), b = CellOf(high);
  std::vector<std::uint32_t> ids;
  for (std::int64_t x = a[0]; x <= b[0]; ++x) {
    for (std::int64_t y = a[1]; y <= b[1]; ++y) {
      for (std::int64_t z = a[2]; z <= b[2]; ++z) {
        const auto it = cells_.find(Cell{x, y, z});
        if (it != cells_.end()) ids.insert(ids.end(), it->second.begin(), it->second.end());
      }
    }
  }
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  return ids;
}

}  // namespace kerf::lab
