#include "service/simulator_service.h"

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/synchronization/mutex.h"
#include "sim/scene.h"

namespace kerf::service {
namespace {

template <typename Message>
bool ParseByteBuffer(const grpc::ByteBuffer& buffer, Message* message) {
  std::vector<grpc::Slice> slices;
  if (!buffer.Dump(&slices).ok()) return false;
  std::string bytes;
  for (const grpc::Slice& slice : slices) {
    bytes.append(reinterpret_cast<const char*>(slice.begin()), slice.size());
  }
  return message->ParseFromString(bytes);
}

// Writes a stream's frames one at a time and finishes it once. Shared by the reactor and the
// callbacks the session holds; once the reactor is done they do nothing.
template <typename Reactor>
class FrameWriter {
 public:
  explicit FrameWriter(Reactor* reactor) : reactor_(reactor) {}

  // From the FrameQueue (under its lock): starts writing `frame`.
  void Write(const SerializedFrame& frame) {
    absl::MutexLock lock(&mutex_);
    if (reactor_ == nullptr || finishing_) return;
    // The slice holds a reference to the bytes until gRPC is done with them: no copy.
    auto* held = new std::shared_ptr<const std::string>(frame.bytes);
    grpc::Slice slice(
        const_cast<char*>((*held)->data()), (*held)->size(),
        [](void* p) { delete static_cast<std::shared_ptr<const std::string>*>(p); }, held);
    buffer_ = grpc::ByteBuffer(&slice, 1);
    writing_ = true;
    reactor_->StartWrite(&buffer_);
  }

  // A write completed: whether to go on writing.
  bool WriteDone(bool ok) {
    absl::MutexLock lock(&mutex_);
    writing_ = false;
    if (!ok && !finishing_) {  // the client is gone
      finishing_ = true;
      waiting_finish_ = grpc::Status::CANCELLED;
    }
    if (waiting_finish_) {
      reactor_->Finish(*waiting_finish_);
      waiting_finish_.reset();
    }
    return !finishing_;
  }

  void Finish(const grpc::Status& status) {
    absl::MutexLock lock(&mutex_);
    if (reactor_ == nullptr || finishing_) return;
    finishing_ = true;
    if (writing_) {
      waiting_finish_ = status;  // after the write in flight
    } else {
      reactor_->Finish(status);
    }
  }

  void Done() {
    absl::MutexLock lock(&mutex_);
    reactor_ = nullptr;
  }

 private:
  absl::Mutex mutex_;
  Reactor* reactor_ ABSL_GUARDED_BY(mutex_);
  grpc::ByteBuffer buffer_ ABSL_GUARDED_BY(mutex_);
  bool writing_ ABSL_GUARDED_BY(mutex_) = false;
  bool finishing_ ABSL_GUARDED_BY(mutex_) = false;
  std::optional<grpc::Status> waiting_finish_ ABSL_GUARDED_BY(mutex_);
};

// The session `id`, when `token` grants `role` in it (NOT_FOUND, UNAUTHENTICATED or
// PERMISSION_DENIED otherwise).
absl::StatusOr<std::shared_ptr<Session>> FindAuthorized(const SessionRegistry& registry,
                                                        const std::string& id, Role role,
                                                        absl::string_view token) {
  absl::StatusOr<std::shared_ptr<Session>> session = registry.Find(id);
  if (!session.ok()) return session.status();
  if (absl::Status s = (*session)->tokens().Authorize(role, token); !s.ok()) return s;
  return session;
}

// What the Observe and Cut reactors share: the writer of their frames, their session and
// subscription, and how a stream ends.
template <typename Base>
class FrameStreamReactor : public Base {
 public:
  void OnWriteDone(bool ok) override {
    const auto subscription = subscription_of();
    if (writer_->WriteDone(ok) && subscription) subscription->queue->WriteDone();
  }
  void OnCancel() override { writer_->Finish(grpc::Status::CANCELLED); }
  void OnDone() override {
    writer_->Done();
    if (const auto subscription = subscription_of(); subscription) {
      session_->Unsubscribe(subscription);  // for the cutter, withdraws the blade
    }
    delete this;
  }

 protected:
  FrameStreamReactor() : writer_(std::make_shared<FrameWriter<FrameStreamReactor>>(this)) {}

