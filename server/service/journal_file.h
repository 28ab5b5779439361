// The journal file of a session: records framed as [length u32 LE][CRC-32C u32 LE][payload]
// (see proto/kerf/v1/journal.proto), appended one at a time, read back up to the last good one.
//
// Flush policy: Append() writes the records to the operating system before it returns, so a
// record survives the server process being killed; a thread of the writer fdatasyncs the file
// every `sync_interval` (default 100 ms) when something was written, and on close, so at most
// that much is lost to a power cut.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/synchronization/mutex.h"
#include "absl/time/time.h"
#include "kerf/v1/journal.pb.h"

namespace kerf::service {

// CRC-32C (Castagnoli), as iSCSI and ext4 use.
std::uint32_t Crc32c(absl::string_view data);

class JournalWriter {
 public:
  // Opens `path` for appending (mode 0600), creating it. INTERNAL naming the path and the reason.
  static absl::StatusOr<std::unique_ptr<JournalWriter>> Open(
      const std::string& path, absl::Duration sync_interval = absl::Milliseconds(100));
  JournalWriter(const JournalWriter&) = delete;
  JournalWriter& operator=(const JournalWriter&) = delete;
  ~JournalWriter();  // syncs and closes

  // Appends records in one write (to the operating system before returning; the sync to the
  // disk happens on the writer's own thread, so the caller never waits for the disk). INTERNAL
  // on a write error, after which the writer refuses further records.
  absl::Status Append(std::span<const kerf::v1::JournalRecord> records);
  absl::Status Append(const kerf::v1::JournalRecord& record) { return Append({&record, 1}); }

  const std::string& path() const { return path_; }

 private:
  JournalWriter(int fd, std::string path, absl::Duration sync_interval);
  void SyncLoop();

  const int fd_;
  const std::string path_;
  const absl::Duration sync_interval_;
  bool failed_ = false;  // on the appending thread
  absl::Mutex mutex_;
  bool dirty_ ABSL_GUARDED_BY(mutex_) = false;
  bool closing_ ABSL_GUARDED_BY(mutex_) = false;
  std::thread syncer_;
};

struct JournalContents {
  std::vector<kerf::v1::JournalRecord> records;
  std::vector<std::uint64_t> record_ends;  // the byte offset where each record ends
  std::uint64_t good_bytes = 0;            // where the last good record ends
  std::uint64_t file_bytes = 0;
  std::string warning;  // empty, or what was cut off at the end and why
};

// The good records of a journal's bytes (`name` for messages). A torn or corrupted tail (short
// frame, bad length, CRC mismatch, an unparsable payload) ends the reading with a warning, never an
// error: everything before it is kept.
JournalContents ParseJournal(absl::string_view bytes, absl::string_view name);

// ParseJournal of a file. NOT_FOUND or INTERNAL when it cannot be read at all.
absl::StatusOr<JournalContents> ReadJournal(const std::string& path);

// Cuts the file at `good_bytes` (from ReadJournal), so that appending goes on after the last
// good record. INTERNAL naming the path on failure.
absl::Status TruncateJournal(const std::string& path, std::uint64_t good_bytes);

}  // namespace kerf::service
