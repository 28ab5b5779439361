// A real kerf server in the test's process, on a free loopback port, for running the client
// binaries against.
#pragma once

#include <gtest/gtest.h>

#include <memory>

#include "service/grpc_server.h"
#include "service/session_registry.h"
#include "service/simulator_service.h"

namespace kerf::testing {

class LoopbackServer {
 public:
  LoopbackServer() : service_(&registry_) {
    absl::StatusOr<service::RunningServer> running =
        service::StartServer(service::LoopbackConfig(), &service_);
    EXPECT_TRUE(running.ok()) << running.status();
    server_ = std::move(running->server);
    port_ = running->port;
  }
  ~LoopbackServer() {
    registry_.CloseAll(absl::UnavailableError("test over"));
    server_->Shutdown(std::chrono::system_clock::now() + std::chrono::seconds(2));
  }
  int port() const { return port_; }
  service::SessionRegistry& registry() { return registry_; }

 private:
  service::SessionRegistry registry_{service::RegistryOptions{}};
  service::SimulatorService service_;
  std::unique_ptr<grpc::Server> server_;
  int port_ = 0;
};

}  // namespace kerf::testing
