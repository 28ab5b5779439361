// kerf-haptic: drives the blade of one session from a haptic device and renders the tool force
// at 1 kHz (see haptic_session.h). Devices: --device=path (a blade path file, followed
// exactly), simulated (that path as a hand holding the blade would play it: 1 kHz, with
// tremble), keyboard (the terminal). Creates a session (--scene) unless --session_id and
// --token name one. Prints what it measured; --csv writes it per second.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "absl/flags/usage.h"
#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "common/blade_path_file.h"
#include "common/channel.h"
#include "common/latency_summary.h"
#include "common/session_calls.h"
#include "haptic/haptic_session.h"
#include "haptic/keyboard_device.h"
#include "haptic/path_device.h"

ABSL_FLAG(std::string, server, "127.0.0.1:50051", "the kerf-server, host:port");
ABSL_FLAG(std::string, tls_ca, "", "PEM root certificate(s) to trust: TLS (plaintext when empty)");
ABSL_FLAG(std::string, session_id, "", "cut in this session (with --token); empty: make one");
ABSL_FLAG(std::string, token, "", "the session's cutter token");
ABSL_FLAG(std::string, scene, "", "embedded scene of the session it makes (empty: the default)");
ABSL_FLAG(double, settle_seconds, 1, "after making a session, let the tissue settle this long");
ABSL_FLAG(bool, keep_session, false, "leave the session it made open at the end (to watch it)");
ABSL_FLAG(std::string, device, "path", "path, simulated or keyboard");
ABSL_FLAG(std::string, path, "", "blade path file (path and simulated devices; keyboard: start)");
ABSL_FLAG(double, tremble_mm, 0.1, "tremble of the simulated hand, mm");
ABSL_FLAG(double, slowdown, 1, "play the path this many times slower (path, simulated)");
ABSL_FLAG(double, loop_rate_hz, 1000, "force loop rate");
ABSL_FLAG(double, pose_rate_hz, 250, "poses sent to the server per second");
ABSL_FLAG(double, frame_rate_hz, 0, "cutter frames asked of the server (0: every physics tick)");
ABSL_FLAG(double, frame_delay_ms, 0, "hold every frame this long before using it (tests)");
ABSL_FLAG(bool, interpolate, true, "render the local force model between frames (else hold)");
ABSL_FLAG(double, max_seconds, 600, "stop the device after this long");
ABSL_FLAG(std::string, csv, "", "write the measurements per second to this CSV file");

namespace {

int Fail(int code, const std::string& what) {
  std::fprintf(stderr, "kerf-haptic: %s\n", what.c_str());
  return code;
}

// The rows of the CSV: one per whole second of the run.
void WriteCsv(const std::string& file, const kerf::client::HapticRecord& r, double rate_hz) {
  std::ofstream out(file);
  out << "second,loop_ticks,period_jitter_p99_us,largest_force_jump_n,frames,frames_missed_total,"
         "latency_p50_ms,latency_p99_ms\n";
  const double end = r.tick_times.empty() ? 0 : r.tick_times.back();
  std::size_t tick = 0, frame = 0;
  for (int second = 0; second < static_cast<int>(end); ++second) {
    std::vector<double> jitter, jumps;
    std::size_t ticks = 0;
    for (; tick < r.tick_times.size() && r.tick_times[tick] < second + 1; ++tick, ++ticks) {
      if (tick == 0) continue;
      jitter.push_back(1e6 * std::abs(r.tick_times[tick] - r.tick_times[tick - 1] - 1 / rate_hz));
      jumps.push_back(r.force_jumps[tick - 1]);
    }
    std::size_t frames = 0;
    for (; frame < r.frame_times.size() && r.frame_times[frame] < second + 1; ++frame) ++frames;
    const kerf::client::Summary j = kerf::client::Summarize(jitter);
    const kerf::client::Summary latency = kerf::client::Summarize(r.latencies);
    out << second << ',' << ticks << ',' << j.p99 << ',' << kerf::client::Summarize(jumps).max
        << ',' << frames << ',' << r.frames_missed << ',' << 1e3 * latency.p50 << ','
        << 1e3 * latency.p99 << '\n';
  }
}

}  // namespace

