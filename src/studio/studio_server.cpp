#include "studio/studio_server.h"

#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <sys/socket.h>
#include <thread>

#include "core/colour.h"
#include "core/image.h"
#include "scene/scene_file.h"
#include "studio/file_under.h"
#include "studio/preview_png.h"
#include "studio/studio_assets.h"
#include "studio/studio_impl.h"

namespace insitu {
namespace fs = std::filesystem;

namespace {

std::string content_type(const std::string& name) {
  const std::string ext = fs::path(name).extension().string();
  if (ext == ".html") return "text/html; charset=utf-8";
  if (ext == ".js") return "text/javascript; charset=utf-8";
  if (ext == ".css") return "text/css; charset=utf-8";
  if (ext == ".json") return "application/json";
  if (ext == ".png") return "image/png";
  if (ext == ".jpg" || ext == ".jpeg") return "image/jpeg";
  return "application/octet-stream";
}

// Why the points panel cannot edit this scene's camera, or "" when it can (a "points" camera
// whose points are a JSON file in top-left pixels). The shots, references and render still work.
std::string points_refusal(const SceneSpec& scene) {
  const CameraSpec& c = scene.camera;
  switch (c.kind) {
    case CameraSpec::Kind::Fspy:
      return "this scene's camera comes from fSpy (" + fs::path(c.file).filename().string() +
             "): the points panel edits a \"points\" camera only";
    case CameraSpec::Kind::File:
      return "this scene's camera comes from " + fs::path(c.file).filename().string() +
             ": the points panel edits a \"points\" camera only";
    case CameraSpec::Kind::LookAt:
    case CameraSpec::Kind::Explicit:
      return "this scene's camera is given by numbers (eye and look, or R and t): the points panel edits a \"points\" "
             "camera only";
    case CameraSpec::Kind::Points:
      break;
  }
  if (fs::path(c.points).extension() != ".json")
    return "the studio saves points as JSON; this scene's points are in " + fs::path(c.points).filename().string();
  if (c.bottom_left_origin)
    return "the studio writes top-left pixel coordinates; this scene's points have \"origin\": \"bottom_left\"";
  return "";
}

// The photo as the page shows it (sRGB, 8-bit PNG) and its luminance for corner snapping.
void load_photo(StudioServer::Impl& s) {
  const Image linear = linearize(read_image_file(s.scene.photo));
  s.width = linear.width, s.height = linear.height;
  s.gray.create(linear.height, linear.width, CV_32F);
  for (int y = 0; y < linear.height; ++y)
    for (int x = 0; x < linear.width; ++x) {
      const Rgb c = linear.rgb(x, y);
      s.gray.at<float>(y, x) =
          0.2126f * linear_to_srgb(c[0]) + 0.7152f * linear_to_srgb(c[1]) + 0.0722f * linear_to_srgb(c[2]);
    }
  s.photo_png = srgb_png(linear);
}

// The headers of every reply: no page of another site may frame the studio (clickjacking), run
// anything but the studio's own scripts in it, or sniff a reply's type; nothing is cached (the
// photo and the token's page are the customer's).
const httplib::Headers kSecurityHeaders = {
    {"X-Frame-Options", "DENY"},
    {"Content-Security-Policy",
     "default-src 'self'; img-src 'self' data: blob:; object-src 'none'; base-uri 'none'; form-action 'none'; "
     "frame-ancestors 'none'"},
    {"X-Content-Type-Options", "nosniff"},
    {"Referrer-Policy", "no-referrer"},
    {"Cache-Control", "no-store"},
};

// The limits of the server. A thread serves one connection at a time, so the pool is larger than
// a browser's six connections per host plus stalled ones; a connection that sends nothing is
// closed after kIdleSeconds, one that stalls mid-request after kReadSeconds.
constexpr int kServerThreads = 32, kIdleSeconds = 2, kReadSeconds = 5, kWriteSeconds = 5;

RequestHeaders headers_of(const httplib::Request& req) {
  return {req.method,
          req.get_header_value("Host"),
          req.get_header_value("Origin"),
          req.get_header_value("Content-Type"),
          req.get_header_value("Authorization"),
          req.get_header_value("Cookie"),
          req.has_param("token") ? req.get_param_value("token") : ""};
}

}  // namespace

void reply_json(httplib::Response& res, const json& body) { res.set_content(json_text(body), "application/json"); }

void reply_error(httplib::Response& res, int status, const std::string& where, const std::string& what) {
  res.status = status;
  reply_json(res, json{{"error", where.empty() ? what : where + ": " + what}, {"where", where}, {"what", what}});
}

StudioServer::Impl::Impl(const StudioOptions& o)
    : options(o),
      scene(parse_scene_file(o.scene)),
      folder(fs::absolute(o.scene).parent_path().string()),
      points_refusal(insitu::points_refusal(scene)),
      scene_file(o.scene, ""),
      render(o.scene),
      guard{random_token(), 0} {
  if (points_refusal.empty()) points.emplace(scene.camera.points);
  load_photo(*this);
  secure_server();
  for (const StudioAsset* a = kStudioAssets; a->name; ++a)
    http.Get(std::string("/") + (std::string(a->name) == "index.html" ? "" : a->name),
             [a](const httplib::Request&, httplib::Response& res) {
               res.set_content(reinterpret_cast<const char*>(a->data), a->size, content_type(a->name).c_str());
             });
  http.Get("/api/photo.png",
           [this](const httplib::Request&, httplib::Response& res) { res.set_content(photo_png, "image/png"); });
  http.Get(R"(/files/(.+))", [this](const httplib::Request& req, httplib::Response& res) {
    const auto file = file_under(folder, req.matches[1]);
    if (!file) return reply_error(res, 404, "", "no such file under the scene's folder");
    std::ifstream in(*file, std::ios::binary);
    res.set_content(std::string(std::istreambuf_iterator<char>(in), {}), content_type(file->string()).c_str());
  });
  add_api_routes();
}

void StudioServer::Impl::secure_server() {
  // The port is this studio's alone: httplib's default also sets SO_REUSEPORT, under which a
  // second studio binds the same port and the kernel splits the requests between the two scenes.
  http.set_socket_options([](socket_t sock) {
    const int yes = 1;  // SO_REUSEADDR: a restart may bind while old connections are in TIME_WAIT
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
  });
  http.new_task_queue = [] { return new httplib::ThreadPool(kServerThreads); };
  http.set_keep_alive_timeout(kIdleSeconds);
  http.set_read_timeout(kReadSeconds, 0);
  http.set_write_timeout(kWriteSeconds, 0);
  http.set_payload_max_length(options.max_body_bytes);
  http.set_default_headers(kSecurityHeaders);
  // Before any route, and before the request's body is read (request_guard.h).
  http.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
    const GuardVerdict v = judge_request(guard, headers_of(req));
    if (v.status != 0) {
      reply_error(res, v.status, "", v.what);
      return httplib::Server::HandlerResponse::Handled;
    }
    if (v.set_cookie) res.set_header("Set-Cookie", token_cookie(guard));
    return httplib::Server::HandlerResponse::Unhandled;
  });
  // A handler's unexpected exception is a 500 with its message, never an empty reply.
  http.set_exception_handler([](const httplib::Request& req, httplib::Response& res, std::exception_ptr ep) {
    std::string what = "unknown exception";
    try {
      std::rethrow_exception(ep);
    } catch (const std::exception& e) {
      what = e.what();
    } catch (...) {
    }
    reply_error(res, 500, req.path, "internal error: " + what);
  });
}

