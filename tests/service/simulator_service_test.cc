// The service end to end: a real gRPC server on loopback (ephemeral port) and real clients.
#include "service/simulator_service.h"

#include <grpcpp/generic/generic_stub.h>
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <set>
#include <thread>

#include "absl/strings/escaping.h"
#include "absl/synchronization/mutex.h"
#include "absl/synchronization/notification.h"
#include "service/grpc_server.h"
#include "service/session_tokens.h"
#include "service/sha256.h"
#include "sim/scene.h"
#include "support/service_bar.h"

namespace kerf::service {
namespace {

using kerf::v1::Frame;

constexpr const char* kBarScene = kerf::testing::kServiceBarScene;

// The tokens of the sessions the tests made, by session id.
struct Tokens {
  std::string cutter, observer;
};
Tokens& TokensOf(const std::string& session) {
  static absl::Mutex mutex(absl::kConstInit);
  static auto* tokens = new std::map<std::string, Tokens>;
  absl::MutexLock lock(&mutex);
  return (*tokens)[session];
}

class Server {
 public:
  explicit Server(RegistryOptions options = {})
      : registry_(std::move(options)), service_(&registry_) {
    absl::StatusOr<RunningServer> running = StartServer(LoopbackConfig(), &service_);
    EXPECT_TRUE(running.ok()) << running.status();
    server_ = std::move(running->server);
    port_ = running->port;
    channel_ =
        grpc::CreateChannel(absl::StrCat("127.0.0.1:", port_), grpc::InsecureChannelCredentials());
    stub_ = kerf::v1::Simulator::NewStub(channel_);
  }
  ~Server() {
    registry_.CloseAll(absl::UnavailableError("test over"));
    server_->Shutdown(std::chrono::system_clock::now() + std::chrono::seconds(2));
  }
  kerf::v1::Simulator::Stub& stub() { return *stub_; }
  grpc::Channel& channel() { return *channel_; }
  int port() const { return port_; }

  kerf::v1::SessionInfo CreateBarSession(double frame_rate_hz = 0, const char* scene = kBarScene) {
    kerf::v1::CreateSessionRequest request;
    request.set_frame_rate_hz(frame_rate_hz);
    *request.mutable_scene() = *sim::ParseSceneText(scene, "test");
    kerf::v1::CreateSessionResponse created;
    grpc::ClientContext context;
    const grpc::Status status = stub_->CreateSession(&context, request, &created);
    EXPECT_TRUE(status.ok()) << status.error_message();
    TokensOf(created.session().session_id()) = {created.cutter_token(), created.observer_token()};
    return created.session();
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
  // `stall`: how long it waits before reading (a slow client).
  Observer(kerf::v1::Simulator::Stub& stub, const std::string& session, kerf::v1::Level level,
           absl::Duration stall = absl::ZeroDuration()) {
    kerf::v1::ObserveRequest request;
    request.set_session_id(session);
    request.set_level(level);
    request.set_token(TokensOf(session).observer);
    reader_ = stub.Observe(&context_, request);
    thread_ = std::thread([this, stall] {
      absl::SleepFor(stall);
      Frame frame;
      View view;
      while (reader_->Read(&frame)) {
        std::string error;
        absl::MutexLock lock(&mutex_);
        if (frames_ == 0) first_was_keyframe_ = frame.keyframe();
        if (frames_ > 0 && !frame.keyframe() && frame.sequence() > last_sequence_ + 1) ++gaps_;
        ++frames_;
        if (!view.Apply(frame, &error)) errors_.push_back(error);
        if (frame.keyframe()) ++keyframes_;
        by_sequence_[frame.sequence()] = view;
        last_sequence_ = frame.sequence();
      }
      const grpc::Status status = reader_->Finish();
      absl::MutexLock lock(&mutex_);
      status_ = status;
      finished_ = true;
    });
  }
  ~Observer() { Stop(); }
  void Stop() {
    context_.TryCancel();
    if (thread_.joinable()) thread_.join();
  }
  // Waits (up to 10 s) until a frame with at least this sequence came; the view at exactly it.
  std::optional<View> At(std::uint64_t sequence) {
    absl::MutexLock lock(&mutex_);
    const auto reached = [&]() ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_) {
      return last_sequence_ >= sequence;
    };
    mutex_.AwaitWithTimeout(absl::Condition(&reached), absl::Seconds(10));
    const auto it = by_sequence_.find(sequence);
    if (it == by_sequence_.end()) return std::nullopt;
    return it->second;
  }
  std::vector<std::string> errors() {
    absl::MutexLock lock(&mutex_);
    return errors_;
  }
  int keyframes() {
    absl::MutexLock lock(&mutex_);
    return keyframes_;
  }
  int gaps() {
    absl::MutexLock lock(&mutex_);
    return gaps_;
  }
  bool first_was_keyframe() {
    absl::MutexLock lock(&mutex_);
    return first_was_keyframe_;
  }
  // The stream's end status, once the server ended it (within 10 s).
  std::optional<grpc::Status> EndStatus() {
    absl::MutexLock lock(&mutex_);
    mutex_.AwaitWithTimeout(absl::Condition(&finished_), absl::Seconds(10));
    if (!finished_) return std::nullopt;
    return status_;
  }

