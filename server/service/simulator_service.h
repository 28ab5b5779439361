// The kerf.v1.Simulator gRPC service over a SessionRegistry (callback API). Observe and Cut
// write frames as the bytes the session serialized once for all its subscribers.
#pragma once

#include <grpcpp/grpcpp.h>

#include <memory>

#include "kerf/v1/simulator.grpc.pb.h"
#include "service/session_registry.h"

namespace kerf::service {

using SimulatorBase = kerf::v1::Simulator::WithCallbackMethod_ListScenes<
    kerf::v1::Simulator::WithCallbackMethod_CreateSession<
        kerf::v1::Simulator::WithCallbackMethod_ListSessions<
            kerf::v1::Simulator::WithCallbackMethod_CloseSession<
                kerf::v1::Simulator::WithCallbackMethod_GetSnapshot<
                    kerf::v1::Simulator::WithRawCallbackMethod_Cut<
                        kerf::v1::Simulator::WithRawCallbackMethod_Observe<
                            kerf::v1::Simulator::Service>>>>>>>;

// absl::Status to grpc::Status, same code and message.
grpc::Status ToGrpcStatus(const absl::Status& status);

class SimulatorService final : public SimulatorBase {
 public:
  explicit SimulatorService(SessionRegistry* registry) : registry_(registry) {}

  grpc::ServerUnaryReactor* ListScenes(grpc::CallbackServerContext* context,
                                       const kerf::v1::ListScenesRequest* request,
                                       kerf::v1::ListScenesResponse* response) override;
  grpc::ServerUnaryReactor* CreateSession(grpc::CallbackServerContext* context,
                                          const kerf::v1::CreateSessionRequest* request,
                                          kerf::v1::CreateSessionResponse* response) override;
  grpc::ServerUnaryReactor* ListSessions(grpc::CallbackServerContext* context,
                                         const kerf::v1::ListSessionsRequest* request,
                                         kerf::v1::ListSessionsResponse* response) override;
  grpc::ServerUnaryReactor* CloseSession(grpc::CallbackServerContext* context,
                                         const kerf::v1::CloseSessionRequest* request,
                                         kerf::v1::CloseSessionResponse* response) override;
  grpc::ServerUnaryReactor* GetSnapshot(grpc::CallbackServerContext* context,
                                        const kerf::v1::GetSnapshotRequest* request,
                                        kerf::v1::Frame* response) override;
  grpc::ServerBidiReactor<grpc::ByteBuffer, grpc::ByteBuffer>* Cut(
      grpc::CallbackServerContext* context) override;
  grpc::ServerWriteReactor<grpc::ByteBuffer>* Observe(grpc::CallbackServerContext* context,
                                                      const grpc::ByteBuffer* request) override;

 private:
  SessionRegistry* registry_;
};

}  // namespace kerf::service
