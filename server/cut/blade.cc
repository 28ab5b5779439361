#include "cut/blade.h"

#include <cmath>

#include "absl/strings/str_cat.h"
#include "google/protobuf/util/json_util.h"

namespace kerf::cut {

absl::Status ValidatePose(const BladePose& pose, const BladePose* previous,
                          const BladeLimits& limits) {
  if (!std::isfinite(pose.time) || !pose.tip.allFinite() || !pose.heel.allFinite()) {
    return absl::InvalidArgumentError("the pose has a non-finite time, tip or heel");
  }
  const double length = (pose.tip - pose.heel).norm();
  if (!(length > 0) || length > limits.max_length) {
    return absl::InvalidArgumentError(absl::StrCat("the blade is ", length,
                                                   " m long; it must be longer than 0 and at "
                                                   "most ",
                                                   limits.max_length, " m"));
  }
  if (previous == nullptr) return absl::OkStatus();
  const double dt = pose.time - previous->time;
  if (!(dt > 0)) {
    return absl::InvalidArgumentError(absl::StrCat(
        "time ", pose.time, " s does not follow the previous pose's ", previous->time, " s"));
  }
  const double travel =
      std::max((pose.tip - previous->tip).norm(), (pose.heel - previous->heel).norm());
  if (travel > limits.max_step) {
    return absl::InvalidArgumentError(absl::StrCat(
        "the blade jumps ", travel, " m in one pose; at most ", limits.max_step, " m is accepted"));
  }
  if (travel / dt > limits.max_speed) {
    return absl::InvalidArgumentError(absl::StrCat("the blade moves at ", travel / dt,
                                                   " m/s; at most ", limits.max_speed,
                                                   " m/s is accepted"));
  }
  return absl::OkStatus();
}

BladePose InterpolatePose(const BladePose& a, const BladePose& b, double time) {
  const double s = (time - a.time) / (b.time - a.time);
  return {time, a.tip + s * (b.tip - a.tip), a.heel + s * (b.heel - a.heel)};
}

absl::StatusOr<BladePose> FromProto(const kerf::v1::BladePose& pose) {
  if (pose.tip_size() != 3 || pose.heel_size() != 3) {
    return absl::InvalidArgumentError(absl::StrCat("tip and heel must be [x, y, z]; got ",
                                                   pose.tip_size(), " and ", pose.heel_size(),
                                                   " numbers"));
  }
  return BladePose{pose.time(),
                   {pose.tip(0), pose.tip(1), pose.tip(2)},
                   {pose.heel(0), pose.heel(1), pose.heel(2)}};
}

kerf::v1::BladePose ToProto(const BladePose& pose) {
  kerf::v1::BladePose message;
  message.set_time(pose.time);
  for (int k = 0; k < 3; ++k) message.add_tip(pose.tip[k]);
  for (int k = 0; k < 3; ++k) message.add_heel(pose.heel[k]);
  return message;
}

absl::StatusOr<std::vector<BladePose>> ParseBladePathJson(absl::string_view json,
                                                          absl::string_view source,
                                                          const BladeLimits& limits) {
  kerf::v1::BladePath path;
  const auto parsed = google::protobuf::util::JsonStringToMessage(std::string(json), &path);
  if (!parsed.ok()) {
    return absl::InvalidArgumentError(
        absl::StrCat(source, ": not a blade path (", parsed.message().as_string(), ")"));
  }
  if (path.poses().empty()) {
    return absl::InvalidArgumentError(absl::StrCat(source, ": the path has no poses"));
  }
  std::vector<BladePose> poses;
  for (int i = 0; i < path.poses_size(); ++i) {
    absl::StatusOr<BladePose> pose = FromProto(path.poses(i));
    absl::Status valid = pose.ok()
                             ? ValidatePose(*pose, poses.empty() ? nullptr : &poses.back(), limits)
                             : pose.status();
    if (!valid.ok()) {
      return absl::InvalidArgumentError(absl::StrCat(source, ": pose ", i, ": ", valid.message()));
    }
    poses.push_back(*pose);
  }
  return poses;
}

}  // namespace kerf::cut
