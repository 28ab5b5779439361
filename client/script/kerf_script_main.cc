// kerf-script: one scripted cut against a running kerf-server. Creates a session, watches it
// as a SURFACE observer, streams a blade path (the `kerf cut` JSON format) in real time as the
// cutter, and prints what it measured. Exits non-zero on any error.
#include <grpcpp/grpcpp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <thread>
#include <vector>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "absl/flags/usage.h"
#include "absl/strings/str_cat.h"
#include "absl/synchronization/mutex.h"
#include "absl/time/clock.h"
#include "common/blade_path_file.h"
#include "common/channel.h"
#include "common/latency_summary.h"
#include "common/pose_log.h"
#include "common/session_calls.h"
#include "kerf/v1/simulator.grpc.pb.h"

ABSL_FLAG(std::string, server, "127.0.0.1:50051", "the kerf-server to cut against, host:port");
ABSL_FLAG(std::string, scene, "", "embedded scene for the session (empty: the server's default)");
ABSL_FLAG(std::string, tls_ca, "",
          "PEM root certificate(s) to trust: connect with TLS (plaintext when empty)");
ABSL_FLAG(double, settle_seconds, 1.0,
          "how long to let the session's tissue settle (held and loaded) before cutting");
ABSL_FLAG(std::string, path, "", "blade path, JSON: {\"poses\": [{\"time\", \"tip\", \"heel\"}]}");

namespace {

int Fail(const std::string& what) {
  std::fprintf(stderr, "kerf-script: %s\n", what.c_str());
  return 1;
}

// Boundary triangles a SURFACE observer holds, and how many lie on a cut.
struct Surface {
  std::set<std::uint32_t> triangles, on_cut;
  void Apply(const kerf::v1::Frame& f) {
    if (f.keyframe()) triangles.clear(), on_cut.clear();
    for (const std::uint32_t id : f.removed_elements()) triangles.erase(id), on_cut.erase(id);
    for (int i = 0; i < f.added_elements_size(); ++i) {
      triangles.insert(f.added_elements(i));
      if (f.added_elements_on_cut()[i] != 0) on_cut.insert(f.added_elements(i));
    }
  }
};

}  // namespace

int main(int argc, char** argv) {
  absl::SetProgramUsageMessage("kerf-script --path=PATH.json [--server=HOST:PORT] [--scene=NAME]");
  absl::ParseCommandLine(argc, argv);
  const absl::StatusOr<kerf::v1::BladePath> read =
      kerf::client::ReadBladePath(absl::GetFlag(FLAGS_path));
  if (!read.ok()) return Fail(std::string(read.status().message()));
  const kerf::v1::BladePath& path = *read;
  absl::StatusOr<std::shared_ptr<grpc::Channel>> channel =
      kerf::client::OpenChannel(absl::GetFlag(FLAGS_server), absl::GetFlag(FLAGS_tls_ca));
  if (!channel.ok()) return Fail(std::string(channel.status().message()));
  auto stub = kerf::v1::Simulator::NewStub(*channel);
  const absl::StatusOr<kerf::v1::CreateSessionResponse> made =
      kerf::client::CreateSession(*stub, absl::GetFlag(FLAGS_scene));
  if (!made.ok()) return Fail(std::string(made.status().message()));
  const kerf::v1::CreateSessionResponse& created = *made;
  const kerf::v1::SessionInfo& info = created.session();

  // The observer.
  absl::Mutex mutex;
  Surface surface;
  std::size_t first_triangles = 0, observer_frames = 0;
  grpc::ClientContext observe_context;
  kerf::v1::ObserveRequest observe;
  observe.set_session_id(info.session_id());
  observe.set_level(kerf::v1::SURFACE);
  observe.set_token(created.observer_token());
  auto observer = stub->Observe(&observe_context, observe);
  std::thread watching([&] {
    kerf::v1::Frame frame;
    while (observer->Read(&frame)) {
      absl::MutexLock lock(&mutex);
      surface.Apply(frame);
      if (observer_frames++ == 0) first_triangles = surface.triangles.size();
    }
  });

  absl::SleepFor(absl::Seconds(absl::GetFlag(FLAGS_settle_seconds)));
  // The cutter: poses sent at their times, frames read on another thread.
  grpc::ClientContext cut_context;
  auto cut = stub->Cut(&cut_context);
  kerf::v1::CutRequest start;
  start.mutable_start()->set_session_id(info.session_id());
  start.mutable_start()->set_level(kerf::v1::FORCES);
  start.mutable_start()->set_token(created.cutter_token());
  cut->Write(start);
  kerf::client::PoseLog sent;
  std::vector<double> latencies_ms;
  std::size_t cutter_frames = 0;
  double largest_force = 0;
  std::thread reading([&] {
    kerf::v1::Frame frame;
    while (cut->Read(&frame)) {
      const auto answer = sent.Answered(frame.blade_time(), absl::Now());
      absl::MutexLock lock(&mutex);
      ++cutter_frames;
      const auto& f = frame.tool_force();
      largest_force =
          std::max(largest_force, std::sqrt(f.x() * f.x() + f.y() * f.y() + f.z() * f.z()));
      if (answer && answer->latency) {
        latencies_ms.push_back(absl::ToDoubleMilliseconds(*answer->latency));
      }
    }
  });
  const absl::Time begin = absl::Now();
  const double t0 = path.poses(0).time();
  for (int k = 0; k < path.poses_size(); ++k) {
    absl::SleepFor(begin + absl::Seconds(path.poses(k).time() - t0) - absl::Now());
    kerf::v1::CutRequest request;
    *request.mutable_pose() = path.poses(k);
    sent.Sent(request.pose(), absl::Now());
    if (!cut->Write(request)) break;
  }
  cut->WritesDone();
  reading.join();
  const grpc::Status cut_status = cut->Finish();
  absl::SleepFor(absl::Milliseconds(200));  // the cut opens; the observer sees it
  // Closing returns the session as it ended (and ends the observer's stream).
  const absl::StatusOr<kerf::v1::SessionInfo> after =
      kerf::client::CloseSession(*stub, info.session_id(), created.cutter_token());
  watching.join();
  if (!cut_status.ok()) return Fail(absl::StrCat("Cut: ", cut_status.error_message()));
  if (!after.ok()) return Fail(std::string(after.status().message()));

  absl::MutexLock lock(&mutex);
  const kerf::client::Summary latency = kerf::client::Summarize(latencies_ms);
  std::printf("session %s, scene %s: %u tets before the cut, %lu after\n",
              info.session_id().c_str(), info.scene_name().c_str(),
              static_cast<unsigned>(info.tets()), static_cast<unsigned long>(after->tets()));
  std::printf(
      "cutter: %d poses sent in %.2f s, %zu frames back, pose-to-frame latency p50 %.2f ms, "
      "p99 %.2f ms; largest tool force %.3f N\n",
      path.poses_size(), absl::ToDoubleSeconds(absl::Now() - begin), cutter_frames, latency.p50,
      latency.p99, largest_force);
  std::printf(
      "observer (SURFACE): %zu frames; %zu boundary triangles before, %zu after, "
      "%zu of them on the cut\n",
      observer_frames, first_triangles, surface.triangles.size(), surface.on_cut.size());
  return 0;
}
