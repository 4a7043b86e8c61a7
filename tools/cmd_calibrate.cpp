// insitu calibrate --points P (--image PHOTO | --size W H) [--model M] [--origin O] [--at X Y Z]
//                  [--box NAME XMIN YMIN ZMIN XMAX YMAX ZMAX]... [-o camera.json] [--vc OUT.vc]
//                  [--blender cam.py]
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

#include "interop/blender_camera.h"
#include "calib/calibration.h"
#include "calib/calibration_summary.h"
#include "commands.h"
#include "core/image.h"
#include "core/json_reader.h"
#include "core/output_paths.h"
#include "core/text_file.h"
#include "calib/view_correlation.h"

namespace insitu {
namespace {

struct CalibrateArgs {
  std::string points, image, model = "auto", origin = "top_left", output, vc, blender;
  std::vector<int> size;
  std::vector<double> at;
  std::vector<std::vector<std::string>> boxes;  // NAME and six numbers each
};

// --box NAME XMIN YMIN ZMIN XMAX YMAX ZMAX: an object's bounding box in world metres.
std::vector<NamedPoint> parse_box(const std::vector<std::string>& b) {
  const std::string where = "--box " + b.at(0);
  double v[6];
  for (int i = 0; i < 6; ++i) {
    std::size_t used = 0;
    try {
      v[i] = std::stod(b.at(std::size_t(i) + 1), &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != b[std::size_t(i) + 1].size() || !std::isfinite(v[i]))
      throw InputError(
          where, "expected six finite numbers XMIN YMIN ZMIN XMAX YMAX ZMAX, got '" + b[std::size_t(i) + 1] + "'");
  }
  if (v[0] > v[3] || v[1] > v[4] || v[2] > v[5]) throw InputError(where, "each minimum must not exceed its maximum");
  return box_corners(Vec3d(v[0], v[1], v[2]), Vec3d(v[3], v[4], v[5]));
}

int run_calibrate(const CalibrateArgs& a) {
  if (a.image.empty() && a.size.empty()) throw InputError("calibrate", "give --image PHOTO or --size W H");
  check_outputs({{a.points, "the control points"}, {a.image, "the photo"}},
                {{a.output, "-o"}, {a.vc, "--vc"}, {a.blender, "--blender"}});
  int width = 0, height = 0;
  if (!a.image.empty())
    std::tie(width, height) = read_image_size(a.image);
  else {
    width = a.size[0];
    height = a.size[1];
  }
  CalibrationOptions options;
  if (a.model != "auto") options.model = parse_model(a.model);
  if (!a.at.empty()) options.insertion_world = Vec3d(a.at[0], a.at[1], a.at[2]);
  std::vector<NamedBox> boxes;
  for (const auto& b : a.boxes) boxes.emplace_back(b.at(0), parse_box(b));
  const auto points = read_control_points(a.points, *parse_bottom_left_origin(a.origin), height);
  CalibrationResult r;
  try {
    r = calibrate(points, width, height, options);
  } catch (const InputError& e) {
    throw e.with_context(a.points);
  }
  const CalibrationSummary summary = summarize_calibration(r, boxes);
  std::printf("%s", summary.report.c_str());
  const nlohmann::json& camera_json = summary.camera_json;
  if (!a.output.empty()) {
    write_text_file(a.output, json_text(camera_json, 2) + "\n");
    std::printf("wrote %s\n", a.output.c_str());
  }
  if (!a.blender.empty()) {
    write_text_file(a.blender, blender_camera_script(r.camera, a.image));
    std::printf("wrote %s\n", a.blender.c_str());
  }
  if (!a.vc.empty()) {
    std::vector<ControlPoint> inliers;
    for (std::size_t i = 0; i < points.size(); ++i)
      if (!r.points[i].outlier) inliers.push_back(points[i]);
    write_view_correlation(a.vc, view_correlation_from_camera(r.camera, inliers));
    std::printf("wrote %s\n", a.vc.c_str());
  }
  return 0;
}

}  // namespace

Command add_calibrate_command(CLI::App& app) {
  auto a = std::make_shared<CalibrateArgs>();
  CLI::App* cmd = app.add_subcommand("calibrate", "recover the camera from 2D-3D control points");
  cmd->add_option("--points", a->points, "control points: .json, .csv or a View Correlation .vc file")->required();
  auto* image_opt = cmd->add_option("--image", a->image, "the photo (for its size)");
  auto* size_opt =
      cmd->add_option("--size", a->size, "the photo's size in pixels")->expected(2)->check(CLI::Range(1, 1 << 20));
  image_opt->excludes(size_opt);
  cmd->add_option("--model", a->model, "camera model: auto, f, f+c, f+c+a")
      ->check(CLI::IsMember({"auto", "f", "f+c", "f+c+a"}))
      ->capture_default_str();
  cmd->add_option("--origin", a->origin, std::string("pixel origin of the points: ") + kOriginNames)
      ->check([](const std::string& s) {
        return parse_bottom_left_origin(s) ? "" : std::string("expected ") + kOriginNames;
      })
      ->capture_default_str();
  cmd->add_option("--at", a->at, "world point (m) where the uncertainty in pixels is reported")->expected(3);
  cmd->add_option(
         "--box", a->boxes,
         "an object's bounding box: NAME XMIN YMIN ZMIN XMAX YMAX ZMAX (m); the uncertainty at its corners is reported")
      ->expected(7);
  cmd->add_option("-o,--output", a->output, "write camera.json");
  cmd->add_option("--vc", a->vc, "also write the View Correlation parameter set");
  cmd->add_option("--blender", a->blender,
                  "also write a Blender Python script that creates the camera (and sets the photo as its background)");
  return [cmd, a] { return cmd->parsed() ? run_calibrate(*a) : -1; };
}

}  // namespace insitu
