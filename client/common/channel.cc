#include "common/channel.h"

#include <fstream>
#include <sstream>

#include "absl/strings/str_cat.h"

namespace kerf::client {

absl::StatusOr<std::shared_ptr<grpc::Channel>> OpenChannel(const std::string& server,
                                                           const std::string& tls_ca,
                                                           bool own_connection) {
  grpc::ChannelArguments arguments;
  if (own_connection) arguments.SetInt(GRPC_ARG_USE_LOCAL_SUBCHANNEL_POOL, 1);
  if (tls_ca.empty()) {
    return grpc::CreateCustomChannel(server, grpc::InsecureChannelCredentials(), arguments);
  }
  std::ifstream file(tls_ca);
  std::stringstream pem;
  pem << file.rdbuf();
  if (!file || pem.str().empty()) {
    return absl::NotFoundError(absl::StrCat("cannot read --tls_ca '", tls_ca, "'"));
  }
  grpc::SslCredentialsOptions options;
  options.pem_root_certs = pem.str();
  return grpc::CreateCustomChannel(server, grpc::SslCredentials(options), arguments);
}

}  // namespace kerf::client