int main(int argc, char** argv) {
  absl::SetProgramUsageMessage(
      "kerf-haptic --device=path|simulated|keyboard --path=PATH.json [--server=HOST:PORT] "
      "[--session_id=ID --token=TOKEN] [--csv=OUT.csv]");
  absl::ParseCommandLine(argc, argv);
  const std::string device_name = absl::GetFlag(FLAGS_device);
  if (device_name != "path" && device_name != "simulated" && device_name != "keyboard") {
    return Fail(
        2, absl::StrCat("--device must be path, simulated or keyboard, got '", device_name, "'"));
  }
  if (!(absl::GetFlag(FLAGS_slowdown) >= 1 && absl::GetFlag(FLAGS_slowdown) <= 1000)) {
    return Fail(2, "--slowdown must be in [1, 1000]");
  }
  if (!(absl::GetFlag(FLAGS_loop_rate_hz) >= 100 && absl::GetFlag(FLAGS_loop_rate_hz) <= 10000)) {
    return Fail(2, "--loop_rate_hz must be in [100, 10000]");
  }
  if (!(absl::GetFlag(FLAGS_pose_rate_hz) > 0 &&
        absl::GetFlag(FLAGS_pose_rate_hz) <= absl::GetFlag(FLAGS_loop_rate_hz))) {
    return Fail(2, "--pose_rate_hz must be positive and at most the loop rate");
  }
  const absl::StatusOr<kerf::v1::BladePath> path =
      kerf::client::ReadBladePath(absl::GetFlag(FLAGS_path));
  if (!path.ok()) return Fail(2, std::string(path.status().message()));
  std::unique_ptr<kerf::client::HapticDevice> device;
  if (device_name == "path") {
    device = std::make_unique<kerf::client::PathDevice>(*path, absl::GetFlag(FLAGS_slowdown));
  } else if (device_name == "simulated") {
    device = std::make_unique<kerf::client::SimulatedHandDevice>(
        *path, absl::GetFlag(FLAGS_slowdown), 1e-3 * absl::GetFlag(FLAGS_tremble_mm), 1);
  } else {
    device =
        std::make_unique<kerf::client::KeyboardDevice>(*kerf::client::PathDevice(*path).Sample(0));
  }

  absl::StatusOr<std::shared_ptr<grpc::Channel>> channel =
      kerf::client::OpenChannel(absl::GetFlag(FLAGS_server), absl::GetFlag(FLAGS_tls_ca));
  if (!channel.ok()) return Fail(2, std::string(channel.status().message()));
  auto stub = kerf::v1::Simulator::NewStub(*channel);
  kerf::client::HapticOptions options;
  options.session_id = absl::GetFlag(FLAGS_session_id);
  options.cutter_token = absl::GetFlag(FLAGS_token);
  std::string made;  // the session this run made (closed at the end)
  if (options.session_id.empty()) {
    const absl::StatusOr<kerf::v1::CreateSessionResponse> created =
        kerf::client::CreateSession(*stub, absl::GetFlag(FLAGS_scene));
    if (!created.ok()) return Fail(1, std::string(created.status().message()));
    options.session_id = made = created->session().session_id();
    options.cutter_token = created->cutter_token();
    std::printf("kerf-haptic: session %s, observer token %s\n", made.c_str(),
                created->observer_token().c_str());
    std::fflush(stdout);
    absl::SleepFor(absl::Seconds(absl::GetFlag(FLAGS_settle_seconds)));
  }
  options.loop_rate_hz = absl::GetFlag(FLAGS_loop_rate_hz);
  options.pose_rate_hz = absl::GetFlag(FLAGS_pose_rate_hz);
  options.cutter_frame_rate_hz = absl::GetFlag(FLAGS_frame_rate_hz);
  options.frame_delay_seconds = 1e-3 * absl::GetFlag(FLAGS_frame_delay_ms);
  options.max_seconds = absl::GetFlag(FLAGS_max_seconds);
  options.force.interpolate = absl::GetFlag(FLAGS_interpolate);
  const kerf::client::HapticRecord r = kerf::client::RunHaptic(*stub, *device, options);
  device.reset();  // a keyboard gives the terminal back
  if (!made.empty() && !absl::GetFlag(FLAGS_keep_session)) {
    (void)kerf::client::CloseSession(*stub, made, options.cutter_token);
  }

  std::vector<double> periods;
  for (std::size_t i = 1; i < r.tick_times.size(); ++i) {
    periods.push_back(1e6 *
                      std::abs(r.tick_times[i] - r.tick_times[i - 1] - 1 / options.loop_rate_hz));
  }
  const double span = r.tick_times.size() > 1 ? r.tick_times.back() - r.tick_times.front() : 0;
  const kerf::client::Summary jitter = kerf::client::Summarize(periods);
  const kerf::client::Summary latency = kerf::client::Summarize(r.latencies);
  const kerf::client::Summary jumps = kerf::client::Summarize(r.force_jumps);
  std::printf(
      "force loop: %zu ticks in %.3f s, %.1f Hz; period jitter p50 %.1f us, p99 %.1f us, "
      "max %.1f us\n",
      r.tick_times.size(), span, span > 0 ? (r.tick_times.size() - 1) / span : 0.0, jitter.p50,
      jitter.p99, jitter.max);
  std::printf(
      "frames: %zu (%.1f per s), %llu missed; pose-to-frame latency p50 %.2f ms, p99 "
      "%.2f ms; %llu reconnects\n",
      r.frame_times.size(), span > 0 ? r.frame_times.size() / span : 0.0,
      static_cast<unsigned long long>(r.frames_missed), 1e3 * latency.p50, 1e3 * latency.p99,
      static_cast<unsigned long long>(r.reconnects));
  std::printf("force: largest %.3f N; jump between ticks mean %.5f N, p99 %.5f N, max %.5f N\n",
              r.largest_force, jumps.mean, jumps.p99, jumps.max);
  if (!absl::GetFlag(FLAGS_csv).empty()) {
    WriteCsv(absl::GetFlag(FLAGS_csv), r, options.loop_rate_hz);
  }
  if (!r.error.empty()) return Fail(1, r.error);
  return 0;
}