 private:
  grpc::ClientContext context_;
  std::unique_ptr<grpc::ClientReader<Frame>> reader_;
  std::thread thread_;
  absl::Mutex mutex_;
  std::map<std::uint64_t, View> by_sequence_;
  std::uint64_t last_sequence_ = 0;
  std::vector<std::string> errors_;
  int keyframes_ = 0;
  int frames_ = 0;
  int gaps_ = 0;
  bool first_was_keyframe_ = false;
  bool finished_ = false;
  grpc::Status status_;
};

Frame Snapshot(Server& server, const std::string& session, kerf::v1::Level level) {
  kerf::v1::GetSnapshotRequest request;
  request.set_session_id(session);
  request.set_level(level);
  request.set_token(TokensOf(session).observer);
  Frame snapshot;
  grpc::ClientContext context;
  const grpc::Status status = server.stub().GetSnapshot(&context, request, &snapshot);
  EXPECT_TRUE(status.ok()) << status.error_message();
  return snapshot;
}

// What the observer rebuilt at the snapshot's sequence equals the snapshot.
void ExpectSeesSnapshot(Observer& observer, const Frame& snapshot) {
  View expected;
  std::string error;
  ASSERT_TRUE(expected.Apply(snapshot, &error)) << error;
  const std::optional<View> seen = observer.At(snapshot.sequence());
  ASSERT_TRUE(seen.has_value()) << "no frame " << snapshot.sequence();
  const std::vector<std::string> errors = observer.errors();
  EXPECT_TRUE(errors.empty()) << errors.front();
  EXPECT_EQ(seen->vertices, expected.vertices);
  EXPECT_EQ(seen->positions, expected.positions);
  EXPECT_EQ(seen->forces, expected.forces);
  if (snapshot.level() == kerf::v1::VOLUME) {
    EXPECT_EQ(seen->elements, expected.elements);
  }
  if (snapshot.level() == kerf::v1::SURFACE) {
    EXPECT_EQ(seen->Triangles(), expected.Triangles());
  }
}

// Reads a stream to its end; its status.
template <typename Stream>
grpc::Status DrainAndFinish(Stream& stream) {
  Frame frame;
  while (stream.Read(&frame)) {
  }
  return stream.Finish();
}

// The first message of a cut stream.
kerf::v1::CutRequest CutStart(const std::string& session, const std::string& token) {
  kerf::v1::CutRequest start;
  start.mutable_start()->set_session_id(session);
  start.mutable_start()->set_token(token);
  return start;
}

// A cut stream that sends its start, then `poses` at once, then ends: its status.
grpc::Status CutWith(kerf::v1::Simulator::Stub& stub, const std::string& session,
                     const std::string& token, const std::vector<kerf::v1::BladePose>& poses) {
  grpc::ClientContext context;
  auto stream = stub.Cut(&context);
  stream->Write(CutStart(session, token));
  for (const kerf::v1::BladePose& pose : poses) {
    kerf::v1::CutRequest request;
    *request.mutable_pose() = pose;
    stream->Write(request);
  }
  stream->WritesDone();
  return DrainAndFinish(*stream);
}

kerf::v1::BladePose Pose(double time, double y) { return kerf::testing::BarBladePose(time, y); }

// The session as ListSessions shows it.
kerf::v1::SessionInfo Listed(Server& server, const std::string& id) {
  kerf::v1::ListSessionsResponse sessions;
  grpc::ClientContext context;
  EXPECT_TRUE(server.stub().ListSessions(&context, {}, &sessions).ok());
  for (const kerf::v1::SessionInfo& s : sessions.sessions()) {
    if (s.session_id() == id) return s;
  }
  ADD_FAILURE() << "no session " << id;
  return {};
}

// Streams a straight cut across the bar at x = 23.7 mm, 2 mm per pose, 100 poses per second.
// Sends 16 poses 10 ms apart (slower than the 1 kHz ticks, so the session interpolates).
// `largest_force`, if given, receives the largest tool force of the frames (N), and
// `poses_applied` what the last frame reports.
grpc::Status CutAcross(kerf::v1::Simulator::Stub& stub, const std::string& session, int* frames,
                       double* largest_force = nullptr, std::uint64_t* poses_applied = nullptr) {
  grpc::ClientContext context;
  auto stream = stub.Cut(&context);
  kerf::v1::CutRequest start = CutStart(session, TokensOf(session).cutter);
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
    const Eigen::Vector3d f(frame.tool_force().x(), frame.tool_force().y(), frame.tool_force().z());
    if (largest_force != nullptr) *largest_force = std::max(*largest_force, f.norm());
    if (poses_applied != nullptr) *poses_applied = frame.statistics().poses_applied();
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
  double largest_force = 0;
  std::uint64_t poses_applied = 0;
  const grpc::Status cut =
      CutAcross(server.stub(), info.session_id(), &cutter_frames, &largest_force, &poses_applied);
  ASSERT_TRUE(cut.ok()) << cut.error_message();
  EXPECT_GT(cutter_frames, 5);
  // The cutter felt the tissue: at least the cutting resistance of 100 N/m over the bar's
  // 2 cm depth (2 N) while the blade moved through it.
  EXPECT_GT(largest_force, 1.0);
  // 16 poses over 150 ms at 1 kHz ticks: interpolated poses in between.
  EXPECT_GT(poses_applied, 100u);
  absl::SleepFor(absl::Milliseconds(100));  // the blade is withdrawn, the cut opens
  for (int l = 0; l < 3; ++l) {
    const Frame snapshot = Snapshot(server, info.session_id(), levels[l]);
    if (levels[l] == kerf::v1::VOLUME) {
      EXPECT_GT(snapshot.added_elements_size(), static_cast<int>(info.tets()));  // it is cut
    }
    if (levels[l] == kerf::v1::SURFACE) {  // the cut's faces are marked
      EXPECT_NE(snapshot.added_elements_on_cut().find('\x01'), std::string::npos);
    }
    for (int i = 0; i < 3; ++i) ExpectSeesSnapshot(*observers[3 * l + i], snapshot);
  }
}

TEST(SimulatorService, ListsScenesAndSessionsAndMakesSessionsByName) {
  Server server;
  kerf::v1::ListScenesResponse scenes;
  {
    grpc::ClientContext context;
    ASSERT_TRUE(server.stub().ListScenes(&context, {}, &scenes).ok());
  }
  std::set<std::string> names;
  for (const auto& scene : scenes.scenes()) {
    names.insert(scene.name());
    EXPECT_FALSE(scene.description().empty()) << scene.name();
  }
  EXPECT_EQ(names, (std::set<std::string>{"bar-cantilever", "lattice-tension",
                                          "lattice-tension-deferred"}));
  kerf::v1::CreateSessionRequest request;
  request.set_scene_name("bar-cantilever");
  kerf::v1::CreateSessionResponse created;
  {
    grpc::ClientContext context;
    ASSERT_TRUE(server.stub().CreateSession(&context, request, &created).ok());
  }
  const kerf::v1::SessionInfo& info = created.session();
  TokensOf(info.session_id()) = {created.cutter_token(), created.observer_token()};
  EXPECT_EQ(info.scene_name(), "bar-cantilever");
  EXPECT_EQ(info.levels_size(), 2);  // the scene needs SURFACE and VOLUME only
  kerf::v1::ListSessionsResponse sessions;
  grpc::ClientContext context;
  ASSERT_TRUE(server.stub().ListSessions(&context, {}, &sessions).ok());
  ASSERT_EQ(sessions.sessions_size(), 1);
  EXPECT_EQ(sessions.sessions(0).session_id(), info.session_id());
  // A level the scene does not offer is refused.
  Observer forces(server.stub(), info.session_id(), kerf::v1::FORCES);
  const std::optional<grpc::Status> end = forces.EndStatus();
  ASSERT_TRUE(end.has_value());
  EXPECT_EQ(end->error_code(), grpc::StatusCode::FAILED_PRECONDITION);
  EXPECT_EQ(end->error_message(), "scene bar-cantilever does not offer FORCES");
}

TEST(SimulatorService, TokensGrantTheirRolesOnly) {
  Server server;
  const kerf::v1::SessionInfo info = server.CreateBarSession();
  const kerf::v1::SessionInfo other = server.CreateBarSession();
  const Tokens tokens = TokensOf(info.session_id());
  EXPECT_EQ(tokens.cutter.size(), 64u);
  EXPECT_EQ(tokens.observer.size(), 64u);
  EXPECT_NE(tokens.cutter, tokens.observer);
  EXPECT_NE(tokens.cutter, TokensOf(other.session_id()).cutter);
  const auto observe_with = [&](const std::string& token) {
    grpc::ClientContext context;
    kerf::v1::ObserveRequest request;
    request.set_session_id(info.session_id());
    request.set_level(kerf::v1::SURFACE);
    request.set_token(token);
    auto reader = server.stub().Observe(&context, request);
    Frame frame;
    if (reader->Read(&frame)) {  // served: that is all this wants to know
      context.TryCancel();
      while (reader->Read(&frame)) {
      }
      (void)reader->Finish();
      return grpc::Status::OK;
    }
    return reader->Finish();
  };
  EXPECT_EQ(observe_with("").error_code(), grpc::StatusCode::UNAUTHENTICATED);
  const grpc::Status wrong = observe_with(TokensOf(other.session_id()).observer);
  EXPECT_EQ(wrong.error_code(), grpc::StatusCode::PERMISSION_DENIED);
  EXPECT_EQ(wrong.error_message(), "the token does not belong to this session");
  EXPECT_TRUE(observe_with(tokens.observer).ok());
  EXPECT_TRUE(observe_with(tokens.cutter).ok());
  {  // the observer token cannot cut
    const grpc::Status status = CutWith(server.stub(), info.session_id(), tokens.observer, {});
    EXPECT_EQ(status.error_code(), grpc::StatusCode::PERMISSION_DENIED);
    EXPECT_EQ(status.error_message(), "the observer token cannot cut or close");
  }
  for (const std::string& token : {std::string(), tokens.observer}) {  // nor close
    kerf::v1::CloseSessionRequest request;
    request.set_session_id(info.session_id());
    request.set_token(token);
    kerf::v1::CloseSessionResponse response;
    grpc::ClientContext context;
    EXPECT_EQ(
        server.stub().CloseSession(&context, request, &response).error_code(),
        token.empty() ? grpc::StatusCode::UNAUTHENTICATED : grpc::StatusCode::PERMISSION_DENIED);
  }
  // Listing sessions shows no token.
  kerf::v1::ListSessionsResponse sessions;
  grpc::ClientContext context;
  ASSERT_TRUE(server.stub().ListSessions(&context, {}, &sessions).ok());
  const std::string listed = sessions.SerializeAsString();
  EXPECT_EQ(listed.find(tokens.cutter), std::string::npos);
  EXPECT_EQ(listed.find(tokens.observer), std::string::npos);
}

TEST(SessionTokens, KeepsOnlyTheDigestsOfTheTokensItIssues) {
  EXPECT_EQ(absl::BytesToHexString(Sha256("abc")),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");  // FIPS 180-2
  const auto [tokens, issued] = SessionTokens::Generate();
  EXPECT_EQ(issued.cutter.size(), 64u);
  EXPECT_NE(issued.cutter, issued.observer);
  EXPECT_EQ(tokens.cutter_sha256(), Sha256(issued.cutter));
  EXPECT_EQ(tokens.observer_sha256(), Sha256(issued.observer));
  // Rebuilt from the digests alone (as a restored session is), it admits the same tokens.
  const absl::StatusOr<SessionTokens> kept =
      SessionTokens::FromDigests(tokens.cutter_sha256(), tokens.observer_sha256());
  ASSERT_TRUE(kept.ok()) << kept.status();
  EXPECT_TRUE(kept->Authorize(Role::kCutter, issued.cutter).ok());
  EXPECT_TRUE(kept->Authorize(Role::kObserver, issued.observer).ok());
  EXPECT_EQ(kept->Authorize(Role::kCutter, issued.observer).code(),
            absl::StatusCode::kPermissionDenied);
  // The digest itself is no token.
  EXPECT_EQ(kept->Authorize(Role::kObserver, tokens.cutter_sha256()).code(),
            absl::StatusCode::kPermissionDenied);
  EXPECT_EQ(kept->Authorize(Role::kObserver, "").code(), absl::StatusCode::kUnauthenticated);
  EXPECT_EQ(SessionTokens::FromDigests("short", tokens.observer_sha256()).status().code(),
            absl::StatusCode::kInvalidArgument);
}

TEST(SessionTokens, ComparesWholeTokens) {
  EXPECT_TRUE(ConstantTimeEquals("abc", "abc"));
  EXPECT_FALSE(ConstantTimeEquals("abc", "abd"));
  EXPECT_FALSE(ConstantTimeEquals("abc", "ab"));
  EXPECT_FALSE(ConstantTimeEquals("", "a"));
}

TEST(SimulatorService, SnapshotsAtAChosenFrameNumber) {
  Server server;
  const kerf::v1::SessionInfo info = server.CreateBarSession();
  const Frame now = Snapshot(server, info.session_id(), kerf::v1::SURFACE);
  const auto at = [&](std::uint64_t sequence, Frame* frame) {
    kerf::v1::GetSnapshotRequest request;
    request.set_session_id(info.session_id());
    request.set_level(kerf::v1::SURFACE);
    request.set_token(TokensOf(info.session_id()).observer);
    request.set_sequence(sequence);
    grpc::ClientContext context;
    return server.stub().GetSnapshot(&context, request, frame);
  };
  Frame later;
  const grpc::Status waited = at(now.sequence() + 5, &later);
  ASSERT_TRUE(waited.ok()) << waited.error_message();
  EXPECT_EQ(later.sequence(), now.sequence() + 5);
  // Frame n is due at the tick where n frames per (physics/frame rate) ticks are done.
  EXPECT_NEAR(later.simulation_time() - now.simulation_time(), 5.0 / 60, 1.5e-3);
  EXPECT_EQ(later.model_sha256().size(), 32u);
  Frame none;
  const grpc::Status past = at(now.sequence(), &none);
  EXPECT_EQ(past.error_code(), grpc::StatusCode::OUT_OF_RANGE);
  EXPECT_NE(past.error_message().find("the session has made"), std::string::npos)
      << past.error_message();
  EXPECT_EQ(at(later.sequence() + 3600 + 60, &none).error_code(),
            grpc::StatusCode::OUT_OF_RANGE);  // more than a minute ahead
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
    kerf::v1::CreateSessionResponse created;
    grpc::ClientContext context;
    const grpc::Status status = server.stub().CreateSession(&context, request, &created);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::NOT_FOUND);
  }
  {  // a malformed scene
    kerf::v1::CreateSessionRequest request;
    *request.mutable_scene() = *sim::ParseSceneText(kBarScene, "test");
    request.mutable_scene()->mutable_material()->set_poisson_ratio(0.7);
    kerf::v1::CreateSessionResponse created;
    grpc::ClientContext context;
    const grpc::Status status = server.stub().CreateSession(&context, request, &created);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
    EXPECT_NE(status.error_message().find("poisson_ratio"), std::string::npos)
        << status.error_message();
  }
  {  // a lattice that would not fit in memory, refused before anything is built
    kerf::v1::CreateSessionRequest request;
    *request.mutable_scene() = *sim::ParseSceneText(kBarScene, "test");
    request.mutable_scene()->mutable_mesh()->mutable_lattice()->set_cells_x(1000);
    request.mutable_scene()->mutable_mesh()->mutable_lattice()->set_cells_y(1000);
    request.mutable_scene()->mutable_mesh()->mutable_lattice()->set_cells_z(1000);
    kerf::v1::CreateSessionResponse created;
    grpc::ClientContext context;
    const grpc::Status status = server.stub().CreateSession(&context, request, &created);
    EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
    EXPECT_EQ(status.error_message(),
              "scene.mesh.lattice: 6000000000 tets is over this server's limit of 2000000");
  }
  const std::string& cutter = TokensOf(info.session_id()).cutter;
  {  // a NaN pose ends the cut stream with INVALID_ARGUMENT
    const grpc::Status status =
        CutWith(server.stub(), info.session_id(), cutter, {Pose(0, std::nan(""))});
    EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  }
  {  // a blade that teleports 5 cm between poses 10 ms apart
    const grpc::Status status =
        CutWith(server.stub(), info.session_id(), cutter, {Pose(0, -0.005), Pose(0.01, 0.045)});
    EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
    EXPECT_NE(status.error_message().find("jumps"), std::string::npos) << status.error_message();
  }
  // The session is unharmed: a proper cut follows.
  int frames = 0;
  EXPECT_TRUE(CutAcross(server.stub(), info.session_id(), &frames).ok());
  EXPECT_GT(frames, 0);
}

TEST(SimulatorService, PosesFarAheadOfTheSessionAreRefused) {
  Server server;
  const kerf::v1::SessionInfo info = server.CreateBarSession();
  // The second pose is 5 s later on the client's clock, sent at once.
  const grpc::Status status =
      CutWith(server.stub(), info.session_id(), TokensOf(info.session_id()).cutter,
              {Pose(0, -0.005), Pose(5, -0.004)});
  EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(status.error_message().find("send poses in real time"), std::string::npos)
      << status.error_message();
}

TEST(SimulatorService, AnObserverPastItsDeadlineIsDropped) {
  Server server;
  const kerf::v1::SessionInfo info = server.CreateBarSession();
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::milliseconds(200));
  kerf::v1::ObserveRequest request;
  request.set_session_id(info.session_id());
  request.set_level(kerf::v1::SURFACE);
  request.set_token(TokensOf(info.session_id()).observer);
  auto reader = server.stub().Observe(&context, request);
  Frame frame;
  int frames = 0;
  while (reader->Read(&frame)) ++frames;
  EXPECT_GT(frames, 0);
  EXPECT_EQ(reader->Finish().error_code(), grpc::StatusCode::DEADLINE_EXCEEDED);
  int observers = -1;
  for (int wait = 0; wait < 100 && observers != 0; ++wait) {
    kerf::v1::ListSessionsResponse sessions;
    grpc::ClientContext list_context;
    ASSERT_TRUE(server.stub().ListSessions(&list_context, {}, &sessions).ok());
    observers = static_cast<int>(sessions.sessions(0).observers());
    absl::SleepFor(absl::Milliseconds(10));
  }
  EXPECT_EQ(observers, 0);
}

