#include "mesh/io/tet_mesh_data_builder.h"

#include <algorithm>

#include "absl/strings/str_cat.h"

namespace kerf::mesh::internal {

absl::Status TetMeshDataBuilder::AddPoint(std::int64_t id, const Eigen::Vector3d& position,
                                          const TextScanner& errors, std::size_t offset) {
  const auto index = static_cast<std::uint32_t>(data_.points.size());
  if (!index_of_id_.emplace(id, index).second) {
    return errors.ErrorAt(offset, absl::StrCat("node ", id, " is defined twice"));
  }
  data_.points.push_back(position);
  data_.point_ids.push_back(id);
  return absl::OkStatus();
}

void TetMeshDataBuilder::AddTet(const std::array<std::int64_t, 4>& corner_ids, std::size_t offset) {
  tets_.push_back({corner_ids, offset});
}

absl::StatusOr<TetMeshData> TetMeshDataBuilder::Finish(const TextScanner& tet_scanner) && {
  data_.tets.reserve(tets_.size());
  for (const PendingTet& tet : tets_) {
    std::array<std::uint32_t, 4> corners;
    for (int c = 0; c < 4; ++c) {
      const auto it = index_of_id_.find(tet.corner_ids[c]);
      if (it == index_of_id_.end()) {
        return tet_scanner.ErrorAt(
            tet.offset,
            absl::StrCat("tetrahedron names node ", tet.corner_ids[c], ", which is not defined"));
      }
      corners[c] = it->second;
    }
    data_.tets.push_back(corners);
  }
  return std::move(data_);
}

absl::StatusOr<Eigen::Vector3d> ReadPoint(TextScanner& s) {
  Eigen::Vector3d p;
  for (int axis = 0; axis < 3; ++axis) {
    absl::StatusOr<double> x =
        s.NextFiniteDouble(absl::StrCat("coordinate ", absl::string_view("xyz").substr(axis, 1)));
    if (!x.ok()) return x.status();
    p[axis] = *x;
  }
  return p;
}

std::size_t ReservableCount(std::int64_t declared, std::size_t text_size) {
  if (declared <= 0) return 0;
  return std::min(static_cast<std::size_t>(declared), text_size / 2);
}

}  // namespace kerf::mesh::internal
