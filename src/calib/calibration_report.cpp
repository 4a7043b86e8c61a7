// The calibration's result for people and programs: the camera file's JSON (with the fit, the
// per-point residuals and the uncertainties) and the text report `insitu calibrate` prints.
#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "calib/calibration.h"

namespace insitu {

nlohmann::json calibration_to_json(const CalibrationResult& r) {
  using nlohmann::json;
  json cam = camera_to_json(r.camera);
  json pts = json::array();
  for (const auto& p : r.points)
    pts.push_back({{"name", p.name},
                   {"uv", {p.uv_px.x(), p.uv_px.y()}},
                   {"residual_px", {p.residual_px.x(), p.residual_px.y()}},
                   {"outlier", p.outlier},
                   {"behind", p.behind}});
  json fits = json::array();
  for (const auto& f : r.fits) {
    json j = {{"model", model_name(f.model)}, {"fitted", f.fitted}, {"note", f.note}};
    if (f.fitted) {
      j["rms_px"] = f.rms_px;
      j["rss_px2"] = f.rss_px2;
    }
    if (f.p_value >= 0) j["p_value"] = f.p_value;
    fits.push_back(j);
  }
  json sigma = nullptr;
  if (r.sigma.known) {
    const auto& s = r.sigma;
    sigma = {{"fx_px", s.fx_px},       {"fy_px", s.fy_px},
             {"cx_px", s.cx_px},       {"cy_px", s.cy_px},
             {"aspect", s.aspect},     {"eye", {s.eye_world.x(), s.eye_world.y(), s.eye_world.z()}},
             {"hfov_deg", s.hfov_deg}, {"view_direction_deg", s.view_direction_deg},
             {"roll_deg", s.roll_deg}};
  }
  cam["calibration"] = {
      {"model", model_name(r.model)},
      {"selection", r.selection},
      {"rms_px", r.rms_px},
      {"sigma_px", r.sigma_px},
      {"inliers", r.inliers},
      {"coplanar", r.coplanar},
      {"points", pts},
      {"fits", fits},
      {"stddev", sigma},
      {"insertion",
       {{"world", {r.insertion_world.x(), r.insertion_world.y(), r.insertion_world.z()}},
        {"uv", {r.insertion_px.x(), r.insertion_px.y()}},
        {"sigma_px", r.insertion_sigma_px},
        {"noise_radius95_px", r.insertion_noise_radius95_px},
        {"model_shift_px", r.insertion_model_shift_px},
        // null: the model's own error is not bounded (object_uncertainty.h)
        {"radius95_px",
         std::isfinite(r.insertion_radius95_px) ? nlohmann::json(r.insertion_radius95_px) : nlohmann::json()}}},
      {"warnings", r.warnings.items},
  };
  return cam;
}

std::string calibration_report(const CalibrationResult& r) {
  const Camera& c = r.camera;
  const auto& s = r.sigma;
  std::string out;
  auto pm = [&](double v, double sd, const char* fmtv) {
    return s.known ? fmt::format(fmt::runtime(std::string(fmtv) + " ± " + fmtv), v, sd)
                   : fmt::format(fmt::runtime(fmtv), v);
  };
  out += fmt::format("model        {}  ({})\n", model_name(r.model), r.selection);
  for (const auto& f : r.fits)
    out += f.fitted ? fmt::format("  {:<6} RMS {:.4g} px{}{}\n", model_name(f.model), f.rms_px,
                                  f.note.empty() ? "" : "; ", f.note)
                    : fmt::format("  {:<6} not fitted: {}\n", model_name(f.model), f.note);
  // A parameter the model does not fit is fixed, not known to ±0: say so, and why.
  const std::string why = r.selection == "requested" ? "by the requested model" : "not supported by the points";
  if (r.model == CameraModel::kFCA)
    out += fmt::format("fx, fy       {} px, {} px\n", pm(c.fx, s.fx_px, "{:.2f}"), pm(c.fy, s.fy_px, "{:.2f}"));
  else
    out += fmt::format("fx, fy       {} px, fy = fx (square pixels: fixed, {})\n", pm(c.fx, s.fx_px, "{:.2f}"), why);
  if (r.model == CameraModel::kF)
    out += fmt::format("cx, cy       {:.2f} px, {:.2f} px (the image centre: fixed, {})\n", c.cx, c.cy, why);
  else
    out += fmt::format("cx, cy       {} px, {} px\n", pm(c.cx, s.cx_px, "{:.2f}"), pm(c.cy, s.cy_px, "{:.2f}"));
  out += fmt::format("fov          {}° horizontal, {:.3f}° vertical\n", pm(c.hfov_deg(), s.hfov_deg, "{:.3f}"),
                     c.vfov_deg());
  const Vec3d eye = c.eye_world(), look = eye + c.forward_world(), up = c.up_world();
  out += fmt::format("eye          ({:.4f}, {:.4f}, {:.4f})", eye.x(), eye.y(), eye.z());
  out +=
      s.known ? fmt::format(" ± ({:.2g}, {:.2g}, {:.2g})\n", s.eye_world.x(), s.eye_world.y(), s.eye_world.z()) : "\n";
  out += fmt::format("look         ({:.4f}, {:.4f}, {:.4f})\n", look.x(), look.y(), look.z());
  out += fmt::format("up           ({:.4f}, {:.4f}, {:.4f})\n", up.x(), up.y(), up.z());
  if (s.known)
    out += fmt::format("orientation  view direction ± {:.2g}°, roll ± {:.2g}°\n", s.view_direction_deg, s.roll_deg);
  out += fmt::format("residuals    RMS {:.3g} px over {} inlier(s) (σ̂ = {:.3g} px)\n", r.rms_px, r.inliers, r.sigma_px);
  for (const auto& p : r.points)
    out += fmt::format("  {:<14} ({:8.2f}, {:8.2f})  {:7.3f} px{}{}\n", p.name, p.uv_px.x(), p.uv_px.y(),
                       p.residual_px.norm(), p.outlier ? "  OUTLIER" : "", p.behind ? "  BEHIND" : "");
  out += fmt::format("insertion    ({:.3f}, {:.3f}, {:.3f}) m at pixel ({:.1f}, {:.1f})", r.insertion_world.x(),
                     r.insertion_world.y(), r.insertion_world.z(), r.insertion_px.x(), r.insertion_px.y());
  // The 95 % radius is the objects' one (the model's own error included); the 1σ is the noise's.
  const std::string r95 =
      std::isfinite(r.insertion_radius95_px) ? fmt::format("{:.2g} px", r.insertion_radius95_px) : "unbounded";
  out += s.known
             ? fmt::format(
                   ": up to {} (95%, the model's own error included); noise alone {:.2g} px (1σ), {:.2g} px (95%)\n",
                   r95, r.insertion_sigma_px, r.insertion_noise_radius95_px)
             : "\n";
  for (const auto& w : r.warnings.items) out += "warning: " + w + "\n";
  return out;
}

}  // namespace insitu
