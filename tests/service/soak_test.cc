// Soak: a real server on loopback, with clients that keep connecting, doing a little and
// disconnecting (observers at every level that leave early, cutters that cut and leave mid-cut,
// snapshots, sessions made and closed, wrong tokens) for KERF_SOAK_SECONDS (default 10). It
// passes when nothing crashed, every call ended with an expected status, the sessions kept
// ticking, and the memory in use did not grow from the first half of the run to the second. Run
// under AddressSanitizer (the asan build) it also finds leaks and memory errors.
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <fstream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/synchronization/mutex.h"
#include "absl/time/clock.h"
#include "kerf/v1/simulator.grpc.pb.h"
#include "service/grpc_server.h"
#include "service/session_registry.h"
#include "service/simulator_service.h"

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#include <sanitizer/allocator_interface.h>
#define KERF_ASAN 1
#endif
#endif

namespace kerf::service {
namespace {

// Under AddressSanitizer, the bytes allocated and not freed (its quarantine of freed memory
// would hide a trend in the resident size); otherwise the resident size of the process.
std::size_t MemoryInUse() {
#ifdef KERF_ASAN
  return __sanitizer_get_current_allocated_bytes();
#else
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmRSS:", 0) == 0) return 1024 * std::stoull(line.substr(6));  // kB
  }
  return 0;
#endif
}

double SoakSeconds() {
  const char* text = std::getenv("KERF_SOAK_SECONDS");
  return text != nullptr ? std::atof(text) : 10.0;
}

struct Tally {
  std::atomic<int> calls{0};
  std::atomic<int> unexpected{0};
  absl::Mutex mutex;
  std::string first_unexpected ABSL_GUARDED_BY(mutex);

