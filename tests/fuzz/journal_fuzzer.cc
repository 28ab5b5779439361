// Fuzz target for journal files (what a restarted server reads): any bytes give the good
// records before the first bad one and a warning for the rest, never a crash; reading the good
// prefix again gives the same records and no warning.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "service/journal_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* bytes, std::size_t size) {
  const absl::string_view input(reinterpret_cast<const char*>(bytes), size);
  const kerf::service::JournalContents contents = kerf::service::ParseJournal(input, "fuzz");
  if (contents.good_bytes > size) std::abort();
  if (contents.warning.empty() != (contents.good_bytes == size)) std::abort();
  const kerf::service::JournalContents again =
      kerf::service::ParseJournal(input.substr(0, contents.good_bytes), "fuzz");
  if (!again.warning.empty() || again.records.size() != contents.records.size()) std::abort();
  for (std::size_t i = 0; i < again.records.size(); ++i) {
    if (again.records[i].SerializeAsString() != contents.records[i].SerializeAsString()) {
      std::abort();
    }
  }
  return 0;
}
