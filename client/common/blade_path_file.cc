#include "common/blade_path_file.h"

#include <fstream>
#include <sstream>

#include "absl/strings/str_cat.h"
#include "google/protobuf/util/json_util.h"

namespace kerf::client {

absl::StatusOr<kerf::v1::BladePath> ReadBladePath(const std::string& file) {
  std::ifstream in(file);
  if (!in) return absl::NotFoundError(absl::StrCat("cannot read blade path '", file, "'"));
  std::stringstream text;
  text << in.rdbuf();
  kerf::v1::BladePath path;
  if (auto s = google::protobuf::util::JsonStringToMessage(text.str(), &path); !s.ok()) {
    return absl::InvalidArgumentError(absl::StrCat(file, ": ", s.ToString()));
  }
  if (path.poses().empty()) return absl::InvalidArgumentError(absl::StrCat(file, ": no poses"));
  for (int i = 0; i < path.poses_size(); ++i) {
    if (path.poses(i).tip_size() != 3 || path.poses(i).heel_size() != 3) {
      return absl::InvalidArgumentError(
          absl::StrCat(file, ": pose ", i, ": tip and heel must be [x, y, z]"));
    }
  }
  return path;
}

}  // namespace kerf::client
