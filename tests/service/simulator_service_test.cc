// The service end to end: a real gRPC server on loopback (ephemeral port) and real clients.
#include "service/simulator_service.h"

#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <set>
#include <thread>

#include "absl/synchronization/mutex.h"
#include "sim/scene.h"

namespace kerf::service {
namespace {

using kerf::v1::Frame;

// A 4 x 2 x 2 cm bar held at x = 0, offering every level. (No gravity: it would sag the free
// end onto the blade's tip, and this test is about the service, not about cutting.)
constexpr char kBarScene[] = R"pb(
  name: "test-bar"
  mesh {
    lattice {
      cells_x: 4
      cells_y: 2
      cells_z: 2
      size { x: 0.04 y: 0.02 z: 0.02 }
    }
  }
  material { youngs_modulus: 5000 poisson_ratio: 0.45 density: 1000 mass_damping: 20 }
  displacements {
    vertices {
      half_space {
        point { x: 0 }
        normal { x: -1 }
      }
    }
  }
)pb";

class Server {
 public:
  explicit Server(RegistryOptions options = {})
      : registry_(std::move(options)), service_(&registry_) {
    grpc::ServerBuilder builder;
    builder.AddListeningPort("127.0.0.1:0", grpc::InsecureServerCredentials(), &port_);
    builder.RegisterService(&service_);
    server_ = builder.BuildAndStart();
    channel_ =
        grpc::CreateChannel(absl::StrCat("127.0.0.1:", port_), grpc::InsecureChannelCredentials());
    stub_ = kerf::v1::Simulator::NewStub(channel_);
  }
  ~Server() {
    registry_.CloseAll(absl::UnavailableError("test over"));
    server_->Shutdown(std::chrono::system_clock::now() + std::chrono::seconds(2));
  }
  kerf::v1::Simulator::Stub& stub() { return *stub_; }

  kerf::v1::SessionInfo CreateBarSession() {
    kerf::v1::CreateSessionRequest request;
    *request.mutable_scene() = *sim::ParseSceneText(kBarScene, "test");
    kerf::v1::SessionInfo info;
    grpc::ClientContext context;
    const grpc::Status status = stub_->CreateSession(&context, request, &info);
    EXPECT_TRUE(status.ok()) << status.error_message();
    return info;
  }

 private:
  SessionRegistry registry_;
  SimulatorService service_;
  int port_ = 0;
  std::unique_ptr<grpc::Server> server_;
  std::shared_ptr<grpc::Channel> channel_;
  std::unique_ptr<kerf::v1::Simulator::Stub> stub_;
};

// What a client rebuilds from a keyframe and deltas.
struct View {
  std::set<std::uint32_t> vertices;
  std::map<std::uint32_t, std::vector<std::uint32_t>> elements;
  std::map<std::uint32_t, bool> on_cut;
  std::string positions, forces;
  std::uint64_t topology_version = 0;

  // Applies a frame; false (with a message) when it does not fit what came before.
  bool Apply(const Frame& f, std::string* error) {
    if (f.keyframe()) {
      vertices.clear();
      elements.clear();
      on_cut.clear();
    } else if (f.topology_version() != topology_version &&
               f.topology_version() != topology_version + 1) {
      *error = absl::StrCat("topology ", f.topology_version(), " after ", topology_version);
      return false;
    }
    topology_version = f.topology_version();
    for (const std::uint32_t v : f.removed_vertices()) vertices.erase(v);
    for (const std::uint32_t v : f.added_vertices()) vertices.insert(v);
    for (const std::uint32_t e : f.removed_elements()) {
      elements.erase(e);
      on_cut.erase(e);
    }
    const int corners = f.level() == kerf::v1::VOLUME ? 4 : 3;
    for (int i = 0; i < f.added_elements_size(); ++i) {
      elements[f.added_elements(i)] = {f.added_element_vertices().begin() + corners * i,
                                       f.added_element_vertices().begin() + corners * (i + 1)};
      if (f.level() == kerf::v1::SURFACE)
        on_cut[f.added_elements(i)] = f.added_elements_on_cut()[i];
    }
    positions = f.positions();
    forces = f.nodal_forces();
    const std::size_t bytes = 12 * vertices.size();
    if ((f.level() == kerf::v1::FORCES ? forces.size() : positions.size()) != bytes) {
      *error =
          absl::StrCat("array of ", positions.size(), " bytes for ", vertices.size(), " vertices");
      return false;
    }
    return true;
  }

