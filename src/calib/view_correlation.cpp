#include "calib/view_correlation.h"
#include "core/file_check.h"

#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/text_file.h"

namespace insitu {

namespace {

// Whitespace-separated numbers, each remembering its line for messages.
class NumberReader {
 public:
  explicit NumberReader(const std::string& path) : path_(path) {
    std::ifstream in(path);
    if (!in) throw InputError(path, exists_quietly(path) ? "cannot read file" : "file not found");
    std::string line;
    for (int lineno = 1; std::getline(in, line); ++lineno) {
      std::istringstream ls(line);
      for (std::string tok; ls >> tok;) tokens_.push_back({tok, lineno});
    }
  }
  double next(const char* what) {
    if (pos_ >= tokens_.size())
      throw InputError(fmt::format("{}:{}", path_, last_line()), fmt::format("missing {}", what));
    const auto& [tok, line] = tokens_[pos_++];
    char* end = nullptr;
    const double x = std::strtod(tok.c_str(), &end);
    if (end == tok.c_str() || *end != '\0' || !std::isfinite(x))
      throw InputError(fmt::format("{}:{}", path_, line), fmt::format("{}: '{}' is not a finite number", what, tok));
    return x;
  }
  Vec3d vec3(const char* what) {
    const double x = next(what), y = next(what), z = next(what);
    return {x, y, z};
  }
  int line() const { return pos_ < tokens_.size() ? tokens_[pos_].second : last_line(); }

 private:
  int last_line() const { return tokens_.empty() ? 1 : tokens_.back().second; }
  std::string path_;
  std::vector<std::pair<std::string, int>> tokens_;
  std::size_t pos_ = 0;
};

}  // namespace

ViewCorrelation read_view_correlation(const std::string& path) {
  NumberReader r(path);
  ViewCorrelation vc;
  vc.eye = r.vec3("eye point");
  vc.look = r.vec3("look point");
  vc.up = r.vec3("up vector");
  vc.d_over_s = r.next("d/s ratio");
  vc.aspect = r.next("aspect ratio");
  vc.halfx = r.next("half screen width");
  vc.halfy = r.next("half screen height");
  vc.xcenter = r.next("image centre x");
  vc.ycenter = r.next("image centre y");
  const std::string where = path;
  if (!(vc.d_over_s > 0) || !(vc.aspect > 0) || !(vc.halfx > 0) || !(vc.halfy > 0))
    throw InputError(where, "d/s, aspect and half screen sizes must be positive");
  if ((vc.look - vc.eye).norm() == 0 || vc.up.cross(vc.look - vc.eye).norm() == 0)
    throw InputError(where, "eye, look and up do not define a view");
  const int n_line = r.line();
  const double n = r.next("number of points");
  if (n < 0 || n != std::floor(n) || n > 1e6)
    throw InputError(fmt::format("{}:{}", path, n_line), "bad number of points");
  for (int i = 0; i < int(n); ++i) {
    ControlPoint p;
    p.where = fmt::format("{}:{}", path, r.line());
    p.p_world = r.vec3("point");
    const double sx = r.next("screen x"), sy = r.next("screen y");
    p.uv_px = {sx, 2 * vc.halfy - sy};
    p.name = fmt::format("#{}", i + 1);
    vc.points.push_back(p);
  }
  return vc;
}

void write_view_correlation(const std::string& path, const ViewCorrelation& vc) {
  std::string text;
  auto line3 = [&](const Vec3d& v) { text += fmt::format("{:.10g} {:.10g} {:.10g}\n", v.x(), v.y(), v.z()); };
  line3(vc.eye);
  line3(vc.look);
  line3(vc.up);
  text += fmt::format("{:.10g} {:.10g}\n", vc.d_over_s, vc.aspect);
  text += fmt::format("{:.10g} {:.10g} {:.10g} {:.10g}\n", vc.halfx, vc.halfy, vc.xcenter, vc.ycenter);
  text += fmt::format("{}\n", vc.points.size());
  for (const auto& p : vc.points)
    text += fmt::format("{:.10g} {:.10g} {:.10g} {:.10g} {:.10g}\n", p.p_world.x(), p.p_world.y(), p.p_world.z(),
                        p.uv_px.x(), 2 * vc.halfy - p.uv_px.y());
  write_text_file(path, text);
}

Camera camera_from_view_correlation(const ViewCorrelation& vc) {
  const Vec3d z = (vc.eye - vc.look).normalized();
  const Vec3d x = vc.up.normalized().cross(z).normalized();
  const Vec3d y = z.cross(x).normalized();
  Camera cam;
  cam.width = int(std::lround(2 * vc.halfx));
  cam.height = int(std::lround(2 * vc.halfy));
  cam.fx = vc.d_over_s * vc.halfx;
  cam.fy = vc.aspect * cam.fx;
  cam.cx = vc.xcenter;
  cam.cy = 2 * vc.halfy - vc.ycenter;
  cam.R_cam_from_world.row(0) = x.transpose();
  cam.R_cam_from_world.row(1) = -y.transpose();
  cam.R_cam_from_world.row(2) = -z.transpose();
  cam.t_cam_from_world = -cam.R_cam_from_world * vc.eye;
  return cam;
}

ViewCorrelation view_correlation_from_camera(const Camera& cam, const std::vector<ControlPoint>& points) {
  ViewCorrelation vc;
  vc.eye = cam.eye_world();
  vc.look = vc.eye + cam.forward_world();
  vc.up = cam.up_world();
  vc.halfx = 0.5 * cam.width;
  vc.halfy = 0.5 * cam.height;
  vc.d_over_s = cam.fx / vc.halfx;
  vc.aspect = cam.fy / cam.fx;
  vc.xcenter = cam.cx;
  vc.ycenter = cam.height - cam.cy;
  vc.points = points;
  return vc;
}

}  // namespace insitu
