// The browser's port against a real registry and gRPC service on loopback, with Beast's own
// HTTP and WebSocket clients standing in for a browser (the real browser's tests are in web/).
#include "service/web_server.h"

#include <gtest/gtest.h>

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <filesystem>
#include <fstream>
#include <map>

#include "absl/strings/str_cat.h"
#include "kerf/v1/simulator.grpc.pb.h"
#include "service/grpc_server.h"
#include "service/simulator_service.h"

namespace kerf::service {
namespace {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = boost::asio::ip::tcp;

class WebServerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = absl::StrCat(::testing::TempDir(), "/kerf-web-", getpid());
    std::filesystem::create_directories(root_);
    std::ofstream(root_ + "/index.html") << "<!doctype html><title>kerf</title>";
    WebServerConfig config;
    config.listen = "127.0.0.1:0";
    config.web_root = root_;
    absl::StatusOr<std::unique_ptr<WebServer>> web = WebServer::Start(config, &registry_);
    ASSERT_TRUE(web.ok()) << web.status();
    web_ = *std::move(web);
    absl::StatusOr<RunningServer> grpc_server = StartServer(LoopbackConfig(), &service_);
    ASSERT_TRUE(grpc_server.ok()) << grpc_server.status();
    grpc_ = std::move(grpc_server->server);
    stub_ = kerf::v1::Simulator::NewStub(grpc::CreateChannel(
        absl::StrCat("127.0.0.1:", grpc_server->port), grpc::InsecureChannelCredentials()));
    absl::StatusOr<CreatedSession> created = registry_.Create({});
    ASSERT_TRUE(created.ok()) << created.status();
    session_ = created->session->id();
    tokens_ = created->tokens;
  }
  void TearDown() override {
    registry_.CloseAll(absl::UnavailableError("test over"));
    web_.reset();
    grpc_->Shutdown(std::chrono::system_clock::now() + std::chrono::seconds(2));
    std::filesystem::remove_all(root_);
  }

  http::response<http::string_body> Get(const std::string& target) {
    boost::asio::io_context io;
    beast::tcp_stream stream(io);
    stream.connect(tcp::endpoint(boost::asio::ip::make_address("127.0.0.1"), web_->port()));
    http::request<http::empty_body> request(http::verb::get, target, 11);
    request.set(http::field::host, "127.0.0.1");
    http::write(stream, request);
    beast::flat_buffer buffer;
    http::response<http::string_body> response;
    http::read(stream, buffer, response);
    return response;
  }

  // A WebSocket to /observe offering `subprotocols`; the handshake's error and response.
  struct Socket {
    boost::asio::io_context io;
    websocket::stream<tcp::socket> ws{io};
    websocket::response_type response;
    beast::error_code error;
  };
  std::unique_ptr<Socket> Connect(const std::string& target, const std::string& subprotocols) {
    auto socket = std::make_unique<Socket>();
    socket->ws.next_layer().connect(
        tcp::endpoint(boost::asio::ip::make_address("127.0.0.1"), web_->port()));
    socket->ws.set_option(
        websocket::stream_base::decorator([subprotocols](websocket::request_type& request) {
          if (!subprotocols.empty()) request.set(http::field::sec_websocket_protocol, subprotocols);
        }));
    socket->ws.handshake(socket->response, "127.0.0.1", target, socket->error);
    return socket;
  }
  std::string ObserveTarget(const std::string& level) const {
    return absl::StrCat("/observe?session=", session_, "&level=", level);
  }

  SessionRegistry registry_{RegistryOptions{}};
  SimulatorService service_{&registry_};
  std::unique_ptr<WebServer> web_;
  std::unique_ptr<grpc::Server> grpc_;
  std::unique_ptr<kerf::v1::Simulator::Stub> stub_;
  std::string root_, session_;
  IssuedTokens tokens_;
};

TEST_F(WebServerTest, ServesTheViewerAndTheSessionList) {
  auto index = Get("/");
  EXPECT_EQ(index.result(), http::status::ok);
  EXPECT_EQ(index.body(), "<!doctype html><title>kerf</title>");
  EXPECT_EQ(index[http::field::content_type], "text/html; charset=utf-8");
  EXPECT_EQ(Get("/missing.js").result(), http::status::not_found);
  EXPECT_EQ(Get("/../../etc/passwd").result(), http::status::not_found);
  auto sessions = Get("/api/sessions");
  EXPECT_EQ(sessions.result(), http::status::ok);
  EXPECT_NE(sessions.body().find(session_), std::string::npos) << sessions.body();
  EXPECT_NE(sessions.body().find("\"tets\":\"576\""), std::string::npos) << sessions.body();
  EXPECT_EQ(sessions.body().find(tokens_.observer), std::string::npos);  // never a token
  EXPECT_EQ(sessions.body().find(tokens_.cutter), std::string::npos);
}

