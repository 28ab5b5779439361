// kerf-load: a load test against a kerf-server (loopback by default). N sessions, each with one
// cutter repeating a blade path in real time and M observers at chosen levels, for a bounded
// time and a bounded number of poses; a progress bar on stderr while it runs, then a report
// (--json: kerf.v1.LoadReport). Exit status: 0, 1 for an error that stopped the run, 2 for
// bad arguments, 3 when the scenario's objective was missed.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "absl/flags/usage.h"
#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "common/blade_path_file.h"
#include "google/protobuf/text_format.h"
#include "google/protobuf/util/json_util.h"
#include "load/load_run.h"

ABSL_FLAG(std::string, server, "127.0.0.1:50051", "the kerf-server, host:port");
ABSL_FLAG(std::string, tls_ca, "", "PEM root certificate(s) to trust: TLS (plaintext when empty)");
ABSL_FLAG(std::string, scenario, "",
          "scenario file (kerf.v1.LoadScenario, protobuf text format); flags override it");
ABSL_FLAG(std::string, path, "", "blade path the cutters repeat (overrides the scenario's)");
ABSL_FLAG(int, sessions, 0, "N sessions (0: the scenario's, or 1)");
ABSL_FLAG(int, observers, -1, "M observers per session (-1: the scenario's)");
ABSL_FLAG(double, duration, 0, "seconds to run (0: the scenario's, or 10)");
ABSL_FLAG(int64_t, max_requests, -1, "poses to send at most, in all (-1: the scenario's)");
ABSL_FLAG(bool, json, false, "print the report as JSON (kerf.v1.LoadReport)");
ABSL_FLAG(bool, progress, true, "draw a progress bar on stderr");

namespace {

int Fail(int code, const std::string& what) {
  std::fprintf(stderr, "kerf-load: %s\n", what.c_str());
  return code;
}

void DrawProgress(double elapsed, double total, const kerf::client::LoadProgress& p) {
  constexpr int kWidth = 30;
  const int filled = static_cast<int>(kWidth * std::min(1.0, elapsed / total));
  std::fprintf(stderr, "\r[%s%s] %5.1f/%.0f s  poses %llu  frames %llu  errors %llu ",
               std::string(filled, '#').c_str(), std::string(kWidth - filled, '.').c_str(), elapsed,
               total, static_cast<unsigned long long>(p.poses_sent.load()),
               static_cast<unsigned long long>(p.frames.load()),
               static_cast<unsigned long long>(p.errors.load()));
}

}  // namespace

