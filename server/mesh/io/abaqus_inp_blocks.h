// The keyword blocks of an Abaqus/CalculiX input deck: "*KEYWORD, PARAM=VALUE, ..." lines,
// each followed by comma-separated data lines. "**" starts a comment line. Keywords and
// parameter names are case-insensitive and are returned upper-cased.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace kerf::mesh::internal {

struct InpDataLine {
  std::vector<absl::string_view> fields;  // trimmed; a trailing empty field is dropped
  std::size_t offset;                     // of the line in the text
};

struct InpKeywordBlock {
  std::string keyword;  // upper case, without '*': "NODE", "ELEMENT", "SOLID SECTION"
  std::vector<std::pair<std::string, std::string>> parameters;  // upper-case names, values as given
  std::vector<InpDataLine> lines;
  std::size_t offset;  // of the keyword line

  // The value of a parameter (case-insensitive name), or nullopt.
  std::optional<absl::string_view> Parameter(absl::string_view name) const;
};

// INVALID_ARGUMENT (source:line) for data before the first keyword or an empty keyword.
absl::StatusOr<std::vector<InpKeywordBlock>> ParseInpKeywordBlocks(absl::string_view text,
                                                                   absl::string_view source);

}  // namespace kerf::mesh::internal
