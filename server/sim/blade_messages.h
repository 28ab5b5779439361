// Blade poses and paths as kerf exchanges them (kerf.v1.BladePose, kerf.v1.BladePath and its
// JSON form), to and from the cutter's cut::BladePose.
#pragma once

#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "cut/blade.h"
#include "kerf/v1/blade.pb.h"

namespace kerf::sim {

// From the message; INVALID_ARGUMENT if tip or heel is not three numbers.
absl::StatusOr<cut::BladePose> BladePoseFromProto(const kerf::v1::BladePose& pose);
// The message of a pose (BladePoseFromProto's inverse, exactly).
kerf::v1::BladePose BladePoseToProto(const cut::BladePose& pose);

// A whole path from its JSON form, every pose validated against the one before.
// INVALID_ARGUMENT "source: ..." naming the pose for a bad one.
absl::StatusOr<std::vector<cut::BladePose>> ParseBladePathJson(absl::string_view json,
                                                               absl::string_view source,
                                                               const cut::BladeLimits& limits);

}  // namespace kerf::sim
