#include "service/recorded_session.h"

#include <gtest/gtest.h>

#include "service/sha256.h"

namespace kerf::service {
namespace {

kerf::v1::JournalRecord Start() {
  kerf::v1::JournalRecord record;
  kerf::v1::JournalStart& start = *record.mutable_start();
  start.set_session_id("s1");
  start.mutable_scene()->set_name("lattice");
  start.set_physics_rate_hz(1000);
  start.set_frame_rate_hz(60);
  start.set_cutter_token_sha256(Sha256("c"));
  start.set_observer_token_sha256(Sha256("o"));
  return record;
}

kerf::v1::JournalRecord Pose(std::uint64_t tick, int coordinates = 3) {
  kerf::v1::JournalRecord record;
  record.mutable_pose()->set_tick(tick);
  for (int k = 0; k < coordinates; ++k) record.mutable_pose()->mutable_pose()->add_tip(0.01 * k);
  for (int k = 0; k < 3; ++k) record.mutable_pose()->mutable_pose()->add_heel(0.02);
  return record;
}

kerf::v1::JournalRecord Withdrawal(std::uint64_t tick) {
  kerf::v1::JournalRecord record;
  record.mutable_withdrawal()->set_tick(tick);
  return record;
}

kerf::v1::JournalRecord End(std::uint64_t tick) {
  kerf::v1::JournalRecord record;
  record.mutable_end()->set_tick(tick);
  return record;
}

// Contents as ParseJournal gives them: record i ends at byte 100 (i + 1).
JournalContents Contents(std::vector<kerf::v1::JournalRecord> records) {
  JournalContents contents;
  for (std::size_t i = 0; i < records.size(); ++i) contents.record_ends.push_back(100 * (i + 1));
  contents.good_bytes = 100 * records.size();
  contents.file_bytes = contents.good_bytes;
  contents.records = std::move(records);
  return contents;
}

TEST(RecordedSession, KeepsTheStartAndTheEventsInOrder) {
  const absl::StatusOr<RecordedSession> session =
      RecordedSessionOf(Contents({Start(), Pose(3), Pose(3), Withdrawal(9)}), "j");
  ASSERT_TRUE(session.ok()) << session.status();
  EXPECT_EQ(session->start.session_id(), "s1");
  ASSERT_EQ(session->events.size(), 3u);
  EXPECT_EQ(session->last_tick, 9u);
  EXPECT_FALSE(session->ended);
  EXPECT_EQ(session->good_bytes, 400u);
  EXPECT_EQ(session->warning, "");
}

TEST(RecordedSession, AnEndMarksASessionClosedForGood) {
  const absl::StatusOr<RecordedSession> session =
      RecordedSessionOf(Contents({Start(), Pose(3), End(5)}), "j");
  ASSERT_TRUE(session.ok()) << session.status();
  EXPECT_TRUE(session->ended);
  EXPECT_EQ(session->last_tick, 5u);
  EXPECT_EQ(session->events.size(), 1u);
}

TEST(RecordedSession, AJournalWithoutAUsableStartIsRefused) {
  EXPECT_EQ(RecordedSessionOf(Contents({}), "j").status().code(),
            absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(RecordedSessionOf(Contents({Pose(1)}), "j").status().code(),
            absl::StatusCode::kInvalidArgument);
  kerf::v1::JournalRecord no_digests = Start();
  no_digests.mutable_start()->clear_cutter_token_sha256();
  const absl::Status status = RecordedSessionOf(Contents({no_digests}), "j").status();
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(status.message().find("token digests"), absl::string_view::npos) << status;
}

// Each broken record ends the reading there, keeping what came before it.
TEST(RecordedSession, ABrokenRecordIsCutOffWithAWarning) {
  const struct {
    kerf::v1::JournalRecord bad;
    const char* why;
  } cases[] = {
      {Pose(4), "tick 4 after tick 7"},
      {Pose(8, 2), "tip and heel must be"},
      {Pose(0), "tick 0"},
      {Start(), "a second start"},
      {kerf::v1::JournalRecord(), "an empty record"},
  };
  for (const auto& c : cases) {
    const absl::StatusOr<RecordedSession> session =
        RecordedSessionOf(Contents({Start(), Pose(7), c.bad, Pose(9)}), "j");
    ASSERT_TRUE(session.ok()) << session.status();
    EXPECT_EQ(session->events.size(), 1u) << c.why;
    EXPECT_EQ(session->last_tick, 7u);
    EXPECT_EQ(session->good_bytes, 200u);  // the end of the last record kept
    EXPECT_NE(session->warning.find(c.why), std::string::npos) << session->warning;
    EXPECT_NE(session->warning.find("record 2 is unusable"), std::string::npos) << session->warning;
  }
  const absl::StatusOr<RecordedSession> after_end =
      RecordedSessionOf(Contents({Start(), End(7), Pose(9)}), "j");
  ASSERT_TRUE(after_end.ok());
  EXPECT_TRUE(after_end->ended);
  EXPECT_NE(after_end->warning.find("after the end"), std::string::npos) << after_end->warning;
}

}  // namespace
}  // namespace kerf::service
