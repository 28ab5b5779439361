// The service's speed on loopback, in one run: a bare gRPC echo stream (the baseline), then
// pose-to-frame latency and frame rates with one cutter and 1, 4 and 16 observers, and the
// bytes of a frame at each level against a keyframe.
//
// Each benchmark is one run (Iterations(1)) of a real server on 127.0.0.1 and real clients;
// the figures are counters: latency percentiles in microseconds, frames per second, bytes.
#include <benchmark/benchmark.h>
#include <grpcpp/grpcpp.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <thread>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/synchronization/mutex.h"
#include "absl/time/clock.h"
#include "service/echo.grpc.pb.h"
#include "service/grpc_server.h"
#include "service/session_registry.h"
#include "service/simulator_service.h"
#include "sim/scene.h"

namespace kerf::service {
namespace {

using kerf::v1::Frame;

double Percentile(std::vector<double> values, double p) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const auto i = static_cast<std::size_t>(p * static_cast<double>(values.size() - 1));
  return values[i];
}

class EchoService final : public kerf::test::Echo::CallbackService {
  grpc::ServerBidiReactor<kerf::test::EchoMessage, kerf::test::EchoMessage>* Stream(
      grpc::CallbackServerContext*) override {
    class Reactor final
        : public grpc::ServerBidiReactor<kerf::test::EchoMessage, kerf::test::EchoMessage> {
     public:
      Reactor() { StartRead(&message_); }
      void OnReadDone(bool ok) override {
        if (!ok) {
          Finish(grpc::Status::OK);
          return;
        }
        StartWrite(&message_);
      }
      void OnWriteDone(bool ok) override {
        if (ok) StartRead(&message_);
      }
      void OnDone() override { delete this; }

     private:
      kerf::test::EchoMessage message_;
    };
    return new Reactor;
  }
};

// A message about the size of a blade pose, bounced 2,000 times, one in flight.
void BM_EchoRoundTrip(benchmark::State& state) {
  EchoService service;
  absl::StatusOr<RunningServer> server = StartServer(LoopbackConfig(), &service);
  auto stub = kerf::test::Echo::NewStub(grpc::CreateChannel(
      absl::StrCat("127.0.0.1:", server->port), grpc::InsecureChannelCredentials()));
  std::vector<double> round_trips;
  for (auto _ : state) {
    grpc::ClientContext context;
    auto stream = stub->Stream(&context);
    kerf::test::EchoMessage message, reply;
    message.set_payload(std::string(64, 'p'));
    for (int i = 0; i < 2000; ++i) {
      const absl::Time start = absl::Now();
      stream->Write(message);
      stream->Read(&reply);
      round_trips.push_back(absl::ToDoubleMicroseconds(absl::Now() - start));
    }
    stream->WritesDone();
    (void)stream->Finish();
  }
  state.counters["p50_us"] = Percentile(round_trips, 0.5);
  state.counters["p99_us"] = Percentile(round_trips, 0.99);
  state.counters["max_us"] = Percentile(round_trips, 1.0);
  server->server->Shutdown();
}

// The default scene (the paper's tensioned 4x6x4 lattice) offering every level.
kerf::v1::Scene LatticeScene() {
  kerf::v1::Scene scene =
      *sim::ParseSceneText(*sim::EmbeddedSceneText("lattice-tension"), "lattice-tension");
  scene.clear_needs();
  return scene;
}

struct ObserverTally {
  kerf::v1::Level level;
  std::atomic<std::int64_t> frames{0}, delta_bytes{0}, deltas{0}, keyframe_bytes{0};
};

// One cutter streams a pose every millisecond for 2 s (a blade 4.5 cm long crossing the
// lattice at 25 mm/s) and takes a frame after every physics tick; `observers` observers take
// frames at 60 Hz, cycling through SURFACE, VOLUME and FORCES. With `journal` 1 the session
// journals every pose to a file (in the temporary directory); with `deferred` 1 the scene cuts
// deferred (and so integrates explicitly) instead of progressively, the default; with
// `guard_off` 1 it cuts progressively with no height guard (cutting.min_temporary_height 0).
void BM_PoseToFrame(benchmark::State& state) {
  const int observer_count = static_cast<int>(state.range(0));
  RegistryOptions options;
  if (state.range(1) != 0) {
    options.journal_dir = absl::StrCat(std::filesystem::temp_directory_path().string(),
                                       "/kerf-benchmark-journal-", getpid());
    std::filesystem::create_directories(options.journal_dir);
  }
  SessionRegistry registry(options);
  SimulatorService service(&registry);
  absl::StatusOr<RunningServer> server = StartServer(LoopbackConfig(), &service);
  auto channel = grpc::CreateChannel(absl::StrCat("127.0.0.1:", server->port),
                                     grpc::InsecureChannelCredentials());
  auto stub = kerf::v1::Simulator::NewStub(channel);
  std::vector<double> latencies, tick_seconds;
  std::int64_t cutter_frames = 0;
  double seconds = 0;
  std::vector<std::unique_ptr<ObserverTally>> tallies;
  for (auto _ : state) {
    kerf::v1::CreateSessionRequest create;
    *create.mutable_scene() = LatticeScene();
    if (state.range(2) != 0) {
      create.mutable_scene()->mutable_cutting()->set_mode(kerf::v1::Cutting::DEFERRED);
    }
    if (state.range(3) != 0) create.mutable_scene()->mutable_cutting()->set_min_temporary_height(0);
    kerf::v1::CreateSessionResponse created;
    {
      grpc::ClientContext context;
      if (!stub->CreateSession(&context, create, &created).ok()) {
        state.SkipWithError("CreateSession failed");
        return;
      }
    }
    const kerf::v1::Level levels[] = {kerf::v1::SURFACE, kerf::v1::VOLUME, kerf::v1::FORCES};
    std::vector<std::unique_ptr<grpc::ClientContext>> contexts;
    std::vector<std::thread> threads;
    for (int i = 0; i < observer_count; ++i) {
      tallies.push_back(std::make_unique<ObserverTally>());
      ObserverTally* tally = tallies.back().get();
      tally->level = levels[i % 3];
      contexts.push_back(std::make_unique<grpc::ClientContext>());
      grpc::ClientContext* context = contexts.back().get();
      threads.emplace_back([&, tally, context] {
        kerf::v1::ObserveRequest request;
        request.set_session_id(created.session().session_id());
        request.set_level(tally->level);
        request.set_token(created.observer_token());
        auto reader = stub->Observe(context, request);
        Frame frame;
        while (reader->Read(&frame)) {
          ++tally->frames;
          const auto bytes = static_cast<std::int64_t>(frame.ByteSizeLong());
          if (frame.keyframe()) {
            tally->keyframe_bytes = bytes;
          } else {
            tally->delta_bytes += bytes;
            ++tally->deltas;
          }
        }
        (void)reader->Finish();
      });
    }
    // The cutter.
    constexpr int kPoses = 2000;
    std::vector<absl::Time> sent(kPoses + 1);
    absl::Mutex mutex;
    grpc::ClientContext cut_context;
    auto stream = stub->Cut(&cut_context);
    kerf::v1::CutRequest start;
    start.mutable_start()->set_session_id(created.session().session_id());
    start.mutable_start()->set_level(kerf::v1::FORCES);
    start.mutable_start()->set_token(created.cutter_token());
    stream->Write(start);
    std::thread reader([&] {
      Frame frame;
      int seen = -1;
      while (stream->Read(&frame)) {
        const absl::Time now = absl::Now();
        ++cutter_frames;
        tick_seconds.push_back(frame.statistics().physics_step_seconds());
        const int pose = static_cast<int>(std::lround(frame.blade_time() * 1000));
        if (frame.blade_time() > 0 && pose > seen && pose <= kPoses) {
          seen = pose;
          absl::MutexLock lock(&mutex);
          latencies.push_back(absl::ToDoubleMicroseconds(now - sent[pose]));
        }
      }
    });
    const absl::Time begin = absl::Now();
    for (int k = 1; k <= kPoses; ++k) {
      const double t = 0.001 * k;
      kerf::v1::CutRequest request;
      request.mutable_pose()->set_time(t);
      const double x = -0.005 + 0.025 * t;
      for (const double c : {x, 0.0385, -0.005}) request.mutable_pose()->add_tip(c);
      for (const double c : {x, 0.0385, 0.04}) request.mutable_pose()->add_heel(c);
      absl::SleepFor(begin + absl::Seconds(t) - absl::Now());
      {
        absl::MutexLock lock(&mutex);
        sent[k] = absl::Now();
      }
      stream->Write(request);
    }
    stream->WritesDone();
    reader.join();
    seconds = absl::ToDoubleSeconds(absl::Now() - begin);
    (void)stream->Finish();
    for (auto& context : contexts) context->TryCancel();
    for (std::thread& t : threads) t.join();
  }
  state.counters["pose_to_frame_p50_us"] = Percentile(latencies, 0.5);
  state.counters["pose_to_frame_p99_us"] = Percentile(latencies, 0.99);
  state.counters["cutter_fps"] = static_cast<double>(cutter_frames) / seconds;
  state.counters["physics_tick_p50_us"] = 1e6 * Percentile(tick_seconds, 0.5);
  state.counters["physics_tick_p99_us"] = 1e6 * Percentile(tick_seconds, 0.99);
  double observer_frames = 0;
  for (const auto& tally : tallies) observer_frames += static_cast<double>(tally->frames);
  if (observer_count > 0) {
    state.counters["observer_fps"] = observer_frames / observer_count / seconds;
  }
  for (const kerf::v1::Level level : {kerf::v1::SURFACE, kerf::v1::VOLUME, kerf::v1::FORCES}) {
    for (const auto& tally : tallies) {
      if (tally->level != level || tally->deltas == 0) continue;
      const std::string name = kerf::v1::Level_Name(level);
      state.counters[name + "_keyframe_bytes"] = static_cast<double>(tally->keyframe_bytes);
      state.counters[name + "_delta_bytes"] =
          static_cast<double>(tally->delta_bytes) / static_cast<double>(tally->deltas);
      break;
    }
  }
  registry.CloseAll(absl::UnavailableError("benchmark over"));
  server->server->Shutdown();
  if (!options.journal_dir.empty()) std::filesystem::remove_all(options.journal_dir);
}

BENCHMARK(BM_EchoRoundTrip)->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_PoseToFrame)
    ->Args({1, 0, 0, 0})
    ->Args({1, 1, 0, 0})
    ->Args({4, 0, 0, 0})
    ->Args({16, 0, 0, 0})
    ->Args({1, 0, 1, 0})
    ->Args({16, 0, 1, 0})
    ->Args({1, 0, 0, 1})
    ->ArgNames({"observers", "journal", "deferred", "guard_off"})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace kerf::service

BENCHMARK_MAIN();
