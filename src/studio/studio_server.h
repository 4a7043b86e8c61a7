// insitu studio: a local web page over one scene, served on 127.0.0.1 only, with three
// panels: the control points (calibrated after every change, saved to points.json), the six shots
// (turned, swapped, the faced wall set in the scene file), and the light and render.
//
// The server (cpp-httplib, Debian's libcpp-httplib-dev) answers:
//   GET  /, /studio.js, ...           the page (src/studio/page/, compiled in)
//   GET  /api/state                   the scene's photo size, points.json's text and version, its
//                                     tone map; for a camera not from points.json (fSpy, a camera
//                                     file, eye and look) "points_refusal" says why, and PUT
//                                     /api/points and /api/calibrate answer 409
//   GET  /api/photo.png               the photo, sRGB 8-bit (any photo format the CLI reads)
//   GET  /files/PATH                  a file under the scene's folder (file_under.h), else 404
//   PUT  /api/points                  {"version", "points"}: saved atomically, or 409 on conflict
//   POST /api/calibrate               {"points", "model"}: calibration_view.h
//   POST /api/snap                    {"uv"}: corner_snap.h
//   GET  /api/shots                   the shots as assembled, and the scene file's version (shots_view.h)
//   GET  /api/shot/N.png              shot N (0..5) as used, clipped pixels red
//   POST /api/shots                   {"version", "op": swap | turn | faced, ...}: scene_edit.h, or 409
//   GET  /api/references              the scene's references of known albedo, and its version
//   POST /api/references              {"version", "op": add | remove, ...}: scene_edit.h, read as the
//                                     CLI reads it (corners within the photo), or 409
//   POST /api/render                  {"integrator", "spp"}: a render started (render_job.h)
//   POST /api/render/stop             stop it (within one sample per pixel)
//   POST /api/render/save             {"overwrite"}: write the scene's outputs from the last finished
//                                     render; 409 if they exist and "overwrite" is not true
//   GET  /api/render                  its state, progress, noise and each integrator's slot
//   GET  /api/render/NAME.png         slot NAME's latest image, ?tonemap=&key=&bias=
//   GET  /api/light/cube.png, /api/light/irradiance.png   the light the render used
// Errors are 400 with {"error": "<where>: <what>", "where", "what"}: the CLI's message. Request
// bodies over 1 MiB are refused (413) before they are read. Every request needs the launch's
// token, its own Host, and (if it changes anything) its own Origin and a JSON body: 403 or 415
// otherwise (request_guard.h).
#pragma once
#include <memory>
#include <string>

namespace insitu {

struct StudioOptions {
  std::string scene;  // the scene file
  int port = 8080;    // 0: any free port
  std::size_t max_body_bytes = std::size_t(1) << 20;
};

class StudioServer {
 public:
  // Reads the scene and its photo; throws InputError as the CLI's other verbs do.
  explicit StudioServer(const StudioOptions& options);
  ~StudioServer();
  // Binds 127.0.0.1 (never another address) and returns the port; throws InputError if it cannot.
  int bind();
  // The address to open, with the launch's token: http://127.0.0.1:PORT/?token=T (after bind()).
  std::string url() const;
  const std::string& token() const;
  // Serves until stop() (from another thread).
  void run();
  void stop();

  struct Impl;  // studio_impl.h: the state its two source files share

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace insitu
