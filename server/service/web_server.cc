#include "service/web_server.h"

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>
#include <thread>
#include <vector>

#include "absl/strings/ascii.h"
#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "google/protobuf/util/json_util.h"
#include "service/grpc_server.h"

namespace kerf::service {
namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = asio::ip::tcp;
using Request = http::request<http::string_body>;
using Response = http::response<http::string_body>;

constexpr char kSubprotocol[] = "kerf.v1";
constexpr char kTokenPrefix[] = "token.";

Response TextResponse(const Request& request, http::status status, std::string body,
                      const std::string& content_type = "text/plain; charset=utf-8") {
  Response response(status, request.version());
  response.set(http::field::content_type, content_type);
  response.set(http::field::cache_control, "no-store");
  response.keep_alive(request.keep_alive());
  response.body() = std::move(body);
  response.prepare_payload();
  return response;
}

std::string ContentType(const std::filesystem::path& file) {
  const std::string ext = file.extension().string();
  if (ext == ".html") return "text/html; charset=utf-8";
  if (ext == ".js" || ext == ".mjs") return "text/javascript; charset=utf-8";
  if (ext == ".css") return "text/css; charset=utf-8";
  if (ext == ".json" || ext == ".map") return "application/json";
  if (ext == ".svg") return "image/svg+xml";
  if (ext == ".png") return "image/png";
  if (ext == ".wasm") return "application/wasm";
  return "application/octet-stream";
}

// The query parameters of a target ("/observe?session=a&level=b").
std::vector<std::pair<std::string, std::string>> Query(absl::string_view target) {
  std::vector<std::pair<std::string, std::string>> query;
  const std::size_t mark = target.find('?');
  if (mark == absl::string_view::npos) return query;
  for (absl::string_view pair : absl::StrSplit(target.substr(mark + 1), '&', absl::SkipEmpty())) {
    const std::size_t eq = pair.find('=');
    query.emplace_back(std::string(pair.substr(0, eq)),
                       eq == absl::string_view::npos ? "" : std::string(pair.substr(eq + 1)));
  }
  return query;
}

std::string QueryValue(absl::string_view target, absl::string_view key) {
  for (const auto& [k, v] : Query(target)) {
    if (k == key) return v;
  }
  return "";
}

// The token offered as a subprotocol "token.<token>", or empty.
std::string OfferedToken(const Request& request) {
  for (absl::string_view offered : absl::StrSplit(
           std::string(request[http::field::sec_websocket_protocol]), ',', absl::SkipEmpty())) {
    offered = absl::StripAsciiWhitespace(offered);
    if (absl::StartsWith(offered, kTokenPrefix)) {
      return std::string(offered.substr(sizeof(kTokenPrefix) - 1));
    }
  }
  return "";
}

http::status HttpStatusOf(const absl::Status& status) {
  switch (status.code()) {
    case absl::StatusCode::kUnauthenticated:
      return http::status::unauthorized;
    case absl::StatusCode::kPermissionDenied:
      return http::status::forbidden;
    case absl::StatusCode::kNotFound:
      return http::status::not_found;
    case absl::StatusCode::kResourceExhausted:
      return http::status::service_unavailable;
    case absl::StatusCode::kInvalidArgument:
    case absl::StatusCode::kFailedPrecondition:
      return http::status::bad_request;
    default:
      return http::status::internal_server_error;
  }
}

// One observer's WebSocket: frames from its subscription, written one at a time.
class ObserverSocket : public std::enable_shared_from_this<ObserverSocket> {
 public:
  ObserverSocket(tcp::socket socket, std::shared_ptr<Session> session)
      : ws_(std::move(socket)), session_(std::move(session)) {}

  void Accept(const Request& request, kerf::v1::Level level) {
    ws_.set_option(websocket::stream_base::decorator([](websocket::response_type& response) {
      response.set(http::field::sec_websocket_protocol, kSubprotocol);
    }));
    ws_.binary(true);
    ws_.async_accept(request, [self = shared_from_this(), level](beast::error_code error) {
      if (!error) self->Subscribe(level);
    });
  }

  // Ends the subscription (the server is stopping). Not on the socket's thread: only after
  // that thread has stopped.
  void Unsubscribe() {
    if (subscription_ != nullptr) session_->Unsubscribe(std::exchange(subscription_, nullptr));
  }

 private:
  void Subscribe(kerf::v1::Level level) {
    const auto executor = ws_.get_executor();
    std::weak_ptr<ObserverSocket> weak = weak_from_this();
    absl::StatusOr<std::shared_ptr<Subscription>> subscription = session_->Observe(
        level,
        [weak, executor](const SerializedFrame& frame) {  // physics thread, queue locked
          asio::post(executor, [weak, bytes = frame.bytes] {
            if (auto self = weak.lock()) self->Write(bytes);
          });
        },
        [weak, executor](const absl::Status& why) {
          asio::post(executor, [weak, why] {
            if (auto self = weak.lock()) self->Close(why);
          });
        });
    if (!subscription.ok()) return Close(subscription.status());
    subscription_ = *std::move(subscription);
    Read();
  }