  // Triangles as rotation-normalised triples with their cut flag (ids are the view's own).
  std::multiset<std::vector<std::uint32_t>> Triangles() const {
    std::multiset<std::vector<std::uint32_t>> out;
    for (const auto& [id, v] : elements) {
      std::vector<std::uint32_t> t = v;
      std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
      t.push_back(on_cut.count(id) ? on_cut.at(id) : 0);
      out.insert(t);
    }
    return out;
  }
};

// An observer on its own thread, keeping what it rebuilt at each sequence number.
class Observer {
 public:
  Observer(kerf::v1::Simulator::Stub& stub, const std::string& session, kerf::v1::Level level) {
    kerf::v1::ObserveRequest request;
    request.set_session_id(session);
    request.set_level(level);
    reader_ = stub.Observe(&context_, request);
    thread_ = std::thread([this] {
      Frame frame;
      View view;
      while (reader_->Read(&frame)) {
        std::string error;
        absl::MutexLock lock(&mutex_);
        if (!view.Apply(frame, &error)) errors_.push_back(error);
        if (frame.keyframe()) ++keyframes_;
        by_sequence_[frame.sequence()] = view;
        last_sequence_ = frame.sequence();
      }
      status_ = reader_->Finish();
    });
  }
  ~Observer() { Stop(); }
  void Stop() {
    context_.TryCancel();
    if (thread_.joinable()) thread_.join();
  }
  // Waits until a frame with at least this sequence came; the view at exactly it.
  std::optional<View> At(std::uint64_t sequence) {
    absl::MutexLock lock(&mutex_);
    mutex_.AwaitWithTimeout(absl::Condition(
                                +[](Observer* o) { return o->last_sequence_ >= o->wanted_; }, this),
                            absl::Seconds(10));
    (void)sequence;
    const auto it = by_sequence_.find(sequence);
    if (it == by_sequence_.end()) return std::nullopt;
    return it->second;
  }
  void Want(std::uint64_t sequence) {
    absl::MutexLock lock(&mutex_);
    wanted_ = sequence;
  }
  std::vector<std::string> errors() {
    absl::MutexLock lock(&mutex_);
    return errors_;
  }
  int keyframes() {
    absl::MutexLock lock(&mutex_);
    return keyframes_;
  }