int main(int argc, char** argv) {
  absl::SetProgramUsageMessage(
      "kerf-load [--scenario=FILE] [--sessions=N] [--observers=M] [--duration=S] "
      "[--path=PATH.json] [--server=HOST:PORT] [--json]");
  absl::ParseCommandLine(argc, argv);
  kerf::v1::LoadScenario scenario;
  scenario.set_sessions(1);
  scenario.set_observers_per_session(4);
  scenario.set_duration_seconds(10);
  scenario.set_settle_seconds(1);
  std::filesystem::path base_dir(".");
  if (const std::string file = absl::GetFlag(FLAGS_scenario); !file.empty()) {
    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    if (!in) return Fail(2, absl::StrCat("cannot read --scenario '", file, "'"));
    if (!google::protobuf::TextFormat::ParseFromString(text.str(), &scenario)) {
      return Fail(
          2, absl::StrCat(file, ": not a kerf.v1.LoadScenario (see proto/kerf/v1/load.proto)"));
    }
    if (std::filesystem::path(file).has_parent_path()) {
      base_dir = std::filesystem::path(file).parent_path();
    }
  }
  if (absl::GetFlag(FLAGS_sessions) > 0) scenario.set_sessions(absl::GetFlag(FLAGS_sessions));
  if (absl::GetFlag(FLAGS_observers) >= 0) {
    scenario.set_observers_per_session(absl::GetFlag(FLAGS_observers));
  }
  if (absl::GetFlag(FLAGS_duration) > 0)
    scenario.set_duration_seconds(absl::GetFlag(FLAGS_duration));
  if (absl::GetFlag(FLAGS_max_requests) >= 0) {
    scenario.set_max_requests(absl::GetFlag(FLAGS_max_requests));
  }
  std::string path_file = absl::GetFlag(FLAGS_path);
  if (path_file.empty() && !scenario.path().empty()) {
    path_file = (base_dir / scenario.path()).string();  // an absolute path stays itself
  }
  if (path_file.empty()) return Fail(2, "a blade path is needed: --path or the scenario's path");
  const absl::StatusOr<kerf::v1::BladePath> path = kerf::client::ReadBladePath(path_file);
  if (!path.ok()) return Fail(2, std::string(path.status().message()));

  kerf::client::LoadProgress progress;
  absl::StatusOr<kerf::v1::LoadReport> report;
  std::thread run([&] {
    report = kerf::client::RunLoad({absl::GetFlag(FLAGS_server), absl::GetFlag(FLAGS_tls_ca)},
                                   scenario, *path, &progress);
  });
  const absl::Time begin = absl::Now();
  const bool draw = absl::GetFlag(FLAGS_progress);
  std::atomic<bool> done{false};
  std::thread bar([&] {
    while (!done) {
      if (draw)
        DrawProgress(absl::ToDoubleSeconds(absl::Now() - begin), scenario.duration_seconds(),
                     progress);
      absl::SleepFor(absl::Milliseconds(250));
    }
  });
  run.join();
  done = true;
  bar.join();
  if (draw) std::fprintf(stderr, "\n");
  if (!report.ok()) {
    return Fail(absl::IsInvalidArgument(report.status()) ? 2 : 1,
                std::string(report.status().message()));
  }
  kerf::client::CheckObjective(scenario.objective(), &*report);
  if (absl::GetFlag(FLAGS_json)) {
    std::string json;
    google::protobuf::util::JsonPrintOptions options;
    options.add_whitespace = true;
    options.always_print_primitive_fields = true;
    options.preserve_proto_field_names = true;
    (void)google::protobuf::util::MessageToJsonString(*report, &json, options);
    std::printf("%s", json.c_str());
  } else {
    const kerf::v1::LoadReport& r = *report;
    std::printf("%u sessions x %u observers for %.1f s: %llu poses sent (server received %llu)\n",
                r.sessions(), r.sessions() == 0 ? 0 : r.observers() / r.sessions(), r.seconds(),
                static_cast<unsigned long long>(r.poses_sent()),
                static_cast<unsigned long long>(r.server_poses_received()));
    std::printf(
        "cutter: %.1f frames/s each; pose-to-frame p50 %.2f, p90 %.2f, p99 %.2f, max %.2f ms\n",
        r.cutter_fps(), r.latency_p50_ms(), r.latency_p90_ms(), r.latency_p99_ms(),
        r.latency_max_ms());
    std::printf(
        "observers: %.1f frames/s each, %llu frames (server sent %llu), frame age p99 %.2f ms, "
        "%llu sequence gaps, %llu resyncs\n",
        r.observer_fps(), static_cast<unsigned long long>(r.observer_frames()),
        static_cast<unsigned long long>(r.server_observer_frames_sent()), r.frame_age_p99_ms(),
        static_cast<unsigned long long>(r.sequence_gaps()),
        static_cast<unsigned long long>(r.resyncs()));
    std::printf("errors: %llu%s\n", static_cast<unsigned long long>(r.errors()),
                r.error_samples().empty()
                    ? ""
                    : absl::StrCat(" (first: ", r.error_samples(0), ")").c_str());
    for (const std::string& missed : r.objective_missed()) {
      std::printf("objective missed: %s\n", missed.c_str());
    }
  }
  return report->objective_met() ? 0 : 3;
}