TEST(SimulatorService, ALateJoinerStartsFromAKeyframeOfTheCutMesh) {
  Server server;
  const kerf::v1::SessionInfo info = server.CreateBarSession();
  int frames = 0;
  ASSERT_TRUE(CutAcross(server.stub(), info.session_id(), &frames).ok());
  Observer late(server.stub(), info.session_id(), kerf::v1::VOLUME);
  const Frame snapshot = Snapshot(server, info.session_id(), kerf::v1::VOLUME);
  EXPECT_GT(snapshot.added_elements_size(), static_cast<int>(info.tets()));  // it is cut
  ExpectSeesSnapshot(late, snapshot);
  EXPECT_TRUE(late.first_was_keyframe());
}

TEST(SimulatorService, ASlowObserverSkipsPositionsButLosesNoTopology) {
  Server server;
  const kerf::v1::SessionInfo info = server.CreateBarSession(500);
  // The slow observer's channel takes 8 kB at a time (a few frames; no window growth), and
  // it does not read for a second: the server's writes to it stall while frames come at 500 Hz.
  grpc::ChannelArguments narrow;
  narrow.SetInt(GRPC_ARG_HTTP2_STREAM_LOOKAHEAD_BYTES, 8192);
  narrow.SetInt(GRPC_ARG_HTTP2_BDP_PROBE, 0);
  const auto slow_stub = kerf::v1::Simulator::NewStub(grpc::CreateCustomChannel(
      absl::StrCat("127.0.0.1:", server.port()), grpc::InsecureChannelCredentials(), narrow));
  Observer prompt(server.stub(), info.session_id(), kerf::v1::VOLUME);
  Observer slow(*slow_stub, info.session_id(), kerf::v1::VOLUME, absl::Seconds(1));
  int frames = 0;
  ASSERT_TRUE(CutAcross(server.stub(), info.session_id(), &frames).ok());
  absl::SleepFor(absl::Seconds(1));
  const Frame snapshot = Snapshot(server, info.session_id(), kerf::v1::VOLUME);
  EXPECT_GT(snapshot.added_elements_size(), static_cast<int>(info.tets()));
  ExpectSeesSnapshot(prompt, snapshot);
  ExpectSeesSnapshot(slow, snapshot);
  EXPECT_GT(slow.gaps() + slow.keyframes() - 1, 0) << "the slow observer was never behind";
  EXPECT_EQ(prompt.keyframes(), 1);
}

