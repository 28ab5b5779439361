#include "sim/blade_messages.h"

#include "absl/strings/str_cat.h"
#include "google/protobuf/util/json_util.h"

namespace kerf::sim {

absl::StatusOr<cut::BladePose> BladePoseFromProto(const kerf::v1::BladePose& pose) {
  if (pose.tip_size() != 3 || pose.heel_size() != 3) {
    return absl::InvalidArgumentError(absl::StrCat("tip and heel must be [x, y, z]; got ",
                                                   pose.tip_size(), " and ", pose.heel_size(),
                                                   " numbers"));
  }
  return cut::BladePose{pose.time(),
                        {pose.tip(0), pose.tip(1), pose.tip(2)},
                        {pose.heel(0), pose.heel(1), pose.heel(2)}};
}

kerf::v1::BladePose BladePoseToProto(const cut::BladePose& pose) {
  kerf::v1::BladePose message;
  message.set_time(pose.time);
  for (int k = 0; k < 3; ++k) message.add_tip(pose.tip[k]);
  for (int k = 0; k < 3; ++k) message.add_heel(pose.heel[k]);
  return message;
}

absl::StatusOr<std::vector<cut::BladePose>> ParseBladePathJson(absl::string_view json,
                                                               absl::string_view source,
                                                               const cut::BladeLimits& limits) {
  kerf::v1::BladePath path;
  const auto parsed = google::protobuf::util::JsonStringToMessage(std::string(json), &path);
  if (!parsed.ok()) {
    return absl::InvalidArgumentError(
        absl::StrCat(source, ": not a blade path (", parsed.message().as_string(), ")"));
  }
  if (path.poses().empty()) {
    return absl::InvalidArgumentError(absl::StrCat(source, ": the path has no poses"));
  }
  std::vector<cut::BladePose> poses;
  for (int i = 0; i < path.poses_size(); ++i) {
    absl::StatusOr<cut::BladePose> pose = BladePoseFromProto(path.poses(i));
    absl::Status valid =
        pose.ok() ? cut::ValidatePose(*pose, poses.empty() ? nullptr : &poses.back(), limits)
                  : pose.status();
    if (!valid.ok()) {
      return absl::InvalidArgumentError(absl::StrCat(source, ": pose ", i, ": ", valid.message()));
    }
    poses.push_back(*pose);
  }
  return poses;
}

}  // namespace kerf::sim
