#include "load/load_run.h"

#include <cmath>
#include <memory>
#include <thread>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/synchronization/mutex.h"
#include "absl/time/clock.h"
#include "common/channel.h"
#include "common/latency_summary.h"
#include "common/pose_log.h"
#include "common/session_calls.h"
#include "kerf/v1/simulator.grpc.pb.h"

namespace kerf::client {
namespace {

constexpr std::size_t kErrorSamples = 5;

// What every client thread adds to, under one lock (taken per frame: cheap next to a frame).
struct Tally {
  absl::Mutex mutex;
  std::vector<double> latencies_ms ABSL_GUARDED_BY(mutex);
  std::vector<double> frame_ages_ms ABSL_GUARDED_BY(mutex);
  std::uint64_t cutter_frames ABSL_GUARDED_BY(mutex) = 0;
  std::uint64_t observer_frames ABSL_GUARDED_BY(mutex) = 0;
  std::uint64_t gaps ABSL_GUARDED_BY(mutex) = 0;
  std::uint64_t resyncs ABSL_GUARDED_BY(mutex) = 0;
  std::vector<std::string> error_samples ABSL_GUARDED_BY(mutex);

  void Error(LoadProgress* progress, const std::string& what) {
    ++progress->errors;
    absl::MutexLock lock(&mutex);
    if (error_samples.size() < kErrorSamples) error_samples.push_back(what);
  }
};

struct SessionClients {
  kerf::v1::CreateSessionResponse created;
  kerf::v1::SessionInfo final_info;
};

std::unique_ptr<kerf::v1::Simulator::Stub> Connect(const LoadTarget& target) {
  absl::StatusOr<std::shared_ptr<grpc::Channel>> channel =
      OpenChannel(target.server, target.tls_ca, /*own_connection=*/true);
  return channel.ok() ? kerf::v1::Simulator::NewStub(*channel) : nullptr;
}

// An observer: counts frames, gaps in the sequence, resyncs and frame ages until the stream
// ends (CANCELLED when its session is closed at the end of the run: not an error).
void Observe(const LoadTarget& target, const kerf::v1::CreateSessionResponse& session,
             kerf::v1::Level level, Tally& tally, LoadProgress* progress) {
  auto stub = Connect(target);
  kerf::v1::ObserveRequest request;
  request.set_session_id(session.session().session_id());
  request.set_level(level);
  request.set_token(session.observer_token());
  grpc::ClientContext context;
  auto reader = stub->Observe(&context, request);
  kerf::v1::Frame frame;
  std::uint64_t last = 0, frames = 0;
  while (reader->Read(&frame)) {
    const double age_ms =
        static_cast<double>(absl::ToUnixNanos(absl::Now()) - frame.send_time_unix_nanos()) / 1e6;
    ++progress->frames;
    absl::MutexLock lock(&tally.mutex);
    ++tally.observer_frames;
    tally.frame_ages_ms.push_back(age_ms);
    if (frame.keyframe() && frames > 0) ++tally.resyncs;
    if (!frame.keyframe() && frames > 0 && frame.sequence() > last + 1) {
      tally.gaps += frame.sequence() - last - 1;
    }
    last = frame.sequence();
    ++frames;
  }
  const grpc::Status status = reader->Finish();
  if (!status.ok() && status.error_code() != grpc::StatusCode::CANCELLED) {
    tally.Error(progress,
                absl::StrCat("observer: ", status.error_code(), " ", status.error_message()));
  }
}

// One pass of the path as the session's cutter; false when the run must stop.
bool CutOnce(kerf::v1::Simulator::Stub& stub, const kerf::v1::CreateSessionResponse& session,
             const kerf::v1::LoadScenario& scenario, const kerf::v1::BladePath& path,
             const std::atomic<bool>& stop, std::atomic<std::uint64_t>& budget, Tally& tally,
             LoadProgress* progress) {
  grpc::ClientContext context;
  auto stream = stub.Cut(&context);
  kerf::v1::CutRequest start;
  start.mutable_start()->set_session_id(session.session().session_id());
  start.mutable_start()->set_token(session.cutter_token());
  start.mutable_start()->set_level(kerf::v1::FORCES);
  start.mutable_start()->set_frame_rate_hz(scenario.cutter_frame_rate_hz());
  if (!stream->Write(start)) return false;
  PoseLog sent;  // this pass's: a frame still showing the last pass's pose answers none
  std::atomic<bool> got_frame{false};
  std::thread reader([&] {
    kerf::v1::Frame frame;
    while (stream->Read(&frame)) {
      got_frame = true;
      const auto answer = sent.Answered(frame.blade_time(), absl::Now());
      ++progress->frames;
      absl::MutexLock lock(&tally.mutex);
      ++tally.cutter_frames;
      if (answer && answer->latency) {
        tally.latencies_ms.push_back(absl::ToDoubleMilliseconds(*answer->latency));
      }
    }
  });
  // The session maps the first pose to its clock when it arrives: wait until the stream is up
  // (its first frame) so that poses are not held back while a connection is made.
  for (int i = 0; i < 500 && !got_frame && !stop; ++i) absl::SleepFor(absl::Milliseconds(10));
  const absl::Time begin = absl::Now();
  const double t0 = path.poses(0).time();
  bool go_on = true;
  for (int k = 0; k < path.poses_size(); ++k) {
    absl::SleepFor(begin + absl::Seconds(path.poses(k).time() - t0) - absl::Now());
    std::uint64_t left = budget.load();
    while (left > 0 && !budget.compare_exchange_weak(left, left - 1)) {
    }
    if (stop || left == 0) {
      go_on = false;
      break;
    }
    kerf::v1::CutRequest request;
    *request.mutable_pose() = path.poses(k);
    sent.Sent(request.pose(), absl::Now());
    if (!stream->Write(request)) break;
    ++progress->poses_sent;
  }
  stream->WritesDone();
  reader.join();
  const grpc::Status status = stream->Finish();
  if (!status.ok()) {
    tally.Error(progress,
                absl::StrCat("cutter: ", status.error_code(), " ", status.error_message()));
    return !stop;
  }
  return go_on;
}

}  // namespace

absl::StatusOr<kerf::v1::LoadReport> RunLoad(const LoadTarget& target,
                                             const kerf::v1::LoadScenario& scenario,
                                             const kerf::v1::BladePath& path,
                                             LoadProgress* progress) {
  if (scenario.sessions() == 0 || scenario.sessions() > 64 ||
      scenario.observers_per_session() > 256) {
    return absl::InvalidArgumentError(
        absl::StrCat("sessions must be 1 to 64 and observers per session at most 256; got ",
                     scenario.sessions(), " and ", scenario.observers_per_session()));
  }
  if (!(scenario.duration_seconds() > 0 && scenario.duration_seconds() <= 3600)) {
    return absl::InvalidArgumentError(
        absl::StrCat("duration_seconds must be in (0, 3600], got ", scenario.duration_seconds()));
  }
  auto stub = Connect(target);
  if (stub == nullptr) return absl::InvalidArgumentError("cannot open a channel");
  std::vector<SessionClients> sessions(scenario.sessions());
  for (SessionClients& s : sessions) {
    absl::StatusOr<kerf::v1::CreateSessionResponse> created =
        CreateSession(*stub, scenario.scene_name());
    if (!created.ok()) {
      for (SessionClients& made : sessions) {  // leave nothing behind
        if (made.created.session().session_id().empty()) break;
        (void)CloseSession(*stub, made.created.session().session_id(), made.created.cutter_token());
      }
      return absl::UnavailableError(created.status().message());
    }
    s.created = *std::move(created);
  }

  Tally tally;
  std::vector<std::thread> observers, cutters;
  for (const SessionClients& s : sessions) {
    for (std::uint32_t m = 0; m < scenario.observers_per_session(); ++m) {
      const kerf::v1::Level level =
          scenario.levels().empty()
              ? kerf::v1::SURFACE
              : static_cast<kerf::v1::Level>(scenario.levels(m % scenario.levels_size()));
      observers.emplace_back([&, level] { Observe(target, s.created, level, tally, progress); });
    }
  }
  const absl::Time begin = absl::Now();
  absl::SleepFor(absl::Seconds(scenario.settle_seconds()));
  std::atomic<bool> stop{false};
  std::atomic<std::uint64_t> budget{scenario.max_requests() == 0 ? ~std::uint64_t{0} >> 1
                                                                 : scenario.max_requests()};
  for (const SessionClients& s : sessions) {
    cutters.emplace_back([&] {
      auto cutter = Connect(target);
      while (CutOnce(*cutter, s.created, scenario, path, stop, budget, tally, progress)) {
      }
    });
  }
  while (absl::Now() < begin + absl::Seconds(scenario.duration_seconds()) && budget.load() > 0) {
    absl::SleepFor(absl::Milliseconds(20));
  }
  stop = true;
  for (std::thread& t : cutters) t.join();
  const double seconds = absl::ToDoubleSeconds(absl::Now() - begin);
  // Closing a session ends its observers' streams after the frames already on their way.
  kerf::v1::LoadReport report;
  for (SessionClients& s : sessions) {
    const absl::StatusOr<kerf::v1::SessionInfo> closed =
        CloseSession(*stub, s.created.session().session_id(), s.created.cutter_token());
    if (!closed.ok()) {
      tally.Error(progress, std::string(closed.status().message()));
      continue;
    }
    report.set_server_poses_received(report.server_poses_received() + closed->poses_received());
    report.set_server_observer_frames_sent(report.server_observer_frames_sent() +
                                           closed->observer_frames_sent());
  }
  for (std::thread& t : observers) t.join();

  absl::MutexLock lock(&tally.mutex);
  const std::uint32_t observer_count = scenario.sessions() * scenario.observers_per_session();
  report.set_sessions(scenario.sessions());
  report.set_observers(observer_count);
  report.set_seconds(seconds);
  report.set_poses_sent(progress->poses_sent.load());
  report.set_cutter_frames(tally.cutter_frames);
  report.set_observer_frames(tally.observer_frames);
  const double cutting_seconds = std::max(1e-9, seconds - scenario.settle_seconds());
  report.set_cutter_fps(static_cast<double>(tally.cutter_frames) / scenario.sessions() /
                        cutting_seconds);
  if (observer_count > 0) {
    report.set_observer_fps(static_cast<double>(tally.observer_frames) / observer_count / seconds);
  }
  const Summary latency = Summarize(tally.latencies_ms);
  report.set_latency_p50_ms(latency.p50);
  report.set_latency_p90_ms(latency.p90);
  report.set_latency_p99_ms(latency.p99);
  report.set_latency_max_ms(latency.max);
  report.set_frame_age_p99_ms(Summarize(tally.frame_ages_ms).p99);
  report.set_sequence_gaps(tally.gaps);
  report.set_resyncs(tally.resyncs);
  report.set_errors(progress->errors.load());
  for (const std::string& e : tally.error_samples) report.add_error_samples(e);
  return report;
}

void CheckObjective(const kerf::v1::LoadObjective& objective, kerf::v1::LoadReport* report) {
  report->clear_objective_missed();
  if (objective.max_latency_p99_ms() > 0 &&
      report->latency_p99_ms() > objective.max_latency_p99_ms()) {
    report->add_objective_missed(absl::StrFormat(
        "latency p99 %.2f ms > %.2f ms", report->latency_p99_ms(), objective.max_latency_p99_ms()));
  }
  if (objective.min_observer_fps() > 0 && report->observer_fps() < objective.min_observer_fps()) {
    report->add_objective_missed(absl::StrFormat("observer fps %.1f < %.1f", report->observer_fps(),
                                                 objective.min_observer_fps()));
  }
  if ((objective.no_errors() || objective.max_errors() > 0) &&
      report->errors() > objective.max_errors()) {
    report->add_objective_missed(
        absl::StrFormat("errors %d > %d", report->errors(), objective.max_errors()));
  }
  report->set_objective_met(report->objective_missed().empty());
}

}  // namespace kerf::client
