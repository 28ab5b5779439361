#include "service/recorded_session.h"

#include <cmath>

#include "absl/strings/str_cat.h"
#include "cut/blade.h"
#include "sim/blade_messages.h"

namespace kerf::service {
namespace {

// Why `record` cannot follow a session whose last event was at `last_tick`; empty if it can.
std::string Unusable(const kerf::v1::JournalRecord& record, std::uint64_t last_tick) {
  std::uint64_t tick = 0;
  switch (record.event_case()) {
    case kerf::v1::JournalRecord::kPose: {
      tick = record.pose().tick();
      const absl::StatusOr<cut::BladePose> pose = sim::BladePoseFromProto(record.pose().pose());
      if (!pose.ok()) return std::string(pose.status().message());
      if (!std::isfinite(pose->time) || !pose->tip.allFinite() || !pose->heel.allFinite()) {
        return "a pose that is not finite";
      }
      break;
    }
    case kerf::v1::JournalRecord::kWithdrawal:
      tick = record.withdrawal().tick();
      break;
    case kerf::v1::JournalRecord::kEnd:
      tick = record.end().tick();
      break;
    case kerf::v1::JournalRecord::kStart:
      return "a second start";
    case kerf::v1::JournalRecord::EVENT_NOT_SET:
      return "an empty record";
  }
  if (tick == 0) return "tick 0 (ticks count from 1)";
  if (tick < last_tick) return absl::StrCat("tick ", tick, " after tick ", last_tick);
  return "";
}

}  // namespace

absl::StatusOr<RecordedSession> RecordedSessionOf(const JournalContents& contents,
                                                  absl::string_view name) {
  if (contents.records.empty() || !contents.records[0].has_start()) {
    return absl::InvalidArgumentError(
        absl::StrCat("journal '", name, "' does not begin with a start record",
                     contents.warning.empty() ? "" : "; ", contents.warning));
  }
  RecordedSession session;
  session.start = contents.records[0].start();
  const kerf::v1::JournalStart& start = session.start;
  if (start.session_id().empty() || !start.has_scene() ||
      !(start.physics_rate_hz() > 0 && start.frame_rate_hz() > 0) ||
      start.cutter_token_sha256().size() != 32 || start.observer_token_sha256().size() != 32) {
    return absl::InvalidArgumentError(
        absl::StrCat("journal '", name,
                     "': its start record lacks a session id, scene, rates or token digests"));
  }
  session.good_bytes = contents.good_bytes;
  session.warning = contents.warning;
  for (std::size_t i = 1; i < contents.records.size(); ++i) {
    const kerf::v1::JournalRecord& record = contents.records[i];
    std::string why = Unusable(record, session.last_tick);
    if (why.empty() && session.ended) why = "a record after the end";
    if (!why.empty()) {
      session.good_bytes = contents.record_ends[i - 1];
      session.warning =
          absl::StrCat("journal '", name, "': record ", i, " is unusable (", why, "); it and the ",
                       contents.records.size() - i - 1, " records after it are dropped");
      break;
    }
    switch (record.event_case()) {
      case kerf::v1::JournalRecord::kEnd:
        session.ended = true;
        session.last_tick = record.end().tick();
        break;
      case kerf::v1::JournalRecord::kPose:
        session.last_tick = record.pose().tick();
        session.events.push_back(record);
        break;
      default:
        session.last_tick = record.withdrawal().tick();
        session.events.push_back(record);
    }
  }
  return session;
}

absl::StatusOr<RecordedSession> ReadRecordedSession(const std::string& path) {
  absl::StatusOr<JournalContents> contents = ReadJournal(path);
  if (!contents.ok()) return contents.status();
  return RecordedSessionOf(*contents, path);
}

}  // namespace kerf::service
