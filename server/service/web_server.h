// The browser's view of the service: one HTTP port (Boost.Beast) serving the built viewer's
// files, the list of sessions, and a WebSocket per observer that carries exactly the
// serialized Frame bytes an Observe stream gets. It subscribes through the same
// Session::Observe, so the fan-out, keyframe and resync rules are the gRPC stream's; gRPC stays
// the one API and this is a view of it.
//
//   GET /api/sessions        {"sessions": [SessionInfo, ...]} as JSON (never a token)
//   GET /observe?session=ID&level=SURFACE|VOLUME|FORCES, upgraded to a WebSocket offering the
//       subprotocols "kerf.v1" and "token.<observer or cutter token>" (browsers cannot set
//       headers on a WebSocket; they can offer subprotocols): one binary message per Frame.
//       The answer selects "kerf.v1". A missing token is 401, a wrong one 403, an unknown
//       session 404, a bad level 400, each with the reason as text.
//   GET /<path>              a file under the web root (index.html for a folder), 404 if none.
#pragma once

#include <memory>
#include <string>

#include "absl/status/statusor.h"
#include "service/session_registry.h"

namespace kerf::service {

struct WebServerConfig {
  std::string listen = "127.0.0.1:8080";  // host:port; port 0 picks a free one
  std::string web_root;                   // the viewer's built files; empty: none served
  bool allow_remote_plaintext = false;    // plain HTTP only on loopback unless set
};

class WebServer {
 public:
  // INVALID_ARGUMENT for plain HTTP off loopback (unless allowed) or a bad address,
  // UNAVAILABLE when it cannot listen. Serves on a thread of its own until destroyed.
  static absl::StatusOr<std::unique_ptr<WebServer>> Start(const WebServerConfig& config,
                                                          SessionRegistry* registry);
  ~WebServer();

  int port() const;

 private:
  struct Impl;
  explicit WebServer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace kerf::service