TEST(SimulatorService, ACutterThatDisconnectsMidCutLeavesAWorkingSession) {
  Server server;
  const kerf::v1::SessionInfo info = server.CreateBarSession();
  Observer observer(server.stub(), info.session_id(), kerf::v1::VOLUME);
  {
    grpc::ClientContext context;
    auto stream = server.stub().Cut(&context);
    stream->Write(CutStart(info.session_id(), TokensOf(info.session_id()).cutter));
    for (int k = 0; k <= 8; ++k) {  // the blade stops inside the bar
      kerf::v1::CutRequest request;
      *request.mutable_pose() = Pose(0.01 * k, -0.005 + 0.002 * k);
      stream->Write(request);
    }
    absl::SleepFor(absl::Milliseconds(50));
    context.TryCancel();  // gone, without a word
    Frame frame;
    while (stream->Read(&frame)) {
    }
  }
  // The blade is withdrawn and free again; everything observed still adds up.
  for (int wait = 0; wait < 100; ++wait) {
    kerf::v1::ListSessionsResponse sessions;
    grpc::ClientContext context;
    ASSERT_TRUE(server.stub().ListSessions(&context, {}, &sessions).ok());
    ASSERT_EQ(sessions.sessions_size(), 1);
    if (!sessions.sessions(0).cutting()) break;
    absl::SleepFor(absl::Milliseconds(10));
  }
  int frames = 0;
  EXPECT_TRUE(CutAcross(server.stub(), info.session_id(), &frames).ok());
  ExpectSeesSnapshot(observer, Snapshot(server, info.session_id(), kerf::v1::VOLUME));
}