// (The refusals are read as a browser's handshake sees them: the HTTP answer to the upgrade.)
TEST_F(WebServerTest, RefusesObserversWithoutTheRightTokenSessionOrLevel) {
  const auto refusal = [&](const std::string& target, const std::string& subprotocols) {
    EXPECT_EQ(Connect(target, subprotocols)->error, websocket::error::upgrade_declined);
    boost::asio::io_context io;
    beast::tcp_stream stream(io);
    stream.connect(tcp::endpoint(boost::asio::ip::make_address("127.0.0.1"), web_->port()));
    http::request<http::empty_body> request(http::verb::get, target, 11);
    request.set(http::field::host, "127.0.0.1");
    request.set(http::field::connection, "Upgrade");
    request.set(http::field::upgrade, "websocket");
    request.set(http::field::sec_websocket_key, "dGhlIHNhbXBsZSBub25jZQ==");
    request.set(http::field::sec_websocket_version, "13");
    if (!subprotocols.empty()) request.set(http::field::sec_websocket_protocol, subprotocols);
    http::write(stream, request);
    beast::flat_buffer buffer;
    http::response<http::string_body> response;
    http::read(stream, buffer, response);
    return std::pair(response.result(), response.body());
  };
  EXPECT_EQ(refusal(ObserveTarget("SURFACE"), "kerf.v1").first, http::status::unauthorized);
  EXPECT_EQ(refusal(ObserveTarget("SURFACE"), "kerf.v1, token.0123").first,
            http::status::forbidden);
  EXPECT_EQ(refusal("/observe?session=nope&level=SURFACE",
                    absl::StrCat("kerf.v1, token.", tokens_.observer))
                .first,
            http::status::not_found);
  const auto [status, body] =
      refusal(ObserveTarget("SIDEWAYS"), absl::StrCat("kerf.v1, token.", tokens_.observer));
  EXPECT_EQ(status, http::status::bad_request);
  EXPECT_EQ(body, "level must be SURFACE, VOLUME or FORCES");
}

// The WebSocket carries the very bytes the gRPC stream does: a frame of the same sequence is
// the same message, byte for byte.
TEST_F(WebServerTest, AnObserverGetsTheSameFrameBytesAsAGrpcObserver) {
  std::unique_ptr<Socket> socket =
      Connect(ObserveTarget("SURFACE"), absl::StrCat("kerf.v1, token.", tokens_.observer));
  ASSERT_FALSE(socket->error) << socket->error.message();
  EXPECT_EQ(socket->response[http::field::sec_websocket_protocol], "kerf.v1");
  grpc::ClientContext context;
  kerf::v1::ObserveRequest request;
  request.set_session_id(session_);
  request.set_level(kerf::v1::SURFACE);
  request.set_token(tokens_.observer);
  auto reader = stub_->Observe(&context, request);
  std::map<std::uint64_t, std::string> over_grpc, over_websocket;
  kerf::v1::Frame frame;
  for (int i = 0; i < 20 && reader->Read(&frame); ++i) {
    if (!frame.keyframe()) over_grpc[frame.sequence()] = frame.SerializeAsString();
  }
  context.TryCancel();
  bool first = true;
  for (int i = 0; i < 20; ++i) {
    beast::flat_buffer buffer;
    socket->ws.read(buffer);
    EXPECT_TRUE(socket->ws.got_binary());
    const std::string bytes = beast::buffers_to_string(buffer.data());
    ASSERT_TRUE(frame.ParseFromString(bytes));
    EXPECT_EQ(frame.keyframe(), first);  // a keyframe first, then deltas
    first = false;
    if (!frame.keyframe()) over_websocket[frame.sequence()] = bytes;
  }
  int compared = 0;
  for (const auto& [sequence, bytes] : over_websocket) {
    const auto it = over_grpc.find(sequence);
    if (it == over_grpc.end()) continue;
    // The bytes hold the send time: the same frame was serialized once for both.
    EXPECT_EQ(bytes, it->second) << "frame " << sequence;
    ++compared;
  }
  EXPECT_GT(compared, 5);
}

TEST_F(WebServerTest, ClosingTheSessionClosesTheWebSocketWithTheReason) {
  std::unique_ptr<Socket> socket =
      Connect(ObserveTarget("SURFACE"), absl::StrCat("kerf.v1, token.", tokens_.observer));
  ASSERT_FALSE(socket->error) << socket->error.message();
  beast::flat_buffer buffer;
  socket->ws.read(buffer);  // the keyframe
  ASSERT_TRUE(registry_.Close(session_).ok());
  beast::error_code error;
  while (!error) {
    buffer.clear();
    socket->ws.read(buffer, error);
  }
  EXPECT_EQ(error, websocket::error::closed);
  EXPECT_EQ(socket->ws.reason().code, websocket::close_code::going_away);
  EXPECT_NE(std::string(socket->ws.reason().reason.c_str()).find("was closed"), std::string::npos);
}

}  // namespace
}  // namespace kerf::service
