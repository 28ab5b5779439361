// Base64 (RFC 4648) for VTU's inline binary arrays.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "absl/strings/string_view.h"

namespace kerf::mesh::internal {

std::string Base64Encode(absl::string_view bytes);

// Decodes, skipping whitespace. Padding may end a block in the middle of the text and decoding
// goes on with the next block (VTK writers encode a header and its data either as one stream
// or as two). nullopt on any other character or a truncated group.
std::optional<std::vector<std::uint8_t>> Base64Decode(absl::string_view text);

}  // namespace kerf::mesh::internal