// A cutter that vanishes with poses queued ahead of the session: they are dropped with it, its
// blade comes out, and the next cutter's blade cuts from its own first pose (the next cut's poses
// were once queued behind the vanished one's and refused by the cutter, without a word).
TEST(SimulatorService, TheNextCutterCutsThoughTheLastLeftPosesQueued) {
  Server server;
  const kerf::v1::SessionInfo info = server.CreateBarSession();
  {
    grpc::ClientContext context;
    auto stream = server.stub().Cut(&context);
    stream->Write(CutStart(info.session_id(), TokensOf(info.session_id()).cutter));
    for (int k = 0; k < 150; ++k) {  // 1.5 s of a blade held still beside the bar
      kerf::v1::CutRequest request;
      *request.mutable_pose() = Pose(0.01 * k, -0.005);
      stream->Write(request);
    }
    Frame frame;
    ASSERT_TRUE(stream->Read(&frame));  // the session took the cut
    context.TryCancel();
    while (stream->Read(&frame)) {
    }
  }
  for (int wait = 0; wait < 100; ++wait) {
    if (!Listed(server, info.session_id()).cutting()) break;
    absl::SleepFor(absl::Milliseconds(10));
  }
  int frames = 0;
  const grpc::Status cut = CutAcross(server.stub(), info.session_id(), &frames);
  ASSERT_TRUE(cut.ok()) << cut.error_message();
  EXPECT_GT(Listed(server, info.session_id()).tets(), info.tets()) << "the second cut cut nothing";
}

