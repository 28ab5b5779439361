// kerf-haptic, the binary, against a real server on loopback.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "absl/time/clock.h"
#include "client/loopback_server.h"
#include "support/run_command.h"
#include "support/server_process.h"

namespace kerf::client {
namespace {

// The number after `key` in `text` (for example "force loop: 1999 ticks in 1.998 s, 1000.4 Hz").
double NumberAfter(const std::string& text, const std::string& key) {
  const std::size_t at = text.find(key);
  if (at == std::string::npos) return -1;
  const std::string rest = text.substr(at + key.size());
  double value = -1;
  (void)absl::SimpleAtod(rest.substr(0, rest.find_first_of(" ,;")), &value);
  return value;
}

// A cut with frames delayed 40 ms on purpose and coming at 100 Hz: the force loop does not
// wait for them, it ticks many times a frame (once a frame if it did; its 1 kHz rate is not
// asserted, a shared machine may slow it: it is measured in the README). (That the rendered
// force is continuous is ForceModel's test.)
TEST(KerfHaptic, CompletesAScriptedCutAndItsForceLoopHoldsItsRateWhileFramesAreDelayed) {
  kerf::testing::LoopbackServer server;
  const std::string csv = ::testing::TempDir() + "/kerf-haptic.csv";
  const kerf::testing::CommandResult run = kerf::testing::RunCommand(absl::StrCat(
      KERF_HAPTIC_BINARY, " --server=127.0.0.1:", server.port(), " --path=", KERF_SOURCE_DIR,
      "/server/lab/paths/lattice-straight.json --device=simulated --slowdown=8 "
      "--frame_rate_hz=100 --frame_delay_ms=40 --csv=",
      csv, " 2>&1"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const double ticks = NumberAfter(run.output, "force loop: ");
  const double seconds = NumberAfter(run.output, " ticks in ");
  const double frames = NumberAfter(run.output, "frames: ");
  ASSERT_GT(seconds, 1.9) << run.output;  // the 0.25 s path played 8 times slower
  EXPECT_GT(frames, 100) << run.output;
  EXPECT_GT(ticks, 5 * frames) << run.output;
  const std::string force = run.output.substr(run.output.find("force: "));
  EXPECT_GT(NumberAfter(force, "force: largest "), 1.0) << run.output;  // it cut
  EXPECT_NE(run.output.find("; 0 reconnects"), std::string::npos) << run.output;
  std::ifstream in(csv);
  std::stringstream text;
  text << in.rdbuf();
  const std::vector<std::string> lines = absl::StrSplit(text.str(), '\n', absl::SkipEmpty());
  ASSERT_GE(lines.size(), 2u) << text.str();  // a header and a row per second
  EXPECT_EQ(lines[0].rfind("second,loop_ticks,", 0), 0u);
  std::remove(csv.c_str());
}

// The server is killed mid-cut and restarted on the same port (restoring the session from its
// journal): kerf-haptic reconnects with backoff and finishes the cut in the same session.
TEST(KerfHaptic, ReconnectsWhenTheServerRestartsMidCut) {
  const std::string journal_dir =
      absl::StrCat(::testing::TempDir(), "/kerf-haptic-", getpid(), "-journal");
  std::filesystem::remove_all(journal_dir);
  const std::string flags = absl::StrCat("--journal_dir=", journal_dir);
  auto server = std::make_unique<kerf::testing::ServerProcess>(KERF_SERVER_BINARY, flags);
  ASSERT_TRUE(server->started()) << server->said();
  const int port = server->port();
  kerf::v1::CreateSessionResponse created;
  {
    grpc::ClientContext context;
    ASSERT_TRUE(server->stub().CreateSession(&context, {}, &created).ok());
  }
  FILE* haptic =
      popen(absl::StrCat(KERF_HAPTIC_BINARY, " --server=127.0.0.1:", port,
                         " --session_id=", created.session().session_id(),
                         " --token=", created.cutter_token(), " --path=", KERF_SOURCE_DIR,
                         "/server/lab/paths/lattice-straight.json --device=path --slowdown=16 2>&1")
                .c_str(),
            "r");
  ASSERT_NE(haptic, nullptr);
  absl::SleepFor(absl::Seconds(1.5));  // a third of the way through the 4 s cut
  server->Stop(SIGKILL);
  server = std::make_unique<kerf::testing::ServerProcess>(KERF_SERVER_BINARY, flags,
                                                          absl::StrCat("127.0.0.1:", port));
  ASSERT_TRUE(server->started()) << server->said();
  EXPECT_NE(server->said().find("restored"), std::string::npos) << server->said();
  std::string output;
  char line[1024];
  while (fgets(line, sizeof(line), haptic) != nullptr) output += line;
  const int status = pclose(haptic);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << output;
  EXPECT_GE(NumberAfter(output, "ms; "), 1) << output;          // "...; N reconnects"
  EXPECT_GT(NumberAfter(output, " ticks in "), 3.9) << output;  // the whole path was played
  std::filesystem::remove_all(journal_dir);
}

TEST(KerfHaptic, BadArgumentsGetAClearError) {
  kerf::testing::CommandResult run =
      kerf::testing::RunCommand(absl::StrCat(KERF_HAPTIC_BINARY, " --device=glove 2>&1"));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.output.find("--device must be path, simulated or keyboard"), std::string::npos)
      << run.output;
  run = kerf::testing::RunCommand(absl::StrCat(KERF_HAPTIC_BINARY, " --path=/nowhere.json 2>&1"));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.output.find("cannot read blade path '/nowhere.json'"), std::string::npos)
      << run.output;
}

}  // namespace
}  // namespace kerf::client
