// The calibration's uncertainty at the objects, for people and for programs (object_uncertainty.h).
#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "calib/object_uncertainty.h"

namespace insitu {

namespace {

std::string px(double v) {
  if (!std::isfinite(v)) return "unbounded";
  return fmt::format(fmt::runtime(v < 10 ? "{:.2f} px" : v < 100 ? "{:.1f} px" : "{:.0f} px"), v);
}

nlohmann::json finite_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

std::string hint_text(const ClickHint& h) {
  return fmt::format(
      "click next a floor point near pixel ({:.0f}, {:.0f}), world ({:.2f}, {:.2f}, {:.2f}) m: the worst 1σ "
      "at the objects would fall from {} to {} (predicted, model {})",
      h.uv_px.x(), h.uv_px.y(), h.p_world.x(), h.p_world.y(), h.p_world.z(), px(h.sigma_before_px),
      px(h.sigma_after_px), h.model);
}

}  // namespace

std::string object_uncertainty_report(const std::vector<ObjectUncertainty>& objects,
                                      const std::optional<ClickHint>& hint) {
  std::string out;
  for (const ObjectUncertainty& o : objects) {
    if (o.points.empty()) continue;
    const PointUncertainty& w = o.points[o.worst];
    out += fmt::format(
        "object       {}: up to {} (95%) at its {} corner, pixel ({:.1f}, {:.1f}); noise alone {}, "
        "model shift {} ({}){}\n",
        o.name, px(w.radius95_px), w.point.name, w.uv_px.x(), w.uv_px.y(), px(w.noise_radius95_px),
        px(w.model_shift_px), o.model_note, o.outside.empty() ? "" : "; OUTSIDE the clicks' span");
  }
  if (hint) out += "hint         " + hint_text(*hint) + "\n";
  return out;
}

nlohmann::json object_uncertainty_json(const std::vector<ObjectUncertainty>& objects,
                                       const std::optional<ClickHint>& hint) {
  using nlohmann::json;
  json list = json::array();
  for (const ObjectUncertainty& o : objects) {
    json points = json::array();
    for (const PointUncertainty& p : o.points)
      points.push_back({{"name", p.point.name},
                        {"world", {p.point.p_world.x(), p.point.p_world.y(), p.point.p_world.z()}},
                        {"uv", {p.uv_px.x(), p.uv_px.y()}},
                        {"sigma_px", finite_or_null(p.noise_sigma_px)},
                        {"noise_radius95_px", finite_or_null(p.noise_radius95_px)},
                        {"model_shift_px", p.model_shift_px},
                        {"radius95_px", finite_or_null(p.radius95_px)},
                        {"outside_clicks", p.outside_clicks}});
    list.push_back({{"name", o.name},
                    {"radius95_px", finite_or_null(o.radius95_px())},
                    {"worst", o.points.empty() ? "" : o.points[o.worst].point.name},
                    {"model", o.model_note},
                    {"outside", o.outside},
                    {"points", points}});
  }
  json h = nullptr;
  if (hint)
    h = {{"world", {hint->p_world.x(), hint->p_world.y(), hint->p_world.z()}},
         {"uv", {hint->uv_px.x(), hint->uv_px.y()}},
         {"sigma_before_px", hint->sigma_before_px},
         {"sigma_after_px", hint->sigma_after_px},
         {"model", hint->model}};
  return {{"objects", list}, {"click_next", h}};
}

std::string outside_clicks_warning(const std::vector<ObjectUncertainty>& objects,
                                   const std::optional<ClickHint>& hint) {
  std::string names;
  double worst = 0;
  for (const ObjectUncertainty& o : objects)
    if (!o.outside.empty()) {
      names += (names.empty() ? "" : ", ") + o.name;
      worst = std::max(worst, o.radius95_px());
    }
  if (names.empty()) return "";
  return fmt::format(
      "object(s) {} lie outside the span of the clicked points, where the camera is extrapolated: up to {} "
      "(95%){}",
      names, px(worst), hint ? "; " + hint_text(*hint) : "");
}

}  // namespace insitu