TEST(SimulatorService, OneCutterAtATime) {
  Server server;
  const kerf::v1::SessionInfo info = server.CreateBarSession();
  grpc::ClientContext first_context;
  auto first = server.stub().Cut(&first_context);
  const kerf::v1::CutRequest start =
      CutStart(info.session_id(), TokensOf(info.session_id()).cutter);
  first->Write(start);
  Frame frame;
  ASSERT_TRUE(first->Read(&frame));  // the first cutter holds the blade
  grpc::ClientContext second_context;
  auto second = server.stub().Cut(&second_context);
  second->Write(start);
  second->WritesDone();
  while (second->Read(&frame)) {
  }
  const grpc::Status status = second->Finish();
  EXPECT_EQ(status.error_code(), grpc::StatusCode::FAILED_PRECONDITION);
  EXPECT_EQ(status.error_message(),
            absl::StrCat("session ", info.session_id(), " already has a cutter; one at a time"));
  first->WritesDone();
  while (first->Read(&frame)) {
  }
  EXPECT_TRUE(first->Finish().ok());
}

TEST(SimulatorService, ClosingASessionEndsItsStreams) {
  Server server;
  const kerf::v1::SessionInfo info = server.CreateBarSession();
  Observer observer(server.stub(), info.session_id(), kerf::v1::SURFACE);
  ExpectSeesSnapshot(observer, Snapshot(server, info.session_id(), kerf::v1::SURFACE));
  kerf::v1::CloseSessionRequest request;
  request.set_session_id(info.session_id());
  request.set_token(TokensOf(info.session_id()).cutter);
  kerf::v1::CloseSessionResponse response;
  grpc::ClientContext context;
  ASSERT_TRUE(server.stub().CloseSession(&context, request, &response).ok());
  const std::optional<grpc::Status> end = observer.EndStatus();
  ASSERT_TRUE(end.has_value());
  EXPECT_EQ(end->error_code(), grpc::StatusCode::CANCELLED);
  EXPECT_EQ(end->error_message(), absl::StrCat("session ", info.session_id(), " was closed"));
  kerf::v1::ListSessionsResponse sessions;
  grpc::ClientContext list_context;
  ASSERT_TRUE(server.stub().ListSessions(&list_context, {}, &sessions).ok());
  EXPECT_EQ(sessions.sessions_size(), 0);
}

