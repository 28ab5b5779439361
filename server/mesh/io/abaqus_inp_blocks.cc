#include "mesh/io/abaqus_inp_blocks.h"

#include "absl/strings/ascii.h"
#include "absl/strings/match.h"
#include "absl/strings/str_split.h"
#include "mesh/io/text_scanner.h"

namespace kerf::mesh::internal {

std::optional<absl::string_view> InpKeywordBlock::Parameter(absl::string_view name) const {
  for (const auto& [key, value] : parameters) {
    if (absl::EqualsIgnoreCase(key, name)) return value;
  }
  return std::nullopt;
}

absl::StatusOr<std::vector<InpKeywordBlock>> ParseInpKeywordBlocks(absl::string_view text,
                                                                   absl::string_view source) {
  TextScanner s(text, source);
  std::vector<InpKeywordBlock> blocks;
  while (s.offset() < text.size()) {
    const std::size_t offset = s.offset();
    const absl::string_view line = absl::StripAsciiWhitespace(s.NextLine());
    if (line.empty() || absl::StartsWith(line, "**")) continue;
    std::vector<absl::string_view> fields = absl::StrSplit(line, ',');
    for (absl::string_view& field : fields) field = absl::StripAsciiWhitespace(field);
    if (fields.size() > 1 && fields.back().empty()) fields.pop_back();
    if (line[0] == '*') {
      InpKeywordBlock block;
      block.offset = offset;
      block.keyword = absl::AsciiStrToUpper(absl::StripAsciiWhitespace(fields[0].substr(1)));
      if (block.keyword.empty()) return s.ErrorAt(offset, "expected a keyword after '*'");
      for (std::size_t i = 1; i < fields.size(); ++i) {
        const std::pair<absl::string_view, absl::string_view> kv =
            absl::StrSplit(fields[i], absl::MaxSplits('=', 1));
        block.parameters.emplace_back(absl::AsciiStrToUpper(absl::StripAsciiWhitespace(kv.first)),
                                      std::string(absl::StripAsciiWhitespace(kv.second)));
      }
      blocks.push_back(std::move(block));
    } else {
      if (blocks.empty()) return s.ErrorAt(offset, "expected a *KEYWORD line before data");
      blocks.back().lines.push_back({std::move(fields), offset});
    }
  }
  return blocks;
}

}  // namespace kerf::mesh::internal
