#include "scene/light_recovery.h"

#include <fmt/format.h>

#include <cmath>

#include "core/colour.h"
#include "light/hdr_merge.h"

namespace insitu {

namespace {

// The references' plates, read and linearized as the photo is (its response and exposure), with
// their clipped masks; a plate of another size than the photo is an InputError naming it.
struct Plates {
  std::vector<Image> linear, clipped;  // per reference; empty images where it has no plate
};

Plates read_plates(LoadedScene& s) {
  Plates p;
  for (const ReferenceSpec& r : s.spec.references) {
    p.linear.emplace_back(), p.clipped.emplace_back();
    if (r.photo.empty()) continue;
    ImageFile plate;
    try {
      plate = read_image_file(r.photo);
    } catch (const InputError& e) {
      throw e.with_context(r.where + ".photo");
    }
    if (plate.stored.width != s.photo.stored.width || plate.stored.height != s.photo.stored.height)
      throw InputError(
          r.where + ".photo",
          fmt::format("{}: {} x {} pixels, the photo {} x {}: a plate is the photo's view", r.photo, plate.stored.width,
                      plate.stored.height, s.photo.stored.width, s.photo.stored.height));
    std::size_t clamped = 0;
    p.linear.back() = linearize_photo(plate, s.environment_info, &clamped);
    p.clipped.back() = clipped_mask(plate);
    if (clamped > 0) s.warnings.add(r.photo, fmt::format("{} negative or non-finite values clamped to 0", clamped));
  }
  return p;
}

InverseLightingInput fit_input(const LoadedScene& s, const Image& photo_clipped, const Plates& plates) {
  InverseLightingInput in;
  in.radiance = &s.environment;
  if (s.environment_info.clipped_cube) in.clipped = &*s.environment_info.clipped_cube;
  in.room = s.room;
  in.camera = &s.camera;
  in.photo_linear = &s.photo_linear;
  in.photo_clipped = &photo_clipped;
  for (const PlaneSpec& p : s.spec.local_scene) {
    if (p.mesh) continue;
    FitPlane f{p.point.cast<float>(), p.normal.normalized().cast<float>(), std::nullopt, std::nullopt};
    if (!p.albedo_from_photo) f.albedo = luminance(p.albedo);
    if (p.mean_albedo) f.mean_albedo = float(*p.mean_albedo);
    in.planes.push_back(f);
  }
  for (std::size_t i = 0; i < s.spec.references.size(); ++i) {
    const ReferenceSpec& r = s.spec.references[i];
    FitReference& f = in.references.emplace_back(FitReference{r.polygon_px, float(r.albedo), std::nullopt});
    if (r.ball) f.ball = FitBall{r.ball->center_world.cast<float>(), float(r.ball->radius_m)};
    if (!r.photo.empty()) f.plate_linear = &plates.linear[i], f.plate_clipped = &plates.clipped[i];
  }
  return in;
}

// A reference that could not serve says why: inverse lighting did not run, or none of its pixels
// was usable (clipped in the photo: a white sheet needs an exposure that keeps it below white).
// A reference has an effect only where a fit runs: on clipped light (every reference), or on the
// light through the room box's openings that the shots never saw (sheets only: unseen_outside.h).
void warn_of_references(LoadedScene& s) {
  if (s.spec.references.empty()) return;
  const bool openings = s.room && !s.room->openings.empty();
  if (!s.spec.environment.inverse_lighting) {
    s.warnings.add(s.spec.path + ":$.references", "environment.inverse_lighting is false: the references are not used");
    return;
  }
  if (!s.environment_info.clipped_cube) {
    for (const ReferenceSpec& r : s.spec.references)
      if (!openings || r.ball)
        s.warnings.add(r.where, openings ? "nothing clipped in the environment: a reference ball is not needed (only "
                                           "sheets help fit the light through the room box's openings)"
                                         : "nothing clipped in the environment and no opening in the room box: the "
                                           "reference is not needed");
    return;
  }
  const auto& uses = s.inverse_lighting->references;
  for (std::size_t r = 0; r < uses.size() && r < s.spec.references.size(); ++r)
    if (uses[r].used == 0)
      s.warnings.add(
          s.spec.references[r].where,
          fmt::format("no pixel of the reference was used ({} sampled: {} clipped in the photo, {} on no real surface "
                      "of the local scene or the room box, the rest too dark)",
                      uses[r].sampled, uses[r].clipped, uses[r].off_surface));
}

}  // namespace

void match_white_balance(LoadedScene& s) {
  const EnvironmentSpec& e = s.spec.environment;
  if (!e.white_balance_to_photo || (!e.from_shots() && !s.environment_info.panorama)) return;
  const auto& clipped = s.environment_info.clipped_cube;
  s.white_balance = white_balance_to_photo(s.environment, clipped ? &*clipped : nullptr, s.room, s.camera,
                                           s.photo_linear, clipped_mask(s.photo));
  const WhiteBalance& wb = *s.white_balance;
  if (!wb.determined) {
    s.warnings.add(e.where, "the light's white balance is not matched to the photo: " + wb.reason);
    return;
  }
  s.environment = scaled(s.environment, wb.gain);
  if ((wb.gain - Rgb::Ones()).cwiseAbs().maxCoeff() > 0.05f)
    s.warnings.add(e.where, fmt::format("the shots' white balance differs from the photo's: the light is multiplied by "
                                        "({:.3f}, {:.3f}, {:.3f}) to match it; lock white balance when you shoot",
                                        wb.gain[0], wb.gain[1], wb.gain[2]));
}

void fill_uncovered_from_photo(LoadedScene& s) {
  const EnvironmentInfo& info = s.environment_info;
  if (info.covered.empty() || !s.room) return;
  const auto& clipped = info.clipped_cube;
  s.photo_fill = fill_from_photo(s.environment, info.covered, clipped ? &*clipped : nullptr, *s.room, s.camera,
                                 s.photo_linear, clipped_mask(s.photo));
}

nlohmann::json photo_fill_report(const LoadedScene& s) {
  if (!s.photo_fill) return nullptr;
  const PhotoFill& f = *s.photo_fill;
  return {{"uncovered_texels", f.uncovered},
          {"from_photo", f.from_photo},
          {"level", f.level},
          {"level_pixels", f.level_pixels},
          {"reason", f.reason.empty() ? nlohmann::json(nullptr) : nlohmann::json(f.reason)}};
}

nlohmann::json white_balance_report(const LoadedScene& s) {
  if (!s.white_balance) return nullptr;
  const WhiteBalance& wb = *s.white_balance;
  return {{"determined", wb.determined},
          {"gain", {wb.gain[0], wb.gain[1], wb.gain[2]}},
          {"log_gain_sigma", {wb.sigma[0], wb.sigma[1], wb.sigma[2]}},
          {"pixels", wb.pixels},
          {"reason", wb.determined ? nlohmann::json(nullptr) : nlohmann::json(wb.reason)}};
}

void recover_clipped_light(LoadedScene& s, const std::atomic<bool>* stop) {
  const bool clipped = s.environment_info.clipped_cube.has_value();
  const bool openings = s.room && !s.room->openings.empty();
  if (!s.spec.environment.inverse_lighting || (!clipped && !openings)) return warn_of_references(s);
  const Image photo_clipped = clipped_mask(s.photo);
  const Plates plates = read_plates(s);
  InverseLightingInput input = fit_input(s, photo_clipped, plates);
  input.stop = stop;
  if (clipped) {
    s.inverse_lighting = recover_clipped_sources(input);
    if (s.inverse_lighting->any_determined()) s.environment = s.inverse_lighting->apply(s.environment);
    if (s.inverse_lighting->status != "fitted" && s.inverse_lighting->status != "none")
      s.warnings.add(s.spec.environment.where, s.inverse_lighting->message);
  }
  if (openings) {
    s.unseen_outside = fit_unseen_outside(input);  // on the light as completed above
    s.room->unseen_outside = s.unseen_outside->radiance();
    if (s.unseen_outside->status == "undetermined") s.warnings.add(s.spec.environment.where, s.unseen_outside->message);
  }
  warn_of_references(s);
}

std::string light_determined_by(const LoadedScene& s) {
  const EnvironmentSpec& e = s.spec.environment;
  if (!e.from_shots() && !s.environment_info.panorama) return "hdr image";
  bool brackets = false;
  for (const ShotSpec& shot : e.shots) brackets = brackets || shot.files.size() >= 2;
  if (!s.environment_info.clipped_cube) return e.from_shots() ? (brackets ? "brackets" : "shots") : "panorama";
  const auto& il = s.inverse_lighting;
  if (!il || !il->any_determined()) return "lower bound";
  return il->reference_surfaces > 0 ? "inverse lighting with a reference" : "inverse lighting";
}

nlohmann::json light_report(const LoadedScene& s) {
  using nlohmann::json;
  json out{{"determined_by", light_determined_by(s)}};
  if (const auto& u = s.unseen_outside)
    out["unseen_outside"] = {{"status", u->status},
                             {"message", u->message},
                             {"unit", {u->unit[0], u->unit[1], u->unit[2]}},
                             {"scale", u->scale},
                             {"scale_sigma", std::isfinite(u->sigma) ? json(u->sigma) : json(nullptr)},
                             {"light_share", u->light_share},
                             {"pixels", u->pixels}};
  const auto& il = s.inverse_lighting;
  if (!il) return out;
  json sources = json::array();
  for (const SourceFit& f : il->sources) {
    const Vec3f& d = f.source.dir_world;
    sources.push_back({{"direction_world", {d.x(), d.y(), d.z()}},
                       {"solid_angle_sr", f.source.solid_angle_sr},
                       {"texels", f.source.texels.size()},
                       {"determined", f.determined},
                       {"scale", f.scale},
                       {"scale_sigma", std::isfinite(f.sigma) ? json(f.sigma) : json(nullptr)},
                       {"power_lower_bound", f.source.power},
                       {"power_added", f.added_power},
                       {"colour", {f.colour[0], f.colour[1], f.colour[2]}},
                       {"colour_sigma", {f.colour_sigma[0], f.colour_sigma[1], f.colour_sigma[2]}},
                       {"colour_determined", f.colour_determined},
                       {"colour_applied", f.colour_applied}});
  }
  json parts = json::array();
  for (const PartFit& p : il->parts) {
    const Vec3f& d = p.texels.dir_world;
    parts.push_back({{"source", p.source},
                     {"direction_world", {d.x(), d.y(), d.z()}},
                     {"texels", p.texels.texels.size()},
                     {"scale", p.scale}});
  }
  json references = json::array();
  for (std::size_t r = 0; r < il->references.size() && r < s.spec.references.size(); ++r) {
    const ReferenceUse& u = il->references[r];
    references.push_back({{"kind", s.spec.references[r].ball ? "ball" : "polygon"},
                          {"albedo", s.spec.references[r].albedo},
                          {"pixels_sampled", u.sampled},
                          {"pixels_clipped", u.clipped},
                          {"pixels_off_surface", u.off_surface},
                          {"pixels_used", u.used},
                          {"pixels_in_its_shadow", u.shadow}});
  }
  out["inverse_lighting"] = {
      {"status", il->status},
      {"message", il->message},
      {"parts", parts},
      {"references", references},
      {"missing_irradiance", il->missing_irradiance ? json(*il->missing_irradiance) : json(nullptr)},
      {"pixels", il->pixels},
      {"surfaces", il->surfaces},
      {"reference_surfaces", il->reference_surfaces},
      {"clipped_power_share", il->clipped_power_share},
      {"residual_sigma_log", il->residual_rms},
      {"fit_face_size", il->fit_face_size},
      {"sources", sources}};
  return out;
}

}  // namespace insitu