TEST(SimulatorService, AnswersStandardHealthChecks) {
  Server server;
  grpc::GenericStub generic(std::shared_ptr<grpc::Channel>(&server.channel(), [](auto*) {}));
  grpc::ClientContext context;
  grpc::Slice empty{std::string()};  // an empty HealthCheckRequest: the whole server
  grpc::ByteBuffer request(&empty, 1), response;
  absl::Notification done;
  grpc::Status status;
  generic.UnaryCall(&context, "/grpc.health.v1.Health/Check", grpc::StubOptions(), &request,
                    &response, [&](grpc::Status s) {
                      status = s;
                      done.Notify();
                    });
  done.WaitForNotification();
  ASSERT_TRUE(status.ok()) << status.error_message();
  std::vector<grpc::Slice> slices;
  ASSERT_TRUE(response.Dump(&slices).ok());
  std::string bytes;
  for (const grpc::Slice& slice : slices) {
    bytes.append(reinterpret_cast<const char*>(slice.begin()), slice.size());
  }
  EXPECT_EQ(bytes, std::string("\x08\x01", 2));  // HealthCheckResponse{status: SERVING}
}

TEST(SimulatorService, ListsItsServicesThroughReflection) {
  Server server;
  grpc::GenericStub generic(std::shared_ptr<grpc::Channel>(&server.channel(), [](auto*) {}));
  // One ServerReflectionRequest{list_services: ""} on the bidirectional stream.
  class Reactor : public grpc::ClientBidiReactor<grpc::ByteBuffer, grpc::ByteBuffer> {
   public:
    Reactor() : request_slice_(std::string("\x3a\x00", 2)), request_(&request_slice_, 1) {}
    void Start() {
      StartWrite(&request_);
      StartRead(&response_);
      StartWritesDone();
      StartCall();
    }
    void OnReadDone(bool ok) override {
      if (ok) {
        std::vector<grpc::Slice> slices;
        (void)response_.Dump(&slices);
        for (const grpc::Slice& s : slices) {
          bytes_.append(reinterpret_cast<const char*>(s.begin()), s.size());
        }
      }
    }
    void OnDone(const grpc::Status& status) override {
      status_ = status;
      done_.Notify();
    }
    std::string Wait() {
      done_.WaitForNotification();
      return status_.ok() ? bytes_ : status_.error_message();
    }

   private:
    grpc::Slice request_slice_;
    grpc::ByteBuffer request_, response_;
    std::string bytes_;
    grpc::Status status_;
    absl::Notification done_;
  } reactor;
  grpc::ClientContext context;
  generic.PrepareBidiStreamingCall(&context,
                                   "/grpc.reflection.v1alpha.ServerReflection/ServerReflectionInfo",
                                   grpc::StubOptions(), &reactor);
  reactor.Start();
  const std::string response = reactor.Wait();
  EXPECT_NE(response.find("kerf.v1.Simulator"), std::string::npos) << response;
  EXPECT_NE(response.find("grpc.health.v1.Health"), std::string::npos) << response;
}

