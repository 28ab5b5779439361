// A kerf-server process as an operator runs it, for tests: started with flags, read until it
// says where it listens, killed (SIGKILL) when the test is done with it.
#pragma once

#include <grpcpp/grpcpp.h>
#include <signal.h>

#include <cstdio>
#include <memory>
#include <string>
#include <utility>

#include "absl/strings/ascii.h"
#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "kerf/v1/simulator.grpc.pb.h"

namespace kerf::testing {

class ServerProcess {
 public:
  ServerProcess(const std::string& binary, const std::string& flags,
                const std::string& listen = "127.0.0.1:0") {
    // The shell prints its pid and becomes the server (exec keeps the pid).
    out_ = popen(absl::StrCat("sh -c 'echo $$; exec ", binary, " --listen=", listen,
                              " --http_listen=127.0.0.1:0 ", flags, " 2>&1'")
                     .c_str(),
                 "r");
    if (out_ == nullptr) return;
    char line[1024];
    if (fgets(line, sizeof(line), out_) == nullptr) return;
    if (!absl::SimpleAtoi(absl::StripAsciiWhitespace(line), &pid_)) return;
    while (fgets(line, sizeof(line), out_) != nullptr) {
      const std::string text = line;
      if (!absl::StartsWith(text, "kerf-server listening on ")) {
        said_ += text;
        continue;
      }
      (void)absl::SimpleAtoi(absl::StripAsciiWhitespace(text.substr(text.rfind(':') + 1)), &port_);
      break;
    }
    stub_ = kerf::v1::Simulator::NewStub(
        grpc::CreateChannel(absl::StrCat("127.0.0.1:", port_), grpc::InsecureChannelCredentials()));
  }
  ~ServerProcess() {
    if (out_ == nullptr) return;
    if (pid_ > 0) kill(pid_, SIGKILL);
    pclose(out_);
  }

  bool started() const { return port_ > 0; }
  int port() const { return port_; }
  // What it printed before listening (restores, warnings).
  const std::string& said() const { return said_; }
  kerf::v1::Simulator::Stub& stub() { return *stub_; }

  // Sends `signal` and waits for the exit; what it printed meanwhile, and its wait status.
  std::pair<std::string, int> Stop(int signal) {
    kill(pid_, signal);
    std::string rest;
    char line[1024];
    while (fgets(line, sizeof(line), out_) != nullptr) rest += line;
    const int status = pclose(out_);
    out_ = nullptr;
    return {rest, status};
  }

 private:
  FILE* out_ = nullptr;
  int pid_ = 0;
  int port_ = 0;
  std::string said_;
  std::unique_ptr<kerf::v1::Simulator::Stub> stub_;
};

}  // namespace kerf::testing