  void Expect(bool ok, const std::string& what) {
    ++calls;
    if (ok) return;
    ++unexpected;
    absl::MutexLock lock(&mutex);
    if (first_unexpected.empty()) first_unexpected = what;
  }
};

kerf::v1::BladePose Pose(double time, double x) {
  kerf::v1::BladePose pose;
  pose.set_time(time);
  for (const double v : {x, 0.0115, -0.005}) pose.add_tip(v);
  for (const double v : {x, 0.0115, 0.025}) pose.add_heel(v);
  return pose;
}

// One client's visit: a fresh connection, one thing done (chosen by `kind`), then gone.
void Visit(int port, const std::vector<kerf::v1::CreateSessionResponse>& sessions, int kind,
           std::mt19937& random, Tally& tally) {
  auto stub = kerf::v1::Simulator::NewStub(
      grpc::CreateChannel(absl::StrCat("127.0.0.1:", port), grpc::InsecureChannelCredentials()));
  const kerf::v1::CreateSessionResponse& s = sessions[random() % sessions.size()];
  const std::string& id = s.session().session_id();
  switch (kind) {
    case 0: {  // an observer at a random level that leaves after a few frames
      grpc::ClientContext context;
      kerf::v1::ObserveRequest request;
      request.set_session_id(id);
      // bar-cantilever offers SURFACE and VOLUME
      request.set_level(random() % 2 == 0 ? kerf::v1::SURFACE : kerf::v1::VOLUME);
      request.set_token(s.observer_token());
      auto reader = stub->Observe(&context, request);
      kerf::v1::Frame frame;
      const int want = 1 + static_cast<int>(random() % 8);
      int got = 0;
      while (got < want && reader->Read(&frame)) ++got;
      context.TryCancel();
      while (reader->Read(&frame)) {
      }
      const grpc::Status status = reader->Finish();
      tally.Expect(got == want, absl::StrCat("observer got ", got, " of ", want,
                                             " frames: ", status.error_message()));
      break;
    }
    case 1: {  // a cutter that cuts part way (or all the way) and leaves
      grpc::ClientContext context;
      auto stream = stub->Cut(&context);
      kerf::v1::CutRequest start;
      start.mutable_start()->set_session_id(id);
      start.mutable_start()->set_token(s.cutter_token());
      start.mutable_start()->set_frame_rate_hz(100);
      stream->Write(start);
      const int poses = 1 + static_cast<int>(random() % 20);
      for (int k = 0; k < poses; ++k) {
        kerf::v1::CutRequest request;
        *request.mutable_pose() = Pose(0.01 * k, -0.005 + 0.002 * k);
        if (!stream->Write(request)) break;
      }
      kerf::v1::Frame frame;
      if (random() % 2 == 0) {  // leaves mid-cut
        stream->Read(&frame);
        context.TryCancel();
      } else {
        stream->WritesDone();
      }
      while (stream->Read(&frame)) {
      }
      const grpc::Status status = stream->Finish();
      // Another cutter may hold the blade (FAILED_PRECONDITION); a cancelled one is CANCELLED.
      tally.Expect(status.ok() || status.error_code() == grpc::StatusCode::CANCELLED ||
                       status.error_code() == grpc::StatusCode::FAILED_PRECONDITION,
                   absl::StrCat("cutter: ", status.error_code(), " ", status.error_message()));
      break;
    }
    case 2: {  // a snapshot
      grpc::ClientContext context;
      kerf::v1::GetSnapshotRequest request;
      request.set_session_id(id);
      request.set_level(kerf::v1::SURFACE);
      request.set_token(s.observer_token());
      kerf::v1::Frame frame;
      const grpc::Status status = stub->GetSnapshot(&context, request, &frame);
      tally.Expect(status.ok() && frame.keyframe(), "snapshot: " + status.error_message());
      break;
    }
    case 3: {  // a session made and closed
      kerf::v1::CreateSessionRequest request;
      request.set_scene_name("bar-cantilever");
      kerf::v1::CreateSessionResponse created;
      grpc::ClientContext context;
      grpc::Status status = stub->CreateSession(&context, request, &created);
      if (status.error_code() == grpc::StatusCode::RESOURCE_EXHAUSTED) {  // others at it too
        tally.Expect(true, "");
        break;
      }
      tally.Expect(status.ok(), "create: " + status.error_message());
      if (!status.ok()) break;
      kerf::v1::CloseSessionRequest close;
      close.set_session_id(created.session().session_id());
      close.set_token(created.cutter_token());
      kerf::v1::CloseSessionResponse closed;
      grpc::ClientContext close_context;
      status = stub->CloseSession(&close_context, close, &closed);
      tally.Expect(status.ok(), "close: " + status.error_message());
      break;
    }
    default: {  // a wrong token
      grpc::ClientContext context;
      kerf::v1::ObserveRequest request;
      request.set_session_id(id);
      request.set_level(kerf::v1::SURFACE);
      request.set_token("not-the-token");
      auto reader = stub->Observe(&context, request);
      kerf::v1::Frame frame;
      while (reader->Read(&frame)) {
      }
      const grpc::Status status = reader->Finish();
      tally.Expect(status.error_code() == grpc::StatusCode::PERMISSION_DENIED,
                   "wrong token: " + status.error_message());
    }
  }
}

TEST(Soak, ClientsComeAndGoWithoutCrashLeakOrGrowth) {
  RegistryOptions options;
  options.max_sessions = 8;
  SessionRegistry registry(options);
  SimulatorService service(&registry);
  ServerConfig config;
  config.listen = "127.0.0.1:0";
  absl::StatusOr<RunningServer> running = StartServer(config, &service);
  ASSERT_TRUE(running.ok()) << running.status();

  // Four long-lived sessions of a small bar, which the visitors share.
  std::vector<kerf::v1::CreateSessionResponse> sessions;
  {
    auto stub = kerf::v1::Simulator::NewStub(grpc::CreateChannel(
        absl::StrCat("127.0.0.1:", running->port), grpc::InsecureChannelCredentials()));
    for (int i = 0; i < 4; ++i) {
      kerf::v1::CreateSessionRequest request;
      request.set_scene_name("bar-cantilever");
      kerf::v1::CreateSessionResponse created;
      grpc::ClientContext context;
      ASSERT_TRUE(stub->CreateSession(&context, request, &created).ok());
      sessions.push_back(created);
    }
  }

  const double seconds = SoakSeconds();
  const absl::Time start = absl::Now(), end = start + absl::Seconds(seconds);
  Tally tally;
  std::atomic<bool> stop{false};
  std::vector<std::thread> clients;
  for (int c = 0; c < 6; ++c) {
    clients.emplace_back([&, c] {
      std::mt19937 random(c);
      while (!stop) Visit(running->port, sessions, static_cast<int>(random() % 5), random, tally);
    });
  }
  // The memory in use, sampled each half second; the first 20% of the run is warm-up.
  std::vector<std::pair<double, std::size_t>> samples;
  const auto simulated = [&] {
    std::vector<double> times;
    for (const auto& s : sessions) {
      times.push_back((*registry.Find(s.session().session_id()))->Info().simulation_time());
    }
    return times;
  };
  std::vector<double> halfway;
  while (absl::Now() < end) {
    absl::SleepFor(absl::Milliseconds(500));
    samples.emplace_back(absl::ToDoubleSeconds(absl::Now() - start), MemoryInUse());
    if (halfway.empty() && absl::Now() > start + absl::Seconds(seconds / 2)) halfway = simulated();
  }
  stop = true;
  for (std::thread& t : clients) t.join();

  {
    absl::MutexLock lock(&tally.mutex);
    EXPECT_EQ(tally.unexpected.load(), 0) << tally.first_unexpected;
  }
  EXPECT_GT(tally.calls.load(), static_cast<int>(10 * seconds));  // it did soak
  // The sessions kept ticking through it all (slower than real time under a sanitizer).
  const std::vector<double> at_end = simulated();
  ASSERT_EQ(halfway.size(), at_end.size());
  for (std::size_t i = 0; i < at_end.size(); ++i) {
    EXPECT_GT(at_end[i], halfway[i] + 0.1 * seconds / 2) << "session " << i;
  }
  // Flat: the median memory in use in the last 40% of the run is within 10% (and 4 MB) of the
  // median from 20% to 60%.
  const auto median_between = [&](double from, double to) {
    std::vector<std::size_t> in;
    for (const auto& [t, bytes] : samples) {
      if (t >= from * seconds && t < to * seconds) in.push_back(bytes);
    }
    std::sort(in.begin(), in.end());
    return in.empty() ? std::size_t{0} : in[in.size() / 2];
  };
  const std::size_t early = median_between(0.2, 0.6), late = median_between(0.6, 1.01);
  ASSERT_GT(early, 0u);
  std::printf("soak: %.0f s, %d calls, memory in use %.1f MB then %.1f MB\n", seconds,
              tally.calls.load(), early / 1e6, late / 1e6);
  EXPECT_LT(static_cast<double>(late),
            static_cast<double>(early) + std::max(0.1 * static_cast<double>(early), 4e6));

  registry.CloseAll(absl::UnavailableError("soak over"));
  running->server->Shutdown(std::chrono::system_clock::now() + std::chrono::seconds(2));
}

}  // namespace
}  // namespace kerf::service