  void Write(std::shared_ptr<const std::string> bytes) {
    if (closing_ || subscription_ == nullptr) return;
    writing_ = true;
    ws_.async_write(asio::buffer(*bytes),
                    [self = shared_from_this(), bytes](beast::error_code error, std::size_t) {
                      self->writing_ = false;
                      if (error) return self->End();
                      if (self->close_after_write_) return self->Close(self->close_reason_);
                      if (self->subscription_ != nullptr) self->subscription_->queue->WriteDone();
                    });
  }

  // The session ended the subscription, or could not make it: a close frame with the reason.
  void Close(const absl::Status& why) {
    if (closing_) return;
    if (writing_) {  // one write at a time: the close goes after the frame on its way
      close_after_write_ = true;
      close_reason_ = why;
      return;
    }
    closing_ = true;
    websocket::close_reason reason(websocket::close_code::going_away,
                                   std::string(why.message()).substr(0, 120));
    ws_.async_close(reason, [self = shared_from_this()](beast::error_code) { self->End(); });
  }

  // Reads (and ignores) what the browser sends, to learn when it goes.
  void Read() {
    ws_.async_read(in_, [self = shared_from_this()](beast::error_code error, std::size_t) {
      if (error) return self->End();
      self->in_.clear();
      self->Read();
    });
  }

  void End() { Unsubscribe(); }

  websocket::stream<beast::tcp_stream> ws_;
  std::shared_ptr<Session> session_;
  std::shared_ptr<Subscription> subscription_;
  beast::flat_buffer in_;
  bool writing_ = false, closing_ = false, close_after_write_ = false;
  absl::Status close_reason_;
};

}  // namespace

struct WebServer::Impl {
  asio::io_context io{1};
  tcp::acceptor acceptor{io};
  SessionRegistry* registry = nullptr;
  std::filesystem::path web_root;
  std::thread thread;
  std::mutex observers_mutex;
  std::vector<std::weak_ptr<ObserverSocket>> observers;

  void Accept();
  void Serve(std::shared_ptr<beast::tcp_stream> stream, std::shared_ptr<beast::flat_buffer> buffer);
  Response Handle(const Request& request) const;
  void Upgrade(std::shared_ptr<beast::tcp_stream> stream, const Request& request);
};

void WebServer::Impl::Accept() {
  acceptor.async_accept([this](beast::error_code error, tcp::socket socket) {
    if (error) return;  // stopping
    Serve(std::make_shared<beast::tcp_stream>(std::move(socket)),
          std::make_shared<beast::flat_buffer>());
    Accept();
  });
}

void WebServer::Impl::Serve(std::shared_ptr<beast::tcp_stream> stream,
                            std::shared_ptr<beast::flat_buffer> buffer) {
  auto request = std::make_shared<Request>();
  stream->expires_after(std::chrono::seconds(60));
  http::async_read(*stream, *buffer, *request,
                   [this, stream, buffer, request](beast::error_code error, std::size_t) {
                     if (error) return;  // closed, timed out, or not HTTP
                     if (websocket::is_upgrade(*request)) return Upgrade(stream, *request);
                     auto response = std::make_shared<Response>(Handle(*request));
                     http::async_write(
                         *stream, *response,
                         [this, stream, buffer, response](beast::error_code e, std::size_t) {
                           if (!e && response->keep_alive()) Serve(stream, buffer);
                         });
                   });
}

void WebServer::Impl::Upgrade(std::shared_ptr<beast::tcp_stream> stream, const Request& request) {
  const absl::string_view target(request.target().data(), request.target().size());
  absl::Status refused;
  std::shared_ptr<Session> session;
  kerf::v1::Level level = kerf::v1::LEVEL_UNSPECIFIED;
  if (!absl::StartsWith(target, "/observe")) {
    refused = absl::NotFoundError("WebSocket endpoints: /observe?session=ID&level=LEVEL");
  } else if (!kerf::v1::Level_Parse(QueryValue(target, "level"), &level) ||
             level == kerf::v1::LEVEL_UNSPECIFIED) {
    refused = absl::InvalidArgumentError("level must be SURFACE, VOLUME or FORCES");
  } else {
    absl::StatusOr<std::shared_ptr<Session>> found = registry->Find(QueryValue(target, "session"));
    if (!found.ok()) {
      refused = found.status();
    } else if (absl::Status s =
                   (*found)->tokens().Authorize(Role::kObserver, OfferedToken(request));
               !s.ok()) {
      refused = s;
    } else {
      session = *std::move(found);
    }
  }
  if (!refused.ok()) {
    auto response = std::make_shared<Response>(
        TextResponse(request, HttpStatusOf(refused), std::string(refused.message())));
    response->keep_alive(false);
    http::async_write(*stream, *response, [stream, response](beast::error_code, std::size_t) {
      beast::error_code ignored;
      stream->socket().shutdown(tcp::socket::shutdown_send, ignored);
    });
    return;
  }
  stream->expires_never();  // the WebSocket keeps its own
  auto observer = std::make_shared<ObserverSocket>(stream->release_socket(), std::move(session));
  {
    std::lock_guard<std::mutex> lock(observers_mutex);
    std::erase_if(observers, [](const auto& weak) { return weak.expired(); });
    observers.push_back(observer);
  }
  observer->Accept(request, level);
}

