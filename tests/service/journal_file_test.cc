#include "service/journal_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <string>

#include "support/status_message.h"

namespace kerf::service {
namespace {

class JournalFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char pattern[] = "/tmp/kerf-journal-XXXXXX";
    directory_ = mkdtemp(pattern);
    path_ = directory_ + "/session.journal";
  }
  void TearDown() override {
    ::unlink(path_.c_str());
    ::rmdir(directory_.c_str());
  }

  static kerf::v1::JournalRecord Pose(std::uint64_t tick) {
    kerf::v1::JournalRecord record;
    record.mutable_pose()->set_tick(tick);
    record.mutable_pose()->mutable_pose()->set_time(0.001 * static_cast<double>(tick));
    for (int k = 0; k < 3; ++k) record.mutable_pose()->mutable_pose()->add_tip(0.01 * k);
    return record;
  }

  void Write(int records) {
    std::unique_ptr<JournalWriter> writer = *JournalWriter::Open(path_);
    kerf::v1::JournalRecord start;
    start.mutable_start()->set_session_id("s");
    ASSERT_TRUE(writer->Append(start).ok());
    // Single records, then a batch of two in one write.
    for (int i = 1; i + 2 < records; ++i) ASSERT_TRUE(writer->Append(Pose(i)).ok());
    const std::vector<kerf::v1::JournalRecord> batch = {Pose(records - 2), Pose(records - 1)};
    ASSERT_TRUE(writer->Append(batch).ok());
  }

  std::uintmax_t Size() const {
    std::ifstream file(path_, std::ios::binary | std::ios::ate);
    return static_cast<std::uintmax_t>(file.tellg());
  }

  void Overwrite(std::uintmax_t at, char byte) {
    std::fstream file(path_, std::ios::binary | std::ios::in | std::ios::out);
    file.seekp(static_cast<std::streamoff>(at));
    file.put(byte);
  }

  std::string directory_, path_;
};

TEST(Crc32c, MatchesTheStandardCheckValue) {
  EXPECT_EQ(Crc32c("123456789"), 0xE3069283u);  // the CRC-32C check value
  EXPECT_EQ(Crc32c(""), 0u);
}

TEST(ReadJournal, ReadsTheFuzzSeedWrittenByAnotherProgram) {
  // The seed was framed by a separate script (its own CRC-32C): the formats agree.
  const JournalContents contents =
      *ReadJournal(std::string(KERF_SOURCE_DIR) + "/tests/fuzz/corpus/journal_fuzzer/valid");
  ASSERT_EQ(contents.records.size(), 3u) << contents.warning;
  EXPECT_EQ(contents.records[0].start().session_id(), "s");
  EXPECT_EQ(contents.records[1].pose().tick(), 7u);
  EXPECT_EQ(contents.records[1].pose().pose().time(), 0.5);
  EXPECT_EQ(contents.records[2].withdrawal().tick(), 9u);
}

TEST_F(JournalFileTest, ReadsBackWhatWasAppended) {
  Write(50);
  const JournalContents contents = *ReadJournal(path_);
  ASSERT_EQ(contents.records.size(), 50u);
  EXPECT_EQ(contents.records[0].start().session_id(), "s");
  EXPECT_EQ(contents.records[49].pose().tick(), 49u);
  EXPECT_EQ(contents.good_bytes, Size());
  EXPECT_EQ(contents.warning, "");
}

TEST_F(JournalFileTest, ATornTailIsCutAtTheLastGoodRecord) {
  Write(10);
  const std::uintmax_t whole = Size();
  ASSERT_EQ(::truncate(path_.c_str(), static_cast<off_t>(whole - 5)), 0);  // a torn write
  const JournalContents torn = *ReadJournal(path_);
  EXPECT_EQ(torn.records.size(), 9u);
  EXPECT_NE(torn.warning.find("is torn"), std::string::npos) << torn.warning;
  EXPECT_NE(torn.warning.find("bytes are dropped"), std::string::npos) << torn.warning;
  // After cutting there, appending goes on cleanly.
  ASSERT_TRUE(TruncateJournal(path_, torn.good_bytes).ok());
  {
    std::unique_ptr<JournalWriter> writer = *JournalWriter::Open(path_);
    ASSERT_TRUE(writer->Append(Pose(100)).ok());
  }
  const JournalContents repaired = *ReadJournal(path_);
  ASSERT_EQ(repaired.records.size(), 10u);
  EXPECT_EQ(repaired.records.back().pose().tick(), 100u);
  EXPECT_EQ(repaired.warning, "");
}

TEST_F(JournalFileTest, ACorruptedRecordEndsTheReadingWithAWarning) {
  Write(10);
  const JournalContents whole = *ReadJournal(path_);
  // Flip a byte inside the sixth record's payload: records 0-4 stay.
  std::uintmax_t at = 0;
  for (int i = 0; i < 5; ++i) at += 8 + whole.records[i].ByteSizeLong();
  Overwrite(at + 10, 'X');
  const JournalContents read = *ReadJournal(path_);
  EXPECT_EQ(read.records.size(), 5u);
  EXPECT_EQ(read.good_bytes, at);
  EXPECT_EQ(read.warning, "journal '" + path_ + "': the record at byte " + std::to_string(at) +
                              " fails its checksum; its last " + std::to_string(Size() - at) +
                              " bytes are dropped");
  // A length past any sane record is caught before it is believed.
  Overwrite(at + 3, '\x7f');
  EXPECT_NE(ReadJournal(path_)->warning.find("claims"), std::string::npos);
}

TEST_F(JournalFileTest, GarbageIsNoRecordsAndAMissingFileIsNotFound) {
  {
    std::ofstream file(path_, std::ios::binary);
    file << "not a journal";
  }
  const JournalContents read = *ReadJournal(path_);
  EXPECT_TRUE(read.records.empty());
  EXPECT_FALSE(read.warning.empty());
  EXPECT_EQ(kerf::testing::StatusMessage(ReadJournal(directory_ + "/nothing")),
            "no journal '" + directory_ + "/nothing'");
}

}  // namespace
}  // namespace kerf::service
