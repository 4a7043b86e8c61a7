// StudioServer's state, shared by its two files: studio_server.cpp (loading, the page, serving)
// and studio_api.cpp (the /api/ routes).
#pragma once
#include <atomic>
#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "scene/spec.h"
#include "studio/points_store.h"
#include "studio/render_job.h"
#include "studio/request_guard.h"
#include "studio/studio_server.h"
#include "studio/versioned_file.h"
// Last: glibc's <resolv.h>, which httplib.h includes, defines _res as a macro that breaks Eigen.
#include <httplib.h>

namespace insitu {

struct StudioServer::Impl {
  StudioOptions options;
  SceneSpec scene;
  std::string folder;  // the scene file's folder: the only one /files/ serves from
  int width = 0, height = 0;
  std::string photo_png;  // the photo, encoded once
  cv::Mat gray;           // its luminance, sRGB-encoded, CV_32F: for corner snapping
  // The points panel's file; none when the camera is not a "points" camera in JSON, and then
  // `points_refusal` says why (the page shows it; PUT /api/points and /api/calibrate answer 409).
  std::optional<PointsStore> points;
  std::string points_refusal;
  VersionedFile scene_file;  // the scene file, which the shots panel edits
  RenderJob render;          // the light and render panel's render (stopped before the server goes)
  httplib::Server http;
  StudioGuard guard;  // the launch's token and, once bound, the port (request_guard.h)
  // httplib's stop() does nothing before listening has begun; these let stop() and run() meet
  // in any order (studio_server.cpp).
  std::atomic<bool> stopping{false}, run_called{false}, run_returned{false};

  explicit Impl(const StudioOptions& o);
  void secure_server();  // studio_server.cpp: the guard, the headers, the limits
  void add_api_routes();
  void add_render_routes();
};

// A 400 (or other) reply with the CLI's message: {"error", "where", "what"}.
void reply_error(httplib::Response& res, int status, const std::string& where, const std::string& what);
// A JSON reply. Text that is not UTF-8 (a message quoting a request's bytes, a file's text) is
// sent with U+FFFD in place of the bad bytes (json_text): json::dump would otherwise throw.
void reply_json(httplib::Response& res, const json& body);

}  // namespace insitu
