// SHA-256 (OpenSSL's), for token digests and model digests.
#pragma once

#include <string>

#include "absl/strings/string_view.h"

namespace kerf::service {

// The digest of `data`, 32 raw bytes.
std::string Sha256(absl::string_view data);

}  // namespace kerf::service
