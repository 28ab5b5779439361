// kerf-server: serves kerf.v1.Simulator over gRPC (with standard health checking and server
// reflection). With no arguments it listens on 127.0.0.1:50051 with the embedded default
// scene, journaling sessions to ./kerf-journal and restoring those found there. SIGINT or
// SIGTERM shut it down gracefully: every stream ends with UNAVAILABLE, and the sessions stay in
// the journal to be restored at the next start.
#include <fcntl.h>
#include <grpcpp/grpcpp.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <thread>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "absl/flags/usage.h"
#include "absl/strings/str_cat.h"
#include "service/grpc_server.h"
#include "service/session_registry.h"
#include "service/simulator_service.h"
#include "service/web_server.h"

ABSL_FLAG(std::string, listen, "127.0.0.1:50051",
          "address to listen on, host:port (port 0 picks a free one, printed at start)");
ABSL_FLAG(std::string, default_scene, "lattice-tension",
          "embedded scene for sessions created without one");
ABSL_FLAG(int, max_sessions, 16, "sessions the server holds at once");
ABSL_FLAG(int, max_observers, 64, "observers per session");
ABSL_FLAG(double, physics_rate_hz, 1000, "default physics tick rate of a session");
ABSL_FLAG(double, frame_rate_hz, 60, "default frame rate for observers");
ABSL_FLAG(int, max_message_bytes, 4 << 20, "largest request accepted, bytes");
ABSL_FLAG(std::string, tls_cert, "", "PEM certificate chain: serve TLS (with --tls_key)");
ABSL_FLAG(std::string, tls_key, "", "PEM private key of --tls_cert");
ABSL_FLAG(bool, allow_remote_plaintext, false,
          "serve plaintext on a non-loopback address (refused otherwise)");
ABSL_FLAG(std::string, http_listen, "127.0.0.1:8080",
          "address of the browser's HTTP and WebSocket port, host:port (port 0 picks a free one, "
          "printed at start; empty: none)");
ABSL_FLAG(std::string, web_root, "web/dist", "the web viewer's built files, served over HTTP");
ABSL_FLAG(std::string, journal_dir, "kerf-journal",
          "directory of the session journals (made if missing); sessions found there are "
          "restored at start; empty: no journal");

namespace {
int signal_pipe[2] = {-1, -1};  // written by the signal handler, read by the shutdown thread
}  // namespace