StudioServer::StudioServer(const StudioOptions& options) : impl_(std::make_unique<Impl>(options)) {}
StudioServer::~StudioServer() = default;

int StudioServer::bind() {
  // Only the loopback address: the studio writes files and must never be reachable from the network.
  const int port = impl_->options.port == 0
                       ? impl_->http.bind_to_any_port("127.0.0.1")
                       : (impl_->http.bind_to_port("127.0.0.1", impl_->options.port) ? impl_->options.port : -1);
  if (port <= 0)
    throw InputError(fmt::format("--port {}", impl_->options.port),
                     "127.0.0.1 has this port in use (another studio?) or will not give it: choose another, or --port "
                     "0 for any free one");
  return impl_->guard.port = port;
}

std::string StudioServer::url() const {
  return fmt::format("http://127.0.0.1:{}/?token={}", impl_->guard.port, impl_->guard.token);
}
const std::string& StudioServer::token() const { return impl_->guard.token; }

void StudioServer::run() {
  impl_->run_called = true;
  if (!impl_->stopping) impl_->http.listen_after_bind();
  impl_->run_returned = true;
}

// A stop() that comes before run() has begun to listen waits until it does (or has returned
// without listening, having seen `stopping`), so the server never starts after it was stopped.
void StudioServer::stop() {
  impl_->stopping = true;
  while (impl_->run_called && !impl_->run_returned && !impl_->http.is_running())
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  impl_->http.stop();
}

}  // namespace insitu