  // The callbacks a Session subscription takes: write a frame, end the stream.
  std::function<void(const SerializedFrame&)> frame_writer() const {
    return [w = writer_](const SerializedFrame& f) { w->Write(f); };
  }
  std::function<void(const absl::Status&)> stream_ender() const {
    return [w = writer_](const absl::Status& s) { w->Finish(ToGrpcStatus(s)); };
  }

  std::shared_ptr<Subscription> subscription_of() {
    absl::MutexLock lock(&mutex_);
    return subscription_;
  }
  void SetSubscription(std::shared_ptr<Subscription> subscription) {
    absl::MutexLock lock(&mutex_);
    subscription_ = std::move(subscription);
  }

  std::shared_ptr<FrameWriter<FrameStreamReactor>> writer_;
  std::shared_ptr<Session> session_;  // set once, before any subscription

 private:
  absl::Mutex mutex_;  // read and write reactions, and the constructor, run concurrently
  std::shared_ptr<Subscription> subscription_ ABSL_GUARDED_BY(mutex_);
};

class ObserveReactor final : public FrameStreamReactor<grpc::ServerWriteReactor<grpc::ByteBuffer>> {
 public:
  ObserveReactor(SessionRegistry* registry, const grpc::ByteBuffer* request) {
    kerf::v1::ObserveRequest parsed;
    if (!ParseByteBuffer(*request, &parsed)) {
      writer_->Finish({grpc::StatusCode::INVALID_ARGUMENT, "malformed ObserveRequest"});
      return;
    }
    absl::StatusOr<std::shared_ptr<Session>> session =
        FindAuthorized(*registry, parsed.session_id(), Role::kObserver, parsed.token());
    if (!session.ok()) {
      writer_->Finish(ToGrpcStatus(session.status()));
      return;
    }
    session_ = *std::move(session);
    absl::StatusOr<std::shared_ptr<Subscription>> subscription =
        session_->Observe(parsed.level(), frame_writer(), stream_ender());
    if (!subscription.ok()) {
      writer_->Finish(ToGrpcStatus(subscription.status()));
      return;
    }
    SetSubscription(*std::move(subscription));
  }
};

class CutReactor final
    : public FrameStreamReactor<grpc::ServerBidiReactor<grpc::ByteBuffer, grpc::ByteBuffer>> {
 public:
  explicit CutReactor(SessionRegistry* registry) : registry_(registry) { StartRead(&request_); }

  void OnReadDone(bool ok) override {
    if (!ok) {  // the client is done sending: its poses are applied, then the blade withdrawn
      if (session_ == nullptr) {
        writer_->Finish(grpc::Status::OK);
        return;
      }
      session_->EndCut([w = writer_] { w->Finish(grpc::Status::OK); });
      return;
    }
    kerf::v1::CutRequest request;
    if (!ParseByteBuffer(request_, &request)) {
      writer_->Finish({grpc::StatusCode::INVALID_ARGUMENT, "malformed CutRequest"});
      return;
    }
    if (absl::Status s = Handle(request); !s.ok()) {
      // The blade is free for the next cutter before the client hears (OnDone unsubscribes
      // again, harmlessly).
      if (const auto subscription = subscription_of(); subscription) {
        session_->Unsubscribe(subscription);
      }
      writer_->Finish(ToGrpcStatus(s));
      return;
    }
    StartRead(&request_);
  }

 private:
  absl::Status Handle(const kerf::v1::CutRequest& request) {
    if (subscription_of() == nullptr) {
      if (!request.has_start()) {
        return absl::InvalidArgumentError("the first CutRequest must be `start`");
      }
      absl::StatusOr<std::shared_ptr<Session>> session = FindAuthorized(
          *registry_, request.start().session_id(), Role::kCutter, request.start().token());
      if (!session.ok()) return session.status();
      session_ = *std::move(session);
      absl::StatusOr<std::shared_ptr<Subscription>> subscription = session_->BeginCut(
          request.start().level(), request.start().frame_rate_hz(), frame_writer(), stream_ender());
      if (!subscription.ok()) return subscription.status();
      SetSubscription(*std::move(subscription));
      return absl::OkStatus();
    }
    if (!request.has_pose()) {
      return absl::InvalidArgumentError("after `start`, every CutRequest must be a `pose`");
    }
    return session_->SubmitPose(request.pose());
  }

  SessionRegistry* registry_;
  grpc::ByteBuffer request_;
};

grpc::ServerUnaryReactor* FinishUnary(grpc::CallbackServerContext* context,
                                      const absl::Status& status) {
  grpc::ServerUnaryReactor* reactor = context->DefaultReactor();
  reactor->Finish(ToGrpcStatus(status));
  return reactor;
}

}  // namespace

grpc::Status ToGrpcStatus(const absl::Status& status) {
  return grpc::Status(static_cast<grpc::StatusCode>(status.code()), std::string(status.message()));
}

grpc::ServerUnaryReactor* SimulatorService::ListScenes(grpc::CallbackServerContext* context,
                                                       const kerf::v1::ListScenesRequest*,
                                                       kerf::v1::ListScenesResponse* response) {
  for (const std::string& name : sim::EmbeddedSceneNames()) {
    kerf::v1::SceneSummary* summary = response->add_scenes();
    summary->set_name(name);
    absl::StatusOr<std::string> text = sim::EmbeddedSceneText(name);
    if (!text.ok()) continue;
    absl::StatusOr<kerf::v1::Scene> scene = sim::ParseSceneText(*text, name);
    if (scene.ok()) summary->set_description(scene->description());
  }
  return FinishUnary(context, absl::OkStatus());
}

grpc::ServerUnaryReactor* SimulatorService::CreateSession(
    grpc::CallbackServerContext* context, const kerf::v1::CreateSessionRequest* request,
    kerf::v1::CreateSessionResponse* response) {
  absl::StatusOr<CreatedSession> created = registry_->Create(*request);
  if (created.ok()) {
    *response->mutable_session() = created->session->Info();
    response->set_cutter_token(created->tokens.cutter);
    response->set_observer_token(created->tokens.observer);
  }
  return FinishUnary(context, created.status());
}

grpc::ServerUnaryReactor* SimulatorService::ListSessions(grpc::CallbackServerContext* context,
                                                         const kerf::v1::ListSessionsRequest*,
                                                         kerf::v1::ListSessionsResponse* response) {
  for (const auto& session : registry_->List()) *response->add_sessions() = session->Info();
  return FinishUnary(context, absl::OkStatus());
}

grpc::ServerUnaryReactor* SimulatorService::CloseSession(
    grpc::CallbackServerContext* context, const kerf::v1::CloseSessionRequest* request,
    kerf::v1::CloseSessionResponse* response) {
  const absl::StatusOr<std::shared_ptr<Session>> session =
      FindAuthorized(*registry_, request->session_id(), Role::kCutter, request->token());
  if (!session.ok()) return FinishUnary(context, session.status());
  absl::StatusOr<kerf::v1::SessionInfo> closed = registry_->Close(request->session_id());
  if (!closed.ok()) return FinishUnary(context, closed.status());
  *response->mutable_session() = *std::move(closed);
  return FinishUnary(context, absl::OkStatus());
}

grpc::ServerUnaryReactor* SimulatorService::GetSnapshot(grpc::CallbackServerContext* context,
                                                        const kerf::v1::GetSnapshotRequest* request,
                                                        kerf::v1::Frame* response) {
  absl::StatusOr<std::shared_ptr<Session>> session =
      FindAuthorized(*registry_, request->session_id(), Role::kObserver, request->token());
  if (!session.ok()) return FinishUnary(context, session.status());
  // Answered by the session when the frame is due (on its thread), not on this one.
  grpc::ServerUnaryReactor* reactor = context->DefaultReactor();
  (*session)->Snapshot(request->level(), request->sequence(),
                       [reactor, response](absl::StatusOr<kerf::v1::Frame> frame) {
                         if (!frame.ok()) return reactor->Finish(ToGrpcStatus(frame.status()));
                         *response = *std::move(frame);
                         reactor->Finish(grpc::Status::OK);
                       });
  return reactor;
}

grpc::ServerBidiReactor<grpc::ByteBuffer, grpc::ByteBuffer>* SimulatorService::Cut(
    grpc::CallbackServerContext*) {
  return new CutReactor(registry_);
}

grpc::ServerWriteReactor<grpc::ByteBuffer>* SimulatorService::Observe(
    grpc::CallbackServerContext*, const grpc::ByteBuffer* request) {
  return new ObserveReactor(registry_, request);
}

}  // namespace kerf::service