int main(int argc, char** argv) {
  absl::SetProgramUsageMessage("kerf-server [--listen=HOST:PORT] [--default_scene=NAME] ...");
  absl::ParseCommandLine(argc, argv);

  // SIGINT and SIGTERM are caught whichever thread they land on (gRPC starts threads of its
  // own before main, so blocking them here would not cover those) and handed to a thread of
  // ours through a pipe.
  if (pipe2(signal_pipe, O_CLOEXEC) != 0) {
    std::perror("kerf-server: pipe");
    return 1;
  }
  struct sigaction action = {};
  action.sa_handler = [](int signal) {
    const char byte = static_cast<char>(signal);
    (void)!write(signal_pipe[1], &byte, 1);  // async-signal-safe
  };
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);

  kerf::service::RegistryOptions options;
  options.max_sessions = static_cast<std::size_t>(absl::GetFlag(FLAGS_max_sessions));
  options.default_scene = absl::GetFlag(FLAGS_default_scene);
  options.session.max_subscribers = static_cast<std::size_t>(absl::GetFlag(FLAGS_max_observers));
  options.session.physics_rate_hz = absl::GetFlag(FLAGS_physics_rate_hz);
  options.session.frame_rate_hz = absl::GetFlag(FLAGS_frame_rate_hz);
  options.journal_dir = absl::GetFlag(FLAGS_journal_dir);
  if (!options.journal_dir.empty()) {
    std::error_code error;
    std::filesystem::create_directories(options.journal_dir, error);
    std::filesystem::permissions(options.journal_dir, std::filesystem::perms::owner_all, error);
    if (error || !std::filesystem::is_directory(options.journal_dir)) {
      std::fprintf(stderr, "kerf-server: cannot use --journal_dir=%s: %s\n",
                   options.journal_dir.c_str(), error.message().c_str());
      return 2;
    }
  }
  kerf::service::SessionRegistry registry(options);
  // The default scene must load: fail at start, not at the first request.
  if (absl::StatusOr<kerf::sim::Scene> scene = kerf::sim::LoadScene(options.default_scene);
      !scene.ok()) {
    std::fprintf(stderr, "kerf-server: %s\n", scene.status().ToString().c_str());
    return 2;
  }
  for (const kerf::service::RestoreOutcome& outcome : registry.Restore()) {
    if (!outcome.warning.empty()) {
      std::fprintf(stderr, "kerf-server: warning: %s\n", outcome.warning.c_str());
    }
    if (!outcome.status.ok()) {
      std::fprintf(stderr, "kerf-server: not restored: %s\n",
                   std::string(outcome.status.message()).c_str());
    } else if (outcome.restored) {
      std::printf("kerf-server: restored %s (%llu ticks)\n", outcome.journal.c_str(),
                  static_cast<unsigned long long>(outcome.ticks));
    }
  }
  kerf::service::SimulatorService service(&registry);

  kerf::service::ServerConfig config;
  config.listen = absl::GetFlag(FLAGS_listen);
  config.max_message_bytes = absl::GetFlag(FLAGS_max_message_bytes);
  config.tls_certificate_file = absl::GetFlag(FLAGS_tls_cert);
  config.tls_key_file = absl::GetFlag(FLAGS_tls_key);
  config.allow_remote_plaintext = absl::GetFlag(FLAGS_allow_remote_plaintext);
  absl::StatusOr<kerf::service::RunningServer> running =
      kerf::service::StartServer(config, &service);
  if (!running.ok()) {
    std::fprintf(stderr, "kerf-server: %s\n", std::string(running.status().message()).c_str());
    return absl::IsInvalidArgument(running.status()) ? 2 : 1;
  }
  grpc::Server* server = running->server.get();
  std::unique_ptr<kerf::service::WebServer> web;
  if (const std::string http = absl::GetFlag(FLAGS_http_listen); !http.empty()) {
    kerf::service::WebServerConfig web_config;
    web_config.listen = http;
    web_config.web_root = absl::GetFlag(FLAGS_web_root);
    web_config.allow_remote_plaintext = absl::GetFlag(FLAGS_allow_remote_plaintext);
    absl::StatusOr<std::unique_ptr<kerf::service::WebServer>> started =
        kerf::service::WebServer::Start(web_config, &registry);
    if (!started.ok()) {
      std::fprintf(stderr, "kerf-server: %s\n", std::string(started.status().message()).c_str());
      registry.CloseAll(absl::UnavailableError("the server could not start"));
      server->Shutdown();
      return absl::IsInvalidArgument(started.status()) ? 2 : 1;
    }
    web = *std::move(started);
    std::printf("kerf-server web on %s:%d\n", http.substr(0, http.rfind(':')).c_str(), web->port());
  }
  const int port = running->port;
  const std::string address = absl::GetFlag(FLAGS_listen);
  std::printf("kerf-server listening on %s:%d\n", address.substr(0, address.rfind(':')).c_str(),
              port);
  std::fflush(stdout);

  std::thread waiter([&] {
    char byte = 0;
    while (read(signal_pipe[0], &byte, 1) < 0 && errno == EINTR) {
    }
    const int signal = byte;
    std::printf("kerf-server: signal %d, shutting down\n", signal);
    std::fflush(stdout);
    registry.CloseAll(absl::UnavailableError("the server is shutting down"));
    server->Shutdown(std::chrono::system_clock::now() + std::chrono::seconds(5));
  });
  server->Wait();
  waiter.join();
  return 0;
}
