#include "service/session_registry.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "absl/strings/str_cat.h"
#include "cut/crack_cutter.h"
#include "service/journal_file.h"
#include "sim/scene.h"

namespace kerf::service {
namespace {

class SessionRegistryJournalTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = absl::StrCat(::testing::TempDir(), "/kerf-registry-", getpid(), "-",
                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  RegistryOptions Options() const {
    RegistryOptions options;
    options.journal_dir = dir_;
    return options;
  }
  std::string JournalOf(const std::string& id) const {
    return absl::StrCat(dir_, "/", id, ".journal");
  }
  // The scene the journal of a session made by `request` (and shut down with the server)
  // starts with; fails the test if there is none.
  kerf::v1::Scene JournaledScene(const kerf::v1::CreateSessionRequest& request) const {
    std::string id;
    {
      SessionRegistry registry(Options());
      absl::StatusOr<CreatedSession> created = registry.Create(request);
      EXPECT_TRUE(created.ok()) << created.status();
      if (!created.ok()) return {};
      id = created->session->id();
      registry.CloseAll(absl::UnavailableError("shutting down"));
    }
    const absl::StatusOr<JournalContents> journal = ReadJournal(JournalOf(id));
    EXPECT_TRUE(journal.ok()) << journal.status();
    if (!journal.ok() || journal->records.empty()) return {};
    return journal->records[0].start().scene();
  }

  std::string dir_;
};

TEST_F(SessionRegistryJournalTest, ASessionLeftOpenIsRestoredWithItsTokens) {
  std::string id;
  IssuedTokens tokens;
  {
    SessionRegistry registry(Options());
    absl::StatusOr<CreatedSession> created = registry.Create({});
    ASSERT_TRUE(created.ok()) << created.status();
    id = created->session->id();
    tokens = created->tokens;
    registry.CloseAll(absl::UnavailableError("shutting down"));  // not for good
  }
  const absl::StatusOr<JournalContents> journal = ReadJournal(JournalOf(id));
  ASSERT_TRUE(journal.ok()) << journal.status();
  ASSERT_GE(journal->records.size(), 1u);
  const std::string bytes = journal->records[0].SerializeAsString();
  EXPECT_EQ(bytes.find(tokens.cutter), std::string::npos);  // never the tokens themselves
  EXPECT_EQ(bytes.find(tokens.observer), std::string::npos);
  EXPECT_EQ(std::filesystem::status(JournalOf(id)).permissions() &
                (std::filesystem::perms::group_all | std::filesystem::perms::others_all),
            std::filesystem::perms::none);

  SessionRegistry restarted(Options());
  const std::vector<RestoreOutcome> outcomes = restarted.Restore();
  ASSERT_EQ(outcomes.size(), 1u);
  EXPECT_TRUE(outcomes[0].status.ok()) << outcomes[0].status;
  EXPECT_TRUE(outcomes[0].restored);
  const absl::StatusOr<std::shared_ptr<Session>> session = restarted.Find(id);
  ASSERT_TRUE(session.ok()) << session.status();
  EXPECT_TRUE((*session)->tokens().Authorize(Role::kCutter, tokens.cutter).ok());
  EXPECT_TRUE((*session)->tokens().Authorize(Role::kObserver, tokens.observer).ok());
  EXPECT_EQ((*session)->Info().tets(), 576u);
}

// A journal names the cut mode, height guard, snap fraction and method its session ran with,
// even where the scene left them to the defaults, so that it replays alike if the defaults
// change.
TEST_F(SessionRegistryJournalTest, AJournalRecordsTheModeAndMethodTheDefaultsChose) {
  const kerf::v1::Scene scene = JournaledScene({});  // the default scene
  EXPECT_EQ(scene.cutting().mode(), kerf::v1::Cutting::PROGRESSIVE);
  ASSERT_TRUE(scene.cutting().has_min_temporary_height());
  EXPECT_EQ(scene.cutting().min_temporary_height(), cut::kDefaultMinTemporaryHeight);
  ASSERT_TRUE(scene.cutting().has_snap_fraction());
  EXPECT_EQ(scene.cutting().snap_fraction(), cut::kDefaultCrackSnapFraction);
  EXPECT_EQ(scene.integration().method(), kerf::v1::Integration::IMPLICIT_EULER);
}

// A sleeping scene's journal names the thresholds it slept by, the defaults included.
TEST_F(SessionRegistryJournalTest, AJournalRecordsTheSleepingThresholds) {
  kerf::v1::CreateSessionRequest request;
  *request.mutable_scene() =
      *sim::ParseSceneText(*sim::EmbeddedSceneText("lattice-tension") +
                               "integration { sleeping { wake_acceleration: 0.01 } }\n",
                           "sleeping");
  const kerf::v1::Sleeping sleeping = JournaledScene(request).integration().sleeping();
  EXPECT_EQ(sleeping.wake_acceleration(), 0.01);
  ASSERT_TRUE(sleeping.has_rest_speed());
  EXPECT_EQ(sleeping.rest_speed(), fem::SleepOptions{}.rest_speed);
  ASSERT_TRUE(sleeping.has_quiet_time());
  EXPECT_EQ(sleeping.quiet_time(), fem::SleepOptions{}.quiet_time);
}

TEST_F(SessionRegistryJournalTest, ASessionClosedByItsClientIsKeptButNotRestored) {
  std::string id;
  {
    SessionRegistry registry(Options());
    absl::StatusOr<CreatedSession> created = registry.Create({});
    ASSERT_TRUE(created.ok()) << created.status();
    id = created->session->id();
    ASSERT_TRUE(registry.Close(id).ok());
  }
  ASSERT_TRUE(std::filesystem::exists(JournalOf(id)));  // kept for replay
  SessionRegistry restarted(Options());
  const std::vector<RestoreOutcome> outcomes = restarted.Restore();
  ASSERT_EQ(outcomes.size(), 1u);
  EXPECT_TRUE(outcomes[0].status.ok()) << outcomes[0].status;
  EXPECT_FALSE(outcomes[0].restored);
  EXPECT_EQ(restarted.Find(id).status().code(), absl::StatusCode::kNotFound);
}

TEST_F(SessionRegistryJournalTest, AJournalThatCannotBeRestoredIsReportedAndLeftAlone) {
  const std::string garbage = JournalOf("0123456789abcdef0123456789abcdef");
  std::ofstream(garbage, std::ios::binary) << "not a journal at all";
  SessionRegistry registry(Options());
  const std::vector<RestoreOutcome> outcomes = registry.Restore();
  ASSERT_EQ(outcomes.size(), 1u);
  EXPECT_EQ(outcomes[0].status.code(), absl::StatusCode::kInvalidArgument) << outcomes[0].status;
  EXPECT_FALSE(outcomes[0].restored);
  EXPECT_EQ(std::filesystem::file_size(garbage), 20u);  // untouched, for a person to look at
  EXPECT_TRUE(registry.List().empty());
}

TEST_F(SessionRegistryJournalTest, RestoringBeyondTheSessionLimitLeavesTheRestForLater) {
  std::vector<std::string> ids;
  {
    SessionRegistry registry(Options());
    for (int i = 0; i < 2; ++i) ids.push_back((*registry.Create({})).session->id());
    registry.CloseAll(absl::UnavailableError("shutting down"));
  }
  RegistryOptions one = Options();
  one.max_sessions = 1;
  SessionRegistry small(one);
  const std::vector<RestoreOutcome> outcomes = small.Restore();
  ASSERT_EQ(outcomes.size(), 2u);
  EXPECT_TRUE(outcomes[0].restored);
  EXPECT_EQ(outcomes[1].status.code(), absl::StatusCode::kResourceExhausted);
  EXPECT_EQ(small.List().size(), 1u);
  small.CloseAll(absl::UnavailableError("shutting down"));
  SessionRegistry big(Options());  // the one left out is still there to restore
  std::size_t restored = 0;
  for (const RestoreOutcome& outcome : big.Restore()) restored += outcome.restored ? 1 : 0;
  EXPECT_EQ(restored, 2u);
}

}  // namespace
}  // namespace kerf::service
