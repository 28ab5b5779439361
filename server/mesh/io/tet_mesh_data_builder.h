// Collects points and tets by their ids in a file and resolves tet corners to point indices
// at the end, so a format may list tets before the points they name. Shared by the readers.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/status/statusor.h"
#include "mesh/io/tet_mesh_data.h"
#include "mesh/io/text_scanner.h"

namespace kerf::mesh::internal {

class TetMeshDataBuilder {
 public:
  // Error located at `offset` in the scanner's text if the id was already used.
  absl::Status AddPoint(std::int64_t id, const Eigen::Vector3d& position, const TextScanner& errors,
                        std::size_t offset);
  // Corner ids are checked in Finish; `offset` locates the tet in the scanner's text.
  void AddTet(const std::array<std::int64_t, 4>& corner_ids, std::size_t offset);
  std::size_t tet_count() const { return tets_.size(); }

  // Error (located by `tet_scanner`, the text the tets came from) for a corner naming no
  // point.
  absl::StatusOr<TetMeshData> Finish(const TextScanner& tet_scanner) &&;

 private:
  struct PendingTet {
    std::array<std::int64_t, 4> corner_ids;
    std::size_t offset;
  };
  TetMeshData data_;
  absl::flat_hash_map<std::int64_t, std::uint32_t> index_of_id_;
  std::vector<PendingTet> tets_;
};

// Three finite coordinates x, y, z.
absl::StatusOr<Eigen::Vector3d> ReadPoint(TextScanner& s);

// A count read from a file, made safe to reserve: never more than the text could hold.
std::size_t ReservableCount(std::int64_t declared, std::size_t text_size);

}  // namespace kerf::mesh::internal
