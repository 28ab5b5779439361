// kerf-load, the binary, against a real server on loopback: its counts agree with the
// server's own, and a missed objective makes it exit 3.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "absl/strings/str_cat.h"
#include "client/loopback_server.h"
#include "google/protobuf/util/json_util.h"
#include "kerf/v1/load.pb.h"
#include "support/run_command.h"

namespace kerf::client {
namespace {

class KerfLoadTest : public ::testing::Test {
 protected:
  kerf::testing::CommandResult Load(const std::string& args) {
    return kerf::testing::RunCommand(absl::StrCat(
        KERF_LOAD_BINARY, " --server=127.0.0.1:", server_.port(), " --progress=false ", args));
  }
  service::SessionRegistry& registry() { return server_.registry(); }

  kerf::testing::LoopbackServer server_;
};

// A scenario file for the lattice and its straight path, with `extra` text appended.
std::string WriteScenario(const std::string& name, const std::string& extra) {
  const std::string file = absl::StrCat(::testing::TempDir(), "/kerf-load-", name, ".textproto");
  std::ofstream(file) << "scene_name: \"lattice-tension\" levels: [SURFACE, FORCES]\n"
                      << "path: \"" << KERF_SOURCE_DIR
                      << "/server/lab/paths/lattice-straight.json\"\n"
                      << extra;
  return file;
}

// (The timing objectives are left out: this checks counting, not this machine's speed.)
TEST_F(KerfLoadTest, ItsCountsAgreeWithTheServers) {
  const std::string scenario = WriteScenario("counts", "settle_seconds: 0.5\n");
  const kerf::testing::CommandResult run = Load(
      absl::StrCat("--scenario=", scenario, " --sessions=2 --observers=3 --duration=3 --json"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  kerf::v1::LoadReport report;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(run.output, &report).ok()) << run.output;
  EXPECT_EQ(report.sessions(), 2u);
  EXPECT_EQ(report.observers(), 6u);
  EXPECT_EQ(report.errors(), 0u);
  EXPECT_GE(report.poses_sent(), 26u);  // at least one pass of the path (slow under ASan)
  EXPECT_EQ(report.poses_sent(), report.server_poses_received());
  EXPECT_GE(report.observer_frames(), 6u);  // a keyframe each at least
  EXPECT_EQ(report.observer_frames(), report.server_observer_frames_sent());
  EXPECT_GT(report.cutter_frames(), 0u);
  EXPECT_GT(report.latency_p50_ms(), 0);
  EXPECT_LE(report.latency_p50_ms(), report.latency_p99_ms());
  EXPECT_TRUE(report.objective_met());
  EXPECT_TRUE(registry().List().empty());  // it closed its sessions
  std::remove(scenario.c_str());
}

TEST_F(KerfLoadTest, AMissedObjectiveExitsThree) {
  const std::string scenario = WriteScenario(
      "impossible",
      "sessions: 1 observers_per_session: 1 duration_seconds: 1.5 settle_seconds: 0.2\n"
      "objective { max_latency_p99_ms: 0.000001 }\n");
  const kerf::testing::CommandResult run = Load(absl::StrCat("--scenario=", scenario, " 2>&1"));
  EXPECT_EQ(run.exit_code, 3) << run.output;
  EXPECT_NE(run.output.find("objective missed: latency p99"), std::string::npos) << run.output;
  std::remove(scenario.c_str());
}

TEST_F(KerfLoadTest, BadArgumentsExitTwoWithAMessage) {
  kerf::testing::CommandResult run = Load("--path=/no/path.json 2>&1");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.output.find("cannot read blade path '/no/path.json'"), std::string::npos)
      << run.output;
  run = Load(absl::StrCat("--path=", KERF_SOURCE_DIR,
                          "/server/lab/paths/lattice-straight.json --sessions=100 2>&1"));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.output.find("sessions must be 1 to 64"), std::string::npos) << run.output;
}

}  // namespace
}  // namespace kerf::client