Response WebServer::Impl::Handle(const Request& request) const {
  if (request.method() != http::verb::get && request.method() != http::verb::head) {
    return TextResponse(request, http::status::method_not_allowed, "only GET\n");
  }
  std::string path(request.target().data(), request.target().size());
  path = path.substr(0, path.find('?'));
  if (path == "/api/sessions") {
    kerf::v1::ListSessionsResponse list;
    for (const auto& session : registry->List()) *list.add_sessions() = session->Info();
    std::string json;
    google::protobuf::util::JsonPrintOptions options;
    options.preserve_proto_field_names = true;
    if (const auto status = google::protobuf::util::MessageToJsonString(list, &json, options);
        !status.ok()) {
      return TextResponse(request, http::status::internal_server_error,
                          absl::StrCat("the session list: ", status.ToString(), "\n"));
    }
    return TextResponse(request, http::status::ok, json, "application/json");
  }
  if (web_root.empty() || absl::StrContains(path, "..") || path.empty() || path[0] != '/') {
    return TextResponse(request, http::status::not_found, "not found\n");
  }
  std::filesystem::path file = web_root / path.substr(1);
  std::error_code error;
  if (std::filesystem::is_directory(file, error)) file /= "index.html";
  std::ifstream in(file, std::ios::binary);
  if (!in) return TextResponse(request, http::status::not_found, "not found\n");
  std::stringstream body;
  body << in.rdbuf();
  Response response = TextResponse(request, http::status::ok, body.str(), ContentType(file));
  response.set(http::field::cache_control, "no-cache");
  return response;
}

WebServer::WebServer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

WebServer::~WebServer() {
  impl_->io.stop();
  if (impl_->thread.joinable()) impl_->thread.join();
  std::lock_guard<std::mutex> lock(impl_->observers_mutex);
  for (const auto& weak : impl_->observers) {
    if (auto observer = weak.lock()) observer->Unsubscribe();
  }
}

int WebServer::port() const { return impl_->acceptor.local_endpoint().port(); }

absl::StatusOr<std::unique_ptr<WebServer>> WebServer::Start(const WebServerConfig& config,
                                                            SessionRegistry* registry) {
  if (!IsLoopback(config.listen) && !config.allow_remote_plaintext) {
    return absl::InvalidArgumentError(absl::StrCat(
        "refusing plain HTTP on ", config.listen,
        ", which is not a loopback address: put it behind a TLS proxy, or allow remote "
        "plaintext explicitly"));
  }
  const std::size_t colon = config.listen.rfind(':');
  int port = -1;
  if (colon == std::string::npos || !absl::SimpleAtoi(config.listen.substr(colon + 1), &port) ||
      port < 0 || port > 65535) {
    return absl::InvalidArgumentError(
        absl::StrCat("HTTP listen address '", config.listen, "' is not HOST:PORT"));
  }
  std::string host = config.listen.substr(0, colon);
  if (host == "localhost") host = "127.0.0.1";
  if (absl::StartsWith(host, "[")) host = host.substr(1, host.size() - 2);
  auto impl = std::make_unique<Impl>();
  impl->registry = registry;
  impl->web_root = config.web_root;
  beast::error_code error;
  const asio::ip::address address = asio::ip::make_address(host, error);
  if (error) {
    return absl::InvalidArgumentError(
        absl::StrCat("HTTP listen address '", config.listen, "': ", error.message()));
  }
  const tcp::endpoint endpoint(address, static_cast<unsigned short>(port));
  impl->acceptor.open(endpoint.protocol(), error);
  if (!error) impl->acceptor.set_option(asio::socket_base::reuse_address(true), error);
  if (!error) impl->acceptor.bind(endpoint, error);
  if (!error) impl->acceptor.listen(asio::socket_base::max_listen_connections, error);
  if (error) {
    return absl::UnavailableError(
        absl::StrCat("cannot listen for HTTP on ", config.listen, ": ", error.message()));
  }
  impl->Accept();
  Impl* raw = impl.get();
  impl->thread = std::thread([raw] { raw->io.run(); });
  return std::unique_ptr<WebServer>(new WebServer(std::move(impl)));
}

}  // namespace kerf::service
