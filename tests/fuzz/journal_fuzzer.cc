// Fuzz target for journal files (what a restarted server reads): any bytes give the good
// records before the first bad one and a warning for the rest, never a crash; reading the good
// prefix again gives the same records and no warning. The session recorded in them is either
// refused with an error or kept up to its last usable record, with ticks in order.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "service/journal_file.h"
#include "service/recorded_session.h"

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
  const absl::StatusOr<kerf::service::RecordedSession> session =
      kerf::service::RecordedSessionOf(contents, "fuzz");
  if (!session.ok()) return 0;
  if (session->good_bytes > contents.good_bytes) std::abort();
  std::uint64_t tick = 0;
  for (const kerf::v1::JournalRecord& event : session->events) {
    const std::uint64_t t = event.has_pose() ? event.pose().tick() : event.withdrawal().tick();
    if (t < tick || !(event.has_pose() || event.has_withdrawal())) std::abort();
    tick = t;
  }
  return 0;
}
