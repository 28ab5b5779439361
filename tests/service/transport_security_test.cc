// TLS on the service, with certificates the test makes with openssl, and the rule that
// plaintext is served only on loopback unless explicitly allowed.
#include <grpcpp/grpcpp.h>
#include <grpcpp/security/credentials.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "absl/strings/str_cat.h"
#include "kerf/v1/simulator.grpc.pb.h"
#include "service/grpc_server.h"
#include "service/session_registry.h"
#include "service/simulator_service.h"
#include "support/run_command.h"
#include "support/status_message.h"

namespace kerf::service {
namespace {

using kerf::testing::RunCommand;

std::string Read(const std::string& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

// A self-signed certificate for localhost and 127.0.0.1, in a fresh directory.
struct Certificate {
  std::string directory, certificate_file, key_file;
  explicit Certificate(const std::string& name) {
    char pattern[] = "/tmp/kerf-tls-XXXXXX";
    directory = mkdtemp(pattern);
    certificate_file = directory + "/" + name + ".crt";
    key_file = directory + "/" + name + ".key";
    const auto made = RunCommand(absl::StrCat(
        "openssl req -x509 -newkey rsa:2048 -nodes -days 1 -subj /CN=localhost -addext "
        "subjectAltName=DNS:localhost,IP:127.0.0.1 -keyout ",
        key_file, " -out ", certificate_file, " 2>&1"));
    EXPECT_EQ(made.exit_code, 0) << made.output;
  }
  ~Certificate() { (void)RunCommand("rm -rf " + directory); }
};

// By address (the certificate names 127.0.0.1), so that no name is resolved.
grpc::Status ListScenes(const std::shared_ptr<grpc::ChannelCredentials>& credentials, int port) {
  auto stub = kerf::v1::Simulator::NewStub(
      grpc::CreateChannel(absl::StrCat("127.0.0.1:", port), credentials));
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(5));
  kerf::v1::ListScenesResponse scenes;
  return stub->ListScenes(&context, {}, &scenes);
}

TEST(TransportSecurity, ServesTlsToClientsThatTrustItsCertificateOnly) {
  const Certificate server_certificate("server"), other("other");
  SessionRegistry registry({});
  SimulatorService service(&registry);
  ServerConfig config;
  config.listen = "127.0.0.1:0";
  config.tls_certificate_file = server_certificate.certificate_file;
  config.tls_key_file = server_certificate.key_file;
  absl::StatusOr<RunningServer> server = StartServer(config, &service);
  ASSERT_TRUE(server.ok()) << server.status();

  grpc::SslCredentialsOptions trusting;
  trusting.pem_root_certs = Read(server_certificate.certificate_file);
  EXPECT_TRUE(ListScenes(grpc::SslCredentials(trusting), server->port).ok());

  grpc::SslCredentialsOptions distrusting;
  distrusting.pem_root_certs = Read(other.certificate_file);
  EXPECT_EQ(ListScenes(grpc::SslCredentials(distrusting), server->port).error_code(),
            grpc::StatusCode::UNAVAILABLE);
  EXPECT_EQ(ListScenes(grpc::InsecureChannelCredentials(), server->port).error_code(),
            grpc::StatusCode::UNAVAILABLE);
  server->server->Shutdown();
}

TEST(TransportSecurity, PlaintextOnlyOnLoopbackUnlessAllowed) {
  EXPECT_TRUE(IsLoopback("127.0.0.1:50051"));
  EXPECT_TRUE(IsLoopback("localhost:0"));
  EXPECT_TRUE(IsLoopback("[::1]:50051"));
  EXPECT_FALSE(IsLoopback("0.0.0.0:50051"));
  EXPECT_FALSE(IsLoopback("[::]:50051"));
  EXPECT_FALSE(IsLoopback("10.0.0.7:50051"));
  SessionRegistry registry({});
  SimulatorService service(&registry);
  ServerConfig config;
  config.listen = "0.0.0.0:0";
  EXPECT_EQ(kerf::testing::StatusMessage(StartServer(config, &service)),
            "refusing plaintext on 0.0.0.0:0, which is not a loopback address: give a TLS "
            "certificate and key, or allow remote plaintext explicitly");
  config.tls_certificate_file = "/nonexistent.crt";
  EXPECT_EQ(kerf::testing::StatusMessage(StartServer(config, &service)),
            "TLS needs both a certificate file and a key file");
  config.tls_key_file = "/nonexistent.key";
  EXPECT_EQ(kerf::testing::StatusMessage(StartServer(config, &service)),
            "cannot read the certificate file '/nonexistent.crt'");
  config = {};
  config.listen = "0.0.0.0:0";
  config.allow_remote_plaintext = true;
  absl::StatusOr<RunningServer> server = StartServer(config, &service);
  ASSERT_TRUE(server.ok()) << server.status();
  server->server->Shutdown();
}

TEST(TransportSecurity, KerfServerRefusesRemotePlaintextAtStart) {
  const auto run = RunCommand(absl::StrCat(KERF_SERVER_BINARY, " --listen=0.0.0.0:0 2>&1"));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.output,
            "kerf-server: refusing plaintext on 0.0.0.0:0, which is not a loopback address: give "
            "a TLS certificate and key, or allow remote plaintext explicitly\n");
}

}  // namespace
}  // namespace kerf::service
