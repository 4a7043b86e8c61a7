#include "studio/studio_server.h"

#include <filesystem>
#include <fmt/format.h>
#include <fstream>
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

std::string points_path(const SceneSpec& scene) {
  if (scene.camera.kind != CameraSpec::Kind::Points)
    throw InputError(scene.path + ":" + scene.camera.where, "the studio edits control points: give \"camera\": {\"points\": \"points.json\"}");
  if (fs::path(scene.camera.points).extension() != ".json")
    throw InputError(scene.path + ":" + scene.camera.where, "the studio saves points as JSON; this scene's points are in " + scene.camera.points);
  if (scene.camera.bottom_left_origin)
    throw InputError(scene.path + ":" + scene.camera.where, "the studio writes top-left pixel coordinates: remove \"origin\": \"bottom_left\"");
  return scene.camera.points;
}

// The photo as the page shows it (sRGB, 8-bit PNG) and its luminance for corner snapping.
void load_photo(StudioServer::Impl& s) {
  const Image linear = linearize(read_image_file(s.scene.photo));
  s.width = linear.width, s.height = linear.height;
  s.gray.create(linear.height, linear.width, CV_32F);
  for (int y = 0; y < linear.height; ++y)
    for (int x = 0; x < linear.width; ++x) {
      const Rgb c = linear.rgb(x, y);
      s.gray.at<float>(y, x) = 0.2126f * linear_to_srgb(c[0]) + 0.7152f * linear_to_srgb(c[1]) + 0.0722f * linear_to_srgb(c[2]);
    }
  s.photo_png = srgb_png(linear);
}

}  // namespace

void reply_error(httplib::Response& res, int status, const std::string& where, const std::string& what) {
  res.status = status;
  res.set_content(json{{"error", where.empty() ? what : where + ": " + what}, {"where", where}, {"what", what}}.dump(),
                  "application/json");
}

StudioServer::Impl::Impl(const StudioOptions& o)
    : options(o), scene(parse_scene_file(o.scene)), folder(fs::absolute(o.scene).parent_path().string()),
      points(points_path(scene)), scene_file(o.scene, ""), render(o.scene) {
  load_photo(*this);
  http.set_payload_max_length(options.max_body_bytes);
  for (const StudioAsset* a = kStudioAssets; a->name; ++a)
    http.Get(std::string("/") + (std::string(a->name) == "index.html" ? "" : a->name), [a](const httplib::Request&, httplib::Response& res) {
      res.set_content(reinterpret_cast<const char*>(a->data), a->size, content_type(a->name).c_str());
    });
  http.Get("/api/photo.png", [this](const httplib::Request&, httplib::Response& res) {
    res.set_content(photo_png, "image/png");
  });
  http.Get(R"(/files/(.+))", [this](const httplib::Request& req, httplib::Response& res) {
    const auto file = file_under(folder, req.matches[1]);
    if (!file) return reply_error(res, 404, "", "no such file under the scene's folder");
    std::ifstream in(*file, std::ios::binary);
    res.set_content(std::string(std::istreambuf_iterator<char>(in), {}), content_type(file->string()).c_str());
  });
  add_api_routes();
}

StudioServer::StudioServer(const StudioOptions& options) : impl_(std::make_unique<Impl>(options)) {}
StudioServer::~StudioServer() = default;

int StudioServer::bind() {
  // Only the loopback address: the studio writes files and must never be reachable from the network.
  const int port = impl_->options.port == 0 ? impl_->http.bind_to_any_port("127.0.0.1")
                                            : (impl_->http.bind_to_port("127.0.0.1", impl_->options.port) ? impl_->options.port : -1);
  if (port <= 0) throw InputError(fmt::format("--port {}", impl_->options.port), "cannot listen on 127.0.0.1 (in use?)");
  return impl_->port = port;
}

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