 private:
  grpc::ClientContext context_;
  std::unique_ptr<grpc::ClientReader<Frame>> reader_;
  std::thread thread_;
  absl::Mutex mutex_;
  std::map<std::uint64_t, View> by_sequence_;
  std::uint64_t last_sequence_ = 0;
  std::uint64_t wanted_ = std::numeric_limits<std::uint64_t>::max();
  std::vector<std::string> errors_;
  int keyframes_ = 0;
  grpc::Status status_;
};

kerf::v1::BladePose Pose(double time, double y) {
  kerf::v1::BladePose pose;
  pose.set_time(time);
  for (const double c : {0.0237, y, -0.005}) pose.add_tip(c);
  for (const double c : {0.0237, y, 0.025}) pose.add_heel(c);
  return pose;
}

// Streams a straight cut across the bar at x = 23.7 mm, 2 mm per pose, 100 poses per second.
grpc::Status CutAcross(kerf::v1::Simulator::Stub& stub, const std::string& session, int* frames) {
  grpc::ClientContext context;
  auto stream = stub.Cut(&context);
  kerf::v1::CutRequest start;
  start.mutable_start()->set_session_id(session);
  start.mutable_start()->set_level(kerf::v1::FORCES);
  start.mutable_start()->set_frame_rate_hz(100);
  stream->Write(start);
  for (int k = 0; k <= 15; ++k) {
    kerf::v1::CutRequest request;
    *request.mutable_pose() = Pose(0.01 * k, -0.005 + 0.002 * k);
    stream->Write(request);
  }
  stream->WritesDone();
  Frame frame;
  while (stream->Read(&frame)) {
    ++*frames;
  }
  return stream->Finish();
}

TEST(SimulatorService, ObserversAtEveryLevelRebuildWhatTheSnapshotShows) {
  Server server;
  const kerf::v1::SessionInfo info = server.CreateBarSession();
  ASSERT_FALSE(info.session_id().empty());
  EXPECT_EQ(info.tets(), 4u * 2 * 2 * 6);
  std::vector<std::unique_ptr<Observer>> observers;
  const kerf::v1::Level levels[] = {kerf::v1::SURFACE, kerf::v1::VOLUME, kerf::v1::FORCES};
  for (const kerf::v1::Level level : levels) {
    for (int i = 0; i < 3; ++i) {
      observers.push_back(std::make_unique<Observer>(server.stub(), info.session_id(), level));
    }
  }
  int cutter_frames = 0;
  const grpc::Status cut = CutAcross(server.stub(), info.session_id(), &cutter_frames);
  ASSERT_TRUE(cut.ok()) << cut.error_message();
  EXPECT_GT(cutter_frames, 5);
  absl::SleepFor(absl::Milliseconds(100));  // the blade is withdrawn, the cut opens
  for (int l = 0; l < 3; ++l) {
    kerf::v1::GetSnapshotRequest request;
    request.set_session_id(info.session_id());
    request.set_level(levels[l]);
    Frame snapshot;
    grpc::ClientContext context;
    ASSERT_TRUE(server.stub().GetSnapshot(&context, request, &snapshot).ok());
    View expected;
    std::string error;
    ASSERT_TRUE(expected.Apply(snapshot, &error)) << error;
    if (levels[l] == kerf::v1::VOLUME) {
      EXPECT_GT(expected.elements.size(), info.tets());  // the cut made tets
    }
    if (levels[l] == kerf::v1::SURFACE) {
      int cut_faces = 0;
      for (const auto& [id, on_cut] : expected.on_cut) cut_faces += on_cut;
      EXPECT_GT(cut_faces, 0);  // the cut's faces are marked
    }
    for (int i = 0; i < 3; ++i) {
      Observer& observer = *observers[3 * l + i];
      observer.Want(snapshot.sequence());
      const std::optional<View> seen = observer.At(snapshot.sequence());
      ASSERT_TRUE(seen.has_value()) << "level " << levels[l] << " observer " << i;
      EXPECT_TRUE(observer.errors().empty()) << observer.errors().front();
      EXPECT_EQ(seen->vertices, expected.vertices);
      EXPECT_EQ(seen->positions, expected.positions);
      EXPECT_EQ(seen->forces, expected.forces);
      if (levels[l] == kerf::v1::VOLUME) {
        EXPECT_EQ(seen->elements, expected.elements);
      }
      if (levels[l] == kerf::v1::SURFACE) {
        EXPECT_EQ(seen->Triangles(), expected.Triangles());
      }
    }
  }
}

TEST(SimulatorService, BadInputGetsAClearErrorAndTheSessionGoesOn) {
  Server server;
  const kerf::v1::SessionInfo info = server.CreateBarSession();
  {  // unknown session
    kerf::v1::GetSnapshotRequest request;
    request.set_session_id("nope");
    request.set_level(kerf::v1::SURFACE);
    Frame frame;
    grpc::ClientContext context;
    const grpc::Status status = server.stub().GetSnapshot(&context, request, &frame);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::NOT_FOUND);
    EXPECT_EQ(status.error_message(), "no session 'nope'");
  }
  {  // unknown scene
    kerf::v1::CreateSessionRequest request;
    request.set_scene_name("liver-of-nobody");
    kerf::v1::SessionInfo created;
    grpc::ClientContext context;
    const grpc::Status status = server.stub().CreateSession(&context, request, &created);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::NOT_FOUND);
  }
  {  // a malformed scene
    kerf::v1::CreateSessionRequest request;
    *request.mutable_scene() = *sim::ParseSceneText(kBarScene, "test");
    request.mutable_scene()->mutable_material()->set_poisson_ratio(0.7);
    kerf::v1::SessionInfo created;
    grpc::ClientContext context;
    const grpc::Status status = server.stub().CreateSession(&context, request, &created);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
    EXPECT_NE(status.error_message().find("poisson_ratio"), std::string::npos)
        << status.error_message();
  }
  {  // a NaN pose ends the cut stream with INVALID_ARGUMENT
    grpc::ClientContext context;
    auto stream = server.stub().Cut(&context);
    kerf::v1::CutRequest start;
    start.mutable_start()->set_session_id(info.session_id());
    stream->Write(start);
    kerf::v1::CutRequest bad;
    *bad.mutable_pose() = Pose(0, std::nan(""));
    stream->Write(bad);
    stream->WritesDone();
    Frame frame;
    while (stream->Read(&frame)) {
    }
    const grpc::Status status = stream->Finish();
    EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  }
  // The session is unharmed: a proper cut follows.
  int frames = 0;
  EXPECT_TRUE(CutAcross(server.stub(), info.session_id(), &frames).ok());
  EXPECT_GT(frames, 0);
}

TEST(SimulatorService, LimitsAreResourceExhausted) {
  RegistryOptions options;
  options.max_sessions = 1;
  Server server(options);
  server.CreateBarSession();
  kerf::v1::CreateSessionRequest request;
  *request.mutable_scene() = *sim::ParseSceneText(kBarScene, "test");
  kerf::v1::SessionInfo created;
  grpc::ClientContext context;
  EXPECT_EQ(server.stub().CreateSession(&context, request, &created).error_code(),
            grpc::StatusCode::RESOURCE_EXHAUSTED);
}

}  // namespace
}  // namespace kerf::service
