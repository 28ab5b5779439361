// Blade path files (the `kerf cut` JSON format: {"poses": [{"time", "tip", "heel"}, ...]}).
#pragma once

#include <string>

#include "absl/status/statusor.h"
#include "kerf/v1/blade.pb.h"

namespace kerf::client {

// NOT_FOUND when the file cannot be read; INVALID_ARGUMENT naming the file for bad JSON, no
// poses, or a pose without three coordinates for tip and heel.
absl::StatusOr<kerf::v1::BladePath> ReadBladePath(const std::string& file);

}  // namespace kerf::client
