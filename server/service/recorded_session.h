// A session as its journal recorded it: the start record, then the events (poses and
// withdrawals, by tick) that changed its model, checked so that replaying them cannot fail in a
// way the original run did not.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "kerf/v1/journal.pb.h"
#include "service/journal_file.h"

namespace kerf::service {

struct RecordedSession {
  kerf::v1::JournalStart start;
  std::vector<kerf::v1::JournalRecord> events;  // poses and withdrawals, ticks not decreasing
  bool ended = false;                           // closed by a client (a JournalEnd record)
  std::uint64_t last_tick = 0;                  // of the last event or the end
  std::uint64_t good_bytes = 0;  // where the last record kept ends (to truncate the file to)
  std::string warning;           // empty, or what was cut off at the end and why
};

// The session in a journal's records (`name` for messages). INVALID_ARGUMENT when the first
// record is not a usable start (no session id, no scene, bad rates or token digests). Past the
// start, a record that breaks the rules (an event before the start, a tick going back, a pose
// without three coordinates, anything after the end) ends the reading with a warning, like a
// torn tail: the records before it are kept.
absl::StatusOr<RecordedSession> RecordedSessionOf(const JournalContents& contents,
                                                  absl::string_view name);

// ReadJournal, then RecordedSessionOf. NOT_FOUND or INTERNAL when the file cannot be read.
absl::StatusOr<RecordedSession> ReadRecordedSession(const std::string& path);

}  // namespace kerf::service
