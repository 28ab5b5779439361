#include "haptic/haptic_session.h"

#include <time.h>

#include <atomic>
#include <cmath>
#include <deque>
#include <optional>
#include <thread>

#include "absl/strings/str_cat.h"
#include "absl/synchronization/mutex.h"
#include "absl/time/clock.h"
#include "common/pose_log.h"

namespace kerf::client {
namespace {

// What the loop and the network hand each other.
struct Exchange {
  absl::Mutex mutex;
  std::optional<std::pair<double, BladeSample>> latest ABSL_GUARDED_BY(mutex);  // from the loop
  bool device_done ABSL_GUARDED_BY(mutex) = false;
  // Frames for the loop: when they may be used (arrival + any delay), the tip of the pose they
  // answer, the force.
  struct Arrival {
    double time;
    Eigen::Vector3d tip, force;
  };
  std::deque<Arrival> arrivals ABSL_GUARDED_BY(mutex);
};

double Seconds(const timespec& t) { return static_cast<double>(t.tv_sec) + 1e-9 * t.tv_nsec; }

timespec Now() {
  timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t;
}

void ForceLoop(HapticDevice& device, const HapticOptions& options, const timespec& start,
               const std::atomic<bool>& stop, Exchange& exchange, HapticRecord& record) {
  ForceModel model(options.force);
  const long period_ns = std::lround(1e9 / options.loop_rate_hz);
  timespec next = start;
  Eigen::Vector3d last_force = Eigen::Vector3d::Zero();
  std::vector<Exchange::Arrival> arrived;
  record.tick_times.reserve(static_cast<std::size_t>(options.loop_rate_hz * 60));
  for (;;) {
    const double t = Seconds(Now()) - Seconds(start);
    std::optional<BladeSample> sample =
        t < options.max_seconds && !stop ? device.Sample(t) : std::nullopt;
    if (exchange.mutex.TryLock()) {  // never waits: if the network holds it, next tick
      if (sample) {
        exchange.latest = {t, *sample};
      } else {
        exchange.device_done = true;
      }
      arrived.clear();
      while (!exchange.arrivals.empty() && exchange.arrivals.front().time <= t) {
        arrived.push_back(exchange.arrivals.front());
        exchange.arrivals.pop_front();
      }
      exchange.mutex.Unlock();
      for (const Exchange::Arrival& a : arrived) {
        if (sample) model.Update(t, a.tip, a.force, sample->tip);
      }
    }
    if (!sample) return;
    const Eigen::Vector3d force = model.At(t, sample->tip);
    device.Render(force);
    record.tick_times.push_back(t);
    if (record.tick_times.size() > 1) record.force_jumps.push_back((force - last_force).norm());
    record.largest_force = std::max(record.largest_force, force.norm());
    last_force = force;
    next.tv_nsec += period_ns;
    while (next.tv_nsec >= 1'000'000'000) {
      next.tv_nsec -= 1'000'000'000;
      ++next.tv_sec;
    }
    clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, nullptr);
  }
}

kerf::v1::CutRequest PoseRequest(double time, const BladeSample& s) {
  kerf::v1::CutRequest request;
  request.mutable_pose()->set_time(time);
  for (int k = 0; k < 3; ++k) request.mutable_pose()->add_tip(s.tip[k]);
  for (int k = 0; k < 3; ++k) request.mutable_pose()->add_heel(s.heel[k]);
  return request;
}

}  // namespace

HapticRecord RunHaptic(kerf::v1::Simulator::Stub& stub, HapticDevice& device,
                       const HapticOptions& options) {
  HapticRecord record;
  Exchange exchange;
  const timespec start = Now();
  const auto clock = [&] { return Seconds(Now()) - Seconds(start); };
  std::atomic<bool> stop_loop{false};
  std::thread loop([&] { ForceLoop(device, options, start, stop_loop, exchange, record); });

  PoseLog sent;
  std::vector<double> frame_times, latencies;
  std::uint64_t missed = 0;
  bool finished = false;
  int attempts = 0;
  absl::Duration backoff = absl::Milliseconds(100);
  while (!finished) {
    grpc::ClientContext context;
    auto stream = stub.Cut(&context);
    kerf::v1::CutRequest start_request;
    start_request.mutable_start()->set_session_id(options.session_id);
    start_request.mutable_start()->set_token(options.cutter_token);
    start_request.mutable_start()->set_level(kerf::v1::FORCES);
    start_request.mutable_start()->set_frame_rate_hz(options.cutter_frame_rate_hz);
    std::atomic<bool> got_frame{false};
    std::thread reader([&] {
      kerf::v1::Frame frame;
      std::uint64_t last = 0;
      while (stream->Read(&frame)) {
        got_frame = true;
        const double now = clock() + options.frame_delay_seconds;  // as if it came that late
        if (last != 0 && frame.sequence() > last + 1) missed += frame.sequence() - last - 1;
        last = frame.sequence();
        frame_times.push_back(now);
        const auto answer = sent.Answered(frame.blade_time(),
                                          absl::Now() + absl::Seconds(options.frame_delay_seconds));
        if (!answer) continue;  // no pose applied yet, or one not sent by this run
        if (answer->latency) latencies.push_back(absl::ToDoubleSeconds(*answer->latency));
        const auto& f = frame.tool_force();
        absl::MutexLock lock(&exchange.mutex);
        exchange.arrivals.push_back(
            {now, Eigen::Vector3d(answer->tip.data()), {f.x(), f.y(), f.z()}});
      }
    });
    bool wrote = stream->Write(start_request);
    // The session maps the first pose to its clock when it arrives: wait until the stream is
    // up (its first frame) so that poses are not held back while the connection is made.
    for (int i = 0; i < 500 && wrote && !got_frame; ++i) absl::SleepFor(absl::Milliseconds(10));
    double last_sent = -1;
    const absl::Duration pose_period = absl::Seconds(1 / options.pose_rate_hz);
    while (wrote) {
      std::optional<std::pair<double, BladeSample>> latest;
      bool done;
      {
        absl::MutexLock lock(&exchange.mutex);
        latest = exchange.latest;
        done = exchange.device_done;
      }
      if (latest && latest->first > last_sent) {
        const kerf::v1::CutRequest request = PoseRequest(latest->first, latest->second);
        sent.Sent(request.pose(), absl::Now());
        wrote = stream->Write(request);
        last_sent = latest->first;
      }
      if (done) break;
      absl::SleepFor(pose_period);
    }
    stream->WritesDone();
    reader.join();
    const grpc::Status status = stream->Finish();
    if (status.ok()) {
      finished = true;
    } else if (status.error_code() == grpc::StatusCode::UNAVAILABLE && attempts < 8) {
      if (got_frame) {
        attempts = 0;
        backoff = absl::Milliseconds(100);
      }
      ++attempts;
      ++record.reconnects;
      absl::SleepFor(backoff);
      backoff = std::min(2 * backoff, absl::Seconds(5));
    } else {
      record.error = absl::StrCat("Cut: ", status.error_code(), " ", status.error_message());
      finished = true;
    }
  }
  stop_loop = true;  // if the network ended first
  loop.join();
  record.frame_times = std::move(frame_times);
  record.latencies = std::move(latencies);
  record.frames_missed = missed;
  return record;
}

}  // namespace kerf::client