TEST(SimulatorService, LimitsAreResourceExhausted) {
  RegistryOptions options;
  options.max_sessions = 1;
  Server server(options);
  server.CreateBarSession();
  kerf::v1::CreateSessionRequest request;
  *request.mutable_scene() = *sim::ParseSceneText(kBarScene, "test");
  kerf::v1::CreateSessionResponse created;
  grpc::ClientContext context;
  EXPECT_EQ(server.stub().CreateSession(&context, request, &created).error_code(),
            grpc::StatusCode::RESOURCE_EXHAUSTED);
}

TEST(SimulatorService, OversizedRequestsAreRefused) {
  Server server;  // the default cap: 4 MB
  kerf::v1::CreateSessionRequest request;
  *request.mutable_scene() = *sim::ParseSceneText(kBarScene, "test");
  request.mutable_scene()->set_description(std::string(5 << 20, 'x'));
  kerf::v1::CreateSessionResponse created;
  grpc::ClientContext context;
  const grpc::Status status = server.stub().CreateSession(&context, request, &created);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(status.error_message().find("message larger than max"), std::string::npos)
      << status.error_message();
}

TEST(SimulatorService, ObserverLimitIsResourceExhausted) {
  RegistryOptions options;
  options.session.max_subscribers = 2;
  Server server(options);
  const kerf::v1::SessionInfo info = server.CreateBarSession();
  Observer a(server.stub(), info.session_id(), kerf::v1::SURFACE);
  Observer b(server.stub(), info.session_id(), kerf::v1::VOLUME);
  ExpectSeesSnapshot(b, Snapshot(server, info.session_id(), kerf::v1::VOLUME));
  Observer c(server.stub(), info.session_id(), kerf::v1::FORCES);
  const std::optional<grpc::Status> end = c.EndStatus();
  ASSERT_TRUE(end.has_value());
  EXPECT_EQ(end->error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(end->error_message(),
            absl::StrCat("session ", info.session_id(), " has its limit of 2 observers"));
}

}  // namespace
}  // namespace kerf::service
