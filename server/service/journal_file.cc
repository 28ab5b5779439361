#include "service/journal_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <utility>

#include "absl/strings/str_cat.h"

namespace kerf::service {
namespace {

// Records larger than this are taken for a corrupted length.
constexpr std::uint32_t kMaxRecordBytes = 64u << 20;

std::array<std::uint32_t, 256> MakeCrcTable() {
  std::array<std::uint32_t, 256> table{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1) != 0 ? 0x82F63B78u ^ (c >> 1) : c >> 1;
    table[i] = c;
  }
  return table;
}

void PutU32(std::uint32_t v, char* out) {
  for (int i = 0; i < 4; ++i) out[i] = static_cast<char>((v >> (8 * i)) & 0xff);
}

std::uint32_t GetU32(const char* in) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= std::uint32_t{static_cast<unsigned char>(in[i])} << (8 * i);
  return v;
}

absl::Status ErrnoError(const std::string& what, const std::string& path) {
  return absl::InternalError(
      absl::StrCat("cannot ", what, " journal '", path, "': ", std::strerror(errno)));
}

}  // namespace

std::uint32_t Crc32c(absl::string_view data) {
  static const std::array<std::uint32_t, 256> table = MakeCrcTable();
  std::uint32_t crc = 0xffffffffu;
  for (const char byte : data) {
    crc = table[(crc ^ static_cast<unsigned char>(byte)) & 0xff] ^ (crc >> 8);
  }
  return crc ^ 0xffffffffu;
}

absl::StatusOr<std::unique_ptr<JournalWriter>> JournalWriter::Open(const std::string& path,
                                                                   absl::Duration sync_interval) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0600);
  if (fd < 0) return ErrnoError("open", path);
  return std::unique_ptr<JournalWriter>(new JournalWriter(fd, path, sync_interval));
}

JournalWriter::JournalWriter(int fd, std::string path, absl::Duration sync_interval)
    : fd_(fd), path_(std::move(path)), sync_interval_(sync_interval) {
  syncer_ = std::thread([this] { SyncLoop(); });
}

JournalWriter::~JournalWriter() {
  {
    absl::MutexLock lock(&mutex_);
    closing_ = true;
  }
  syncer_.join();
  ::fdatasync(fd_);
  ::close(fd_);
}

void JournalWriter::SyncLoop() {
  absl::MutexLock lock(&mutex_);
  while (!closing_) {
    mutex_.AwaitWithTimeout(absl::Condition(&closing_), sync_interval_);
    if (!dirty_) continue;
    dirty_ = false;
    mutex_.Unlock();
    ::fdatasync(fd_);  // a failure shows at the next write, which Append reports
    mutex_.Lock();
  }
}

absl::Status JournalWriter::Append(std::span<const kerf::v1::JournalRecord> records) {
  if (failed_) return absl::InternalError(absl::StrCat("journal '", path_, "' failed earlier"));
  std::string frames;
  for (const kerf::v1::JournalRecord& record : records) {
    const std::string payload = record.SerializeAsString();
    char header[8];
    PutU32(static_cast<std::uint32_t>(payload.size()), header);
    PutU32(Crc32c(payload), header + 4);
    frames.append(header, sizeof(header));
    frames += payload;
  }
  // One write, so that a crash tears at most the end of it.
  std::size_t written = 0;
  while (written < frames.size()) {
    const ssize_t n = ::write(fd_, frames.data() + written, frames.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      failed_ = true;
      return ErrnoError("write", path_);
    }
    written += static_cast<std::size_t>(n);
  }
  absl::MutexLock lock(&mutex_);
  dirty_ = true;
  return absl::OkStatus();
}

absl::StatusOr<JournalContents> ReadJournal(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    return errno == ENOENT ? absl::NotFoundError(absl::StrCat("no journal '", path, "'"))
                           : ErrnoError("read", path);
  }
  std::stringstream buffer;
  buffer << file.rdbuf();
  return ParseJournal(buffer.str(), path);
}

JournalContents ParseJournal(absl::string_view bytes, absl::string_view name) {
  JournalContents contents;
  contents.file_bytes = bytes.size();
  std::size_t at = 0;
  while (at < bytes.size()) {
    const std::string where = absl::StrCat("journal '", name, "': the record at byte ", at);
    const std::string dropped =
        absl::StrCat("; its last ", bytes.size() - at, " bytes are dropped");
    if (bytes.size() - at < 8) {
      contents.warning = absl::StrCat(where, " is torn (", bytes.size() - at,
                                      " bytes of an 8-byte header)", dropped);
      break;
    }
    const std::uint32_t length = GetU32(bytes.data() + at);
    const std::uint32_t crc = GetU32(bytes.data() + at + 4);
    if (length > kMaxRecordBytes) {
      contents.warning = absl::StrCat(where, " claims ", length, " bytes", dropped);
      break;
    }
    if (bytes.size() - at - 8 < length) {
      contents.warning = absl::StrCat(where, " is torn (", bytes.size() - at - 8, " of ", length,
                                      " bytes)", dropped);
      break;
    }
    const absl::string_view payload(bytes.data() + at + 8, length);
    if (Crc32c(payload) != crc) {
      contents.warning = absl::StrCat(where, " fails its checksum", dropped);
      break;
    }
    kerf::v1::JournalRecord record;
    if (!record.ParseFromArray(payload.data(), static_cast<int>(payload.size()))) {
      contents.warning = absl::StrCat(where, " does not parse", dropped);
      break;
    }
    contents.records.push_back(std::move(record));
    at += 8 + length;
    contents.good_bytes = at;
    contents.record_ends.push_back(at);
  }
  return contents;
}

absl::Status TruncateJournal(const std::string& path, std::uint64_t good_bytes) {
  if (::truncate(path.c_str(), static_cast<off_t>(good_bytes)) != 0) {
    return ErrnoError("truncate", path);
  }
  return absl::OkStatus();
}

}  // namespace kerf::service
